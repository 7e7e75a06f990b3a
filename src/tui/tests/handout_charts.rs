//! A handout's SVG is the chart its step shows: the inf-sup chart on an inf-sup step, the
//! work–precision chart on a convergence step, the pressure chart otherwise (the paper's
//! tour wrote the same pressure chart for its inf-sup step 5 and step 7).

use riplab::tui::tour::Tour;
use riplab::tui::tour::handout::write_handout;

/// Explore, inf-sup and convergence at the same settings.
const THREE: &str = "title = \"Three scenes\"

[[step]]
title = \"Explore\"
caption = \"p and p̄.\"
scheme = \"M1\"
level = 1

[[step]]
title = \"Inf-sup\"
caption = \"β_h/√h.\"
scene = \"infsup\"
scheme = \"M1\"
level = 1

[[step]]
title = \"Convergence\"
caption = \"Errors.\"
scene = \"convergence\"
scheme = \"M1\"
level = 1
";

#[test]
fn each_steps_svg_is_the_chart_of_its_scene() {
    let dir = std::env::temp_dir().join(format!("riplab-handout-charts-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let tour = Tour::parse(THREE, "three.toml", None).unwrap();
    write_handout(&tour, &dir, 100, 30, |_, _| {}).unwrap();
    let svg = |n: u32| std::fs::read_to_string(dir.join(format!("step-{n:02}.svg"))).unwrap();
    let (explore, infsup, convergence) = (svg(1), svg(2), svg(3));
    assert!(explore.contains("smoothed p̄"), "{explore}");
    assert!(
        infsup.contains("β_h/√h against h") && !infsup.contains("smoothed p̄"),
        "{infsup}"
    );
    // Each curve's name in the legend (a text element of its own line).
    let texts: Vec<&str> = infsup.lines().map(str::trim).collect();
    for scheme in ["M1", "M2: β = 0, kernel", "M3", "M4", "M1 p̄"] {
        assert!(texts.contains(&scheme), "{scheme}: {infsup}");
    }
    assert!(
        convergence.contains("work–precision") && convergence.contains("relative error of p̄"),
        "{convergence}"
    );
    assert!(
        ["M1 p̄", "M3 p̄", "M4 p̄", "M1 p (raw)"]
            .iter()
            .all(|name| convergence.lines().any(|l| l.trim() == *name)),
        "{convergence}"
    );
    assert!(!convergence.contains("smoothed p̄"), "{convergence}");
    std::fs::remove_dir_all(&dir).unwrap();
}
