//! What the mouse does to the lab ([`App::mouse`]): a click on a scene's tab shows that
//! scene, the wheel scrolls the open help or log, and a click on the pressure chart places
//! the cursor at the contact point nearest it. Where things are is what the last frame drew
//! ([`super::Drawn`]).

use crossterm::event::{KeyCode, MouseButton, MouseEvent, MouseEventKind};
use ratatui::layout::{Position, Rect};

use super::{App, Notice, Scene};

/// Lines one notch of the wheel scrolls.
const WHEEL_LINES: usize = 3;

impl App {
    /// Handle one mouse event; whether the screen changed.
    pub(super) fn mouse(&mut self, event: MouseEvent) -> bool {
        let at = Position::new(event.column, event.row);
        let overlay = self.show_help || self.overlays.show_log;
        match event.kind {
            MouseEventKind::ScrollUp | MouseEventKind::ScrollDown if overlay => {
                let code = if event.kind == MouseEventKind::ScrollUp {
                    KeyCode::Up
                } else {
                    KeyCode::Down
                };
                for _ in 0..WHEEL_LINES {
                    self.scroll_overlay(code);
                }
                true
            }
            MouseEventKind::Down(MouseButton::Left) if !overlay && !self.overlays.too_small => self.click(at),
            _ => false,
        }
    }

    /// A left click at `at`: on a tab, its scene; on the pressure chart, the cursor there.
    fn click(&mut self, at: Position) -> bool {
        let drawn = self.overlays.drawn.get();
        if let Some(scene) = drawn.tabs.and_then(|tabs| tab_at(tabs, at)) {
            self.notice = None;
            self.scene = scene;
            return true;
        }
        let Some((graph, [lo, hi])) = drawn.chart.filter(|(graph, _)| graph.contains(at)) else {
            return false;
        };
        let x = lo + (hi - lo) * fraction(graph, at.x);
        let Some(solved) = &self.solved else {
            return false;
        };
        let pbar = &solved.shown.pbar;
        let nearest =
            (0..pbar.len()).min_by(|&a, &b| (pbar[a].0 - x).abs().total_cmp(&(pbar[b].0 - x).abs()));
        if nearest.is_some() {
            self.overlays.cursor = nearest;
            self.notice = Some(Notice::info(
                ", and . move the cursor one contact point; x hides it",
            ));
        }
        nearest.is_some()
    }
}

/// Where column `x` stands across `graph`, from 0 (its left edge) to 1, at the cell's middle.
fn fraction(graph: Rect, x: u16) -> f64 {
    (f64::from(x - graph.x) + 0.5) / f64::from(graph.width.max(1))
}

/// The scene whose tab is at `at`, the tabs drawn in `tabs` (right-aligned, each ` name `
/// in [`Scene::ALL`]'s order), if any.
fn tab_at(tabs: Rect, at: Position) -> Option<Scene> {
    if !tabs.contains(at) {
        return None;
    }
    let widths = Scene::ALL.map(|s| s.name().chars().count() as u16 + 2);
    let total: u16 = widths.iter().sum();
    let mut x = tabs.right().saturating_sub(total);
    for (scene, width) in Scene::ALL.into_iter().zip(widths) {
        if (x..x + width).contains(&at.x) {
            return Some(scene);
        }
        x += width;
    }
    None
}
