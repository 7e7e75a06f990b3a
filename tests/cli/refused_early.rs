//! Requests with no answer refused before any work, in the user's words: graded and inf-sup
//! requests estimated from their lines and refused naming the level, the element, the
//! grading and the memory; a method that takes no friction refused before the assembly. Each
//! runs under an address-space limit of half riplab's own estimate for the uniform level the
//! command would build first (`riplab_under_half_of`): had the command gone on to build it,
//! its memory guard would have refused it in other words.

use riplab::mesh::Element;
use riplab::scenario::Scenario;

use riplab::grading::Grading;

use crate::common::{no_panic, riplab_under, riplab_under_half_of, scratch_file};

fn paper_sizes(level: u32, element: Element) -> riplab::fem::memory::Sizes {
    Scenario::paper().sizes(level, element)
}

/// Exit 2, nothing printed, and every fragment in the message.
fn refused(out: (i32, String, String), fragments: &[&str]) {
    let (code, stdout, stderr) = out;
    no_panic(&stderr);
    assert_eq!(code, 2, "{stderr}");
    assert!(stdout.is_empty(), "{stdout}");
    for f in fragments {
        assert!(stderr.contains(f), "lacks {f:?}: {stderr}");
    }
}

/// `solve --level 8 --refine-edges 8z` (44–54 s and 5.5 GB before it was refused as "graded 1
/// times at the contact edges"), an edge grading of level 8, `infsup --levels 6 --refine-edges
/// 8z --element q2`, `render --level 7 --refine-edges 8z` (exit 1 after 46 s) and a scenario's
/// `[mesh] refine_edges = "8z"` at q2 level 7: each refused from its lines, exit 2, naming the
/// level, the element, the grading and the memory.
#[test]
fn graded_requests_are_refused_from_their_lines_before_any_assembly() {
    let memory = ["GiB", "available", "choose fewer passes or a coarser level"];
    let zone8 = "graded over the contact zone, 8 passes (8z)";
    refused(
        riplab_under_half_of(
            &paper_sizes(8, Element::Q1),
            &["solve", "--level", "8", "--refine-edges", "8z"],
        ),
        &[&[&format!("level 8 with q1 {zone8}")[..]][..], &memory].concat(),
    );
    refused(
        riplab_under_half_of(
            &paper_sizes(8, Element::Q1),
            &["solve", "--level", "8", "--refine-edges", "3"],
        ),
        &[
            &["level 8 with q1 graded at the contact edges, 3 passes (3)"][..],
            &memory,
        ]
        .concat(),
    );
    refused(
        riplab_under_half_of(
            &paper_sizes(6, Element::Q2),
            &[
                "infsup",
                "--levels",
                "6",
                "--refine-edges",
                "8z",
                "--element",
                "q2",
            ],
        ),
        &[&[&format!("level 6 with q2 {zone8}")[..]][..], &memory].concat(),
    );
    refused(
        riplab_under_half_of(
            &paper_sizes(7, Element::Q1),
            &["render", "--level", "7", "--refine-edges", "8z"],
        ),
        &[&[&format!("level 7 with q1 {zone8}")[..]][..], &memory].concat(),
    );
    let text = crate::common::paper_text(&[
        ("element", "element = \"q2\""),
        ("level", "level = 7\nrefine_edges = \"8z\""),
    ]);
    let file = scratch_file("graded-q2-level-7.toml", &text);
    refused(
        riplab_under_half_of(&paper_sizes(7, Element::Q2), &["solve", file.to_str().unwrap()]),
        &[&[&format!("level 7 with q2 {zone8}")[..]][..], &memory].concat(),
    );
}

/// `solve scenarios/cattaneo-mindlin.toml --level 5 --method nitsche` was a usage error found
/// after 9–16 s of assembly; so was ε_t with its exact method. Both are refused first,
/// naming the flag and the scenario's friction.
#[test]
fn a_method_that_takes_no_friction_is_refused_before_any_assembly() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/scenarios/cattaneo-mindlin.toml");
    let sizes = Scenario::load(path.as_ref()).unwrap().sizes(5, Element::Q1);
    refused(
        riplab_under_half_of(&sizes, &["solve", path, "--level", "5", "--method", "nitsche"]),
        &[
            "invalid value for --method: nitsche takes no friction",
            "`[friction] law = \"coulomb\"`",
        ],
    );
    refused(
        riplab_under_half_of(&sizes, &["solve", path, "--level", "5", "--epsilon-t", "1e-6"]),
        &[
            "invalid value for --epsilon-t: is the tangential penalty of penalty and alm; the method here is exact",
        ],
    );
    let full = concat!(env!("CARGO_MANIFEST_DIR"), "/scenarios/hertz-paper-full.toml");
    let sizes = Scenario::load(full.as_ref()).unwrap().sizes(7, Element::Q1);
    refused(
        riplab_under_half_of(
            &sizes,
            &[
                "solve",
                full,
                "--level",
                "7",
                "--method",
                "nitsche",
                "--friction",
                "coulomb",
                "--mu",
                "0.3",
            ],
        ),
        &["invalid value for --friction: friction is imposed by penalty, exact or alm, not by nitsche"],
    );
}

/// `study --refine-edges 0,8z` refused its graded rows one by one, each after the reference
/// and the rows before it were solved (exit 1 after 56 s under a 1.2 GiB limit: "4 of 12 rows
/// have no certified result"). Every graded row is estimated from its lines first, and the
/// whole study is refused, exit 2, naming a row's level, element and grading and the memory,
/// with nothing computed (not even the reference's note). Under half the estimate of the
/// largest Q1 row, and (with Q2 alone, graded at the edges) under half of its only graded row's.
#[test]
fn a_study_whose_graded_rows_cannot_fit_is_refused_before_any_assembly() {
    let paper = Scenario::paper();
    let memory = ["GiB", "available", "choose fewer passes or a coarser level"];
    let (_, need) = paper.graded_estimate(3, Element::Q1, Grading::Zone(8), |_| 0);
    let out = riplab_under(
        need / 2,
        &[
            "study",
            "--levels",
            "0..3",
            "--schemes",
            "M1,M4",
            "--refine-edges",
            "0,8z",
            "--no-cache",
        ],
    );
    let stderr = out.2.clone();
    refused(
        out,
        &[&["graded over the contact zone, 8 passes (8z): "][..], &memory].concat(),
    );
    let named = (0..=3).any(|l| {
        ["q1", "q2"]
            .iter()
            .any(|e| stderr.contains(&format!("level {l} with {e} graded over")))
    });
    assert!(named && !stderr.contains("the reference"), "{stderr}");
    let edges = Grading::parse("8").unwrap();
    let (_, need) = paper.graded_estimate(7, Element::Q2, edges, |_| 0);
    let out = riplab_under(
        need / 2,
        &[
            "study",
            "--levels",
            "7",
            "--schemes",
            "M4",
            "--refine-edges",
            "0,8",
            "--no-cache",
        ],
    );
    let stderr = out.2.clone();
    refused(
        out,
        &[
            &["level 7 with q2 graded at the contact edges, 8 passes (8): "][..],
            &memory,
        ]
        .concat(),
    );
    assert!(!stderr.contains("the reference"), "{stderr}");
}

/// A tour step at level 7 graded `8z` made `tour --handout` solve its passes until one did not
/// fit (300 s and 16 GB before it was stopped, nothing refused). Every graded step is
/// estimated from its lines first, as the lab's engine does: refused, exit 2, naming the step,
/// the level, the element, the grading and the memory, and no directory made; `tour --check`
/// refuses it in the same words. Under half the estimate of level 7, which the handout would
/// build first.
#[test]
fn a_handout_whose_graded_step_cannot_fit_is_refused_before_any_assembly() {
    let tour = scratch_file(
        "graded-step-level-7.toml",
        "title = \"t\"\n[[step]]\ntitle = \"s\"\ncaption = \"c\"\nlevel = 7\nrefine_edges = \"8z\"\n",
    );
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("graded-step-handout");
    let _ = std::fs::remove_dir_all(&dir);
    refused(
        riplab_under_half_of(
            &paper_sizes(7, Element::Q1),
            &[
                "tour",
                "--tour",
                tour.to_str().unwrap(),
                "--handout",
                dir.to_str().unwrap(),
                "--size",
                "80x24",
            ],
        ),
        &[
            "step 1: level 7 with q1 graded over the contact zone, 8 passes (8z): ",
            "GiB",
            "available",
            "choose fewer passes or a coarser level",
        ],
    );
    assert!(!dir.exists());
    // `tour --check` called it a valid tour of 1 step (exit 0): it says what the lab would.
    let file = tour.to_str().unwrap();
    refused(
        riplab_under_half_of(&paper_sizes(7, Element::Q1), &["tour", "--check", file]),
        &[
            &format!("{file}: step 1: level 7 with q1 graded over the contact zone, 8 passes (8z): ")[..],
            "GiB",
            "available",
        ],
    );
}
