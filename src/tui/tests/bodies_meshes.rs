//! The two-body scene's meshes panel (docs/lab.md, "Two bodies"): both meshes near the
//! interface, each body's own elements, deformed by each body's whole displacement.

use std::path::Path;

use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
use ratatui::symbols::Marker;
use riplab::contact::interface::InterfaceMethod;
use riplab::material::{Material, Plane};
use riplab::scenario::Scenario;
use riplab::tui::bodies::{BodiesApp, settle_bodies, view};
use riplab::tui::theme::Theme;
use riplab::tui::view::Look;

const PATCH: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/scenarios/patch-two-blocks.toml");

const LOOK: Look = Look {
    theme: Theme { color: false },
    marker: Marker::Braille,
};

/// The patch scenario's scene with mortar, settled after `keys` (characters).
fn patch(keys: &str) -> BodiesApp {
    let scenario = Scenario::load(Path::new(PATCH)).unwrap();
    let mut app = BodiesApp::new(scenario, InterfaceMethod::Mortar).expect("two bodies");
    let keys: Vec<KeyEvent> = keys
        .chars()
        .map(|c| KeyEvent::new(KeyCode::Char(c), KeyModifiers::NONE))
        .collect();
    settle_bodies(&mut app, &keys).unwrap();
    app
}

/// The meshes' panel's inner rows in the frame at `width`×`height`, monochrome: the title's
/// line, then each row between the borders.
fn panel(app: &BodiesApp, width: u16, height: u16) -> (String, Vec<String>) {
    let frame = riplab::tui::render_frame(width, height, |f| view::view(app, f, &LOOK));
    let lines: Vec<&str> = frame.lines().collect();
    let top = lines
        .iter()
        .position(|l| l.starts_with("┌ meshes"))
        .unwrap_or_else(|| panic!("no meshes panel:\n{frame}"));
    let rows = lines[top + 1..]
        .iter()
        .take_while(|l| !l.starts_with('└'))
        .map(|l| l.trim_start_matches('│').trim_end_matches('│').to_string())
        .collect();
    (lines[top].to_string(), rows)
}

/// The cells of `row` that are not blank.
fn marks(row: &str) -> usize {
    row.chars().filter(|&c| c != ' ' && c != '\u{2800}').count()
}

/// On the patch scenario (the interface 1.5 long, 12 lower elements across at level 1) the
/// panel shows the whole interface: above the interface's line, the upper body's vertical
/// lines (9 at 2:3, its 8 elements; 13 at 1:1), below it the lower body's 13 — the two element
/// sizes side by side, at 80×24 and at 120×40.
#[test]
fn the_meshes_panel_shows_each_bodys_elements() {
    for (keys, upper_lines) in [("", 9), ("k", 13)] {
        let app = patch(keys);
        for (w, h) in [(80, 24), (120, 40)] {
            let (title, rows) = panel(&app, w, h);
            let what = format!("keys {keys:?} at {w}×{h}:\n{title}\n{}", rows.join("\n"));
            assert!(
                title.contains("meshes, x 0 to 1.5: upper above, lower below"),
                "{what}"
            );
            // The rows not drawn across (those of the bodies' horizontal lines, the
            // interface's among them) cross the vertical lines: the upper body's first, then
            // the lower body's.
            let full = usize::from(w) - 4;
            let crossed: Vec<usize> = rows.iter().map(|r| marks(r)).filter(|&m| m < full).collect();
            let upper_rows = crossed.iter().take_while(|&&m| m == upper_lines).count();
            assert!(upper_rows > 0, "no row of the upper body: {what}");
            if upper_lines == 13 {
                // Matching meshes: as many lines above as below, and rows of both bodies.
                assert!(upper_rows == crossed.len() && upper_rows >= 2, "{what}");
            } else {
                let lower = &crossed[upper_rows..];
                assert!(
                    !lower.is_empty() && lower.iter().all(|&m| m == 13),
                    "the lower body's rows: {lower:?} against 13 each: {what}"
                );
            }
        }
    }
}

/// The meshes are drawn from each body's whole displacement, the upper body's mirrored back
/// and translated by its top's descent: on the contact patch test (mortar, exact multipliers)
/// both bodies are compressed uniformly by the applied pressure q, so the lower body's top
/// sinks q·H_l/E'_l, the upper body's bottom as much (they touch, g₀ = 0), and its top by the
/// prescribed 0.01 (E' = E/(1 − ν²), plane strain: docs/design.md §12).
#[test]
fn the_meshes_move_as_the_uniform_compression_does() {
    let app = patch("");
    let solved = app.solved.as_ref().expect("solved");
    let (q, error) = solved.patch.expect("the patch test");
    assert!(error <= 1e-10, "{error}");
    let scenario = &app.scenario;
    let upper = scenario.upper.as_ref().unwrap();
    // Plane strain: σ_yy = −q, σ_xx = 0 and ε_zz = 0 give ε_yy = −q/E'.
    let plane = |m: &Material| {
        assert_eq!(m.plane, Plane::Strain);
        m.young / (1.0 - m.poisson * m.poisson)
    };
    let sink = q * scenario.height / plane(&scenario.material);
    let [lower_strip, upper_strip] = &solved.strips;
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * b.abs().max(1e-3);
    for n in &lower_strip.rows[0] {
        assert!(close(n.y, scenario.height) && n.lift == 0.0, "{n:?}");
        assert!(close(n.uy, -sink), "the lower top: {} against {}", n.uy, -sink);
    }
    for n in &upper_strip.rows[0] {
        assert!(close(n.y, scenario.height), "{n:?}");
        assert!(close(n.uy, -sink), "the upper bottom: {} against {}", n.uy, -sink);
    }
    // The upper body (0.5 high) lies whole in its strip: its last row is its top.
    let top = upper_strip.rows.last().unwrap();
    for n in top {
        assert!(close(n.y, scenario.height + upper.height), "{n:?}");
        assert!(close(n.uy, -upper.displacement), "the upper top: {}", n.uy);
    }
    // Between, u_y is linear in y: the upper body's uniform strain q/E'_u.
    let strain = q / plane(&upper.material);
    assert!(close(upper.displacement - sink, strain * upper.height));
    for row in &upper_strip.rows {
        for n in row {
            let want = -sink - strain * (n.y - scenario.height);
            assert!(close(n.uy, want), "{n:?} against {want}");
        }
    }
}

/// Under a pressure q on the upper body's top (docs/design.md §12, "A pressure on the top")
/// the meshes carry the top's own displacement u_q too: both bodies compressed uniformly by q,
/// the lower's top sinking q·H_l/E'_l, the upper's top q·(H_l/E'_l + H_u/E'_u) — the pin's
/// descent — and every node between on the line.
#[test]
fn under_a_pressure_the_meshes_carry_the_tops_displacement() {
    let q = 5.0;
    let text = std::fs::read_to_string(PATCH).unwrap().replace(
        "support = \"roller\"\ndisplacement = 0.01",
        &format!("pressure = {q:?}"),
    );
    let scenario = Scenario::parse(&text, "pressed.toml").unwrap();
    assert_eq!(scenario.upper.as_ref().unwrap().pressure, Some(q));
    let mut app = BodiesApp::new(scenario, InterfaceMethod::Mortar).expect("two bodies");
    settle_bodies(&mut app, &[]).unwrap();
    let solved = app.solved.as_ref().unwrap_or_else(|| panic!("{:?}", app.error));
    let (scenario, upper) = (&app.scenario, app.scenario.upper.as_ref().unwrap());
    let plane = |m: &Material| m.young / (1.0 - m.poisson * m.poisson);
    let (lower_strain, upper_strain) = (q / plane(&scenario.material), q / plane(&upper.material));
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * b.abs().max(1e-3);
    let [lower_strip, upper_strip] = &solved.strips;
    for n in &lower_strip.rows[0] {
        assert!(
            close(n.uy, -lower_strain * scenario.height),
            "the lower top: {n:?}"
        );
    }
    let top = scenario.height + upper.height;
    assert!(close(upper_strip.rows.last().unwrap()[0].y, top));
    for n in upper_strip.rows.iter().flatten() {
        let want = -lower_strain * scenario.height - upper_strain * (n.y - scenario.height);
        assert!(close(n.uy, want), "{n:?} against {want}");
    }
}
