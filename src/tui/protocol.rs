//! What the lab and its worker thread say to each other: the keys that name a solve, an
//! inf-sup estimate or a study, the requests, the progress reports and the replies, and the
//! finished solve ([`Solved`]) they share. The app ([`super::app`]) and the worker
//! ([`super::worker`]) both depend on this module and not on each other's insides.

use std::sync::{Arc, OnceLock};
use std::time::Instant;

use crossterm::event::{KeyEvent, MouseEvent};

use super::export_error::ExportError;
use super::lab_error::LabError;
use crate::contact::friction::Friction;
use crate::contact::method::Gamma0;
use crate::contact::solution::Solution;
use crate::contact::{Method, Rule};
use crate::discretization::Discretization;
use crate::fem::Integration;
use crate::grading::Grading;
use crate::mesh::Element;
use crate::mesh::MAX_LEVEL;
use crate::scenario::Scenario;
use crate::scheme::Scheme;
use crate::stress::{StressError, StressField};
use crate::study::StudyRow;

use super::beta::InfSup;
use super::shown::Shown;

/// Everything a contact solve depends on (the scenario aside).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SolveKey {
    /// The mesh level.
    pub level: u32,
    /// The displacement element.
    pub element: Element,
    /// The contact rule, whose points carry p.
    pub rule: Rule,
    /// The contact method (`m` cycles it).
    pub method: Method,
    /// The penalty parameter of `penalty` and `alm` (kept while another method is shown).
    pub epsilon: f64,
    /// The obstacle's depth d.
    pub depth: f64,
    /// How the solve grades its mesh: at the contact edges or over the contact zone (`E`
    /// cycles it; docs/design.md §6).
    pub refine_edges: Grading,
    /// How the stiffness's volumetric part is integrated (`i` toggles full and selective;
    /// [`Integration`]): each has its own discretisation.
    pub integration: Integration,
    /// The friction law and the shift after the press (`F`, `u`/`U`, `<`/`>`; docs/design.md
    /// §11): a solve with friction is another solve.
    pub friction: Friction,
}

/// Everything an inf-sup estimate depends on (the scenario aside).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct InfSupKey {
    /// The mesh level.
    pub level: u32,
    /// The displacement element.
    pub element: Element,
    /// The contact rule, whose points span the pressure space Q_h.
    pub rule: Rule,
}

/// What the convergence scene compares (`w` toggles).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Compare {
    /// The paper's schemes M1–M4, each with the lab's method.
    #[default]
    Schemes,
    /// The contact methods (penalty, alm, nitsche, exact), each on the lab's scheme.
    Methods,
}

/// What a work–precision study depends on: the scenario (by name), the finest level
/// studied, and the schemes and methods it runs (each scheme with each method at levels
/// 0..=`max_level`, at `epsilon`) against the Q2 reference at `max_level + 1`.
#[derive(Clone, Debug, PartialEq)]
pub struct StudyKey {
    /// The scenario's name.
    pub scenario: String,
    /// The finest level studied (levels 0..=`max_level`).
    pub max_level: u32,
    /// What the scene compares (and so how it draws the rows).
    pub compare: Compare,
    /// The schemes (element, rule) run, in the legend's order.
    pub schemes: Vec<(Element, Rule)>,
    /// The methods run, in the legend's order.
    pub methods: Vec<Method>,
    /// The penalty parameter of `penalty` and `alm` (the others do not use it).
    pub epsilon: f64,
    /// How the stiffness's volumetric part is integrated (the lab's `i`).
    pub integration: Integration,
    /// The lab's grading (`E`, at the edges or over the zone): when it grades, each scheme and
    /// method also has a series graded so at every level, beside the uniform one (`riplab
    /// study --refine-edges 0,N` or `0,Nz`).
    pub refine_edges: Grading,
    /// The friction of every row and of the reference (the lab's `F`; boxed: the study's
    /// key travels in the worker's replies, which stay small).
    pub friction: Box<Friction>,
}

/// A method's parameters and ε are finite ([`Method::check`], [`super::app::EPSILON_RANGE`]),
/// so equality is an equivalence.
impl Eq for StudyKey {}

impl std::hash::Hash for StudyKey {
    fn hash<H: std::hash::Hasher>(&self, state: &mut H) {
        self.scenario.hash(state);
        self.max_level.hash(state);
        self.compare.hash(state);
        self.schemes.hash(state);
        self.epsilon.to_bits().hash(state);
        self.integration.hash(state);
        self.refine_edges.to_string().hash(state);
        super::friction_settings::hash_friction(&self.friction, state);
        for m in &self.methods {
            m.name().hash(state);
            m.theta().hash(state);
            // `auto` as None, a given γ₀ as its bits.
            m.gamma0()
                .map(|g| match g {
                    Gamma0::Auto => None,
                    Gamma0::Given(g) => Some(g.to_bits()),
                })
                .hash(state);
            m.alm_tol().map(f64::to_bits).hash(state);
        }
    }
}

impl StudyKey {
    /// The level of the reference solution.
    pub fn reference_level(&self) -> u32 {
        self.max_level + 1
    }

    /// What is compared, for messages: `M1–M4 (penalty)` or `the methods on M3`, with
    /// `, uniform and +2e` when graded series go beside the uniform ones, and the friction
    /// when on (`… with coulomb μ = 0.3, shift ξ = 0.0815`).
    pub fn label(&self) -> String {
        let graded = self
            .graded_suffix()
            .map(|g| format!(", uniform and {g}"))
            .unwrap_or_default();
        let compared = match self.compare {
            Compare::Schemes => {
                let methods: Vec<&str> = self.methods.iter().map(|m| m.name()).collect();
                format!("M1–M4 ({})", methods.join(", "))
            }
            Compare::Methods => {
                let schemes: Vec<String> = self
                    .schemes
                    .iter()
                    .map(|&(e, r)| Scheme::new(e, r).label())
                    .collect();
                format!("the methods on {}", schemes.join(", "))
            }
        };
        if self.friction.is_on() {
            format!(
                "{compared}{graded} with {}",
                super::friction_settings::label(&self.friction)
            )
        } else {
            compared + &graded
        }
    }
}

/// A finished study: one row per scheme, method and level, in the key's order (scheme, then
/// method, then level).
#[derive(Clone, Debug)]
pub struct Study {
    /// What was studied.
    pub key: StudyKey,
    /// The rows, in the key's order.
    pub rows: Vec<StudyRow>,
}

/// A study to run; dropped unstarted if a newer generation exists (a running one cannot be
/// stopped, and its reply is dropped by the app if a newer study was asked for meanwhile).
#[derive(Clone, Debug, PartialEq)]
pub struct StudyRequest {
    /// Orders the requests: a newer one supersedes this.
    pub generation: u64,
    /// The study to run.
    pub key: StudyKey,
}

/// A solve to run; `generation` orders requests (a newer one cancels an older one).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SolveRequest {
    /// Orders the requests: a newer one cancels this.
    pub generation: u64,
    /// The solve to run.
    pub key: SolveKey,
}

/// The stresses of `solved` to compute (into its `stresses`, shared with the app).
#[derive(Clone, Debug)]
pub struct StressRequest {
    /// The solve whose stresses to compute.
    pub solved: Arc<Solved>,
}

/// Two requests are the same when they are for the same solution.
impl PartialEq for StressRequest {
    fn eq(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.solved, &other.solved)
    }
}

/// The displacement of `solved` to compute (into its `displacement`): the worker computes it
/// after every solve, and passes over one whose solve a newer one followed (a burst of keys);
/// the app asks for it when it comes back to such a solution ([`super::app::Command::Supersede`]).
#[derive(Clone, Debug)]
pub struct DisplaceRequest {
    /// The solve whose displacement to compute.
    pub solved: Arc<Solved>,
}

/// Two requests are the same when they are for the same solution.
impl PartialEq for DisplaceRequest {
    fn eq(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.solved, &other.solved)
    }
}

/// An inf-sup estimate to run; dropped unstarted if a newer generation exists.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InfSupRequest {
    /// Orders the requests: this is dropped unstarted when a newer one exists.
    pub generation: u64,
    /// The estimate to run.
    pub key: InfSupKey,
}

/// Where a running solve or study is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Progress {
    /// Assembling and factorising K for a new mesh of `unknowns` unknowns at `level`, begun
    /// at `started` and expected to take `estimate_ms` (see [`super::eta`]).
    Assembling {
        /// The level being built.
        level: u32,
        /// Its number of unknowns.
        unknowns: usize,
        /// When the build began.
        started: Instant,
        /// What the build is expected to take, ms.
        estimate_ms: f64,
        /// The method whose preparation the build includes (or is: Nitsche's layer on a mesh
        /// already built), when it is long work (Nitsche's).
        method: Option<&'static str>,
    },
    /// A study's stage: the reference (`level` None) or the schemes at `level`.
    Study {
        /// The level of the schemes; None for the reference.
        level: Option<u32>,
        /// When the stage began.
        started: Instant,
        /// What the stage is expected to take, ms.
        estimate_ms: f64,
    },
    /// Newton iteration `iteration` reached relative residual `residual`.
    Newton {
        /// The iteration's number.
        iteration: usize,
        /// The relative residual it reached.
        residual: f64,
        /// The size of the active set: the points in contact.
        active: usize,
    },
}

/// A message from the worker.
#[derive(Clone, Debug)]
pub enum Response {
    /// Where the solve asked for with `generation` is.
    Progress {
        /// The request's generation.
        generation: u64,
        /// Where it is.
        progress: Progress,
    },
    /// The solve asked for with `generation` finished: its result, or why it has none.
    Solved {
        /// The request's generation.
        generation: u64,
        /// The finished solve, or why it failed.
        result: Result<Arc<Solved>, LabError>,
    },
    /// A stage of the study asked for with `generation` began.
    StudyProgress {
        /// The request's generation.
        generation: u64,
        /// The stage ([`Progress::Study`]).
        progress: Progress,
    },
    /// The levels of the study asked for with `generation` finished so far, as a study of
    /// those levels (its points are drawn while the rest is computed).
    StudyPartial {
        /// The request's generation.
        generation: u64,
        /// The rows so far.
        study: Arc<Study>,
    },
    /// The solve of `generation` was superseded and stopped.
    Cancelled {
        /// The request's generation.
        generation: u64,
    },
    /// The mesh the estimate of `key` waits for is being built ([`Progress::Assembling`]).
    InfSupProgress {
        /// The estimate's key.
        key: InfSupKey,
        /// Where its build is.
        progress: Progress,
    },
    /// `result` is None when the request was dropped as stale before it started.
    InfSup {
        /// The estimate's key.
        key: InfSupKey,
        /// The estimate, or why it failed; None when dropped unstarted.
        result: Option<Result<InfSup, LabError>>,
    },
    /// The displacement of the solution with `key` is computed.
    Displaced {
        /// The solve's key.
        key: SolveKey,
    },
    /// The stresses of the solution with `key` are computed (or failed; see
    /// [`Solved::stresses`]).
    Stresses {
        /// The solve's key.
        key: SolveKey,
    },
    /// `result` is None when the request was dropped as stale before it started.
    Study {
        /// The request's generation.
        generation: u64,
        /// The study's key.
        key: StudyKey,
        /// The study, or why it failed; None when dropped unstarted.
        result: Option<Result<Arc<Study>, LabError>>,
    },
}

/// A finished solve with the discretisation it was computed on.
#[derive(Clone)]
pub struct Solved {
    /// The settings it was solved with.
    pub key: SolveKey,
    /// The discretisation of its mesh (shared with the worker's cache).
    pub disc: Arc<Discretization>,
    /// The solution of the contact problem, with p and p̄.
    pub solution: Solution,
    /// Displacement on every dof, node-major (u_x at `2n`, u_y at `2n + 1`): one solve with
    /// the whole factor, computed by the worker just after the solution is shown
    /// (`Engine::displace`), so that a level step shows its pressures without waiting for it.
    pub displacement: OnceLock<Vec<f64>>,
    /// What the views show of the solution, computed with it.
    pub shown: Shown,
    /// Wall time of the request, mesh work included, in ms.
    pub total_ms: f64,
    /// With edge grading on, how the solve came by its graded grid (None: uniform).
    pub regrade: Option<super::regrade::Regrade>,
    /// The stresses, computed by the worker when the stress scene first shows this solution
    /// (`Engine::stresses`).
    pub stresses: OnceLock<Result<Arc<StressField>, StressError>>,
}

impl Solved {
    /// The displacement ([`Solved::displacement`]), computed on first use and kept.
    pub fn u(&self) -> &[f64] {
        self.displacement
            .get_or_init(|| self.solution.displacement(&self.disc))
    }

    /// The stresses of this solution (on `scenario`'s material, with its discretisation's
    /// integration), computed on first use and kept.
    pub fn stress_field(&self, scenario: &Scenario) -> Result<Arc<StressField>, StressError> {
        self.stresses
            .get_or_init(|| {
                StressField::new(
                    &self.disc.mesh,
                    &scenario.material,
                    self.disc.integration,
                    self.u(),
                )
                .map(Arc::new)
            })
            .clone()
    }
}

impl std::fmt::Debug for Solved {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Solved")
            .field("key", &self.key)
            .field("load", &self.solution.load)
            .finish_non_exhaustive()
    }
}

/// The finest level the interactive lab (and `riplab render`) offers. A change at level 7
/// costs about 3–6 s and 1.3 GB with Q1 or P1, and 25–30 s and 5.8 GiB with Q2, whose level 7
/// has the unknowns of Q1's level 8 (BENCHMARKS.md, "Level 7 in the lab"): the lab builds it
/// on a thread of its own with the time left shown, and the memory guard refuses it, saying
/// why, where memory does not allow it. Level 8 is too slow to explore by key; `riplab solve`
/// goes there.
pub const MAX_APP_LEVEL: u32 = if MAX_LEVEL < 7 { MAX_LEVEL } else { 7 };

/// An input to the app's update (`App::update` in [`super::app`]).
#[derive(Clone, Debug)]
pub enum Msg {
    /// A key pressed.
    Key(KeyEvent),
    /// A click, a wheel turn or a move of the mouse (with `--no-mouse`, none arrive).
    Mouse(MouseEvent),
    /// The terminal was resized (redraw).
    Resize,
    /// A message from the worker.
    Worker(Response),
    /// The result of [`Command::Export`]: the file written, or what went wrong.
    Exported(Result<String, Arc<ExportError>>),
    /// Time passed while something long runs (the time left changes).
    Tick,
    /// A message for the status line (a tour step saved, a recording that failed).
    Notice(Notice),
}

/// Work for the runtime.
#[derive(Clone, Debug, PartialEq)]
pub enum Command {
    /// Solve the contact problem of the settings.
    Solve(SolveRequest),
    /// Estimate β_h and β̄_h (docs/design.md §5) for a level, element and rule.
    InfSup(InfSupRequest),
    /// Run the convergence scene's work–precision study.
    Study(StudyRequest),
    /// Compute the stresses of a solution the stress scene shows (kept with it).
    Stresses(StressRequest),
    /// Compute the displacement of the solution shown (kept with it), when the worker passed
    /// it over for a newer solve that the app then left behind.
    Displace(DisplaceRequest),
    /// Write the displayed solution to a new file, or the lab's state as a tour step, as
    /// the app's `export_kind` says (the kind travels in the app so that the variant stays a
    /// plain `Export`).
    Export,
    /// Ctrl-Z: give the terminal back and stop until resumed.
    Suspend,
    /// Every solve, estimate and study older than this generation is no longer wanted (the
    /// settings came back to the solution shown while a solve of others was under way).
    Supersede(u64),
}

/// A one-off message for the status line.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Notice {
    /// The message.
    pub text: String,
    /// Something failed (drawn as bad news).
    pub failure: bool,
}

impl Notice {
    /// A message that is not bad news.
    pub fn info(text: impl Into<String>) -> Self {
        Notice {
            text: text.into(),
            failure: false,
        }
    }
    /// A message that something failed.
    pub fn failure(text: impl Into<String>) -> Self {
        Notice {
            text: text.into(),
            failure: true,
        }
    }
}
