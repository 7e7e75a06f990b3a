//! `T` in the lab: the lab's current state (scenario, scheme, level, the grading when it
//! grades or differs from the scenario's, the integration when switched from the scenario's,
//! ε, method and its parameters, depth, friction, scene, what it compares, overlays, zoom, the
//! stress quantity) added as a `[[step]]` to a tour file, with a caption left for the teacher
//! to write. The file is `--tour-out FILE`, else `riplab-tour.toml` in the export directory;
//! it is created if it does not exist, and added to only if it already reads as a valid tour
//! and stays within the size a tour file may have, so that `T` never changes another kind of
//! file nor makes a tour unreadable. A screen whose friction a step would not play (the tour's
//! check refuses it: [`super::friction_step::check`]) is not written. `riplab tour --tour
//! FILE` plays the steps back to the same screens.

use std::io::Write as _;
use std::path::{Path, PathBuf};

use crate::contact::method::Gamma0;
use crate::fem::Integration;
use crate::grading::{Grading, RefineEdges};
use crate::input::read::MAX_FILE_BYTES;
use crate::scheme::Scheme;
use crate::stress::Quantity;

use super::super::app::{App, Compare, Notice};
use super::errors::AuthorError;
use super::{MAX_TITLE_WIDTH, Tour};

/// The name of the tour file in the export directory when `--tour-out` is not given.
pub const DEFAULT_TOUR_OUT: &str = "riplab-tour.toml";

/// The caption a new step is given, for the teacher to replace.
pub const CAPTION_PLACEHOLDER: &str =
    "(write this step's caption: what to look at, in at most 4 lines of 96 characters)";

/// Where the lab adds tour steps, and the scenario file it was opened on.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct LabSource {
    /// The tour file (absolute).
    pub tour_out: PathBuf,
    /// The lab's scenario file (absolute); None: the paper's problem.
    pub scenario_file: Option<PathBuf>,
}

/// What the first lines of a new tour file say.
const HEADER: &str = "# A tour written by riplab's lab: each `T` added the lab's screen as a [[step]].
# Write each step's title and caption (at most 4 lines of 96 characters), then play it:
#   riplab tour --tour THIS_FILE      (riplab tour --check THIS_FILE lists the steps)
# The keys a step may set are listed in riplab's tours/paper.toml.

title = \"A tour from the lab\"
";

/// The `[[step]]` table of the lab's state, its scenario given as `scenario` (a path relative
/// to the tour file's directory, or absolute; None: the tour's scenario).
pub fn step_toml(app: &App, scenario: Option<&str>) -> String {
    let s = &app.settings;
    let scheme = Scheme::new(s.element, s.rule).label();
    let title: String = format!(
        "{scheme} at level {}, {}: {}",
        s.level,
        s.method.name(),
        app.scene.name()
    )
    .chars()
    .take(MAX_TITLE_WIDTH)
    .collect();
    let mut lines = vec![
        "[[step]]".to_string(),
        format!("title = {}", text(&title)),
        format!("caption = {}", text(CAPTION_PLACEHOLDER)),
    ];
    if let Some(path) = scenario {
        lines.push(format!("scenario = {}", text(path)));
    }
    lines.push(format!("scheme = {}", text(&scheme)));
    lines.push(format!("level = {}", s.level));
    if s.refine_edges.grades() || s.refine_edges != app.scenario.grading() {
        lines.push(format!("refine_edges = {}", grading(s.refine_edges)));
    }
    if s.integration != app.scenario.integration {
        let name = match s.integration {
            Integration::Full => "full",
            Integration::Selective => "selective",
        };
        lines.push(format!("integration = {}", text(name)));
    }
    lines.push(format!("epsilon = {}", float(s.epsilon)));
    lines.push(format!("method = {}", text(s.method.name())));
    if let Some(theta) = s.method.theta() {
        lines.push(format!("theta = {theta}"));
    }
    match s.method.gamma0() {
        Some(Gamma0::Auto) => lines.push("gamma0 = \"auto\"".into()),
        Some(Gamma0::Given(g)) => lines.push(format!("gamma0 = {}", float(g))),
        None => {}
    }
    if let Some(tol) = s.method.alm_tol() {
        lines.push(format!("alm_tol = {}", float(tol)));
    }
    lines.push(format!("depth = {}", float(s.depth)));
    lines.extend(super::friction_step::lines(
        &s.friction,
        &app.scenario.friction,
        float,
    ));
    lines.push(format!("scene = {}", text(app.scene.name())));
    if app.compare == Compare::Methods {
        lines.push("compare = \"methods\"".into());
    }
    let overlays: Vec<String> = [
        (app.guides.gap, "gap"),
        (app.guides.hertz, "hertz"),
        (app.guides.circle, "circle"),
        (app.guides.mindlin, "mindlin"),
        (app.all_levels, "all-levels"),
        (app.zoom, "zoom"),
    ]
    .into_iter()
    .filter(|&(on, _)| on)
    .map(|(_, name)| text(name))
    .collect();
    if !overlays.is_empty() {
        lines.push(format!("overlays = [{}]", overlays.join(", ")));
    }
    if app.stress_quantity != Quantity::PrincipalShear {
        lines.push(format!("quantity = {}", text(app.stress_quantity.name())));
    }
    lines.join("\n") + "\n"
}

/// A grading as `[mesh] refine_edges` takes it: a count of passes at the contact edges, or
/// `"auto"`, or `"Nz"` over the contact zone.
fn grading(value: Grading) -> String {
    match value {
        Grading::Edges(RefineEdges::Passes(n)) => n.to_string(),
        other => text(&other.to_string()),
    }
}

/// A TOML string (quoted and escaped by the toml crate).
fn text(value: &str) -> String {
    toml::Value::String(value.to_string()).to_string()
}

/// A TOML float as a person writes it: plain from 1e-4 to 1e6, else with an exponent (`1e-6`,
/// never `0.000001`); both are Rust's shortest forms, which read back to the same number.
fn float(value: f64) -> String {
    let plain = format!("{value}");
    if (1e-4..1e6).contains(&value.abs()) && plain.contains('.') {
        plain
    } else if (1e-4..1e6).contains(&value.abs()) {
        format!("{plain}.0")
    } else {
        format!("{value:e}")
    }
}

/// Add the lab's state as a step to the tour file of `source`: what the status line says.
pub fn save_step(app: &App, source: &LabSource) -> Notice {
    match add_step(app, source) {
        Ok((n, path)) => Notice::info(format!(
            "added step {n} to {} (write its caption there)",
            crate::text::sanitize(&path.display().to_string())
        )),
        Err(e) => Notice::failure(format!("tour step not saved: {e}")),
    }
}

/// Add the step; the step's number and the file.
fn add_step(app: &App, source: &LabSource) -> Result<(usize, PathBuf), AuthorError> {
    let path = &source.tour_out;
    let shown = || crate::text::sanitize(&path.display().to_string()).into_owned();
    let dir = path.parent().unwrap_or(Path::new("."));
    let scenario = match &source.scenario_file {
        None => None,
        Some(file) => {
            let relative = file.strip_prefix(dir).unwrap_or(file);
            Some(
                relative
                    .to_str()
                    .ok_or_else(|| AuthorError::NotUtf8 { path: file.clone() })?
                    .to_string(),
            )
        }
    };
    super::friction_step::check(app)?;
    let step = step_toml(app, scenario.as_deref());
    let exists = std::fs::symlink_metadata(path).is_ok();
    let (n, text) = if exists {
        let (tour, size) = Tour::read(path).map_err(|source| AuthorError::Invalid { source })?;
        let text = format!("\n{step}");
        if (size + text.len()) as u64 > MAX_FILE_BYTES {
            return Err(AuthorError::TooLarge {
                path: shown(),
                size,
                adding: text.len(),
            });
        }
        (tour.steps.len() + 1, text)
    } else {
        (1, format!("{HEADER}\n{step}"))
    };
    let mut file = if exists {
        std::fs::OpenOptions::new().append(true).open(path)
    } else {
        std::fs::File::create_new(path)
    }
    .map_err(|source| AuthorError::Write {
        path: shown(),
        source,
    })?;
    file.write_all(text.as_bytes())
        .and_then(|()| file.sync_all())
        .map_err(|source| AuthorError::Write {
            path: shown(),
            source,
        })?;
    Ok((n, path.clone()))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Floats are written as a person writes them and read back to the same number.
    #[test]
    fn floats_read_back_exactly() {
        for (value, written) in [
            (1e-6, "1e-6"),
            (1e-10, "1e-10"),
            (0.7, "0.7"),
            (1.0, "1.0"),
            (0.0, "0e0"),
            (2.5e7, "2.5e7"),
            (0.1 + 0.2, "0.30000000000000004"),
        ] {
            assert_eq!(float(value), written);
            let back: toml::Table = toml::from_str(&format!("x = {written}")).unwrap();
            assert_eq!(back["x"].as_float(), Some(value), "{written}");
        }
    }

    /// Text from the lab (a scenario's name in a path) is quoted and escaped.
    #[test]
    fn strings_are_escaped() {
        let back: toml::Table = toml::from_str(&format!("x = {}", text("a \"b\"\n\\c"))).unwrap();
        assert_eq!(back["x"].as_str(), Some("a \"b\"\n\\c"));
    }
}
