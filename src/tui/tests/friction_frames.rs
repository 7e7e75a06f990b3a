//! The lab's drawing of friction: every friction series visible near each of its
//! values at every size a class meets (80×24 to 200×60, monochrome), the stick zone marked on
//! the x axis between its ends and nowhere else, the status area with P, Q, Q/(μP), the
//! stick half-width, Mindlin's c and t̄'s distance from q whole (wrapped, never cut), the
//! cursor reading t and t̄, and snapshots of the frames.

use riplab::tui::render_app;
use riplab::tui::view::plot::cell_of;

use super::friction::{LOOK, cattaneo, lab, press};

/// The sizes a class meets: the smallest, a laptop's, a projector's, a big screen's.
const SIZES: [(u16, u16); 4] = [(80, 24), (100, 30), (120, 40), (200, 60)];

/// The graph rows of the chart titled `title` (right of the y axis, inside the border) and
/// its x axis row, as characters.
fn graph(frame: &str, title: &str) -> (Vec<Vec<char>>, Vec<char>) {
    let lines: Vec<&str> = frame.lines().collect();
    let top = lines
        .iter()
        .position(|l| l.starts_with(&format!("┌ {title}")))
        .unwrap_or_else(|| panic!("no chart `{title}` in\n{frame}"));
    let mut rows = Vec::new();
    for line in &lines[top + 1..] {
        let chars: Vec<char> = line.chars().collect();
        let Some(axis) = chars[1..].iter().position(|&c| matches!(c, '┤' | '│' | '└')) else {
            continue;
        };
        // The y axis sits right of the ticks' labels (a legend row's first is the border).
        let axis = axis + 1;
        if axis + 2 >= chars.len() {
            continue;
        }
        let body: Vec<char> = chars[axis + 1..chars.len() - 1].to_vec();
        if chars[axis] == '└' {
            return (rows, body);
        }
        rows.push(body);
    }
    panic!("no x axis in\n{frame}");
}

/// On cattaneo-mindlin with M1 (t zigzags) zoomed, with Mindlin (`M`): t (`×`), t̄ (`~`)
/// and q (`*`) each have a mark within three columns of each of their points' x (a glyph that
/// lands on another series' moves up to three cells), on at least two rows (t/μ and q/μ span
/// the chart), the stick zone's `═` covers exactly the axis columns of its ends, the legend
/// names every series, and the status area holds the numbers whole.
#[test]
fn every_friction_series_is_visible_at_every_size() {
    let (mut app, mut engine) = lab(&cattaneo(), 2);
    press(&mut app, &mut engine, "1M");
    // The status line's state, not the `M` key's notice.
    app.notice = None;
    let solved = app.current().unwrap().clone();
    let shown = solved.shown.friction.as_ref().unwrap();
    let zone = solved.shown.zone.unwrap();
    assert!(app.zoom, "cattaneo-mindlin opens zoomed in");
    let mu = shown.law.mu().unwrap();
    let m = shown.mindlin.unwrap();
    for (w, h) in SIZES {
        let frame = render_app(&app, &LOOK, w, h);
        let (rows, axis) = graph(&frame, "p and t on Γ_C");
        let rows = &rows;
        let width = rows[0].len() as u16;
        let col = |x: f64| cell_of(x, zone, width, 2);
        // `under`: an overlay (q), drawn under t̄, t and p̄, has a mark at half its points at
        // least (at_value.rs checks that each of the others lies under them).
        let marks = |glyph: char, xs: &mut dyn Iterator<Item = f64>, under: bool| {
            let mut seen_rows = std::collections::BTreeSet::new();
            let (mut points, mut missed) = (0, Vec::new());
            for x in xs {
                let Some(c) = col(x) else { continue };
                let near = (c.saturating_sub(3)..=(c + 3).min(width - 1))
                    .flat_map(|c| (0..rows.len()).filter(move |&r| rows[r][usize::from(c)] == glyph))
                    .collect::<Vec<_>>();
                points += 1;
                if near.is_empty() {
                    missed.push(x);
                }
                seen_rows.extend(near);
            }
            let allowed = if under { points / 2 } else { 0 };
            assert!(
                missed.len() <= allowed,
                "{glyph} at x = {missed:?} ({w}×{h})\n{frame}"
            );
            assert!(
                seen_rows.len() >= 2,
                "{glyph} on {seen_rows:?} ({w}×{h})\n{frame}"
            );
        };
        marks(
            '×',
            &mut shown.t.iter().filter(|p| p.1 != 0.0).map(|p| p.0),
            false,
        );
        marks(
            '~',
            &mut shown.tbar.iter().filter(|p| p.1 != 0.0).map(|p| p.0),
            false,
        );
        let a = m.hertz.a;
        marks(
            '*',
            &mut (0..41)
                .map(|i| zone[0] + (zone[1] - zone[0]) * f64::from(i) / 40.0)
                .filter(|x| x.abs() < a),
            true,
        );
        // The stick zone: exactly the columns of its ends and those between.
        let (left, right, runs) = shown.stick.unwrap();
        assert_eq!(runs, 1);
        let (cl, cr) = (col(left).unwrap(), col(right).unwrap());
        for (c, &ch) in axis.iter().enumerate() {
            let inside = (usize::from(cl)..=usize::from(cr)).contains(&c);
            assert_eq!(
                matches!(ch, '═' | '╤'),
                inside,
                "axis column {c} ({w}×{h})\n{frame}"
            );
        }
        for name in [
            "⠒⠒⠒ p̄",
            "⠒ ⠒ p",
            "⠒~⠒ t̄/μ",
            "× t/μ",
            "═ stick",
            "* q/μ Mindlin",
            "p, t/μ (units of E)",
        ] {
            assert!(frame.contains(name), "legend `{name}` ({w}×{h})\n{frame}");
        }
        // The status area: every number whole, nothing cut.
        let status = super::scenes::status_of(&frame);
        for part in [
            format!("load P={}", riplab::tui::view::fmt::sig(solved.solution.load, 5)),
            format!("Q={}", riplab::tui::view::fmt::sig(shown.tangential_load, 5)),
            format!(
                "Q/(μP)={}",
                riplab::tui::view::fmt::sig(shown.load_ratio.unwrap(), 4)
            ),
            format!(
                "stick half-width {}",
                riplab::tui::view::fmt::sig(shown.stick_half_width.unwrap(), 4)
            ),
            format!("Mindlin c={}", riplab::tui::view::fmt::sig(m.c, 4)),
            format!(
                "t̄ off q {}%",
                riplab::tui::view::fmt::sig(100.0 * shown.mindlin_error.unwrap(), 2)
            ),
            format!("coulomb μ = {mu}, shift ξ = 0.0815"),
        ] {
            assert!(
                status.contains(&part),
                "`{part}` in the status ({w}×{h}): {status}\n{frame}"
            );
        }
        assert!(!status.contains('…'), "{status}");
    }
}

/// The cursor's readout reads what the chart plots: t/μ (one-sided where M1's raw t steps)
/// and t̄/μ — the solution's own values at the cursor's vertex divided by cattaneo-mindlin's
/// μ = 0.3 — and then t itself (it read `t 8.28` where the chart plotted t/μ ≈ 27.6).
#[test]
fn the_cursor_reads_t_over_mu_and_t() {
    let (mut app, mut engine) = lab(&cattaneo(), 2);
    press(&mut app, &mut engine, "1x..");
    let solved = app.current().unwrap().clone();
    let f = solved.solution.friction.as_ref().unwrap();
    let mu = 0.3;
    let (x, _) = app.cursor_point().unwrap();
    let i = solved
        .solution
        .points
        .vertex_x
        .iter()
        .position(|&v| v == x)
        .unwrap();
    let frame = render_app(&app, &LOOK, 120, 40);
    let sig = |v: f64| riplab::tui::view::fmt::sig(v, 4);
    // M1: the vertex lies between two points; t steps there, read from each side.
    let q = solved
        .solution
        .points
        .points
        .iter()
        .position(|p| p.x > x)
        .unwrap();
    let (tl, tr) = (f.t[q - 1], f.t[q]);
    let readout = format!(
        " · t/μ {} | {} · t̄/μ {} (t {} | {})",
        sig(tl / mu),
        sig(tr / mu),
        sig(f.tbar[i] / mu),
        sig(tl),
        sig(tr)
    );
    assert!(frame.contains(&readout), "{readout}\n{frame}");
}

/// Item 3's claim as snapshots: M3 (the scenario's) at level 2 with Hertz, the circle and
/// Mindlin on (`h`, `o`, `M`), 80×24 and 120×40, monochrome (at 80×24 the legend says the
/// circle has no room); and M1 at 120×40 (t zigzags, t̄ does not).
#[test]
fn friction_frames() {
    let (mut app, mut engine) = lab(&cattaneo(), 2);
    press(&mut app, &mut engine, "hoM");
    // The status line's readout, not the `h` key's notice.
    app.notice = None;
    snap!("tui__friction_m3_80x24", render_app(&app, &LOOK, 80, 24));
    snap!("tui__friction_m3_120x40", render_app(&app, &LOOK, 120, 40));
    press(&mut app, &mut engine, "1");
    app.notice = None;
    snap!("tui__friction_m1_120x40", render_app(&app, &LOOK, 120, 40));
}
