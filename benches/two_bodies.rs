//! Two elastic bodies against one body of as many unknowns (docs/design.md §12): `cargo bench
//! --bench two_bodies`.
//!
//! two_bodies: `scenarios/hertz-two-bodies.toml` solved fresh at a level by mortar with the
//! exact multipliers (both bodies discretised and factorised, the coupling, the condensed
//! solve). one_body: the lower body alone under the same cylinder as a rigid obstacle, its
//! height (and rows of elements, the element size kept) raised until its unknowns are the two
//! bodies' (within one row of elements), solved fresh by the exact multipliers (M3).
//!
//! patch_two_bodies and patch_one_body: the same at level 6 on `scenarios/patch-two-blocks.toml`
//! (whose level 6 fits where the Hertz scenario's 21 M unknowns do not), the one body the lower
//! block, raised, under a flat punch as wide as its top: a uniform compression as the patch
//! test's.

use divan::Bencher;
use riplab::contact::interface::InterfaceMethod;
use riplab::mesh::Element;
use riplab::scenario::Scenario;
use riplab::solve::solve_scenario;

/// As the binary: huge pages for the large blocks (`riplab::huge_pages`).
#[global_allocator]
static ALLOCATOR: riplab::huge_pages::HugePages = riplab::huge_pages::HugePages;

const TWO: &str = include_str!("../scenarios/hertz-two-bodies.toml");
const LEVELS: &[u32] = &[2, 3, 4];
const PATCH: &str = include_str!("../scenarios/patch-two-blocks.toml");
const PATCH_LEVELS: &[u32] = &[5, 6];

fn main() {
    divan::main();
}

fn two() -> Scenario {
    Scenario::parse(TWO, "hertz-two-bodies.toml").unwrap()
}

/// The unknowns of both bodies at `level`.
fn unknowns(s: &Scenario, level: u32) -> usize {
    let lower = s.discretize(level, Element::Q1).unwrap();
    let upper = s.discretize_upper(level, Element::Q1, 0).unwrap().unwrap();
    lower.n_dofs() + upper.n_dofs()
}

/// `two` with its `[upper]` table replaced by `obstacle`, `rows` base rows of elements of
/// `row_height` high (`height` and `ny` as written in `two`).
fn lower_alone(
    two: &str,
    obstacle: &str,
    (height, ny): (&str, &str),
    rows: usize,
    row_height: f64,
) -> Scenario {
    let start = two.find("[upper]").unwrap();
    let end = start + two[start..].find("\n\n").unwrap();
    let text = format!("{}{obstacle}{}", &two[..start], &two[end..])
        .replace(height, &format!("height = {:?}", rows as f64 * row_height))
        .replace(ny, &format!("ny = {rows}"));
    Scenario::parse(&text, "one-body.toml").unwrap()
}

/// The lower body alone, `rows` base rows of unit elements high, under the cylinder.
fn one(rows: usize) -> Scenario {
    let cylinder = "[obstacle]\nshape = \"cylinder\"\nradius = 10.0\ndepth = 0.1";
    lower_alone(TWO, cylinder, ("height = 20.0", "ny = 20"), rows, 1.0)
}

/// The patch scenario's lower block alone, `rows` base rows (0.25 high) of elements, under a
/// flat punch as wide as its top.
fn one_patch(rows: usize) -> Scenario {
    let punch =
        "[obstacle]\nshape = \"punch\"\nhalf_width = 1.5\ncorner_radius = 0.05\ndepth = 0.01\ncenter = 0.0";
    lower_alone(PATCH, punch, ("height = 1.0", "ny = 4"), rows, 0.25)
}

#[divan::bench(args = LEVELS, sample_count = 3, sample_size = 1)]
fn two_bodies(bencher: Bencher, level: u32) {
    let s = two();
    bencher.bench(|| s.solve_bodies(level, InterfaceMethod::Mortar, 0.0).unwrap());
}

#[divan::bench(args = LEVELS, sample_count = 3, sample_size = 1)]
fn one_body(bencher: Bencher, level: u32) {
    let want = unknowns(&two(), level);
    // A row of base elements adds 2 (40·2^L + 1)·2^L unknowns.
    let per_row = (2 * (40 * (1usize << level) + 1)) << level;
    let mut s = one(want.div_ceil(per_row).max(1));
    s.level = level;
    eprintln!(
        "level {level}: two bodies {want} unknowns, one body {}",
        s.discretize(level, Element::Q1).unwrap().n_dofs()
    );
    bencher.bench(|| {
        let (_, sol) = solve_scenario(&s).unwrap();
        assert!(sol.newton.converged);
    });
}

#[divan::bench(args = PATCH_LEVELS, sample_count = 3, sample_size = 1)]
fn patch_two_bodies(bencher: Bencher, level: u32) {
    let s = Scenario::parse(PATCH, "patch-two-blocks.toml").unwrap();
    bencher.bench(|| s.solve_bodies(level, InterfaceMethod::Mortar, 0.0).unwrap());
}

#[divan::bench(args = PATCH_LEVELS, sample_count = 3, sample_size = 1)]
fn patch_one_body(bencher: Bencher, level: u32) {
    let two = Scenario::parse(PATCH, "patch-two-blocks.toml").unwrap();
    let want = two.sizes(level, Element::Q1).unknowns + two.upper_sizes(level, Element::Q1).unwrap().unknowns;
    // The fewest base rows whose unknowns reach the two bodies'.
    let rows = (4..)
        .find(|&rows| one_patch(rows).sizes(level, Element::Q1).unknowns >= want)
        .unwrap();
    let mut s = one_patch(rows);
    s.level = level;
    eprintln!(
        "patch level {level}: two bodies {want} unknowns, one body {}",
        s.sizes(level, Element::Q1).unknowns
    );
    bencher.bench(|| {
        let (_, sol) = solve_scenario(&s).unwrap();
        assert!(sol.newton.converged);
    });
}
