//! Two elastic bodies against one body of as many unknowns (docs/design.md §12): `cargo bench
//! --bench two_bodies`.
//!
//! two_bodies: `scenarios/hertz-two-bodies.toml` solved fresh at a level by mortar with the
//! exact multipliers (both bodies discretised and factorised, the coupling, the condensed
//! solve). one_body: the lower body alone under the same cylinder as a rigid obstacle, its
//! height (and rows of elements, the element size kept) raised until its unknowns are the two
//! bodies' (within one row of elements), solved fresh by the exact multipliers (M3).

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

/// The lower body alone, `rows` base rows of unit elements high, under the cylinder.
fn one(rows: usize) -> Scenario {
    let start = TWO.find("[upper]").unwrap();
    let end = start + TWO[start..].find("\n\n").unwrap();
    let text = format!(
        "{}[obstacle]\nshape = \"cylinder\"\nradius = 10.0\ndepth = 0.1{}",
        &TWO[..start],
        &TWO[end..]
    )
    .replace("height = 20.0", &format!("height = {rows}.0"))
    .replace("ny = 20", &format!("ny = {rows}"));
    Scenario::parse(&text, "one-body.toml").unwrap()
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
