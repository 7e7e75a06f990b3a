//! Views only draw, and draw as exactly as the lab computes: ticks, sizes, the status line, the inf-sup table.

use super::*;

// ---- views only draw ----------------------------------------------------

/// What the views show of a solution is computed once with it ([`riplab::tui::shown::Shown`]),
/// checked against the solution itself: a half model's p̄ mirrored about x = 0, the whole
/// body's load twice the half's, Hertz for that load, and a zoom range that is symmetric and
/// holds every vertex in contact; a full model is neither mirrored nor doubled.
#[test]
fn shown_is_the_solution_mirrored_once() {
    let app = settled(1, Scene::Explore);
    let solved = app.current().expect("solved");
    let (sol, shown) = (&solved.solution, &solved.shown);
    let xs = &sol.points.vertex_x;
    let n = sol.pbar.len();
    assert_eq!(shown.pbar.len(), 2 * n);
    for (i, (&x, &p)) in xs.iter().zip(&sol.pbar).enumerate() {
        assert_eq!(shown.pbar[n + i], (x, p));
        assert_eq!(shown.pbar[n - 1 - i], (-x, p));
    }
    let half_width = app.scenario.width / 2.0;
    assert_eq!(shown.x_range, [-half_width, half_width]);
    assert_eq!(shown.full_load, 2.0 * sol.load);
    let hertz = Hertz::for_load(&sol.params.obstacle, &app.scenario.material, 2.0 * sol.load);
    assert!(hertz.is_some());
    assert_eq!(shown.hertz, hertz);
    let [a, b] = shown.zone.expect("in contact");
    assert_eq!(a, -b);
    let in_contact = (0..n).filter(|&i| sol.pbar[i] > 0.0);
    assert!(in_contact.clone().count() > 0);
    for i in in_contact {
        assert!(a < -xs[i] && xs[i] < b, "x = ±{} in [{a}, {b}]", xs[i]);
    }
    let full = Scenario::load(std::path::Path::new("scenarios/hertz-paper-full.toml")).unwrap();
    assert!(!full.half_model);
    let mut app = App::new(full.clone());
    app.settings.level = 0;
    settle(&mut app, &mut Engine::new(full));
    let solved = app.current().expect("solved");
    assert_eq!(solved.shown.full_load, solved.solution.load);
    assert_eq!(solved.shown.pbar.len(), solved.solution.pbar.len());
}

// ---- the lab draws as exactly as it computes ------------------------------------

/// The text of row `y` of `buf`, one char per cell (wide cells are not used by the charts).
pub(super) fn row_text(buf: &Buffer, y: u16) -> Vec<String> {
    (0..buf.area.width)
        .map(|x| buf[(x, y)].symbol().to_string())
        .collect()
}

/// The centre column of each whole-word label in `row` that parses as a number.
fn numbers_in(row: &[String]) -> Vec<(f64, f64)> {
    let mut out = Vec::new();
    let mut x = 0;
    let gap = |c: &str| c.trim().is_empty() || ["│", "┤", "┬", "└", "─"].contains(&c);
    while x < row.len() {
        if gap(&row[x]) {
            x += 1;
            continue;
        }
        let start = x;
        let mut word = String::new();
        while x < row.len() && !gap(&row[x]) {
            word.push_str(&row[x]);
            x += 1;
        }
        if let Ok(v) = word.parse::<f64>() {
            out.push((v, (start + x - 1) as f64 / 2.0));
        }
    }
    out
}

/// A plot of one glyph series on an 80×14 test terminal.
fn plot_buffer(x: PlotAxis, y: PlotAxis, data: &[(f64, f64)]) -> Buffer {
    let mut terminal = ratatui::Terminal::new(TestBackend::new(80, 14)).unwrap();
    terminal
        .draw(|f| {
            Plot {
                title: " test ".into(),
                overlays: Vec::new(),
                x: x.clone(),
                y: y.clone(),
                series: vec![PlotSeries {
                    name: "pts".into(),
                    color: Color::Red,
                    stroke: Stroke::None,
                    glyph: Some('@'),
                    data,
                }],
                marker: Marker::Braille,
                theme: Theme { color: true },
            }
            .render(f, f.area())
            .expect("room for the graph");
        })
        .unwrap();
    terminal.backend().buffer().clone()
}

/// Where `@` is drawn in the graph (below the border and the legend row): (column, row).
fn glyphs(buf: &Buffer) -> Vec<(u16, u16)> {
    let mut out = Vec::new();
    for y in 2..buf.area.height {
        for x in 0..buf.area.width {
            if buf[(x, y)].symbol() == "@" {
                out.push((x, y));
            }
        }
    }
    out
}

/// Every tick label sits within one cell of where a point of its value is drawn,
/// on linear and log axes, in x and in y.
#[test]
fn tick_labels_sit_at_their_values() {
    let xs = [-8.0, -6.0, -4.0, -2.0, 0.0, 2.0, 4.0, 6.0, 8.0];
    // x linear over [-8, 8] (the paper's mirrored Γ_C), y log10 over 10^-2.3 .. 10^0.4: a
    // row of points at y = 0.01, and points at x = 4 of y = 0.1 and 1.
    let mut points: Vec<(f64, f64)> = xs.iter().map(|&x| (x, -2.0)).collect();
    points.extend([(4.0, -1.0), (4.0, 0.0)]);
    let buf = plot_buffer(
        PlotAxis {
            title: "x".into(),
            bounds: [-8.0, 8.0],
            scale: Scale::Linear,
        },
        PlotAxis {
            title: "y".into(),
            bounds: [-2.3, 0.4],
            scale: Scale::Log10,
        },
        &points,
    );
    let at = glyphs(&buf);
    let bottom = at.iter().map(|p| p.1).max().unwrap();
    let mut cols: Vec<u16> = at.iter().filter(|p| p.1 == bottom).map(|p| p.0).collect();
    cols.sort();
    assert_eq!(cols.len(), xs.len(), "{}", riplab::tui::buffer_text(&buf));
    // x: the labels on the last row inside the border.
    let labels = numbers_in(&row_text(&buf, buf.area.height - 2));
    assert!(labels.len() >= 5, "{labels:?}");
    for (v, centre) in &labels {
        let i = xs.iter().position(|x| x == v).expect("a tick at a point");
        assert!(
            (f64::from(cols[i]) - centre).abs() <= 1.0,
            "label {v} centred at {centre}, its point at column {}",
            cols[i]
        );
    }
    // y: each label (in the left margin) on the row of a point of its value: 0.01 is the
    // bottom row of points, 1 the topmost point, 0.1 the other one.
    let upper: Vec<u16> = at.iter().filter(|p| p.1 != bottom).map(|p| p.1).collect();
    let row_of = |v: f64| -> u16 {
        match v {
            0.01 => bottom,
            1.0 => *upper.iter().min().unwrap(),
            0.1 => *upper.iter().max().unwrap(),
            _ => panic!("a label without a point: {v}"),
        }
    };
    let mut seen = 0;
    for row in 0..buf.area.height - 3 {
        for (v, _) in numbers_in(&row_text(&buf, row)[..8]) {
            let point_row = row_of(v);
            assert!(
                (i32::from(point_row) - i32::from(row)).abs() <= 1,
                "label {v} on row {row}, its point on row {point_row}"
            );
            seen += 1;
        }
    }
    assert_eq!(
        seen,
        3,
        "labels 0.01, 0.1 and 1:\n{}",
        riplab::tui::buffer_text(&buf)
    );
}

/// Item 1 on the lab's own pressure chart: at 80×24 the x labels are where their values are
/// (the contact edge of the paper's problem at x = ±3 lies between the labels 2 and 4).
#[test]
fn pressure_chart_labels_are_linear_in_their_values() {
    for (w, h) in [(80, 24), (100, 30)] {
        let text = render_to_string(&Scenario::paper(), "explore", w, h, Some(0), None, None, None)
            .unwrap()
            .text;
        let lines: Vec<Vec<String>> = text
            .lines()
            .map(|l| l.chars().map(String::from).collect())
            .collect();
        // The axis line of the pressure chart: "└┬───┬…"; its labels are the next row.
        let axis = lines
            .iter()
            .position(|l| l.iter().any(|c| c == "└") && l.iter().any(|c| c == "┬"))
            .unwrap();
        let ticks: Vec<usize> = (0..lines[axis].len())
            .filter(|&i| lines[axis][i] == "┬")
            .collect();
        let start = lines[axis].iter().position(|c| c == "└").unwrap() + 1;
        let end = lines[axis].iter().rposition(|c| c == "─" || c == "┬").unwrap();
        let labels = numbers_in(&lines[axis + 1]);
        assert!(labels.iter().any(|(v, _)| *v == 4.0), "{w}x{h}: {labels:?}");
        for (v, centre) in labels {
            let expected = start as f64 + (v + 8.0) / 16.0 * (end - start) as f64;
            assert!(
                (centre - expected).abs() <= 1.0,
                "{w}x{h}: label {v} at {centre}, value at {expected}"
            );
            assert!(
                ticks.iter().any(|&t| (t as f64 - centre).abs() <= 1.0),
                "{w}x{h}: a tick under label {v}"
            );
        }
    }
}

/// The test terminal's buffer of `app` drawn with `look` at `w`×`h`.
pub(super) fn buffer(app: &App, look: &Look, w: u16, h: u16) -> Buffer {
    let mut terminal = ratatui::Terminal::new(TestBackend::new(w, h)).unwrap();
    terminal.draw(|f| riplab::tui::view::view(app, f, look)).unwrap();
    terminal.backend().buffer().clone()
}

pub(super) const MONO: Look = Look {
    theme: Theme { color: false },
    marker: Marker::Braille,
};

/// Without colour every chart's series differ in their symbols, and the legend shows
/// each symbol.
#[test]
fn monochrome_series_have_distinct_symbols_in_the_legend() {
    let mut app = settled(1, Scene::Explore);
    app.guides = riplab::tui::app::Guides::ALL;
    let text = render_app(&app, &MONO, 100, 30);
    // (At 100×30 the gap has no room: the legend names it with its symbol all the same.)
    for entry in ["⠒⠒⠒ p̄ smoothed", "⠒ ⠒ p gauss1", "+ Hertz", "· gap"] {
        assert!(text.contains(entry), "legend entry `{entry}` in\n{text}");
    }
    let text = render_app(&infsup_app(), &MONO, 80, 24);
    for entry in ["⠒1⠒ M1", "⠒2⠒ M2", "⠒3⠒ M3", "⠒4⠒ M4", "⠒*⠒ M1 p̄"] {
        assert!(text.contains(entry), "legend entry `{entry}` in\n{text}");
    }
    // The glyphs are on the curves too: each scheme's digit appears in the graph.
    // (The legend shares the chart's title row: the graph starts on the row under it.)
    let graph: String = text.lines().skip(3).take(9).collect();
    // (M3's β_h equals M1's β̄_h, so `*` covers `3`; M2's β_h is 0, off a log axis.)
    assert!(text.contains("M2 β=0, kernel"), "{text}");
    for digit in ['1', '4', '*'] {
        assert!(graph.contains(digit), "{digit} on a curve:\n{text}");
    }
    let text = render_app(&convergence_app(), &MONO, 80, 24);
    for entry in ["⠒ r ⠒ M1 p (raw)", "⠒1⠒ M1 p̄", "⠒4⠒ M4 p̄"] {
        assert!(text.contains(entry), "legend entry `{entry}` in\n{text}");
    }
}

/// No tour caption relies on a colour's name.
#[test]
fn tour_captions_do_not_name_colours() {
    let tour = riplab::tui::tour::Tour::paper();
    for step in &tour.steps {
        let caption = step.caption.to_lowercase();
        for colour in ["yellow", "cyan", "magenta", "red", "green", "blue"] {
            assert!(
                !caption.split(|c: char| !c.is_alphabetic()).any(|w| w == colour),
                "step `{}` names {colour}",
                step.title
            );
        }
    }
}

/// One size rule for the lab and render, checked before anything is allocated.
#[test]
fn sizes_outside_the_rule_are_refused() {
    use riplab::tui::parse_size;
    assert_eq!(parse_size("80x24"), Ok((80, 24)));
    assert_eq!(parse_size("80×24"), Ok((80, 24)));
    assert_eq!(parse_size("120X40"), Ok((120, 40)));
    for bad in [
        "1x1",
        "5x5",
        "79x24",
        "80x23",
        "10000x10000",
        "1001x40",
        "70000x30",
    ] {
        let e = parse_size(bad).unwrap_err().to_string();
        assert!(e.contains("allowed: 80x24 to 1000x500"), "{bad}: {e}");
    }
    assert!(
        parse_size("eighty")
            .unwrap_err()
            .to_string()
            .contains("not a size")
    );
    assert!(render_to_string(&Scenario::paper(), "mesh", 5, 5, Some(0), None, None, None).is_err());
}

/// At 80 columns the status line keeps its message whole (unit included);
/// the key hints keep their place and a message too long wraps to further rows, not cut.
#[test]
fn status_message_wins_over_the_key_hints() {
    let mut app = settled(1, Scene::Explore);
    app.show_timing = true;
    let mut solved = (**app.solved.as_ref().unwrap()).clone();
    solved.total_ms = 3048.0;
    app.solved = Some(Arc::new(solved));
    let text = frame(&app, 80, 24);
    let status = status_of(&text);
    assert!(
        status.contains("· 3050 ms") || status.contains("· 3048 ms"),
        "{status}"
    );
    assert!(status.contains("load P=646.13 (full 1292.3)"), "{status}");
    let wide = frame(&app, 120, 40);
    assert!(wide.lines().last().unwrap().ends_with("? help  q quit"), "{wide}");
    let long = "a long notice with many words that cannot fit in eighty columns of a terminal window at all, none of them";
    app.notice = Some(riplab::tui::app::Notice::info(long));
    let text = frame(&app, 80, 24);
    assert_eq!(status_of(&text), long, "whole:\n{text}");
    let rows: Vec<&str> = text.lines().collect();
    assert!(
        rows[rows.len() - 1].ends_with("? help  q quit"),
        "the key bar in place:\n{text}"
    );
}

/// A failed export shows in the status line with the absolute path; files are named
/// with ε and depth.
#[test]
fn export_failures_show_and_names_carry_epsilon_and_depth() {
    let mut app = settled(1, Scene::Explore);
    let solved = app.current().unwrap().clone();
    assert_eq!(
        riplab::tui::export::stem(&app.scenario, &solved),
        "hertz-paper-q1-gauss1-L1-eps1e-6-d0.8"
    );
    // A file where the directory should be: nothing can be written under it.
    let file = std::env::temp_dir().join(format!("riplab-not-a-dir-{}", std::process::id()));
    std::fs::write(&file, "x").unwrap();
    let err = riplab::tui::export::export_csv(&app.scenario, &solved, &file).unwrap_err();
    assert!(
        matches!(&err, riplab::tui::export::ExportError::Write { .. }),
        "{err:?}"
    );
    assert!(err.to_string().contains(&file.display().to_string()), "{err}");
    app.update(Msg::Exported(Err(err.into())));
    let text = frame(&app, 120, 40);
    let status = status_of(&text);
    // The absolute directory, then why.
    assert!(
        status.contains(&format!("✗ export failed: {}: Not a directory", file.display())),
        "{status}"
    );
    std::fs::remove_file(&file).unwrap();
}

/// A made-up estimate (the table's layout, not its numbers, is under test).
fn estimate(level: u32) -> riplab::tui::beta::InfSup {
    let h = 1.0 / f64::from(1 << level);
    riplab::tui::beta::InfSup {
        h,
        beta: 0.1 * h,
        beta_over_sqrt_h: 0.1 * h.sqrt(),
        beta_bar: 0.9 * h.sqrt(),
        beta_bar_over_sqrt_h: 0.9,
        kernel: None,
    }
}

/// The current level's row is always shown and marked, whatever the height.
#[test]
fn infsup_table_shows_the_current_level() {
    let mut app = settled(0, Scene::Explore);
    let key = app.infsup_key();
    for level in 0..=MAX_APP_LEVEL {
        app.infsup
            .insert(riplab::tui::app::InfSupKey { level, ..key }, Ok(estimate(level)));
    }
    for current in [0, 2, MAX_APP_LEVEL] {
        app.settings.level = current;
        let text = frame(&app, 80, 24);
        let marked: Vec<&str> = text
            .lines()
            .filter(|l| l.contains(&format!("│▸ {current} ")))
            .collect();
        assert_eq!(marked.len(), 1, "level {current} marked:\n{text}");
        // Whole on its line (h at level 7, 0.00781, is a digit longer than the others).
        assert!(marked[0].contains(" 0.9│"), "level {current}:\n{text}");
        let of = format!(" of {}", MAX_APP_LEVEL + 1);
        assert!(text.contains(&of), "the title says rows are hidden:\n{text}");
    }
}

/// Stepping levels quickly loses no row: an estimate the worker drops as stale is
/// asked for again.
#[test]
fn stepping_levels_fast_loses_no_row() {
    let mut app = App::new(Scenario::paper());
    app.settings.level = 1;
    let mut queue: Vec<Command> = app.update(Msg::Resize).commands;
    queue.extend(app.update(key(KeyCode::Right)).commands);
    queue.extend(app.update(key(KeyCode::Right)).commands);
    assert_eq!(app.settings.level, 3);
    // The worker: solves fail fast, the stale estimate (level 2) is dropped unstarted, the
    // others are made up; replies may ask for more.
    let latest = app.generation;
    let mut rounds = 0;
    while let Some(command) = queue.pop() {
        rounds += 1;
        assert!(rounds < 100);
        let reply = match command {
            Command::Solve(r) => Response::Solved {
                generation: r.generation,
                result: Err(SolveError::Cancelled.into()),
            },
            Command::InfSup(r) => Response::InfSup {
                key: r.key,
                result: (r.generation >= latest).then(|| Ok(estimate(r.key.level))),
            },
            _ => continue,
        };
        queue.extend(app.update(Msg::Worker(reply)).commands);
    }
    let text = frame(&app, 100, 40);
    for level in 1..=3 {
        assert!(
            text.lines()
                .any(|l| l.contains(&format!("│  {level} ")) || l.contains(&format!("│▸ {level} "))),
            "row {level}:\n{text}"
        );
    }
}

/// The legend has a row of its own above the graph, at 80×24 too.
#[test]
fn legends_are_present_and_never_over_data() {
    let mut app = settled(1, Scene::Explore);
    app.guides.hertz = true;
    for (text, name) in [
        // Hertz's entry (with its readout) may wrap to a row of its own: p̄'s shares one.
        (frame(&app, 80, 24), "p̄ smoothed"),
        (frame(&infsup_app(), 80, 24), "M4"),
        (frame(&convergence_app(), 80, 24), "M4 p̄"),
    ] {
        let row = text
            .lines()
            .find(|l| l.contains(&format!(" {name} ")) && l.contains("⠒"))
            .unwrap_or_else(|| panic!("legend with {name}:\n{text}"));
        let braille = row
            .chars()
            .filter(|c| ('\u{2801}'..='\u{28ff}').contains(c))
            .count();
        // The legend's own samples are the only braille on its row.
        let samples = row.matches('⠒').count();
        assert_eq!(braille, samples, "no data on the legend's row: {row}");
    }
}

/// `z` zooms the pressure chart and the contact zone to where p̄ > 0, and back.
#[test]
fn zoom_narrows_to_the_contact_zone() {
    let scenario = Scenario::load(std::path::Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/scenarios/hertz-block.toml"
    )))
    .unwrap();
    let mut app = App::new(scenario.clone());
    app.show_timing = false;
    // It opens zoomed in on its narrow contact: start from the whole Γ_C.
    app.zoom = false;
    settle(&mut app, &mut Engine::new(scenario));
    let x_labels = |text: &str| -> Vec<f64> {
        let lines: Vec<Vec<String>> = text
            .lines()
            .map(|l| l.chars().map(String::from).collect())
            .collect();
        let axis = lines.iter().position(|l| l.iter().any(|c| c == "┬")).unwrap();
        numbers_in(&lines[axis + 1]).into_iter().map(|(v, _)| v).collect()
    };
    let before = x_labels(&frame(&app, 100, 30));
    app.update(ch('z'));
    assert!(app.zoom);
    let text = frame(&app, 100, 30);
    assert!(text.contains("zoom"), "{text}");
    let after = x_labels(&text);
    let span = |v: &[f64]| {
        v.iter().cloned().fold(f64::NEG_INFINITY, f64::max) - v.iter().cloned().fold(f64::INFINITY, f64::min)
    };
    let solved = app.current().unwrap();
    let xs = &solved.solution.points.vertex_x;
    let reach = xs
        .iter()
        .zip(&solved.solution.pbar)
        .filter(|(_, p)| **p > 0.0)
        .map(|(x, _)| x.abs())
        .fold(0.0, f64::max);
    // The zone is under a tenth of the block: the zoomed axis spans the zone and its margin.
    assert!(reach < span(&before) / 20.0, "reach {reach}");
    assert!(
        span(&after) <= 2.0 * (2.0 * reach),
        "the zone and its margin: {after:?}, reach {reach}"
    );
    assert!(
        span(&after) >= 2.0 * reach * 0.9,
        "the whole zone: {after:?}, reach {reach}"
    );
    app.update(ch('z'));
    assert_eq!(x_labels(&frame(&app, 100, 30)), before);
    // The mesh scene says when it thins its lines.
    let text = render_to_string(&Scenario::paper(), "mesh", 80, 24, Some(4), None, None, None)
        .unwrap()
        .text;
    assert!(text.contains(" grid lines"), "{text}");
}

/// The key that closes the help does nothing else; a key that does nothing says
/// why; ranges read "a to b"; Ctrl-Z suspends; `0` resets.
#[test]
fn keys_say_why_and_close_help_only() {
    let mut app = App::new(Scenario::paper());
    app.update(ch('?'));
    app.update(ch(']'));
    assert!(!app.show_help);
    assert_eq!(
        app.settings.level,
        Scenario::paper().level,
        "] only closed the help"
    );
    app.settings.level = MAX_APP_LEVEL;
    app.update(ch(']'));
    let notice = app.notice.clone().expect("says why").text;
    assert!(
        notice.contains("level 7") && notice.contains("level 8"),
        "{notice}"
    );
    // Whole on an 80-column status line.
    assert!(notice.chars().count() < 80, "{notice}");
    app.settings.level = 0;
    app.update(key(KeyCode::Left));
    assert!(app.notice.is_some());
    for _ in 0..20 {
        app.update(ch('-'));
    }
    let notice = app.notice.clone().unwrap().text;
    assert!(
        notice.contains("1e-14 to 1e2") && !notice.contains("..="),
        "{notice}"
    );
    let effect = app.update(Msg::Key(KeyEvent::new(KeyCode::Char('z'), KeyModifiers::CONTROL)));
    assert_eq!(effect.commands, [Command::Suspend]);
    app.update(ch('D'));
    app.update(ch('2'));
    app.update(ch('g'));
    app.update(ch('0'));
    assert_eq!(app.settings, App::new(Scenario::paper()).settings);
    assert!(!app.guides.gap);
    // No Hertz solution for a punch.
    let punch = Scenario::load(std::path::Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/scenarios/flat-punch.toml"
    )))
    .unwrap();
    let mut app = App::new(punch);
    app.update(ch('h'));
    assert!(!app.guides.hertz);
    assert!(app.notice.unwrap().text.contains("no Hertz"));
}
