//! The SVG pressure chart of `riplab::plot`: written atomically, with its title, both series,
//! axis labels and legend, never overwriting a file unless asked.

use std::path::PathBuf;

use riplab::contact::solution::Solution;
use riplab::mesh::Element;
use riplab::plot::{chart_title, pressure_svg, pressure_svg_string, write_file};
use riplab::scenario::Scenario;
use riplab::scheme::Scheme;
use riplab::solve::solve_scenario;

/// The paper's problem solved with the preset `scheme` at `level`.
fn solve(scheme: &str, level: u32) -> (Scenario, Element, Solution) {
    let mut s = Scenario::paper();
    let Scheme { element, rule } = Scheme::parse(scheme).unwrap();
    (s.element, s.rule, s.level) = (element, rule, level);
    let (_, sol) = solve_scenario(&s).unwrap();
    (s, element, sol)
}

/// A fresh empty directory for one test.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("riplab-plot-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn title_names_the_scheme_level_and_epsilon() {
    let (s, element, sol) = solve("M1", 1);
    assert_eq!(
        chart_title(&s.name, element, 1, &sol),
        "hertz-paper: M1 (q1 + gauss1), level 1, ε = 1e-6"
    );
    let mut s = Scenario::paper();
    s.epsilon = 0.0;
    let (_, sol) = solve_scenario(&s).unwrap();
    assert!(chart_title(&s.name, s.element, 0, &sol).ends_with("ε = 0 (exact constraint)"));
}

#[test]
fn svg_is_written_with_title_series_and_axes() {
    let dir = scratch("write");
    for scheme in ["M1", "M2", "M3", "M4"] {
        let (s, element, sol) = solve(scheme, 1);
        let title = chart_title(&s.name, element, 1, &sol);
        let path = dir.join(format!("{scheme}.svg"));
        pressure_svg(&path, &title, &sol, s.half_model, false).unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        assert!(
            text.starts_with("<svg") && text.trim_end().ends_with("</svg>"),
            "{text}"
        );
        assert_eq!(text.matches("<svg").count(), 1);
        assert!(text.contains(&title), "title {title}");
        assert!(
            text.contains(&format!("raw p ({}", sol.params.rule.name())),
            "raw series"
        );
        assert!(text.contains("smoothed p̄"), "smoothed series");
        assert!(text.contains("x along Γ_C"), "x label");
        assert!(text.contains("pressure ("), "y label");
        // Two series drawn: polylines in both colours.
        assert!(text.contains("<polyline"), "lines");
        assert!(
            text.contains("#D66E00") && text.contains("#006EBE"),
            "both colours"
        );
    }
    let left: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(left.len(), 4, "no temporary file left behind: {left:?}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn half_model_is_mirrored() {
    let (s, _, sol) = solve("M1", 0);
    let half = pressure_svg_string("t", &sol, true).unwrap();
    let full = pressure_svg_string("t", &sol, false).unwrap();
    assert!(s.half_model);
    // The mirrored chart's x axis runs from −8 to 8; the unmirrored one from 0.
    let ticks = |svg: &str| -> Vec<String> { svg.lines().map(|l| l.trim().to_string()).collect() };
    assert!(ticks(&half).contains(&"-8".to_string()), "{half}");
    assert!(!ticks(&full).iter().any(|t| t.starts_with('-')));
    assert!(half.contains("half model mirrored") && !full.contains("mirrored"));
}

#[test]
fn an_existing_file_is_not_overwritten_unless_asked() {
    let dir = scratch("keep");
    let path = dir.join("chart.svg");
    std::fs::write(&path, "mine").unwrap();
    let (s, element, sol) = solve("M3", 0);
    let title = chart_title(&s.name, element, 0, &sol);
    let err = pressure_svg(&path, &title, &sol, true, false).unwrap_err();
    assert!(matches!(err, riplab::plot::PlotError::Exists { .. }), "{err}");
    assert!(err.to_string().contains("exists"), "{err}");
    assert_eq!(std::fs::read_to_string(&path).unwrap(), "mine");
    pressure_svg(&path, &title, &sol, true, true).unwrap();
    assert!(std::fs::read_to_string(&path).unwrap().starts_with("<svg"));
    let left: Vec<_> = std::fs::read_dir(&dir).unwrap().collect();
    assert_eq!(left.len(), 1, "no temporary file left behind");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn write_file_reports_a_missing_directory_and_a_bad_name() {
    let dir = scratch("bad");
    let err = write_file(&dir.join("no/such/dir/x.svg"), b"x", false).unwrap_err();
    assert_eq!(err.kind(), std::io::ErrorKind::NotFound);
    assert!(write_file(std::path::Path::new("/"), b"x", true).is_err());
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Links planted at the temporary names a writer could predict (`.a.svg.<pid>-<n>.tmp`, the
/// names it used) are neither blamed on the target (it said "a.svg: exists"), followed nor
/// removed (it deleted the link it had not made): the temporary is a fresh random name, and
/// only riplab's own file is ever removed. With `overwrite` likewise.
#[test]
fn planted_temporaries_are_never_followed_or_removed() {
    let dir = scratch("planted");
    let victim = dir.join("victim.txt");
    std::fs::write(&victim, "keep").unwrap();
    let pid = std::process::id();
    let planted: Vec<PathBuf> = (0..256)
        .map(|n| dir.join(format!(".a.svg.{pid}-{n}.tmp")))
        .collect();
    for link in &planted {
        std::os::unix::fs::symlink(&victim, link).unwrap();
    }
    let target = dir.join("a.svg");
    write_file(&target, b"<svg/>", false).unwrap_or_else(|e| panic!("{e}"));
    write_file(&target, b"<svg>2</svg>", true).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(std::fs::read_to_string(&target).unwrap(), "<svg>2</svg>");
    assert_eq!(std::fs::read_to_string(&victim).unwrap(), "keep");
    for link in &planted {
        let kind = std::fs::symlink_metadata(link).unwrap().file_type();
        assert!(kind.is_symlink(), "{}", link.display());
    }
    // Nothing else is left: the planted links, the victim and the chart.
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), planted.len() + 2);
    std::fs::remove_dir_all(&dir).unwrap();
}
