//! The key bar under each scene (the three to six keys that act there, as lazygit's footer
//! and htop's F-key bar show them) and the help's lines for the scene shown first: both read
//! from the one key table, [`super::keys::LAB`], so that a key cannot be shown as another.

use crossterm::event::KeyCode;

use super::app::Scene;
use super::keys::{LAB, LabAction, Row, help_lines, lab_help};

use LabAction as L;

/// A bar's entry: the actions whose keys it shows, and its word.
type Entry = (&'static [LabAction], &'static str);

/// The key bar's entries of each scene ([`bar`]): the keys that act there most, each with
/// a word; their keys are read from [`LAB`].
const BAR: &[(Scene, &[Entry])] = &[
    (
        Scene::Explore,
        &[
            (&[L::Coarser, L::Finer], "level"),
            (&[L::Scheme(1), L::Scheme(4)], "scheme"),
            (&[L::NextMethod], "method"),
            (&[L::EpsilonUp, L::EpsilonDown], "ε"),
            (&[L::Cursor], "cursor"),
            (&[L::NextScene], "scene"),
        ],
    ),
    (
        Scene::InfSup,
        &[
            (&[L::Coarser, L::Finer], "level"),
            (&[L::Scheme(1), L::Scheme(4)], "scheme"),
            (&[L::AllLevels], "levels"),
            (&[L::Projector], "full"),
            (&[L::NextScene], "scene"),
        ],
    ),
    (
        Scene::Mesh,
        &[
            (&[L::Coarser, L::Finer], "level"),
            (&[L::Scheme(1), L::Scheme(4)], "scheme"),
            (&[L::Shallower, L::Deeper], "depth"),
            (&[L::NextScene], "scene"),
        ],
    ),
    (
        Scene::Convergence,
        &[
            (&[L::Compare], "compare"),
            (&[L::NextMethod], "method"),
            (&[L::EpsilonUp, L::EpsilonDown], "ε"),
            (&[L::Projector], "full"),
            (&[L::NextScene], "scene"),
        ],
    ),
    (
        Scene::Stress,
        &[
            (&[L::NextQuantity], "quantity"),
            (&[L::Zoom], "zoom"),
            (&[L::Cursor], "cursor"),
            (&[L::Coarser, L::Finer], "level"),
            (&[L::NextScene], "scene"),
        ],
    ),
];

/// The two-body scene's bar ([`bodies_bar`]).
const BODIES: &[Entry] = &[
    (&[L::Coarser, L::Finer], "level"),
    (&[L::NextContact], "contact"),
    (&[L::RatioDown, L::RatioUp], "ratio"),
    (&[L::OffsetDown, L::OffsetUp], "offset"),
    (&[L::NextScene], "inf-sup"),
    (&[L::Reset], "reset"),
];

/// The projector view's bar (`f` back, the cursor).
const PROJECTOR: &[Entry] = &[(&[L::Projector], "back"), (&[L::Cursor], "cursor")];

/// The key bar of `scene` (or of the projector view): (keys, word) for the keys that act
/// there, as [`LAB`] binds them (`←→`, `1-4`), then `? help` and `q quit`.
pub fn bar(scene: Scene, projector: bool) -> Vec<(String, &'static str)> {
    let entries: &[Entry] = if projector {
        PROJECTOR
    } else {
        BAR.iter().find(|(s, _)| *s == scene).map_or(&[], |(_, e)| e)
    };
    with_help_and_quit(entries)
}

/// The key bar of the two-body scene (docs/lab.md, "Two bodies"), as [`bar`] writes one.
pub fn bodies_bar() -> Vec<(String, &'static str)> {
    with_help_and_quit(BODIES)
}

/// The entries' keys as [`LAB`] binds them, then `? help` and `q quit`.
fn with_help_and_quit(entries: &[Entry]) -> Vec<(String, &'static str)> {
    let mut out: Vec<(String, &'static str)> = entries
        .iter()
        .map(|(actions, word)| {
            let keys: Vec<String> = actions.iter().map(first_key).collect();
            let joint = if matches!(actions[0], L::Scheme(_)) {
                "-"
            } else {
                ""
            };
            (keys.join(joint), *word)
        })
        .collect();
    out.push((first_key(&L::Help), "help"));
    out.push((first_key(&L::Quit), "quit"));
    out
}

/// The actions of `scene`'s key bar ([`bar`]).
pub fn bar_actions(scene: Scene) -> Vec<LabAction> {
    BAR.iter()
        .filter(|(s, _)| *s == scene)
        .flat_map(|(_, entries)| entries.iter().flat_map(|(actions, _)| actions.iter().copied()))
        .collect()
}

/// The first key [`LAB`] binds to `action`, as the bar writes it.
fn first_key(action: &LabAction) -> String {
    let code = LAB
        .iter()
        .flat_map(|row| row.bindings)
        .find(|(_, a)| a == action)
        .map(|(code, _)| *code);
    match code {
        Some(KeyCode::Char(c)) => c.to_string(),
        Some(KeyCode::Left) => "←".into(),
        Some(KeyCode::Right) => "→".into(),
        Some(KeyCode::Tab) => "Tab".into(),
        Some(KeyCode::Esc) => "Esc".into(),
        Some(other) => format!("{other:?}"),
        None => String::new(),
    }
}

/// The lab's help overlay for `scene`: the rows of [`LAB`] whose keys act in it (its key
/// bar's) first, then every key ([`lab_help`]), then the mouse.
pub fn scene_help(scene: Scene) -> Vec<(&'static str, &'static str)> {
    let acting = bar_actions(scene);
    let mut lines = vec![("", scene_heading(scene))];
    for row in LAB
        .iter()
        .filter(|row| row.bindings.iter().any(|(_, a)| acting.contains(a)))
    {
        lines.extend(help_lines(std::slice::from_ref::<Row<LabAction>>(row)));
    }
    lines.push(("", "every key:"));
    lines.extend(lab_help());
    lines.extend(MOUSE);
    lines
}

/// The two-body scene's help: the rows of [`LAB`] that act there first, then every key
/// (the others say on the status line why they do not act on two bodies).
pub fn bodies_help() -> Vec<(&'static str, &'static str)> {
    let acting: Vec<LabAction> = BODIES.iter().flat_map(|(a, _)| a.iter().copied()).collect();
    let mut lines = vec![("", "in the two-body scene:")];
    for row in LAB
        .iter()
        .filter(|row| row.bindings.iter().any(|(_, a)| acting.contains(a)))
    {
        lines.extend(help_lines(std::slice::from_ref::<Row<LabAction>>(row)));
    }
    lines.push(("", "every key (one body's say why not):"));
    lines.extend(lab_help());
    lines
}

/// The heading of the help's first lines.
fn scene_heading(scene: Scene) -> &'static str {
    match scene {
        Scene::Explore => "in the explore scene:",
        Scene::InfSup => "in the inf-sup scene:",
        Scene::Mesh => "in the mesh scene:",
        Scene::Convergence => "in the convergence scene:",
        Scene::Stress => "in the stress scene:",
    }
}

/// The mouse, in the help (off with `--no-mouse`).
const MOUSE: [(&str, &str); 3] = [
    ("mouse", "click a tab: its scene; the wheel scrolls"),
    ("", "help and log; a click on the pressure chart"),
    ("", "places the cursor (--no-mouse: no mouse)"),
];

#[cfg(test)]
mod tests {
    use super::*;

    /// Every scene's bar has three to six keys of its own, each bound in [`LAB`] to the
    /// action the bar names, and fits 80 columns; the help lists them first.
    #[test]
    fn each_scene_has_a_bar_read_from_the_key_table() {
        for scene in Scene::ALL {
            let bar = bar(scene, false);
            let own = bar.len() - 2;
            assert!((3..=6).contains(&own), "{scene:?}: {bar:?}");
            assert!(bar.iter().all(|(k, _)| !k.is_empty()), "{bar:?}");
            let width: usize = bar
                .iter()
                .map(|(k, w)| k.chars().count() + w.chars().count() + 3)
                .sum();
            assert!(width <= 80, "{scene:?}: {width}");
            let help = scene_help(scene);
            let every = help.iter().position(|l| l.1 == "every key:").unwrap();
            for action in bar_actions(scene) {
                let row = LAB
                    .iter()
                    .find(|r| r.bindings.iter().any(|(_, a)| *a == action))
                    .unwrap();
                assert!(
                    help[..every].iter().any(|l| l.0 == row.keys),
                    "{scene:?} {action:?}"
                );
            }
            assert!(help.iter().any(|l| l.1.contains("--no-mouse")), "{help:?}");
        }
        assert_eq!(bar(Scene::Explore, false)[0], ("←→".to_string(), "level"));
        assert_eq!(bar(Scene::Explore, false)[1], ("1-4".to_string(), "scheme"));
    }
}
