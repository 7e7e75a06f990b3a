//! The keys table, the method line, the settings line and coinciding series.

use super::*;

/// The key table drives the dispatch: every key it binds is handled by the
/// lab (the frame changes or a notice says why not), and a key it does not bind is not.
#[test]
fn every_key_of_the_table_is_handled_and_no_other() {
    use riplab::tui::keys::{CONTROL, LAB};
    for row in LAB {
        for &(code, action) in row.bindings {
            let mut app = App::new(Scenario::paper());
            assert!(app.update(key(code)).redraw, "{code:?} ({action:?}) does nothing");
        }
    }
    for row in CONTROL {
        for &(code, action) in row.bindings {
            let mut app = App::new(Scenario::paper());
            let ctrl = Msg::Key(KeyEvent::new(code, KeyModifiers::CONTROL));
            assert!(app.update(ctrl).redraw, "Ctrl {code:?} ({action:?}) does nothing");
        }
    }
    // A key with no action says so.
    for code in [KeyCode::Char('y'), KeyCode::F(5)] {
        let mut app = App::new(Scenario::paper());
        assert!(app.update(key(code)).redraw);
        assert!(app.notice.unwrap().text.contains("does nothing here"));
    }
}

/// `m` cycles the method (penalty → exact → alm → nitsche → penalty); each change
/// re-solves, the line under the pressure chart names the method, what it needs and its
/// iteration counts (the ALM's updates and inner Newton steps), at 80×24 too.
#[test]
fn the_method_key_cycles_and_the_method_line_shows() {
    let mut engine = Engine::new(Scenario::paper());
    let mut app = App::new(Scenario::paper());
    app.show_timing = false;
    app.settings.level = 1;
    app.settings.epsilon = 1e-3;
    settle(&mut app, &mut engine);
    let line = |app: &App| {
        frame(app, 80, 24)
            .lines()
            .find(|l| l.contains("needs"))
            .map(str::to_string)
            .unwrap_or_default()
    };
    assert!(
        line(&app).contains("penalty: needs ε > 0"),
        "{}",
        frame(&app, 80, 24)
    );
    let penalty_load = app.current().unwrap().solution.load;
    let mut seen = Vec::new();
    for _ in 0..4 {
        let commands = app.update(ch('m')).commands;
        riplab::tui::settle::carry_out(&mut app, &mut engine, commands);
        seen.push(app.settings.method.name());
        let text = frame(&app, 80, 24);
        match app.settings.method.name() {
            "exact" => assert!(line(&app).contains("exact: needs inf-sup"), "{text}"),
            "alm" => {
                let l = line(&app);
                assert!(l.contains("alm: needs ε > 0 (no ε error)"), "{text}");
                let sol = &app.current().unwrap().solution;
                let outer = sol.outer_iterations.unwrap();
                // Warm-started from `exact`'s multipliers: one update confirms them.
                let plural = if outer == 1 { "" } else { "s" };
                assert!(
                    l.contains(&format!(
                        "{outer} update{plural} × {} Newton",
                        sol.newton.iterations
                    )),
                    "{l}"
                );
                // The ALM at ε = 1e-3 carries the exact load, not the penalty's.
                assert!(
                    sol.load > 1.3 * penalty_load,
                    "{} against {penalty_load}",
                    sol.load
                );
                assert!(text.contains("alm ε=1e-3"), "the header names the method: {text}");
            }
            "nitsche" => {
                assert!(line(&app).contains("nitsche: needs γ₀"), "{text}");
                let sol = &app.current().unwrap().solution;
                assert!(sol.newton.converged && sol.load > 0.0, "{text}");
            }
            _ => assert!(line(&app).contains("penalty"), "{text}"),
        }
    }
    assert_eq!(seen, ["exact", "alm", "nitsche", "penalty"]);
}

/// The settings line at 80 columns never cuts a number: with a long method label (Nitsche's
/// parameters) at the finest level, the counts and then the parameters give way and the depth
/// is whole ("d=0" was drawn for d = 0.8).
#[test]
fn the_settings_line_drops_fields_rather_than_cutting_a_number() {
    use riplab::contact::Method;
    use riplab::contact::method::Gamma0;
    for method in [
        Method::Penalty,
        Method::Exact,
        Method::Alm { tolerance: 1e-10 },
        Method::Nitsche {
            theta: -1,
            gamma0: Gamma0::Given(100.0),
        },
        Method::Nitsche {
            theta: 1,
            gamma0: Gamma0::Auto,
        },
    ] {
        for level in [0, MAX_APP_LEVEL] {
            let mut app = App::new(Scenario::paper());
            (app.settings.method, app.settings.level) = (method, level);
            app.settings.rule = Rule::Trapezoid;
            let text = render_app(&app, &LOOK, 80, 24);
            let line = text.lines().nth(1).unwrap().trim_end();
            assert!(line.ends_with("│ d=0.8"), "{method:?} level {level}: {line}");
            assert!(line.contains(&format!("level {level} ")), "{line}");
        }
    }
}

/// A series equal to an earlier one (as M1's β̄_h/√h equals M3's
/// β_h/√h, by (18)) is said to coincide in the legend, and its glyph stands beside the
/// other's at every point instead of under it; a series elsewhere keeps its cells.
#[test]
fn coinciding_series_are_named_and_both_drawn() {
    let same = [(-1.0, 0.0), (-0.5, 0.02), (0.0, 0.05)];
    let apart = [(-1.0, -1.0), (-0.5, -0.9), (0.0, -0.8)];
    for (width, height) in [(80, 14), (120, 30), (40, 10)] {
        let mut terminal = ratatui::Terminal::new(TestBackend::new(width, height)).unwrap();
        terminal
            .draw(|f| {
                let series = |name: &str, glyph: char, data| PlotSeries {
                    name: name.into(),
                    color: Color::Green,
                    stroke: Stroke::None,
                    glyph: Some(glyph),
                    data,
                };
                Plot {
                    title: " test ".into(),
                    overlays: Vec::new(),
                    x: PlotAxis {
                        title: "h".into(),
                        bounds: [-1.2, 0.2],
                        scale: Scale::Log10,
                    },
                    y: PlotAxis {
                        title: "β".into(),
                        bounds: [-1.5, 0.5],
                        scale: Scale::Log10,
                    },
                    series: vec![
                        series("M3", '3', &same[..]),
                        series("M4", '4', &apart[..]),
                        series("M1 p̄", '*', &same[..]),
                    ],
                    marker: Marker::Braille,
                    theme: Theme { color: false },
                }
                .render(f, f.area())
                .expect("room for the graph");
            })
            .unwrap();
        let buf = terminal.backend().buffer().clone();
        let text: Vec<String> = (0..height).map(|y| row_text(&buf, y).concat()).collect();
        // On the title's row when the graph is short, else on the rows under it.
        let legend = text[0..3].concat();
        assert!(legend.contains("M1 p̄ (= 3)"), "{width}×{height}: {legend}");
        assert!(!legend.contains("M4 (="), "{width}×{height}: {legend}");
        let at = |g: &str| -> Vec<(u16, u16)> {
            let mut out = Vec::new();
            for y in 2..height {
                for x in 0..width {
                    if buf[(x, y)].symbol() == g {
                        out.push((x, y));
                    }
                }
            }
            out
        };
        let (threes, stars, fours) = (at("3"), at("*"), at("4"));
        assert_eq!(threes.len(), 3, "{width}×{height}:\n{}", text.join("\n"));
        assert_eq!(stars.len(), 3, "{width}×{height}:\n{}", text.join("\n"));
        assert_eq!(fours.len(), 3, "{width}×{height}:\n{}", text.join("\n"));
        for (t, s) in threes.iter().zip(&stars) {
            assert_eq!(t.1, s.1, "same row");
            assert_eq!(t.0.abs_diff(s.0), 1, "side by side: {t:?} {s:?}");
        }
    }
}
