//! `s` and `S`: the displayed solution as CSV (the CLI's `--format csv`) or its pressure chart
//! as SVG ([`crate::plot`]) in a new file of the export directory (`--export-dir`, else the
//! current directory), named after the scenario, element, rule, level, ε and depth. Never
//! overwrites: the name
//! is fresh, and each file is written to a temporary name and then linked into place, which
//! fails if the name was taken meanwhile (see [`crate::plot::write_file`]).

use std::io::ErrorKind;
use std::path::{Path, PathBuf};

use crate::output::{Report, SolveReport};
use crate::plot::{chart_title, pressure_svg_string, write_file};
use crate::scenario::Scenario;

use super::app::{App, ExportKind, Msg, Scene};
pub use super::export_error::ExportError;
use super::protocol::Solved;

/// How many numbered names to try before giving up.
const MAX_TRIES: u32 = 1000;

/// Write `solved` to `<scenario>-<element>-<rule>-L<level>-eps<ε>-d<depth>[-N].csv` in `dir`;
/// returns the path (absolute when `dir` is).
pub fn export_csv(scenario: &Scenario, solved: &Solved, dir: &Path) -> Result<PathBuf, ExportError> {
    let report = SolveReport::new(scenario, solved.key.level, &solved.disc, &solved.solution);
    save_fresh(dir, &stem(scenario, solved), "csv", report.csv().as_bytes())
}

/// Write the pressure chart of `solved` to `<…>[-N].svg` in `dir` (the CSV export's names);
/// returns the path.
pub fn export_svg(scenario: &Scenario, solved: &Solved, dir: &Path) -> Result<PathBuf, ExportError> {
    let title = chart_title(
        &scenario.name,
        solved.key.element,
        solved.key.level,
        &solved.solution,
    );
    let svg = pressure_svg_string(&title, &solved.solution, scenario.half_model)?;
    save_fresh(dir, &stem(scenario, solved), "svg", svg.as_bytes())
}

/// Write the body and Γ_C of `solved` as VTU ([`crate::vtu`]) to `<stem>[-N].vtu` and the
/// same name with `.contact.vtu` in `dir`; returns the body's path.
pub fn export_vtu(scenario: &Scenario, solved: &Solved, dir: &Path) -> Result<PathBuf, ExportError> {
    let field = solved.stress_field(scenario).map_err(ExportError::Stress)?;
    let u = solved.u();
    let mesh = &solved.disc.mesh;
    let body = crate::vtu::xml(crate::vtu::body(mesh, u, &field))?;
    let contact = crate::vtu::xml(crate::vtu::contact(mesh, &solved.solution, u))?;
    let path = save_fresh(dir, &stem(scenario, solved), "vtu", &body)?;
    let second = crate::vtu::contact_path(&path);
    write_file(&second, &contact, false).map_err(|source| ExportError::WriteContact {
        path: second.clone(),
        source,
    })?;
    Ok(path)
}

/// `<scenario>-<element>-<rule>-L<level>-eps<ε>-d<depth>`, e.g.
/// `hertz-paper-q1-gauss1-L1-eps1e-6-d0.8`; a method other than the penalty is named after
/// the rule (`…-gauss1-alm-L1-…`; `exact` has ε = 0); with friction the law, μ or g and the
/// shift follow (`…-d0.35-coulomb0.3-xi0.0815`).
pub fn stem(scenario: &Scenario, solved: &Solved) -> String {
    let params = &solved.solution.params;
    let method = match params.method {
        crate::contact::Method::Penalty => String::new(),
        m => format!("-{}", m.name()),
    };
    // With friction: the law, μ or g, and the shift.
    let friction = solved.solution.friction.as_ref().map_or(String::new(), |f| {
        let law = f.friction.law;
        let value = law.mu().or(law.threshold()).unwrap_or(0.0);
        format!("-{}{value}-xi{}", law.name(), f.friction.shift)
    });
    format!(
        "{}-{}-{}{method}-L{}-eps{:e}-d{}{friction}",
        sanitize(&scenario.name),
        solved.key.element.name(),
        params.rule.name(),
        solved.key.level,
        params.epsilon,
        solved.key.depth
    )
}

/// Write `bytes` to the first free name `stem.ext`, `stem-1.ext`, … in `dir`.
fn save_fresh(dir: &Path, stem: &str, ext: &str, bytes: &[u8]) -> Result<PathBuf, ExportError> {
    for n in 0..MAX_TRIES {
        let path = dir.join(if n == 0 {
            format!("{stem}.{ext}")
        } else {
            format!("{stem}-{n}.{ext}")
        });
        match write_file(&path, bytes, false) {
            Ok(()) => return Ok(path),
            Err(e) if e.kind() == ErrorKind::AlreadyExists => continue,
            Err(source) => {
                return Err(ExportError::Write {
                    dir: dir.to_path_buf(),
                    source,
                });
            }
        }
    }
    Err(ExportError::NoFreeName {
        name: format!("{stem}.{ext}"),
        dir: dir.to_path_buf(),
    })
}

/// The scenario name reduced to characters safe in a file name.
fn sanitize(name: &str) -> String {
    name.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' || c == '.' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// Carry out [`Command::Export`] into `dir`: the reply for the app (a tour step is the lab's
/// business: see [`super::tour::author::save_step`]).
pub(super) fn export_shown(app: &App, dir: &Path) -> Msg {
    let result = match (app.current(), app.export_kind) {
        (_, ExportKind::TourStep) => Err(ExportError::TourStepInTour),
        (Some(solved), ExportKind::Csv) => {
            export_csv(&app.scenario, solved, dir).map(|p| p.display().to_string())
        }
        (Some(solved), ExportKind::Svg) => export_svg(&app.scenario, solved, dir).map(|p| {
            // The SVG is the pressure chart, whatever the scene: said where another is shown.
            let chart = if app.scene == Scene::Explore {
                ""
            } else {
                " (explore's pressure chart)"
            };
            format!("{}{chart}", p.display())
        }),
        (Some(solved), ExportKind::Vtu) => export_vtu(&app.scenario, solved, dir).map(|p| {
            let contact = crate::vtu::contact_path(&p);
            format!("{} and {}", p.display(), contact.display())
        }),
        (None, _) => Err(ExportError::NoSolution),
    };
    Msg::Exported(result.map_err(std::sync::Arc::new))
}
