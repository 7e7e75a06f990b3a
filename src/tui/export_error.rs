//! Why a lab's export wrote nothing ([`super::export`]), in a module of its own so that the
//! worker's replies ([`super::protocol`]) can carry it without depending on the exports.

use std::path::PathBuf;

use crate::plot::PlotError;
use crate::stress::StressError;
use crate::vtu::VtuError;

/// Why an export (`s`, `S`, `v`, or `T` inside a tour) wrote nothing.
#[derive(Debug, thiserror::Error)]
pub enum ExportError {
    /// `T` inside a tour: tour steps are the lab's (`riplab --tour-out FILE`).
    #[error("T adds a tour step in the lab (riplab --tour-out FILE), not inside a tour")]
    TourStepInTour,
    /// Nothing solved yet.
    #[error("no solution to export")]
    NoSolution,
    /// The file could not be written in `dir`.
    #[error("{}: {source}", dir.display())]
    Write {
        /// The export directory.
        dir: PathBuf,
        /// What the system said.
        source: std::io::Error,
    },
    /// Every numbered name is taken.
    #[error("no free file name for {name} in {}", dir.display())]
    NoFreeName {
        /// The first name tried (`stem.ext`).
        name: String,
        /// The export directory.
        dir: PathBuf,
    },
    /// The VTU's second file (Γ_C) could not be written.
    #[error("{}: {source}", path.display())]
    WriteContact {
        /// The `.contact.vtu` file.
        path: PathBuf,
        /// What the system said.
        source: std::io::Error,
    },
    /// The pressure chart could not be drawn.
    #[error(transparent)]
    Chart(#[from] PlotError),
    /// The VTU could not be made.
    #[error(transparent)]
    Vtu(#[from] VtuError),
    /// The stresses the VTU carries could not be computed.
    #[error(transparent)]
    Stress(#[from] StressError),
}
