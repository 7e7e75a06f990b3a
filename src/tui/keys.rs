//! Every key of the lab and of the tour, in one table each. The dispatch
//! ([`lab_action`], [`tour_action`]), the help overlays and docs/lab.md's key table are all
//! read from these tables (a test keeps docs/lab.md equal to [`readme_table`]), so that a key
//! cannot do one thing and be documented as another.

use crossterm::event::KeyCode;

/// One overlay of the pressure chart ([`super::app::Guides`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Guide {
    /// −g, scaled to p's axis (`g`).
    Gap,
    /// Hertz's pressure for the computed load (`h`; a cylinder).
    Hertz,
    /// The exact circular indenter's pressure for the computed load (`o`; a cylinder).
    Circle,
    /// Cattaneo–Mindlin's traction q (`M`; a cylinder with Coulomb friction).
    Mindlin,
}

/// What an export key writes ([`super::app::Command::Export`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ExportKind {
    /// `s`: the solution's numbers as CSV.
    #[default]
    Csv,
    /// `S`: the pressure chart as SVG.
    Svg,
    /// `v`: the body and Γ_C as VTU files.
    Vtu,
    /// `T`: the lab's state as a step of a tour file (`--tour-out`).
    TourStep,
}

/// What a key does in the lab.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LabAction {
    /// Quit the lab.
    Quit,
    /// Back: close the help or the log, else leave the projector view; never quits.
    Back,
    /// Open the help overlay.
    Help,
    /// The next coarser mesh level.
    Coarser,
    /// The next finer mesh level (at most [`super::app::MAX_APP_LEVEL`]).
    Finer,
    /// The paper's scheme M1–M4 (1–4).
    Scheme(u8),
    /// The next contact rule.
    NextRule,
    /// The next element (q1, q2, p1).
    NextElement,
    /// ε × 10.
    EpsilonUp,
    /// ε ÷ 10.
    EpsilonDown,
    /// The next contact method (penalty, exact, alm, nitsche).
    NextMethod,
    /// The convergence scene compares the schemes or the methods.
    Compare,
    /// Depth − [`super::app::DEPTH_STEP`].
    Shallower,
    /// Depth + [`super::app::DEPTH_STEP`].
    Deeper,
    /// The next scene.
    NextScene,
    /// The previous scene.
    PreviousScene,
    /// Toggle one overlay of the pressure chart (−g, Hertz, the circle, Mindlin).
    Guide(Guide),
    /// Zoom to the contact zone (p̄ > 0) and back.
    Zoom,
    /// The next grading: 0, 1, 2, 3 passes at the contact edges, auto, 1z, 2z, 3z over the
    /// contact zone.
    Grade,
    /// The stiffness's volumetric integration: full ↔ selective
    /// ([`crate::fem::Integration`]).
    Integration,
    /// Toggle the inf-sup estimate at every level up to the current one.
    AllLevels,
    /// The stress scene's next quantity (τ₁, von Mises, σ_yy).
    NextQuantity,
    /// Write the displayed solution to a new file of this kind.
    Export(ExportKind),
    /// Back to the scenario's settings.
    Reset,
    /// Ctrl-Z: give the terminal back until resumed.
    Suspend,
    /// Show or hide the cursor on the pressure chart and the stress map.
    Cursor,
    /// The cursor one contact point left.
    CursorLeft,
    /// The cursor one contact point right.
    CursorRight,
    /// The projector view: the scene's main chart on the whole screen, and back.
    Projector,
    /// Open the log of every message since the lab started.
    Log,
    /// The next friction law: none, coulomb, tresca (a full model only).
    NextLaw,
    /// μ (coulomb) one step up its list, or g (tresca) × 1.25.
    FrictionUp,
    /// μ one step down, or g ÷ 1.25.
    FrictionDown,
    /// The shift ξ × 1.25.
    ShiftUp,
    /// The shift ξ ÷ 1.25.
    ShiftDown,
    /// Two bodies: the next discretisation across the interface (nts, nts2, mortar,
    /// mortar-dual, rip with each rule; docs/design.md §12).
    NextContact,
    /// Two bodies: the previous element ratio across the interface.
    RatioDown,
    /// Two bodies: the next element ratio across the interface.
    RatioUp,
    /// Two bodies: the upper mesh's offset a tenth of its element down.
    OffsetDown,
    /// Two bodies: the upper mesh's offset a tenth of its element up.
    OffsetUp,
}

/// What a key does in the tour (any other key is the lab's).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TourAction {
    /// The next step.
    Next,
    /// The previous step.
    Previous,
    /// The first step.
    First,
    /// The last step.
    Last,
    /// Scroll a long caption up a line.
    ScrollUp,
    /// Scroll a long caption down a line.
    ScrollDown,
    /// Quit the tour (asking once before its last step).
    Quit,
    /// Open the help overlay.
    Help,
}

/// One row of a key table: the keys as the help writes them, what they do (one help line
/// each; the README joins them), and the keys with their actions.
pub struct Row<A: 'static> {
    /// The keys as the help writes them (`Tab  Shift-Tab`).
    pub keys: &'static str,
    /// What they do, one help line each.
    pub what: &'static [&'static str],
    /// Each key with its action.
    pub bindings: &'static [(KeyCode, A)],
}

use KeyCode::Char;
use LabAction as L;
use TourAction as T;

/// The lab's keys (and with Ctrl held: [`CONTROL`]).
pub const LAB: &[Row<LabAction>] = &[
    Row {
        keys: "q",
        what: &["quit"],
        bindings: &[(Char('q'), L::Quit)],
    },
    Row {
        keys: "Esc",
        what: &["back: close help, log or projector view"],
        bindings: &[(KeyCode::Esc, L::Back)],
    },
    Row {
        keys: "?",
        what: &["this help (↑ ↓ scroll, other keys close)"],
        bindings: &[(Char('?'), L::Help)],
    },
    Row {
        keys: "←  →   [  ]",
        what: &[LEVELS],
        bindings: &[
            (KeyCode::Left, L::Coarser),
            (KeyCode::Right, L::Finer),
            (Char('['), L::Coarser),
            (Char(']'), L::Finer),
        ],
    },
    Row {
        keys: "1 2 3 4",
        what: &["the paper's schemes M1–M4"],
        bindings: &[
            (Char('1'), L::Scheme(1)),
            (Char('2'), L::Scheme(2)),
            (Char('3'), L::Scheme(3)),
            (Char('4'), L::Scheme(4)),
        ],
    },
    Row {
        keys: "r  e",
        what: &["next contact rule / element (q1, q2, p1)"],
        bindings: &[(Char('r'), L::NextRule), (Char('e'), L::NextElement)],
    },
    Row {
        keys: "+  -",
        what: &[EPSILON],
        bindings: &[
            (Char('+'), L::EpsilonUp),
            (Char('='), L::EpsilonUp),
            (Char('-'), L::EpsilonDown),
            (Char('_'), L::EpsilonDown),
        ],
    },
    Row {
        keys: "m",
        what: &["next method: penalty, exact, alm, nitsche"],
        bindings: &[(Char('m'), L::NextMethod)],
    },
    Row {
        keys: "w",
        what: &["convergence: compare schemes / methods"],
        bindings: &[(Char('w'), L::Compare)],
    },
    Row {
        keys: "d  D",
        what: &[DEPTH],
        bindings: &[(Char('d'), L::Shallower), (Char('D'), L::Deeper)],
    },
    Row {
        keys: "Tab  Shift-Tab",
        what: &["next / previous scene"],
        bindings: &[(KeyCode::Tab, L::NextScene), (KeyCode::BackTab, L::PreviousScene)],
    },
    Row {
        keys: "g  h  o  M",
        what: &[
            "overlays, each on its own: gap −g /",
            "Hertz + / circle o / Mindlin q *",
        ],
        bindings: &[
            (Char('g'), L::Guide(Guide::Gap)),
            (Char('h'), L::Guide(Guide::Hertz)),
            (Char('o'), L::Guide(Guide::Circle)),
            (Char('M'), L::Guide(Guide::Mindlin)),
        ],
    },
    Row {
        keys: "F",
        what: &["friction law: none, coulomb, tresca"],
        bindings: &[(Char('F'), L::NextLaw)],
    },
    Row {
        keys: "u  U",
        what: &["friction μ (or g) down / up a step"],
        bindings: &[(Char('u'), L::FrictionDown), (Char('U'), L::FrictionUp)],
    },
    Row {
        keys: "<  >",
        what: &["shift ξ ÷ 1.25 / × 1.25 after the press"],
        bindings: &[(Char('<'), L::ShiftDown), (Char('>'), L::ShiftUp)],
    },
    Row {
        keys: "z",
        what: &["zoom to the contact zone (p̄ > 0) and back"],
        bindings: &[(Char('z'), L::Zoom)],
    },
    Row {
        keys: "E",
        what: &["grading: 0–3, auto (edges), 1z–3z (zone)"],
        bindings: &[(Char('E'), L::Grade)],
    },
    Row {
        keys: "i",
        what: &["volumetric integration: full / selective"],
        bindings: &[(Char('i'), L::Integration)],
    },
    Row {
        keys: "a",
        what: &["inf-sup at every level up to this one"],
        bindings: &[(Char('a'), L::AllLevels)],
    },
    Row {
        keys: "s  S  v",
        what: &[
            "export CSV / SVG / VTU (new files, ε and",
            "d in the name; --export-dir sets where)",
        ],
        bindings: &[
            (Char('s'), L::Export(ExportKind::Csv)),
            (Char('S'), L::Export(ExportKind::Svg)),
            (Char('v'), L::Export(ExportKind::Vtu)),
        ],
    },
    Row {
        keys: "T",
        what: &["add this screen as a step to a tour file"],
        bindings: &[(Char('T'), L::Export(ExportKind::TourStep))],
    },
    Row {
        keys: "x  ,  .",
        what: &["cursor (pressure, stress map); , . move it"],
        bindings: &[
            (Char('x'), L::Cursor),
            (Char(','), L::CursorLeft),
            (Char('.'), L::CursorRight),
        ],
    },
    Row {
        keys: "f",
        what: &["projector: the scene's chart, whole screen"],
        bindings: &[(Char('f'), L::Projector)],
    },
    Row {
        keys: "l",
        what: &["log of every message (↑ ↓ scroll)"],
        bindings: &[(Char('l'), L::Log)],
    },
    Row {
        keys: "c",
        what: &["stress scene: τ₁ / von Mises / σ_yy"],
        bindings: &[(Char('c'), L::NextQuantity)],
    },
    Row {
        keys: "n",
        what: &["two bodies: next contact (nts … rip)"],
        bindings: &[(Char('n'), L::NextContact)],
    },
    Row {
        keys: "k  K",
        what: &["two bodies: element ratio 1:1 2:3 3:4 5:7"],
        bindings: &[(Char('k'), L::RatioDown), (Char('K'), L::RatioUp)],
    },
    Row {
        keys: "j  J",
        what: &["two bodies: offset − / + 0.1 element"],
        bindings: &[(Char('j'), L::OffsetDown), (Char('J'), L::OffsetUp)],
    },
    Row {
        keys: "0",
        what: &["reset to the scenario's settings"],
        bindings: &[(Char('0'), L::Reset)],
    },
];

/// The lab's keys with Ctrl held (they work while the help is open).
pub const CONTROL: &[Row<LabAction>] = &[Row {
    keys: "Ctrl-C  Ctrl-Z",
    what: &["quit / suspend (fg resumes)"],
    bindings: &[(Char('c'), L::Quit), (Char('z'), L::Suspend)],
}];

/// The help's words for [`super::app::MAX_APP_LEVEL`], [`super::app::EPSILON_RANGE`] and
/// [`super::app::DEPTH_STEP`] (a test
/// keeps them equal).
const LEVELS: &str = "coarser / finer mesh level (0 to 7)";
const EPSILON: &str = "ε × 10 / ε ÷ 10 (1e-14 to 1e2)";
const DEPTH: &str = "depth − 0.1 / + 0.1";

/// The tour's own keys; every other key goes to the lab inside the step.
pub const TOUR: &[Row<TourAction>] = &[
    Row {
        keys: "Space  →  Enter",
        what: &["next step (PageDown too)"],
        bindings: &[
            (Char(' '), T::Next),
            (KeyCode::Right, T::Next),
            (KeyCode::Enter, T::Next),
            (KeyCode::PageDown, T::Next),
        ],
    },
    Row {
        keys: "←  Backspace",
        what: &["previous step (PageUp too)"],
        bindings: &[
            (KeyCode::Left, T::Previous),
            (KeyCode::Backspace, T::Previous),
            (KeyCode::PageUp, T::Previous),
        ],
    },
    Row {
        keys: "Home  End",
        what: &["first / last step"],
        bindings: &[(KeyCode::Home, T::First), (KeyCode::End, T::Last)],
    },
    Row {
        keys: "↑  ↓",
        what: &["scroll a long caption"],
        bindings: &[(KeyCode::Up, T::ScrollUp), (KeyCode::Down, T::ScrollDown)],
    },
    Row {
        keys: "q  Ctrl-C",
        what: &["quit the tour (q asks once before the end)"],
        bindings: &[(Char('q'), T::Quit)],
    },
    Row {
        keys: "?",
        what: &["show this help (any key closes it)"],
        bindings: &[(Char('?'), T::Help)],
    },
];

fn find<A: Copy>(table: &[Row<A>], code: KeyCode) -> Option<A> {
    table
        .iter()
        .flat_map(|row| row.bindings)
        .find(|(k, _)| *k == code)
        .map(|&(_, a)| a)
}

/// The lab's action for `code`, with Ctrl held or not, if it has one.
pub fn lab_action(code: KeyCode, control: bool) -> Option<LabAction> {
    if control {
        // Ctrl with a letter arrives as either case depending on the terminal.
        let code = match code {
            Char(c) => Char(c.to_ascii_lowercase()),
            other => other,
        };
        find(CONTROL, code)
    } else {
        find(LAB, code)
    }
}

/// The tour's action for `code`, if it has one (otherwise the key is the lab's).
pub fn tour_action(code: KeyCode) -> Option<TourAction> {
    find(TOUR, code)
}

/// The help lines of `rows`: (keys, what), one per line of `what`, the keys on the first.
pub fn help_lines<A>(rows: &[Row<A>]) -> Vec<(&'static str, &'static str)> {
    rows.iter()
        .flat_map(|row| {
            row.what
                .iter()
                .enumerate()
                .map(move |(i, what)| (if i == 0 { row.keys } else { "" }, *what))
        })
        .collect()
}

/// The lab's help overlay: its keys, the Ctrl keys and a note on units.
pub fn lab_help() -> Vec<(&'static str, &'static str)> {
    let mut lines = help_lines(LAB);
    lines.extend(help_lines(CONTROL));
    lines.extend([
        ("", "p, p̄, E share a unit, x is a length; load"),
        ("", "P = ∫p dx per unit thickness (full: both)"),
    ]);
    lines
}

/// docs/lab.md's key table (Markdown), from [`LAB`] and [`CONTROL`].
#[cfg(test)]
pub fn readme_table() -> String {
    let mut out = String::from("| key | action |\n|---|---|\n");
    for row in LAB.iter().chain(CONTROL) {
        let keys: Vec<String> = row.keys.split_whitespace().map(|k| format!("`{k}`")).collect();
        out.push_str(&format!("| {} | {} |\n", keys.join(" "), row.what.join(" ")));
    }
    out
}

/// `notes` after the lab's keys, one row each as the help writes them: `riplab render
/// --help`'s text after the options (what `--keys` can press), read from [`LAB`] like the
/// help overlay and the README's table.
pub fn with_lab_keys(notes: &str) -> String {
    let mut out = String::from("Keys (for --keys; the lab's):\n");
    for row in LAB {
        out.push_str(&format!("  {:<16}{}\n", row.keys, row.what.join(" ")));
    }
    out.push('\n');
    out.push_str(notes);
    out
}

/// The lab's keys that work inside a tour's step (those the tour does not take), as the
/// lab's help writes them, row by row: for the tour's help.
pub fn lab_keys_in_tour() -> Vec<String> {
    let taken: Vec<&str> = TOUR.iter().flat_map(|row| row.keys.split_whitespace()).collect();
    LAB.iter()
        .chain(CONTROL)
        .map(|row| {
            row.keys
                .split_whitespace()
                .filter(|k| !taken.contains(k))
                .collect::<Vec<_>>()
                .join(" ")
        })
        .filter(|keys| !keys.is_empty())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::super::app::{DEPTH_STEP, EPSILON_RANGE, MAX_APP_LEVEL};
    use super::*;

    /// No key is bound twice in a table, and the help's texts quote the app's constants.
    #[test]
    fn every_key_is_bound_once() {
        fn unique<A>(table: &[Row<A>]) {
            let codes: Vec<KeyCode> = table
                .iter()
                .flat_map(|r| r.bindings.iter().map(|b| b.0))
                .collect();
            for (i, c) in codes.iter().enumerate() {
                assert!(!codes[..i].contains(c), "{c:?} bound twice");
            }
        }
        unique(LAB);
        unique(CONTROL);
        unique(TOUR);
        assert_eq!(EPSILON_RANGE, (1e-14, 1e2), "the help says 1e-14 to 1e2");
        assert_eq!(DEPTH_STEP, 0.1, "the help says 0.1");
        assert!(LEVELS.contains(&MAX_APP_LEVEL.to_string()));
    }
}
