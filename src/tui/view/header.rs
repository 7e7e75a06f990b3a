//! The two header lines: scenario and scene tabs; then the discretisation and the parameters.

use ratatui::Frame;
use ratatui::layout::{Alignment, Constraint, Layout, Rect};
use ratatui::text::{Line, Span};
use ratatui::widgets::Paragraph;

use crate::contact::Method;
use crate::fem::Integration;
use crate::scheme::Scheme;
use crate::warning::LOCKING_POISSON;

use super::super::app::{App, Drawn, Scene};
use super::super::study_grading::graded_suffix;
use super::super::theme::Theme;
use super::fmt::{sig, title_fit};

pub fn render(app: &App, frame: &mut Frame, area: Rect, theme: Theme) {
    let [first, second] = Layout::vertical([Constraint::Length(1), Constraint::Length(1)]).areas(area);
    let model = if app.scenario.half_model {
        " (half model, mirrored)"
    } else {
        " (full model)"
    };
    let mut tabs = Vec::new();
    for scene in Scene::ALL {
        let style = if scene == app.scene {
            theme.selected()
        } else {
            ratatui::style::Style::new()
        };
        // The padding of each tab separates it from the next (room for the title at 80 columns).
        tabs.push(Span::styled(format!(" {} ", scene.name()), style));
    }
    let tabs_width = Line::from(tabs.clone()).width() as u16;
    let [left, right] =
        Layout::horizontal([Constraint::Fill(1), Constraint::Length(tabs_width)]).areas(first);
    // A long name ends with "…" rather than running under the tabs.
    let room = left.width.saturating_sub(9);
    let name = format!("{}{model}", app.scenario.name);
    let title = Line::from(vec![
        Span::styled(" riplab ", theme.selected()),
        Span::raw(" "),
        Span::styled(title_fit(&name, room), theme.title()),
    ]);
    frame.render_widget(Paragraph::new(title), left);
    frame.render_widget(
        Paragraph::new(Line::from(tabs)).alignment(Alignment::Right),
        right,
    );
    let drawn = app.overlays.drawn.get();
    app.overlays.drawn.set(Drawn {
        tabs: Some(right),
        ..drawn
    });
    frame.render_widget(Paragraph::new(settings_line(app, theme, second.width)), second);
}

/// "M1 q1+gauss1 │ level 0 h=1 │ 32 el 90 dofs │ ε=1e-6 │ d=0.8" (dofs once solved; then
/// "ν=0.49 selective" where locking is the lesson), within
/// `width` columns: the element and dof counts go first, then the method's parameters, so
/// that no number is ever cut (a cut "d=0.8" would read "d=0").
fn settings_line(app: &App, theme: Theme, width: u16) -> Line<'static> {
    let s = &app.settings;
    let scheme = match Scheme::new(s.element, s.rule).name() {
        Some(m) => format!("{m} "),
        None => String::new(),
    };
    let dofs = app
        .current()
        .map(|c| format!(" {} dofs", c.disc.n_dofs()))
        .unwrap_or_default();
    // The solved mesh's own count (a graded mesh has more than its level).
    let elements = app.current().map_or_else(
        || app.scenario.n_elements(s.level, s.element),
        |c| c.disc.mesh.n_elements(),
    );
    let counts = format!("{elements} el{dofs}");
    // The penalty is the paper's method: its ε alone (the method line names it).
    let method = match s.method {
        Method::Penalty => format!("ε={:e}", s.epsilon),
        Method::Alm { .. } => format!("alm ε={:e}", s.epsilon),
        // Nitsche's γ₀ as the shown solve used it (`auto`'s value once chosen).
        m => match app.current() {
            Some(c) if c.solution.params.method == m => c.solution.method_fields().label(),
            _ => m.label(),
        },
    };
    let short_method = match s.method {
        Method::Penalty | Method::Alm { .. } => method.clone(),
        m => m.name().to_string(),
    };
    // ν and the volumetric integration where locking is the lesson: a selective integration,
    // one switched from the scenario's (`i`), or a ν from which Q1 integrated exactly locks
    // (crate::warning::LOCKING_POISSON).
    let (poisson, integration) = (app.scenario.material.poisson, s.integration);
    let switched = integration != app.scenario.integration;
    let material =
        (integration == Integration::Selective || switched || poisson >= LOCKING_POISSON).then(|| {
            let name = match integration {
                Integration::Full => "full",
                Integration::Selective => "selective",
            };
            format!("ν={} {name}", sig(poisson, 7))
        });
    let fields = |counts: Option<&str>, method: &str| -> Line<'static> {
        let sep = || Span::styled(" │ ", theme.faint());
        let mut spans = vec![
            Span::raw(" "),
            Span::styled(
                format!("{scheme}{}+{}", s.element.name(), s.rule.name()),
                theme.title(),
            ),
            sep(),
            Span::raw(format!(
                "level {}{} h={}",
                s.level,
                graded_suffix(s.refine_edges).unwrap_or_default(),
                sig(app.scenario.h(s.level), 3)
            )),
        ];
        if let Some(c) = counts {
            spans.extend([sep(), Span::raw(c.to_string())]);
        }
        spans.extend([
            sep(),
            Span::raw(method.to_string()),
            sep(),
            Span::raw(format!("d={}", sig(s.depth, 4))),
        ]);
        if let Some(material) = &material {
            spans.extend([sep(), Span::raw(material.clone())]);
        }
        Line::from(spans)
    };
    // The fullest line that fits; the shortest when none does.
    let [full, no_counts, shortest] = [
        fields(Some(&counts), &method),
        fields(None, &method),
        fields(None, &short_method),
    ];
    [full, no_counts]
        .into_iter()
        .find(|line| line.width() <= usize::from(width))
        .unwrap_or(shortest)
}
