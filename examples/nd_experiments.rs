use riplab::fem::condense::TraceOrdering;
use riplab::fem::{DofMap, Form, assemble};
use riplab::mesh::{Element, Mesh};
use riplab::scenario::Scenario;

#[derive(Clone, Copy)]
struct Part {
    i: (usize, usize),
    j: (usize, usize),
}

fn separator(lo: usize, hi: usize, p: usize) -> Option<usize> {
    if hi < lo + 3 {
        return None;
    }
    let mid = (lo + hi) / 2;
    let below = mid - mid % p;
    [below, below + p]
        .into_iter()
        .filter(|&s| s > lo && s + 1 < hi)
        .min_by_key(|&s| s.abs_diff(mid))
}

fn dissect(part: Part, p: usize, leaf: usize, horiz_bias: f64, emit: &mut impl FnMut(usize, usize)) {
    let (wide, high) = (part.i.1 - part.i.0, part.j.1 - part.j.0);
    let split = if wide * high <= leaf {
        None
    } else if wide as f64 >= high as f64 * horiz_bias {
        separator(part.i.0, part.i.1, p)
            .map(|s| (s, true))
            .or_else(|| separator(part.j.0, part.j.1, p).map(|s| (s, false)))
    } else {
        separator(part.j.0, part.j.1, p)
            .map(|s| (s, false))
            .or_else(|| separator(part.i.0, part.i.1, p).map(|s| (s, true)))
    };
    match split {
        None => {
            for j in part.j.0..part.j.1 {
                for i in part.i.0..part.i.1 {
                    emit(i, j);
                }
            }
        }
        Some((s, true)) => {
            dissect(
                Part {
                    i: (part.i.0, s),
                    ..part
                },
                p,
                leaf,
                horiz_bias,
                emit,
            );
            dissect(
                Part {
                    i: (s + 1, part.i.1),
                    ..part
                },
                p,
                leaf,
                horiz_bias,
                emit,
            );
            for j in part.j.0..part.j.1 {
                emit(s, j);
            }
        }
        Some((s, false)) => {
            dissect(
                Part {
                    j: (part.j.0, s),
                    ..part
                },
                p,
                leaf,
                horiz_bias,
                emit,
            );
            dissect(
                Part {
                    j: (s + 1, part.j.1),
                    ..part
                },
                p,
                leaf,
                horiz_bias,
                emit,
            );
            for i in part.i.0..part.i.1 {
                emit(i, s);
            }
        }
    }
}

fn main() {
    let level: u32 = std::env::args().nth(1).unwrap().parse().unwrap();
    let element = match std::env::args().nth(2).as_deref() {
        Some("q2") => Element::Q2,
        Some("p1") => Element::P1,
        _ => Element::Q1,
    };
    let s = Scenario::paper();
    let mesh: Mesh = s.mesh(level, element);
    let dofs = DofMap::model(&mesh);
    let k = assemble(&mesh, &dofs, Form::Elasticity(s.material, s.integration));
    let trace: Vec<usize> = mesh
        .top_nodes()
        .iter()
        .map(|&t| dofs.free_index(2 * t + 1).unwrap())
        .collect();
    let p = element.order();
    let run = |name: &str, leaf: usize, bias: f64, top_last: bool, constrained: bool| {
        let mut is_trace = vec![false; dofs.n_free()];
        if constrained {
            for &d in &trace {
                is_trace[d] = true;
            }
        }
        let nny = mesh.node_y.len();
        let mut order = Vec::new();
        let mut emit = |i: usize, j: usize| {
            let node = mesh.node(i, j);
            for c in 0..2 {
                if let Some(d) = dofs.free_index(2 * node + c).filter(|&d| !is_trace[d]) {
                    order.push(d);
                }
            }
        };
        let rows = if top_last { nny - 1 } else { nny };
        dissect(
            Part {
                i: (0, mesh.nnx()),
                j: (0, rows),
            },
            p,
            leaf,
            bias,
            &mut emit,
        );
        if top_last {
            for i in 0..mesh.nnx() {
                emit(i, nny - 1);
            }
        }
        let t = std::time::Instant::now();
        let tr: &[usize] = if constrained { &trace } else { &[] };
        let o = TraceOrdering::with_interior_order(&k, order, tr).unwrap();
        let sym = t.elapsed().as_secs_f64() * 1e3;
        let mut num = vec![];
        for th in [1, 2, 1, 2] {
            riplab::fem::set_threads(th);
            let t = std::time::Instant::now();
            let f = riplab::fem::condense::TraceFactor::new(&o, &k).unwrap();
            let a = t.elapsed().as_secs_f64() * 1e3;
            let t = std::time::Instant::now();
            if constrained {
                let _ = f.compliance();
            }
            num.push(format!("{th}t {a:.0}+{:.0}", t.elapsed().as_secs_f64() * 1e3));
        }
        println!(
            "{name:20} leaf {leaf:4} bias {bias} len {:>11} flops {:.3e} sym {sym:.0} ms num {num:?}",
            o.factor_len(),
            o.factor_flops()
        );
    };
    for leaf in [4, 8, 16, 32] {
        run("nd trace last", leaf, 1.0, false, true);
    }
    let amd = TraceOrdering::new(&k, &trace).unwrap();
    println!("amd len {} flops {:.3e}", amd.factor_len(), amd.factor_flops());
    for th in [1, 2, 1, 2] {
        riplab::fem::set_threads(th);
        let t = std::time::Instant::now();
        let _f = riplab::fem::condense::TraceFactor::new(&amd, &k).unwrap();
        println!("amd {th}t {:.0}", t.elapsed().as_secs_f64() * 1e3);
    }
}
