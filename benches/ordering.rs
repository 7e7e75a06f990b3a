//! The ordering of K against faer's own Cholesky: `cargo bench --bench ordering`.
//!
//! In one run, on the paper's problem (Q1, M1) at `RIPLAB_LEVELS` (default 6 and 7):
//! - `fresh_m1`: the whole fresh solve (assembly, the grid's nested dissection with Γ_C last,
//!   symbolic and numeric factorisation, the trace compliance, Newton), as `riplab solve`
//!   (on two threads or more, two subdomains side by side: `riplab::fem::split`);
//! - `faer_default`: faer's Cholesky of the same K with its default (AMD) ordering, symbolic
//!   and numeric, no compliance, on the same threads;
//! - `constrained_amd`: the previous ordering (AMD on all but Γ_C, then Γ_C), symbolic and
//!   numeric, no compliance.
//!
//! Before the timings it prints each ordering's factor size and flop count (no timing
//! noise); with `--features metis`, METIS's nested dissection (`METIS_NodeND` on the graph of
//! K without Γ_C, then Γ_C) among them, with the time METIS took. `RIPLAB_THREADS` (default: the cores available, as `--threads`) sets the threads of
//! every variant alike; the binary's allocator serves all of them.

use std::ops::ControlFlow;

use divan::Bencher;
use faer::Side;
use faer::sparse::linalg::cholesky::{
    CholeskySymbolicParams, SymmetricOrdering, factorize_symbolic_cholesky,
};
use faer::sparse::linalg::solvers::{Llt, SymbolicLlt};
use riplab::contact::ContactParams;
use riplab::contact::newton::NewtonOptions;
use riplab::fem::condense::{TraceFactor, TraceOrdering, factor_flops};
use riplab::fem::factor::Analysis;
use riplab::fem::{DofMap, Form, SymCsc, assemble};
use riplab::mesh::Element;
use riplab::scenario::Scenario;
use riplab::solve::solve_contact;

/// As the binary: huge pages for the large blocks (`riplab::huge_pages`).
#[global_allocator]
static ALLOCATOR: riplab::huge_pages::HugePages = riplab::huge_pages::HugePages;

fn levels() -> Vec<u32> {
    std::env::var("RIPLAB_LEVELS")
        .ok()
        .map(|v| v.split(',').filter_map(|l| l.trim().parse().ok()).collect())
        .unwrap_or_else(|| vec![6, 7])
}

fn main() {
    let threads = std::env::var("RIPLAB_THREADS")
        .ok()
        .and_then(|t| t.parse().ok())
        .unwrap_or_else(riplab::fem::available_threads);
    riplab::fem::set_threads(threads);
    println!("threads {threads}");
    println!("| level | unknowns | ordering | factor values | flops |");
    println!("|---|---|---|---|---|");
    for level in levels() {
        let (k, mesh, dofs, trace) = stiffness(level);
        let grid = TraceOrdering::grid(&k, &mesh, &dofs, &trace).unwrap();
        let amd = TraceOrdering::new(&k, &trace).unwrap();
        let split = Analysis::split(&k, &mesh, &dofs, &trace).unwrap();
        #[cfg(feature = "metis")]
        let metis = {
            let started = std::time::Instant::now();
            let metis = TraceOrdering::with_order(&k, metis_order(&k, &trace), &trace).unwrap();
            println!(
                "level {level}: METIS ordering and analysis {:.0} ms",
                started.elapsed().as_secs_f64() * 1e3
            );
            metis
        };
        let faer = factorize_symbolic_cholesky(
            k.symbolic(),
            Side::Lower,
            SymmetricOrdering::Amd,
            CholeskySymbolicParams::default(),
        )
        .unwrap();
        let rows = vec![
            (
                "grid nested dissection, Γ_C last",
                grid.factor_len(),
                grid.factor_flops(),
            ),
            (
                "two subdomains (each half's nested dissection, its side of Γ last) and the dense S",
                split.factor_len(),
                split.factor_flops(),
            ),
            ("AMD, Γ_C last (before)", amd.factor_len(), amd.factor_flops()),
            ("faer default (AMD)", faer.len_val(), factor_flops(&faer)),
        ];
        #[cfg(feature = "metis")]
        let rows = {
            let mut rows = rows;
            let row = (
                "METIS nested dissection, Γ_C last",
                metis.factor_len(),
                metis.factor_flops(),
            );
            rows.insert(2, row);
            rows
        };
        for (name, len, flops) in rows {
            println!("| {level} | {} | {name} | {len} | {flops:.3e} |", k.n);
        }
    }
    divan::main();
}

/// METIS's fill-reducing order (`METIS_NodeND`, default options) of the free dofs of `k` but
/// `trace`: the graph of K's pattern without them.
#[cfg(feature = "metis")]
fn metis_order(k: &SymCsc, trace: &[usize]) -> Vec<usize> {
    type Idx = metis_sys::idx_t;
    let mut local = vec![usize::MAX; k.n];
    let mut is_trace = vec![false; k.n];
    for &d in trace {
        is_trace[d] = true;
    }
    let interior: Vec<usize> = (0..k.n).filter(|&d| !is_trace[d]).collect();
    for (i, &d) in interior.iter().enumerate() {
        local[d] = i;
    }
    // Both triangles of K's pattern among the interior dofs, without the diagonal.
    let mut neighbours = vec![Vec::new(); interior.len()];
    for c in 0..k.n {
        for &r in &k.row_idx[k.col_ptr[c]..k.col_ptr[c + 1]] {
            if r != c && local[r] != usize::MAX && local[c] != usize::MAX {
                neighbours[local[c]].push(local[r] as Idx);
                neighbours[local[r]].push(local[c] as Idx);
            }
        }
    }
    let mut xadj = vec![0 as Idx];
    let mut adjncy = Vec::new();
    for list in &neighbours {
        adjncy.extend_from_slice(list);
        xadj.push(adjncy.len() as Idx);
    }
    let mut nvtxs = interior.len() as Idx;
    let (mut perm, mut iperm) = (vec![0 as Idx; interior.len()], vec![0 as Idx; interior.len()]);
    // SAFETY: xadj (nvtxs + 1 entries) and adjncy describe a symmetric graph on nvtxs vertices;
    // perm and iperm have nvtxs entries; null vertex weights and options ask for the defaults.
    let status = unsafe {
        metis_sys::METIS_NodeND(
            &mut nvtxs,
            xadj.as_mut_ptr(),
            adjncy.as_mut_ptr(),
            std::ptr::null_mut(),
            std::ptr::null_mut(),
            perm.as_mut_ptr(),
            iperm.as_mut_ptr(),
        )
    };
    assert_eq!(
        status,
        metis_sys::rstatus_et_METIS_OK as std::os::raw::c_int,
        "METIS_NodeND failed"
    );
    // Position i of the new order holds the old vertex perm[i] (the METIS manual).
    perm.iter().map(|&v| interior[v as usize]).collect()
}

/// K of the paper's problem (Q1) at `level`, its mesh, dofs and Γ_C normal dofs.
fn stiffness(level: u32) -> (SymCsc, riplab::mesh::Mesh, DofMap, Vec<usize>) {
    let s = Scenario::paper();
    let mesh = s.mesh(level, Element::Q1);
    let dofs = DofMap::model(&mesh);
    let k = assemble(&mesh, &dofs, Form::Elasticity(s.material, s.integration));
    let trace = mesh
        .top_nodes()
        .iter()
        .map(|&t| dofs.free_index(2 * t + 1).unwrap())
        .collect();
    (k, mesh, dofs, trace)
}

#[divan::bench(args = levels(), sample_count = 3, sample_size = 1)]
fn fresh_m1(bencher: Bencher, level: u32) {
    let s = Scenario::paper();
    let params = ContactParams::by_epsilon(s.rule, s.epsilon, s.obstacle.clone());
    bencher.bench(|| {
        let disc = s.discretize(level, Element::Q1).unwrap();
        solve_contact(&disc, &params, None, &NewtonOptions::default(), &mut |_| {
            ControlFlow::Continue(())
        })
        .unwrap()
        .load
    });
}

#[divan::bench(args = levels(), sample_count = 3, sample_size = 1)]
fn faer_default(bencher: Bencher, level: u32) {
    let (k, ..) = stiffness(level);
    // faer's Cholesky on as many threads as riplab's (`riplab::fem::set_threads` leaves faer's
    // global parallelism sequential for riplab's own dense eigensolvers).
    faer::set_global_parallelism(riplab::fem::parallelism());
    bencher.bench(|| {
        let symbolic = SymbolicLlt::try_new(k.symbolic(), Side::Lower).unwrap();
        Llt::try_new_with_symbolic(symbolic, k.view(&k.values), Side::Lower).unwrap()
    });
    faer::set_global_parallelism(faer::Par::Seq);
}

#[divan::bench(args = levels(), sample_count = 3, sample_size = 1)]
fn constrained_amd(bencher: Bencher, level: u32) {
    let (k, _, _, trace) = stiffness(level);
    bencher.bench(|| TraceFactor::new(&TraceOrdering::new(&k, &trace).unwrap(), &k).unwrap());
}
