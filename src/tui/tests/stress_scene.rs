//! The lab's stress scene: frames at 80×24 and 120×40, the monochrome rendering,
//! the quantity key, computing the stresses only when shown, and the VTU export key.

use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use ratatui::style::Color;
use ratatui::symbols::Marker;

use std::sync::Arc;

use crate::tui::tests::settled;
use riplab::scenario::Scenario;
use riplab::stress::Quantity;
use riplab::tui::app::{Command, ExportKind, Msg, Scene};
use riplab::tui::engine::Engine;
use riplab::tui::export::export_vtu;
use riplab::tui::render_app;
use riplab::tui::settle::carry_out;
use riplab::tui::theme::Theme;
use riplab::tui::view::{Look, view};

fn look(color: bool) -> Look {
    Look {
        theme: Theme { color },
        marker: Marker::Braille,
    }
}

fn ch(c: char) -> Msg {
    Msg::Key(KeyEvent::new(KeyCode::Char(c), KeyModifiers::NONE))
}

#[test]
fn stress_80x24() {
    let app = settled(1, Scene::Stress);
    snap!("tui__stress_80x24", render_app(&app, &look(true), 80, 24));
}

/// The cursor in the stress scene reads the stress under it (the quantity shown, at Γ_C and
/// its largest in the column), not p, p̄ and the gap of the pressure chart.
#[test]
fn the_stress_cursor_reads_the_stress_under_it() {
    let mut app = settled(1, Scene::Stress);
    app.update(ch('x'));
    let (x, _) = app.cursor_point().unwrap();
    let frame = render_app(&app, &look(false), 100, 30);
    let caption = frame
        .lines()
        .find(|l| l.contains("cursor x"))
        .unwrap_or_else(|| panic!("no readout\n{frame}"));
    let head = format!("cursor x {} · τ₁ under it ", riplab::tui::view::fmt::sig(x, 4));
    assert!(
        caption.contains(&head) && caption.contains("at Γ_C, largest") && caption.contains("at depth"),
        "{caption}"
    );
    assert!(!caption.contains("p̄") && !caption.contains("gap"), "{caption}");
}

#[test]
fn stress_120x40_von_mises() {
    let mut app = settled(2, Scene::Stress);
    app.update(ch('c'));
    assert_eq!(app.stress_quantity, Quantity::VonMises);
    snap!(
        "tui__stress_von_mises_120x40",
        render_app(&app, &look(true), 120, 40)
    );
}

/// The quantity key cycles τ₁ → von Mises → σ_yy → τ₁, and the title and caption follow.
#[test]
fn c_cycles_the_quantity() {
    let mut app = settled(1, Scene::Stress);
    let mut titles = Vec::new();
    for _ in 0..3 {
        let text = render_app(&app, &look(true), 100, 30);
        titles.push(text.lines().nth(2).unwrap().to_string());
        app.update(ch('c'));
    }
    assert_eq!(app.stress_quantity, Quantity::PrincipalShear);
    assert!(titles[0].contains("τ₁ near the contact"), "{titles:?}");
    assert!(titles[1].contains("σ_vM near the contact"), "{titles:?}");
    assert!(titles[2].contains("σ_yy near the contact"), "{titles:?}");
    app.update(ch('c'));
    app.update(ch('c'));
    let text = render_app(&app, &look(true), 100, 30);
    assert!(text.contains("most compressive σ_yy = -"), "{text}");
}

/// The maximum of τ₁ is below the surface under the cylinder: the marker is on the axis
/// (the middle column of the mirrored map), not in the first row, and the caption says
/// where.
#[test]
fn the_marker_sits_below_the_surface_on_the_axis() {
    let app = settled(2, Scene::Stress);
    let text = render_app(&app, &look(true), 100, 30);
    let rows: Vec<&str> = text.lines().collect();
    let (r, line) = rows
        .iter()
        .enumerate()
        .find(|(_, l)| l.contains('✕') && l.contains('│'))
        .unwrap();
    assert!(r > 3, "not in the first map row:\n{text}");
    let col = line.chars().position(|c| c == '✕').unwrap();
    let map_width = 100 - 2 - 12;
    assert!(
        (col as i64 - 1 - map_width as i64 / 2).abs() <= 1,
        "column {col}:\n{text}"
    );
    assert!(text.contains("max τ₁ = 109.5 at depth 1.66 (x = 0)"), "{text}");
}

/// Under NO_COLOR the map is drawn in shading glyphs with no colour at all.
#[test]
fn monochrome_map_uses_shading_glyphs_and_no_colour() {
    let app = settled(1, Scene::Stress);
    let mut terminal = Terminal::new(TestBackend::new(100, 30)).unwrap();
    terminal.draw(|f| view(&app, f, &look(false))).unwrap();
    let buffer = terminal.backend().buffer();
    let mut glyphs = std::collections::BTreeSet::new();
    for cell in buffer.content() {
        assert!(
            matches!(cell.fg, Color::Reset) && matches!(cell.bg, Color::Reset),
            "a colour under NO_COLOR: {cell:?}"
        );
        if "·░▒▓█✕".contains(cell.symbol()) {
            glyphs.insert(cell.symbol().to_string());
        }
    }
    assert_eq!(glyphs.len(), 6, "every level and the marker: {glyphs:?}");
}

/// The stresses are computed when the scene first shows a solution, by the worker (a
/// request), not while drawing: the frame says they are coming meanwhile. They are kept with
/// the solution and asked for once.
#[test]
fn stresses_are_computed_by_the_worker_only_when_shown() {
    let mut app = settled(1, Scene::Explore);
    render_app(&app, &look(true), 100, 30);
    let solved = app.solved.clone().unwrap();
    assert!(
        solved.stresses.get().is_none(),
        "not computed for the explore scene"
    );
    app.scene = Scene::Stress;
    let effect = app.update(Msg::Resize);
    assert!(
        matches!(&effect.commands[..], [Command::Stresses(r)] if Arc::ptr_eq(&r.solved, &solved)),
        "{:?}",
        effect.commands
    );
    assert!(app.update(Msg::Resize).commands.is_empty(), "asked once");
    let waiting = render_app(&app, &look(true), 100, 30);
    assert!(solved.stresses.get().is_none(), "drawing computes nothing");
    assert!(waiting.contains("computing the stresses…"), "{waiting}");
    carry_out(&mut app, &mut Engine::new(Scenario::paper()), effect.commands);
    assert!(solved.stresses.get().is_some(), "computed by the worker");
    let text = render_app(&app, &look(true), 100, 30);
    assert!(text.contains("max τ₁ ="), "{text}");
    assert!(app.update(Msg::Resize).commands.is_empty(), "kept");
}

/// The zoom of the pressure chart applies to the map: its window is the zoomed chart's x
/// range (the contact zone and its margin, mirrored), narrower than the unzoomed window.
#[test]
fn z_zooms_the_stress_map_to_the_contact_zone() {
    let mut app = settled(2, Scene::Stress);
    let window = |text: &str| -> (f64, f64) {
        let tail = &text[text.find(" · x ").expect("the window in the caption") + 5..];
        let (a, rest) = tail.split_once('…').unwrap();
        let b = rest.split(',').next().unwrap();
        (a.trim().parse().unwrap(), b.trim().parse().unwrap())
    };
    let before = window(&render_app(&app, &look(false), 100, 30));
    app.update(ch('z'));
    assert!(app.zoom);
    let text = render_app(&app, &look(false), 100, 30);
    assert!(text.contains("zoom (z: back)"), "{text}");
    let after = window(&text);
    let solved = app.solved.clone().unwrap();
    let xs = &solved.solution.points.vertex_x;
    let pbar = &solved.solution.pbar;
    let last = (0..pbar.len()).filter(|&i| pbar[i] > 0.0).max().unwrap();
    let edge = xs[(last + 1).min(xs.len() - 1)];
    // The zoomed chart's margin: a quarter of the zone's width or two cells.
    let cell = xs[1] - xs[0];
    let expected = edge + (0.5 * edge).max(2.0 * cell);
    assert!(
        (after.1 - expected).abs() < 0.01 * expected && (after.0 + expected).abs() < 0.01 * expected,
        "zoomed window {after:?}, expected ±{expected}"
    );
    assert!(after.1 - after.0 < before.1 - before.0, "{before:?} → {after:?}");
}

/// `v` asks for a VTU export of the displayed solution; the export writes the body and Γ_C
/// to fresh names (never over an existing file) that read back as VTK XML.
#[test]
fn v_exports_vtu_to_fresh_files() {
    let mut app = settled(1, Scene::Stress);
    let effect = app.update(ch('v'));
    assert_eq!(effect.commands, vec![Command::Export]);
    assert_eq!(app.export_kind, ExportKind::Vtu);
    let dir = std::env::temp_dir().join(format!("riplab-tui-vtu-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let solved = app.solved.clone().unwrap();
    let first = export_vtu(&app.scenario, &solved, &dir).unwrap();
    let second = export_vtu(&app.scenario, &solved, &dir).unwrap();
    assert_eq!(first, dir.join("hertz-paper-q1-gauss1-L1-eps1e-6-d0.8.vtu"));
    assert_eq!(second, dir.join("hertz-paper-q1-gauss1-L1-eps1e-6-d0.8-1.vtu"));
    for p in [&first, &second] {
        for file in [p.clone(), riplab::vtu::contact_path(p)] {
            vtkio::model::Vtk::import(&file).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
