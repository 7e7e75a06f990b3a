//! Data flows one way through the library (docs/design.md §9): no module uses a module that
//! uses it back, at the granularity of the top-level modules (`contact`, `discretization`,
//! `solve`, …), of their children (`tui::app`, `tui::keys`, …) and of theirs. Read from the
//! sources with Rust's own grammar (syn): every `use` tree (groups, renames, `self`, globs) and
//! every `crate::`, `self::` and `super::` path of the code, outside comments, doc text and
//! test code (`#[cfg(test)]` items and the modules declared so); each resolved from the module
//! it is written in (`super::super::` climbs two) and through the `use` items of the modules
//! it passes (`crate::Method` is `contact::method`'s).

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

use proc_macro2::{Spacing, TokenStream, TokenTree};
use quote::ToTokens as _;
use syn::{Attribute, ImplItem, Item, TraitItem, UseTree};

/// A path of the crate, absolute (from its root): its segments.
type Segments = Vec<String>;

/// Module path (`a::b`) of every source file of the library under `src` (the binary's
/// `main.rs` is not the library's), with its text.
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
            if path.extension().is_none_or(|e| e != "rs") || path == root.join("main.rs") {
                continue;
            }
            let rel = path.strip_prefix(&root).unwrap().with_extension("");
            let mut parts: Vec<String> = rel.iter().map(|p| p.to_string_lossy().into_owned()).collect();
            if matches!(parts.last().map(String::as_str), Some("mod" | "lib")) {
                parts.pop();
            }
            out.insert(parts.join("::"), std::fs::read_to_string(&path).unwrap());
        }
    }
    out
}

/// What a module's file says: the paths it names, the names its `use` items bring into each
/// of its modules (the file's and those written inline in it), and its child modules declared
/// as test code.
#[derive(Debug, Default)]
struct Reading {
    named: BTreeSet<Segments>,
    imports: BTreeMap<String, BTreeMap<String, Segments>>,
    tests: BTreeSet<String>,
}

/// Read the file of module `me`.
fn read(me: &str, text: &str) -> Reading {
    let file = syn::parse_file(text).unwrap_or_else(|e| panic!("{me}: {e}"));
    let mut reading = Reading::default();
    let module: Segments = me
        .split("::")
        .filter(|s| !s.is_empty())
        .map(String::from)
        .collect();
    reading.items(&module, &file.items);
    reading
}

/// The absolute paths module `me`'s file names, joined (for the tests of the reader).
fn named(me: &str, text: &str) -> BTreeSet<String> {
    read(me, text).named.into_iter().map(|p| p.join("::")).collect()
}

/// Whether the attributes make an item test code (`#[cfg(test)]`).
fn is_test(attrs: &[Attribute]) -> bool {
    attrs
        .iter()
        .any(|a| a.path().is_ident("cfg") && a.parse_args::<syn::Ident>().is_ok_and(|cfg| cfg == "test"))
}

/// An item's attributes (none for the kinds that cannot be test code here).
fn attrs(item: &Item) -> &[Attribute] {
    match item {
        Item::Const(i) => &i.attrs,
        Item::Enum(i) => &i.attrs,
        Item::Fn(i) => &i.attrs,
        Item::Impl(i) => &i.attrs,
        Item::Macro(i) => &i.attrs,
        Item::Mod(i) => &i.attrs,
        Item::Static(i) => &i.attrs,
        Item::Struct(i) => &i.attrs,
        Item::Trait(i) => &i.attrs,
        Item::Type(i) => &i.attrs,
        Item::Use(i) => &i.attrs,
        _ => &[],
    }
}

/// Whether `tokens[at..]` starts with `::`.
fn separator(tokens: &[TokenTree], at: usize) -> bool {
    matches!(
        (tokens.get(at), tokens.get(at + 1)),
        (Some(TokenTree::Punct(a)), Some(TokenTree::Punct(b)))
            if a.as_char() == ':' && a.spacing() == Spacing::Joint && b.as_char() == ':'
    )
}

/// `path` as written in `module`, made absolute: `crate::` (and a macro's `$crate::`) from
/// the root, `self::` from `module`, each `super::` one module up; any other path from
/// `module` (a `use` path names a module's child or import, or an external crate, which
/// then resolves to `module` itself).
fn absolute(module: &[String], path: &[String]) -> Segments {
    match path.first().map(String::as_str) {
        Some("crate") => path[1..].to_vec(),
        Some("self") => [module, &path[1..]].concat(),
        Some("super") => {
            let up = path.iter().take_while(|s| *s == "super").count();
            assert!(
                up <= module.len(),
                "{path:?} climbs above the crate from {module:?}"
            );
            [&module[..module.len() - up], &path[up..]].concat()
        }
        _ => [module, path].concat(),
    }
}

impl Reading {
    /// The items of `module` (the file's or one written inline in it).
    fn items(&mut self, module: &[String], items: &[Item]) {
        for item in items {
            match item {
                Item::Mod(m) if is_test(&m.attrs) => {
                    if m.content.is_none() {
                        self.tests
                            .insert([module, &[m.ident.to_string()]].concat().join("::"));
                    }
                }
                _ if is_test(attrs(item)) => {}
                Item::Use(u) => self.tree(module, Vec::new(), &u.tree),
                Item::Mod(m) => {
                    if let Some((_, inner)) = &m.content {
                        self.items(&[module, &[m.ident.to_string()]].concat(), inner);
                    }
                }
                Item::Impl(i) => {
                    self.tokens(module, i.generics.to_token_stream());
                    self.tokens(module, i.self_ty.to_token_stream());
                    if let Some((_, path, _)) = &i.trait_ {
                        self.tokens(module, path.to_token_stream());
                    }
                    for member in &i.items {
                        let test = match member {
                            ImplItem::Fn(f) => is_test(&f.attrs),
                            ImplItem::Const(c) => is_test(&c.attrs),
                            _ => false,
                        };
                        if !test {
                            self.tokens(module, member.to_token_stream());
                        }
                    }
                }
                Item::Trait(t) => {
                    for member in t
                        .items
                        .iter()
                        .filter(|m| !matches!(m, TraitItem::Fn(f) if is_test(&f.attrs)))
                    {
                        self.tokens(module, member.to_token_stream());
                    }
                    self.tokens(module, t.generics.to_token_stream());
                    self.tokens(module, t.supertraits.to_token_stream());
                }
                other => self.tokens(module, other.to_token_stream()),
            }
        }
    }

    /// A `use` tree of `module` under `prefix`: each leaf an import of its name.
    fn tree(&mut self, module: &[String], mut prefix: Segments, tree: &UseTree) {
        match tree {
            UseTree::Path(p) => {
                prefix.push(p.ident.to_string());
                self.tree(module, prefix, &p.tree);
            }
            // `a::{self}` imports `a` as `a`.
            UseTree::Name(n) if n.ident == "self" => {
                let name = prefix.last().cloned();
                self.import(module, name, &prefix);
            }
            UseTree::Name(n) => {
                prefix.push(n.ident.to_string());
                self.import(module, Some(n.ident.to_string()), &prefix);
            }
            UseTree::Rename(r) => {
                if r.ident != "self" {
                    prefix.push(r.ident.to_string());
                }
                let name = (r.rename != "_").then(|| r.rename.to_string());
                self.import(module, name, &prefix);
            }
            UseTree::Glob(_) => self.import(module, None, &prefix),
            UseTree::Group(g) => {
                for tree in &g.items {
                    self.tree(module, prefix.clone(), tree);
                }
            }
        }
    }

    /// `path`, written in `module`, named there (as `name`, for an import that has one).
    fn import(&mut self, module: &[String], name: Option<String>, path: &[String]) {
        let path = absolute(module, path);
        if let Some(name) = name {
            self.imports
                .entry(module.join("::"))
                .or_default()
                .insert(name, path.clone());
        }
        self.named.insert(path);
    }

    /// The paths of some code of `module` that start with `crate`, `self` or `super` (the
    /// other paths of code go through a name its `use` items bring in), and its `use` items.
    fn tokens(&mut self, module: &[String], stream: TokenStream) {
        let tokens: Vec<TokenTree> = stream.into_iter().collect();
        let mut at = 0;
        while at < tokens.len() {
            match &tokens[at] {
                TokenTree::Group(g) => self.tokens(module, g.stream()),
                // A `use` item in a function's body.
                TokenTree::Ident(word) if word == "use" => {
                    let end = tokens[at..]
                        .iter()
                        .position(|t| matches!(t, TokenTree::Punct(p) if p.as_char() == ';'));
                    let item = end.and_then(|end| {
                        let stream: TokenStream = tokens[at..=at + end].iter().cloned().collect();
                        Some((end, syn::parse2::<syn::ItemUse>(stream).ok()?))
                    });
                    if let Some((end, item)) = item {
                        self.tree(module, Vec::new(), &item.tree);
                        at += end + 1;
                        continue;
                    }
                }
                TokenTree::Ident(word)
                    if (word == "crate" || word == "self" || word == "super")
                        && separator(&tokens, at + 1) =>
                {
                    let mut path = vec![word.to_string()];
                    at += 1;
                    while separator(&tokens, at) {
                        let Some(TokenTree::Ident(next)) = tokens.get(at + 2) else {
                            break;
                        };
                        path.push(next.to_string());
                        at += 3;
                    }
                    self.named.insert(absolute(module, &path));
                    continue;
                }
                _ => {}
            }
            at += 1;
        }
    }
}

/// The library's modules: each file's reading, without the files of test code.
fn library() -> BTreeMap<String, Reading> {
    let mut read_all: BTreeMap<String, Reading> = sources()
        .iter()
        .map(|(me, text)| (me.clone(), read(me, text)))
        .collect();
    let tests: BTreeSet<String> = read_all.values().flat_map(|r| r.tests.clone()).collect();
    read_all.retain(|m, _| !tests.iter().any(|t| m == t || m.starts_with(&format!("{t}::"))));
    read_all
}

/// The module `path` names: the longest prefix of it that is a module, unless the next
/// segment is a name that module imports, in which case the path it stands for.
fn resolve(
    path: &[String],
    modules: &BTreeSet<String>,
    imports: &BTreeMap<String, BTreeMap<String, Segments>>,
) -> String {
    expand(path, modules, imports).0
}

/// The module `path` names ([`resolve`]) and the whole path it stands for, its imports
/// followed (`solve::solve` written under `use crate::solve` is `solve::solve`).
fn expand(
    path: &[String],
    modules: &BTreeSet<String>,
    imports: &BTreeMap<String, BTreeMap<String, Segments>>,
) -> (String, Segments) {
    let mut path = path.to_vec();
    // Imports that run in a circle (which rustc refuses) end the walk.
    for _ in 0..64 {
        let Some(k) = (0..=path.len())
            .rev()
            .find(|&k| modules.contains(&path[..k].join("::")))
        else {
            break;
        };
        let module = path[..k].join("::");
        match path.get(k).and_then(|name| imports.get(&module)?.get(name)) {
            Some(stands_for) if stands_for[..] != path[..=k] => {
                path = [stands_for, &path[k + 1..]].concat();
            }
            _ => return (module, path),
        }
    }
    panic!("{path:?} does not resolve")
}

/// Every use of a module by another, read once: (the module whose file names a path, the
/// module the path resolves to).
fn uses() -> Vec<(String, String)> {
    let library = library();
    let modules: BTreeSet<String> = library.keys().cloned().collect();
    let imports: BTreeMap<String, BTreeMap<String, Segments>> =
        library.values().flat_map(|r| r.imports.clone()).collect();
    library
        .iter()
        .flat_map(|(me, reading)| {
            reading
                .named
                .iter()
                .map(|path| (me.clone(), resolve(path, &modules, &imports)))
        })
        .collect()
}

/// The module graph of `uses` cut to `depth` path segments, without self-edges and edges
/// between a module and its ancestors or descendants.
fn graph(uses: &[(String, String)], depth: usize) -> BTreeMap<String, BTreeSet<String>> {
    let cut = |m: &str| m.split("::").take(depth).collect::<Vec<_>>().join("::");
    let nested = |a: &str, b: &str| a.starts_with(&format!("{b}::"));
    let mut g: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for (from, to) in uses {
        let (from, to) = (cut(from), cut(to));
        if from.is_empty() || to.is_empty() || to == from || nested(&to, &from) || nested(&from, &to) {
            continue;
        }
        g.entry(from).or_default().insert(to);
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
    let uses = uses();
    for depth in [1, 2, 3] {
        let g = graph(&uses, depth);
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
        BTreeSet::from(["tui::app::X".to_string(), "contact::Method".to_string()])
    );
}

/// The reader takes every leaf of a grouped import (`crate::{a, b::{self, c as d}}`), climbs
/// one module per `super::` (`super::super::` from `a::b::c` is `a`), reads the paths of code
/// and of a `use` in a function's body, and leaves out comments, doc text and test code.
#[test]
fn grouped_imports_and_super_super_are_read() {
    let text = "//! [`crate::in_doc`]
use crate::{x, y::{self, z as w}};
use super::super::d::E;
use super::{f, g::*};
// crate::in_comment
fn h() {
    use crate::inner::{I, J};
    crate::k::l();
    super::m::n();
    self::o::P::new();
}
#[cfg(test)]
mod tests {
    use crate::t;
}
#[cfg(test)]
mod more;
";
    let expected = [
        "x",
        "y",
        "y::z",
        "a::d::E",
        "a::b::f",
        "a::b::g",
        "inner::I",
        "inner::J",
        "k::l",
        "a::b::m::n",
        "a::b::c::o::P::new",
    ];
    assert_eq!(named("a::b::c", text), expected.map(String::from).into());
    let reading = read("a::b::c", text);
    assert_eq!(reading.imports["a::b::c"]["w"], ["y", "z"]);
    assert_eq!(reading.imports["a::b::c"]["y"], ["y"]);
    assert_eq!(reading.imports["a::b::c"]["E"], ["a", "d", "E"]);
    assert_eq!(reading.tests, BTreeSet::from(["a::b::c::more".to_string()]));
}

/// A path resolves to the module it names through the `use` items of the modules it passes:
/// a re-export at the root, an import of a module under another name, and a name the module
/// defines itself.
#[test]
fn paths_resolve_through_imports() {
    let modules: BTreeSet<String> = ["", "a", "a::b", "c"].map(String::from).into();
    let text = "pub use a::b::B;\nuse c as see;";
    let imports = read("", text).imports;
    let resolved = |path: &str| {
        resolve(
            &path.split("::").map(String::from).collect::<Vec<_>>(),
            &modules,
            &imports,
        )
    };
    assert_eq!(resolved("B"), "a::b");
    assert_eq!(resolved("see::X"), "c");
    assert_eq!(resolved("a::b::X::f"), "a::b");
    assert_eq!(resolved("a::Y"), "a");
}

/// The solvers: the entry's conveniences for tests and benches, its children, and the
/// methods in `contact` with their iterations, friction's and Nitsche's solves on a
/// discretisation included (docs/design.md §9, "one solve entry").
const SOLVERS: [&str; 15] = [
    "solve::solve_contact",
    "solve::solve_friction",
    "solve::solve_graded",
    "solve::sweep",
    "solve::methods",
    "contact::friction::solve",
    "contact::friction::solve_with",
    "contact::friction::solve_frictional",
    "grading::passes",
    "contact::nitsche",
    "contact::penalty::solve",
    "contact::alm::solve",
    "contact::signorini::solve_exact",
    "contact::friction::path::PathProblem",
    "contact::friction::newton",
];

/// One solve entry (docs/design.md §9): outside `solve`, `contact` and `fem`, the library
/// (the command line, the study, the verify pack, the lab) reaches a solver only through
/// `solve::solve` (or `solve::solve_scenario`, which builds a scenario's mesh and calls it);
/// the root's re-exports name the core, not a call.
#[test]
fn only_the_solve_entry_calls_the_solvers() {
    let library = library();
    let modules: BTreeSet<String> = library.keys().cloned().collect();
    let imports: BTreeMap<String, BTreeMap<String, Segments>> =
        library.values().flat_map(|r| r.imports.clone()).collect();
    let inside = |m: &str, folder: &str| m == folder || m.starts_with(&format!("{folder}::"));
    let mut calls = Vec::new();
    for (me, reading) in &library {
        if me.is_empty() || ["solve", "contact", "fem"].iter().any(|f| inside(me, f)) {
            continue;
        }
        for path in &reading.named {
            let named = expand(path, &modules, &imports).1.join("::");
            if SOLVERS.iter().any(|s| inside(&named, s)) {
                calls.push(format!("{me} names {named}"));
            }
        }
    }
    assert!(
        library.len() > 100,
        "the library was read: {} modules",
        library.len()
    );
    assert!(
        calls.is_empty(),
        "solvers reached around the entry:\n{}",
        calls.join("\n")
    );
}

/// The check above sees a solver named around the entry, through an import.
#[test]
fn a_solver_named_around_the_entry_is_seen() {
    let text =
        "use crate::solve::{self, solve_contact};\nfn f() { solve_contact(); crate::solve::graded::x(); }";
    let reading = read("cli::solve", text);
    let modules: BTreeSet<String> = ["cli::solve", "solve"].map(String::from).into();
    let named: BTreeSet<String> = reading
        .named
        .iter()
        .map(|p| expand(p, &modules, &reading.imports).1.join("::"))
        .collect();
    assert!(named.contains("solve::solve_contact"), "{named:?}");
    assert!(named.contains("solve::graded::x"), "{named:?}");
}
