//! docs/design.md §9 ("Where things live") names every source file: a file `src/F/S.rs` is
//! named by a row of the map that names its folder `F/` and the module `S`, a top-level file
//! by `S.rs`; a folder's `mod.rs` by the folder, and the lab's tests (`tests/` folders) by the
//! folder alone. A file added without its place in the map fails here.

use std::path::Path;

/// The rows of §9's table.
fn map_rows() -> Vec<String> {
    let design = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/design.md")).unwrap();
    let start = design.find("## §9 ").expect("docs/design.md has a §9");
    let section = &design[start..];
    let heading = section.find('\n').unwrap_or(section.len());
    let end = section[heading..]
        .find("\n## ")
        .map_or(section.len(), |e| e + heading);
    section[..end]
        .lines()
        .filter(|l| l.starts_with("| `"))
        .map(str::to_string)
        .collect()
}

/// `word` stands alone in `text` (not inside a longer identifier).
fn has_word(text: &str, word: &str) -> bool {
    let ident = |c: char| c.is_alphanumeric() || c == '_';
    text.match_indices(word).any(|(at, _)| {
        let before = text[..at].chars().next_back();
        let after = text[at + word.len()..].chars().next();
        !before.is_some_and(ident) && !after.is_some_and(ident)
    })
}

/// Every `.rs` file under `dir`, relative to `src/`, with `/` separators.
fn sources(root: &Path, dir: &Path, out: &mut Vec<String>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            sources(root, &path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            let rel = path
                .strip_prefix(root)
                .unwrap()
                .to_string_lossy()
                .replace('\\', "/");
            out.push(rel);
        }
    }
}

#[test]
fn the_design_map_names_every_source_file() {
    let rows = map_rows();
    assert!(rows.len() > 10, "§9's table was not found");
    let root = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/src"));
    let mut files = Vec::new();
    sources(root, root, &mut files);
    files.sort();
    let mut missing = Vec::new();
    for file in &files {
        let (folder, name) = file.rsplit_once('/').map_or(("", file.as_str()), |(f, n)| (f, n));
        let stem = name.trim_end_matches(".rs");
        let named = if folder.is_empty() {
            rows.iter()
                .any(|r| r.contains(&format!("`{name}`")) || has_word(r, name))
        } else if let Some(at) = folder.find("tests") {
            let tests = &folder[..at + "tests".len()];
            rows.iter().any(|r| r.contains(&format!("{tests}/")))
        } else if stem == "mod" {
            rows.iter().any(|r| r.contains(&format!("{folder}/")))
        } else {
            rows.iter()
                .any(|r| r.contains(&format!("{folder}/")) && has_word(r, stem))
        };
        if !named {
            missing.push(file.clone());
        }
    }
    assert!(
        missing.is_empty(),
        "docs/design.md §9 does not name these files of src/: {missing:?}"
    );
}
