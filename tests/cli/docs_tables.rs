//! The docs' tables of numbers are generated, not copied: every block of command output
//! in README.md and docs/*.md is introduced by a line
//!
//! ```text
//! Output of `riplab ARGS`:
//! ```
//!
//! followed by a fenced block, and these tests run `riplab ARGS` and compare its standard output
//! with the block, line by line (trailing blanks ignored). A table's time columns (`solve ms`)
//! are measurements, not results: they are masked on both sides.
//!
//! Two tiers, by cost on two cores:
//! - [`docs_tables_at_small_levels`] (in `cargo test`) checks the blocks whose reference level is
//!   at most [`SMALL_REFERENCE_LEVEL`];
//! - [`docs_tables_at_their_levels`] checks every block, at the documented levels (several
//!   minutes on two cores: a level-6 reference of a million unknowns). It is ignored by default; run it with
//!   `cargo test --test cli docs_tables -- --include-ignored` (the test profile is optimised).
//!
//! `RIPLAB_BLESS_DOCS=1` with either rewrites the blocks from the fresh output instead of failing:
//! review the diff (`git diff docs/`) as one reviews a snapshot.

use crate::common::{no_panic, riplab};
use std::path::{Path, PathBuf};

/// The finest reference the default tier builds (level 4: 65,664 unknowns).
const SMALL_REFERENCE_LEVEL: u32 = 4;

/// One generated block: where it is, the command, and the lines it holds.
#[derive(Debug)]
struct Block {
    file: PathBuf,
    /// 1-based line of the `Output of` line.
    line: usize,
    args: Vec<String>,
    /// 0-based line range of the block's body in the file (between the fences).
    body: std::ops::Range<usize>,
}

impl Block {
    /// The finest reference level the command builds: `--reference-level`, else one above the
    /// finest studied or solved level.
    fn reference_level(&self) -> u32 {
        let value = |flag: &str| self.args.windows(2).find(|w| w[0] == flag).map(|w| w[1].clone());
        if let Some(level) = value("--reference-level") {
            return level.parse().expect("a level");
        }
        let finest = value("--levels")
            .map(|range| {
                let hi = range.split("..").last().unwrap_or(&range);
                hi.trim_start_matches('=').parse::<u32>().expect("a level")
            })
            .or_else(|| value("--level").map(|l| l.parse().expect("a level")))
            .unwrap_or(0);
        finest + 1
    }

    fn place(&self) -> String {
        format!("{}:{}", self.file.display(), self.line)
    }
}

/// Every `Output of` block of `path`.
fn blocks_in(path: &Path) -> Vec<Block> {
    let text = std::fs::read_to_string(path).expect("readable");
    let lines: Vec<&str> = text.lines().collect();
    let mut out = Vec::new();
    for (i, line) in lines.iter().enumerate() {
        let Some(rest) = line.strip_prefix("Output of `riplab ") else {
            continue;
        };
        let command = rest.split('`').next().expect("a command");
        let open = (i + 1..lines.len())
            .find(|&j| !lines[j].trim().is_empty())
            .filter(|&j| lines[j].starts_with("```"))
            .unwrap_or_else(|| panic!("{}:{}: no fenced block follows", path.display(), i + 1));
        let close = (open + 1..lines.len())
            .find(|&j| lines[j].starts_with("```"))
            .unwrap_or_else(|| panic!("{}:{}: the block is not closed", path.display(), open + 1));
        out.push(Block {
            file: path.to_path_buf(),
            line: i + 1,
            args: command.split_whitespace().map(str::to_string).collect(),
            body: open + 1..close,
        });
    }
    out
}

/// The README and docs/*.md.
fn documents() -> Vec<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files: Vec<PathBuf> = std::fs::read_dir(root.join("docs"))
        .expect("docs/")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "md"))
        .collect();
    files.sort();
    files.insert(0, root.join("README.md"));
    files
}

/// `lines` with every time column blanked: below a header holding `solve ms`, the characters from
/// the end of the header's previous column to the end of `ms` (the columns are right-aligned).
fn masked(lines: &[String]) -> Vec<String> {
    let mut span: Option<(usize, usize)> = None;
    lines
        .iter()
        .map(|line| {
            let chars: Vec<char> = line.chars().collect();
            if let Some(at) = line.find("solve ms") {
                let start = line[..at].trim_end().chars().count();
                let end = line[..at + "solve ms".len()].chars().count();
                span = Some((start, end));
                return line.clone();
            }
            match span {
                Some((start, end)) if chars.len() > start => chars
                    .iter()
                    .enumerate()
                    .map(|(k, &c)| if (start..end).contains(&k) { '·' } else { c })
                    .collect(),
                _ => line.clone(),
            }
        })
        .collect()
}

/// Run each block's command and compare (or, under `RIPLAB_BLESS_DOCS`, rewrite).
fn check(select: impl Fn(&Block) -> bool) {
    let bless = std::env::var_os("RIPLAB_BLESS_DOCS").is_some();
    let mut failures = Vec::new();
    let mut checked = 0;
    for file in documents() {
        let blocks: Vec<Block> = blocks_in(&file).into_iter().filter(&select).collect();
        if blocks.is_empty() {
            continue;
        }
        let text = std::fs::read_to_string(&file).expect("readable");
        let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
        // From the last block up, so that a rewritten block does not move the ones above it.
        for block in blocks.iter().rev() {
            let args: Vec<&str> = block.args.iter().map(String::as_str).collect();
            let (code, stdout, stderr) = riplab(&args);
            no_panic(&stderr);
            assert!(
                code == 0 || code == 1,
                "{}: `riplab {}` exited {code}: {stderr}",
                block.place(),
                args.join(" ")
            );
            let fresh: Vec<String> = stdout.lines().map(|l| l.trim_end().to_string()).collect();
            let documented: Vec<String> = lines[block.body.clone()]
                .iter()
                .map(|l| l.trim_end().to_string())
                .collect();
            checked += 1;
            if masked(&fresh) == masked(&documented) {
                continue;
            }
            if bless {
                lines.splice(block.body.clone(), fresh);
                continue;
            }
            let (a, b) = (masked(&documented), masked(&fresh));
            let k = (0..a.len().max(b.len()))
                .find(|&k| a.get(k) != b.get(k))
                .unwrap_or(0);
            failures.push(format!(
                "{}: `riplab {}` prints another table; first difference at the block's line {}:\n  \
                 documented: {:?}\n  printed:    {:?}",
                block.place(),
                args.join(" "),
                k + 1,
                a.get(k).map(String::as_str).unwrap_or("(nothing)"),
                b.get(k).map(String::as_str).unwrap_or("(nothing)"),
            ));
        }
        if bless {
            std::fs::write(&file, lines.join("\n") + "\n").expect("writable");
        }
    }
    assert!(checked > 0, "no generated block selected");
    assert!(
        failures.is_empty(),
        "{} of {checked} generated blocks disagree with their commands \
         (RIPLAB_BLESS_DOCS=1 rewrites them; review the diff):\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// The blocks whose reference is small enough for every `cargo test`.
#[test]
fn docs_tables_at_small_levels() {
    check(|b| b.reference_level() <= SMALL_REFERENCE_LEVEL);
}

/// Every block at its documented levels (see the module doc for how to run it).
#[test]
#[ignore = "several minutes of level-6 references: run with --include-ignored"]
fn docs_tables_at_their_levels() {
    check(|_| true);
}

/// The parser finds the blocks the docs promise, and the masking leaves the results alone.
#[test]
fn generated_blocks_are_found_and_only_times_are_masked() {
    let all: Vec<Block> = documents().iter().flat_map(|f| blocks_in(f)).collect();
    let convergence = all
        .iter()
        .filter(|b| b.file.ends_with("docs/convergence.md"))
        .count();
    assert!(
        convergence >= 8,
        "docs/convergence.md has {convergence} generated blocks"
    );
    assert!(all.iter().any(|b| b.reference_level() <= SMALL_REFERENCE_LEVEL));
    let table = [
        "scheme         level         h        ε     dofs  Newton  solve ms          p".to_string(),
        "M1                 0  1.000000  1.0e-10       68       1       0.9   2.061e-1".to_string(),
    ];
    let out = masked(&table);
    assert_eq!(out[0], table[0]);
    assert_eq!(
        out[1],
        "M1                 0  1.000000  1.0e-10       68       1··········   2.061e-1"
    );
}
