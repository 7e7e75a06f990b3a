//! The lab's commands on the binary: `render`'s keys, marker, ranges and sizes, the README's
//! sample frame, and the lab started without a terminal. (What the lab draws is tested in
//! process, in src/tui/tests.)

/// The largest level the lab and `render` take, as `render --help` states it ("Mesh level 0 to
/// N").
fn lab_max_level() -> u32 {
    let (code, help, err) = crate::common::riplab(&["render", "--help"]);
    assert_eq!(code, 0, "{err}");
    let at = help
        .find("Mesh level 0 to ")
        .expect("render --help states the levels");
    let rest = &help[at + "Mesh level 0 to ".len()..];
    let digits: String = rest.chars().take_while(char::is_ascii_digit).collect();
    digits.parse().expect("a level")
}

/// `render --keys f`, `--keys x`, `--keys l` and `--marker halfblock` show
/// the projector view, the cursor's readout, the message log and no braille.
#[test]
fn render_applies_keys_and_the_marker() {
    let render = |args: &[&str]| {
        let mut all = vec!["render", "--size", "80x24"];
        all.extend(args);
        let (code, out, err) = crate::common::riplab(&all);
        assert_eq!(code, 0, "{args:?}: {err}");
        out
    };
    let projector = render(&["--keys", "f"]);
    assert!(projector.starts_with("┌ pressure on Γ_C"), "{projector}");
    assert!(projector.contains("f back"), "{projector}");
    assert!(render(&["--keys", "x"]).contains("cursor x "));
    let log = render(&["--keys", "xl"]);
    assert!(
        log.contains("┌ messages") && log.contains(", and . move the cursor"),
        "{log}"
    );
    // Before any message the log says so in its title, not "1 lines" over a placeholder.
    let empty = render(&["--keys", "l"]);
    assert!(
        empty.contains("┌ messages: none yet") && !empty.contains("1 lines"),
        "{empty}"
    );
    assert!(log.contains("messages: 1 line (any key closes)"), "{log}");
    let braille = |s: &str| s.chars().any(|c| ('\u{2801}'..='\u{28ff}').contains(&c));
    assert!(braille(&render(&[])));
    let half = render(&["--marker", "halfblock"]);
    assert!(!braille(&half) && half.contains('▀'), "{half}");
    let (code, _, err) = crate::common::riplab(&["render", "--keys", "<ctrl-c>"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("<ctrl-c>") && err.contains("<tab>"), "{err}");
}

/// `render` refuses a level above the lab's range with the range its help states (and says
/// what the first one above would cost), and takes `--epsilon 0` as the exact constraint (as
/// `--method`'s help says).
#[test]
fn render_ranges_and_the_exact_constraint() {
    let max = lab_max_level();
    for level in [max + 1, max + 2, 70] {
        let level = level.to_string();
        let (code, _, err) = crate::common::riplab(&["render", "--level", &level, "--size", "80x24"]);
        assert_eq!(code, 2, "{err}");
        assert!(err.contains(&format!("allowed: 0 to {max}")), "{level}: {err}");
    }
    let above = (max + 1).to_string();
    let (_, _, err) = crate::common::riplab(&["render", "--level", &above, "--size", "80x24"]);
    assert!(err.contains(&format!("level {above} takes")), "{err}");
    let (code, out, err) =
        crate::common::riplab(&["render", "--epsilon", "0", "--size", "80x24", "--level", "0"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("exact"), "{out}");
}

/// One size rule for the lab and render, checked before anything is allocated: a size outside
/// it is refused with the flag and the range (exit 2, nothing drawn).
#[test]
fn render_refuses_sizes_outside_the_rule() {
    for (size, code) in [("10000x10000", 2), ("5x5", 2), ("1x1", 2), ("80×24", 0)] {
        let (got, out, err) = crate::common::riplab(&["render", "--size", size, "--level", "0"]);
        assert_eq!(got, code, "--size {size}: {err}");
        if code == 2 {
            assert!(err.contains("--size") && err.contains("allowed"), "{err}");
            assert!(out.is_empty());
        }
    }
}

/// Started without a terminal, the lab says what to use instead (exit 2).
#[test]
fn the_lab_without_a_terminal_names_render() {
    let (code, _, err) = crate::common::riplab(&[]);
    assert_eq!(code, 2);
    assert!(err.contains("riplab render"), "{err}");
}

/// The README's sample frame is what `riplab render` prints for the command it names.
#[test]
fn readme_frame_is_rendered() {
    let readme = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/README.md")).unwrap();
    let marker = "this is `riplab render ";
    let at = readme.find(marker).expect("the README names its render command");
    let rest = &readme[at + marker.len() - "render ".len()..];
    let command = &rest[..rest.find('`').unwrap()];
    let args: Vec<&str> = command.split_whitespace().collect();
    let fence = rest.find("```\n").unwrap() + 4;
    let frame = &rest[fence..fence + rest[fence..].find("```").unwrap()];
    let (code, out, err) = crate::common::riplab(&args);
    assert_eq!(code, 0, "{err}");
    assert_eq!(frame, out, "the README's frame differs from `riplab {command}`");
}

/// The stress scene's caption reads a peak on the axis of symmetry as x = 0, not as the
/// round-off of the full model's node there (it read "x = -2.56e-14" on hertz-paper-full).
#[test]
fn a_peak_on_the_axis_reads_x_0() {
    let (code, out, err) = crate::common::riplab(&[
        "render",
        "scenarios/hertz-paper-full.toml",
        "--scene",
        "stress",
        "--size",
        "80x24",
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("(x = 0)") && !out.contains("e-1"), "{out}");
}

/// Esc goes back and never quits: `render --keys` of an overlay's key, Esc, Esc draws the
/// scene (the lab still running); a key that quits is refused, naming its place, exit 2.
#[test]
fn esc_closes_overlays_and_render_refuses_a_quitting_key() {
    for keys in ["l<esc>", "l<esc><esc>", "?<esc>", "?<esc><esc>", "f<esc><esc>"] {
        let (code, out, err) = crate::common::riplab(&["render", "--size", "80x24", "--keys", keys]);
        assert_eq!(code, 0, "{keys}: {err}");
        assert!(
            out.contains("pressure on Γ_C") && out.contains("explore") && !out.contains("┌ messages"),
            "{keys}: {out}"
        );
    }
    let (code, out, err) = crate::common::riplab(&["render", "--keys", "]q]"]);
    assert_eq!(code, 2, "{out}");
    assert!(out.is_empty() && err.contains("key 2 quits the lab"), "{err}");
}
