//! The scenario files the embedded tour (`tours/paper.toml`) may name: it is read from no
//! directory, so a step's `scenario` is looked up here, by the path it has relative to
//! `tours/` (what the same tour read from its file resolves to the same file).

/// Each scenario file by its path relative to `tours/`.
const EMBEDDED: &[(&str, &str)] = &[
    (
        "../scenarios/cattaneo-mindlin.toml",
        include_str!("../../../scenarios/cattaneo-mindlin.toml"),
    ),
    (
        "../scenarios/patch-two-blocks.toml",
        include_str!("../../../scenarios/patch-two-blocks.toml"),
    ),
];

/// The text of the embedded scenario file at `path` (relative to `tours/`), if any.
pub fn scenario_text(path: &str) -> Option<&'static str> {
    EMBEDDED.iter().find(|(p, _)| *p == path).map(|(_, text)| *text)
}
