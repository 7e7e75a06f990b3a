//! Issue 11: data flows one way through the library (docs/design.md §9): no module uses a
//! module that uses it back, at the granularity of the top-level modules (`contact`,
//! `discretization`, `solve`, …) and of their children (`tui::app`, `tui::keys`, …). Read
//! from the sources: the `crate::` and `super::` paths of the code outside comments and test
//! modules.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// Module path (`a::b`) of every source file under `src`, with its text.
fn sources() -> BTreeMap<String, String> {
    let mut out = BTreeMap::new();
    let mut stack = vec![Path::new(env!("CARGO_MANIFEST_DIR")).join("src")];
    let root = stack[0].clone();
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                stack.push(path);
                continue;
            }
            if path.extension().is_none_or(|e| e != "rs") {
                continue;
            }
            let rel = path.strip_prefix(&root).unwrap().with_extension("");
            let mut parts: Vec<String> = rel.iter().map(|p| p.to_string_lossy().into_owned()).collect();
            if matches!(parts.last().map(String::as_str), Some("mod" | "lib" | "main")) {
                parts.pop();
            }
            out.insert(parts.join("::"), std::fs::read_to_string(&path).unwrap());
        }
    }
    out
}

/// The module paths `text` (of module `me`) names through `crate::` and `super::`, outside
/// comments and the test module.
fn named(me: &str, text: &str) -> BTreeSet<String> {
    let code = text.split("#[cfg(test)]\nmod tests").next().unwrap();
    let mut out = BTreeSet::new();
    for line in code.lines().filter(|l| !l.trim_start().starts_with("//")) {
        for (prefix, base) in [("crate::", String::new()), ("super::", parent(me))] {
            for (at, _) in line.match_indices(prefix) {
                // `super::` inside a longer identifier (e.g. `a_super::`) is not a path.
                if line[..at].ends_with(|c: char| c.is_alphanumeric() || c == '_') {
                    continue;
                }
                let path: String = line[at + prefix.len()..]
                    .chars()
                    .take_while(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || *c == '_' || *c == ':')
                    .collect();
                let path = path.trim_end_matches(':');
                if !path.is_empty() {
                    out.insert(if base.is_empty() {
                        path.to_string()
                    } else {
                        format!("{base}::{path}")
                    });
                }
            }
        }
    }
    out
}

fn parent(module: &str) -> String {
    module
        .rsplit_once("::")
        .map_or(String::new(), |(p, _)| p.to_string())
}

/// The module graph cut to `depth` path segments, without self-edges and edges between a
/// module and its own parent or child.
fn graph(depth: usize) -> BTreeMap<String, BTreeSet<String>> {
    let modules = sources();
    let cut = |m: &str| m.split("::").take(depth).collect::<Vec<_>>().join("::");
    let mut g: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for (me, text) in &modules {
        let from = cut(me);
        for path in named(me, text) {
            // The longest prefix of the path that is a module.
            let segments: Vec<&str> = path.split("::").collect();
            let Some(target) = (1..=segments.len())
                .rev()
                .map(|k| segments[..k].join("::"))
                .find(|m| modules.contains_key(m))
            else {
                continue;
            };
            let to = cut(&target);
            let nested = |a: &str, b: &str| a.starts_with(&format!("{b}::"));
            if from.is_empty() || to == from || nested(&to, &from) || nested(&from, &to) {
                continue;
            }
            g.entry(from.clone()).or_default().insert(to);
        }
    }
    g
}

/// A cycle of `g`, if there is one (depth-first search).
fn cycle(g: &BTreeMap<String, BTreeSet<String>>) -> Option<Vec<String>> {
    fn visit(
        v: &str,
        g: &BTreeMap<String, BTreeSet<String>>,
        state: &mut BTreeMap<String, u8>,
        path: &mut Vec<String>,
    ) -> Option<Vec<String>> {
        state.insert(v.to_string(), 1);
        path.push(v.to_string());
        for w in g.get(v).into_iter().flatten() {
            match state.get(w.as_str()) {
                Some(1) => {
                    let start = path.iter().position(|p| p == w).unwrap();
                    let mut found = path[start..].to_vec();
                    found.push(w.clone());
                    return Some(found);
                }
                Some(_) => {}
                None => {
                    if let Some(c) = visit(w, g, state, path) {
                        return Some(c);
                    }
                }
            }
        }
        path.pop();
        state.insert(v.to_string(), 2);
        None
    }
    let mut state = BTreeMap::new();
    g.keys().find_map(|v| {
        (!state.contains_key(v))
            .then(|| visit(v, g, &mut state, &mut Vec::new()))
            .flatten()
    })
}

#[test]
fn the_modules_form_no_cycle() {
    for depth in [1, 2, 3] {
        let g = graph(depth);
        assert!(g.len() > 10, "the graph was read: {g:?}");
        if let Some(c) = cycle(&g) {
            panic!("module cycle at depth {depth}: {}", c.join(" → "));
        }
    }
}

/// The detector finds a cycle where there is one.
#[test]
fn a_cycle_is_found() {
    let mut g: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for (a, b) in [("a", "b"), ("b", "c"), ("c", "a"), ("c", "d")] {
        g.entry(a.into()).or_default().insert(b.into());
    }
    assert_eq!(cycle(&g).unwrap(), ["a", "b", "c", "a"]);
    g.get_mut("c").unwrap().remove("a");
    assert_eq!(cycle(&g), None);
    // The parent named in a doc comment or through `super::` counts only outside comments.
    let uses = named(
        "tui::keys",
        "//! see [`super::app`]\nuse super::app::X;\nuse crate::contact::Method;",
    );
    assert_eq!(
        uses,
        BTreeSet::from(["tui::app".to_string(), "contact".to_string()])
    );
}
