//! `riplab render --refine-edges N` draws the lab on the
//! graded solve (`level 2+2e` in the header, the graded mesh's dofs: those of `riplab solve
//! --refine-edges 2`), the same header as the key `E` pressed twice; a bad count exits 2.

#[test]
fn render_draws_the_graded_solve() {
    let render = |extra: &[&str]| {
        let mut args = vec!["render", "--level", "2", "--size", "80x24"];
        args.extend(extra);
        let (code, out, err) = crate::common::riplab(&args);
        assert_eq!(code, 0, "{extra:?}: {err}");
        out
    };
    let graded = render(&["--refine-edges", "2"]);
    assert!(graded.contains("level 2+2e"), "{graded}");
    let (code, json, err) =
        crate::common::riplab(&["solve", "--level", "2", "--refine-edges", "2", "--format", "json"]);
    assert_eq!(code, 0, "{err}");
    let json: serde_json::Value = serde_json::from_str(&json).unwrap();
    let dofs = json["n_dofs"].as_u64().expect("n_dofs in the JSON");
    assert!(graded.contains(&format!(" {dofs} dofs")), "{dofs} in\n{graded}");
    // The key's frame: the same header (its status line, two rows, says what `E` did).
    let keyed = render(&["--keys", "EE"]);
    let head = |s: &str| s.lines().take(2).collect::<Vec<_>>().join("\n");
    assert_eq!(head(&graded), head(&keyed));
    assert!(keyed.contains("edge grading: 2 passes"), "{keyed}");
    let (code, _, err) = crate::common::riplab(&["render", "--refine-edges", "9"]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("--refine-edges") && err.contains("allowed: 0 to 8, or auto"),
        "{err}"
    );
}
