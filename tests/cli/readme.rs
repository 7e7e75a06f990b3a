//! Every command the README and docs/*.md show runs: each `riplab …` line of a shell
//! code block (```sh), and each `cargo run --release -- …` or `riplab …` code span after "Command:"
//! or "Output of" (whose output docs_tables.rs compares at the documented levels), is run
//! against the built binary and must exit as documented and print what it promises.
//!
//! Documented substitutions, so that the whole suite stays fast on two cores:
//! - mesh levels are capped at [`LEVEL_CAP`] (`--level`, the upper end of `--levels`) and a
//!   `--reference-level` at one above the cap;
//! - the lab (`riplab` or `riplab SCENARIO`) is run as `riplab render [SCENARIO] --size 80x24`;
//! - an output file or directory (`--plot FILE`, `--vtu FILE`, `--handout DIR`) goes to a fresh
//!   temporary directory, and a redirection
//!   `> FILE` is dropped (the test reads standard output instead).
//!
//! A command whose comment says `exit N` must exit N; every other command must exit 0.

use std::path::{Path, PathBuf};

/// The finest level a documented command is run at here.
const LEVEL_CAP: u32 = 2;

/// One documented command: where it was found, its arguments after `riplab`, and the exit
/// code its comment promises.
#[derive(Debug)]
struct Documented {
    place: String,
    args: Vec<String>,
    exit: i32,
}

/// `riplab …` lines of code blocks, and `Command: \`…\`` spans of prose.
fn commands_in(path: &Path) -> Vec<Documented> {
    let text = std::fs::read_to_string(path).expect("readable");
    let name = path.file_name().unwrap().to_string_lossy().into_owned();
    let mut out = Vec::new();
    let mut in_block = false;
    for (i, line) in text.lines().enumerate() {
        let place = format!("{name}:{}", i + 1);
        // Shell blocks only: other blocks show output (frames, tables).
        if let Some(tag) = line.trim_start().strip_prefix("```") {
            in_block = !in_block && ["sh", "bash", "shell", "console"].contains(&tag.trim());
            continue;
        }
        let (command, comment) = if in_block {
            let (command, comment) = line.split_once(" #").unwrap_or((line, ""));
            (command.trim().to_string(), comment.to_string())
        } else if let Some(rest) = ["Command: `", "Output of `"]
            .iter()
            .find_map(|lead| line.trim_start().strip_prefix(lead))
        {
            let command = rest.split('`').next().unwrap_or("");
            (command.to_string(), rest.to_string())
        } else {
            continue;
        };
        let command = command
            .strip_prefix("cargo run --release -- ")
            .map(|rest| format!("riplab {rest}"))
            .unwrap_or(command);
        if command != "riplab" && !command.starts_with("riplab ") {
            continue;
        }
        let exit = comment
            .split("exit ")
            .nth(1)
            .and_then(|rest| rest.chars().next())
            .and_then(|c| c.to_digit(10))
            .map_or(0, |d| d as i32);
        let args = command.split_whitespace().skip(1).map(str::to_string).collect();
        out.push(Documented { place, args, exit });
    }
    out
}

/// Every documented command of the README and docs/*.md.
fn documented() -> Vec<Documented> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = vec![root.join("README.md")];
    let mut docs: Vec<PathBuf> = std::fs::read_dir(root.join("docs"))
        .expect("docs/")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "md"))
        .collect();
    docs.sort();
    files.extend(docs);
    files.iter().flat_map(|f| commands_in(f)).collect()
}

/// The documented arguments with the substitutions of this file's header applied.
fn substitute(args: &[String], tmp: &Path) -> Vec<String> {
    let cap = |v: &str, by: u32| {
        v.parse::<u32>()
            .map_or(v.to_string(), |l| l.min(LEVEL_CAP + by).to_string())
    };
    let mut out: Vec<String> = Vec::new();
    let mut it = args.iter().peekable();
    while let Some(a) = it.next() {
        match a.as_str() {
            ">" => {
                it.next();
            }
            "--level" | "-l" => {
                out.push(a.clone());
                out.push(cap(it.next().expect("a level"), 0));
            }
            "--reference-level" => {
                out.push(a.clone());
                out.push(cap(it.next().expect("a level"), 1));
            }
            "--levels" => {
                out.push(a.clone());
                let range = it.next().expect("levels");
                let (lo, hi) = range.split_once("..").unwrap_or((range, range));
                let hi = hi.trim_start_matches('=');
                let lo = cap(lo, 0);
                let hi = cap(hi, 0).max(lo.clone());
                out.push(format!("{lo}..{hi}"));
            }
            "--plot" | "--vtu" | "--handout" => {
                out.push(a.clone());
                let file = it.next().expect("a file");
                out.push(
                    tmp.join(Path::new(file).file_name().unwrap())
                        .display()
                        .to_string(),
                );
            }
            _ => out.push(a.clone()),
        }
    }
    // The lab is drawn by `render`.
    let subcommands = [
        "solve",
        "infsup",
        "study",
        "verify",
        "render",
        "tour",
        "completions",
        "man",
    ];
    if out
        .first()
        .is_none_or(|first| !subcommands.contains(&first.as_str()))
    {
        let mut lab = vec!["render".to_string()];
        lab.extend(out);
        lab.extend(["--size".into(), "80x24".into()]);
        return lab;
    }
    out
}

/// Why a documented command's run breaks its promise.
#[derive(Debug, thiserror::Error)]
enum Broken {
    #[error("exit {code}, documented {documented}: {stderr}")]
    Exit {
        code: i32,
        documented: i32,
        stderr: String,
    },
    #[error("not JSON: {0}")]
    NotJson(serde_json::Error),
    #[error("an empty JSON array")]
    EmptyJson,
    #[error("no CSV header")]
    NoHeader,
    #[error("not a CSV table: {0}")]
    NotCsv(String),
    #[error("the output lacks {0:?}")]
    Lacks(&'static str),
    #[error("no {what} written: {source}")]
    NotWritten {
        what: &'static str,
        source: std::io::Error,
    },
    #[error("the {0} file is not what it should be")]
    Malformed(&'static str),
    #[error("no size")]
    NoSize,
    #[error("{got} lines, not {rows}")]
    Lines { got: usize, rows: usize },
    #[error("no {}", .0.display())]
    Missing(PathBuf),
    #[error("no check for `riplab {0}`: add one to tests/cli/readme.rs")]
    NoCheck(String),
}

/// What the command printed is what it promises: a check per subcommand and format.
fn check_output(args: &[String], stdout: &str, tmp: &Path) -> Result<(), Broken> {
    let has = |flag: &str, value: &str| args.windows(2).any(|w| w[0] == flag && w[1] == value);
    let json = has("--format", "json") || has("-f", "json");
    let csv = has("--format", "csv") || has("-f", "csv");
    // A command's help (docs/cli.md shows each one): clap's usage line.
    if args.iter().any(|a| a == "--help") {
        return if stdout.contains("Usage: riplab") {
            Ok(())
        } else {
            Err(Broken::Lacks("Usage: riplab"))
        };
    }
    if json {
        let value: serde_json::Value = serde_json::from_str(stdout).map_err(Broken::NotJson)?;
        let objects: Vec<&serde_json::Value> = match &value {
            serde_json::Value::Array(a) => a.iter().collect(),
            other => vec![other],
        };
        if objects.is_empty() {
            return Err(Broken::EmptyJson);
        }
        return Ok(());
    }
    if csv {
        let mut lines = stdout.lines();
        let header = lines.next().ok_or(Broken::NoHeader)?;
        let columns = header.split(',').count();
        if columns < 2 || lines.clone().count() == 0 {
            return Err(Broken::NotCsv(header.to_string()));
        }
        return Ok(());
    }
    let expect = |needle: &'static str| {
        if stdout.contains(needle) {
            Ok(())
        } else {
            Err(Broken::Lacks(needle))
        }
    };
    let written = |flag: &str, what: &'static str, mark: &str| -> Result<(), Broken> {
        let Some(i) = args.iter().position(|a| a == flag) else {
            return Ok(());
        };
        let text = std::fs::read_to_string(tmp.join(Path::new(&args[i + 1]).file_name().unwrap()))
            .map_err(|source| Broken::NotWritten { what, source })?;
        if text.contains(mark) {
            Ok(())
        } else {
            Err(Broken::Malformed(what))
        }
    };
    match args[0].as_str() {
        "solve" => {
            written("--vtu", "VTU", "<VTKFile")?;
            written("--plot", "SVG", "<svg")?;
            let sweep = args
                .windows(2)
                .any(|w| ["--epsilon", "--depth", "--kappa"].contains(&w[0].as_str()) && w[1].contains(','));
            expect(if sweep { "total ms" } else { "load P =" })
        }
        // The one-body table has β̄_h/√h beside it; a two-body one a row per space, p̄ one.
        "infsup" => expect("β_h/√h"),
        "study" => expect("reference"),
        "verify" => expect("checks OK"),
        "render" => {
            let size = args
                .windows(2)
                .find(|w| w[0] == "--size")
                .map_or("120x40", |w| w[1].as_str());
            let rows: usize = size
                .split(['x', '×'])
                .nth(1)
                .and_then(|r| r.parse().ok())
                .ok_or(Broken::NoSize)?;
            let got = stdout.lines().count();
            if got != rows {
                return Err(Broken::Lines { got, rows });
            }
            expect("riplab")
        }
        "tour" if args.iter().any(|a| a == "--check") => expect("a valid tour"),
        "tour" if args.iter().any(|a| a == "--handout") => {
            expect("index.md")?;
            let dir = args
                .windows(2)
                .find(|w| w[0] == "--handout")
                .map(|w| w[1].clone());
            let index = Path::new(&dir.unwrap_or_default()).join("index.md");
            index.is_file().then_some(()).ok_or(Broken::Missing(index))
        }
        "completions" => expect("riplab"),
        "man" => expect(".TH riplab"),
        other => Err(Broken::NoCheck(other.to_string())),
    }
}

#[test]
fn every_documented_command_runs() {
    let commands = documented();
    assert!(
        commands.len() >= 15,
        "found only {} commands: is the extraction broken?",
        commands.len()
    );
    let root = env!("CARGO_MANIFEST_DIR");
    let mut failures = Vec::new();
    for (i, doc) in commands.iter().enumerate() {
        let tmp = std::env::temp_dir().join(format!("riplab-readme-{}-{i}", std::process::id()));
        std::fs::create_dir_all(&tmp).expect("a temporary directory");
        let args = substitute(&doc.args, &tmp);
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_riplab"))
            .args(&args)
            .current_dir(root)
            .env("NO_COLOR", "1")
            .env("XDG_CACHE_HOME", crate::common::test_cache())
            .output()
            .expect("runs");
        let (stdout, stderr) = (
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr),
        );
        let code = out.status.code().unwrap_or(-1);
        let verdict = if code != doc.exit {
            Err(Broken::Exit {
                code,
                documented: doc.exit,
                stderr: stderr.to_string(),
            })
        } else {
            check_output(&args, &stdout, &tmp)
        };
        if let Err(why) = verdict {
            failures.push(format!(
                "{} `riplab {}` (run as `{}`): {why}",
                doc.place,
                doc.args.join(" "),
                args.join(" ")
            ));
        }
        let _ = std::fs::remove_dir_all(&tmp);
    }
    assert!(
        failures.is_empty(),
        "documented commands that fail:\n{}",
        failures.join("\n")
    );
}

#[test]
fn the_extraction_finds_the_readme_commands() {
    let commands = documented();
    let find = |needle: &str| commands.iter().find(|c| c.args.join(" ") == needle);
    let sweep = find("study --level 4 --sweep-epsilon 1e-2,1e-4,1e-6,1e-8,0")
        .expect("the ε-sweep study is documented");
    assert_eq!(sweep.exit, 1, "its M2 row has no result at ε = 0, so it exits 1");
    assert!(find("solve --level 1 --scheme M1").is_some());
    assert!(commands.iter().any(|c| c.place.starts_with("convergence.md")));
    // Substitutions: levels capped, redirections dropped, the lab drawn by render.
    let tmp = Path::new("/tmp/x");
    let s = |a: &str| substitute(&a.split(' ').map(str::to_string).collect::<Vec<_>>(), tmp).join(" ");
    assert_eq!(s("infsup --all --levels 0..6"), "infsup --all --levels 0..2");
    assert_eq!(
        s("study --level 4 --reference-level 6"),
        "study --level 2 --reference-level 3"
    );
    assert_eq!(s("man > riplab.1"), "man");
    assert_eq!(s("scenarios/x.toml"), "render scenarios/x.toml --size 80x24");
    assert_eq!(s("solve --plot m1.svg"), "solve --plot /tmp/x/m1.svg");
}
