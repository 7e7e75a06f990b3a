//! The linear system of one semismooth Newton (primal–dual active-set) step (docs/design.md
//! §11): with the points split into contact A = S ∪ L (stick S, slip L with the direction σ)
//! and open O, the iterate that satisfies the sets' equations —
//!
//! ```text
//!   s_A = D_n y_A,   v_S = −D_t z_S,   z_L = σ_L b_L,   y_O = z_O = 0
//! ```
//!
//! (D_n = diag(ε/w), D_t = diag(ε_t/w), both zero for the exact multipliers) — solves, in the
//! unknowns (y_A, z_S), with Coulomb's z_L = μ Σ_L y_L or Tresca's known z_L = σ_L w_L g_L:
//!
//! ```text
//!   [ (D_n + G_nn)_AA − μ (G_nt)_AL Σ_L    −(G_nt)_AS      ] [y_A]   [ d_A + (G_nt)_AL z_L      ]
//!   [ −(G_tn)_SA + μ (G_tt)_SL Σ_L          (D_t + G_tt)_SS ] [z_S] = [ ξ + r̂_S − e_S − (G_tt)_SL z_L ]
//! ```
//!
//! (the z_L terms of the right-hand side are Tresca's; Coulomb's are in the matrix). Tresca's
//! matrix (and Coulomb's with no slip or μ = 0) is a principal block of the symmetric 𝔾 + D:
//! Cholesky, LBLᵀ on round-off. Coulomb's is unsymmetric once a point slips: faer's LU with
//! partial pivoting, checked by its residual, then full pivoting; a system neither solves is
//! reported (μ too large for a unique incremental solution).

use faer::linalg::solvers::Solve;
use faer::{Mat, Side};

use super::State;
use super::law::{Bound, Imposition, StepProblem};
use crate::error::Diagnosis;

/// The residual ‖Mx − b‖ an LU solution must meet, relative to ‖M‖‖x‖ + ‖b‖.
const LU_TOLERANCE: f64 = 1e-10;

/// How a step's system was solved.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Factorisation {
    /// Cholesky (or LBLᵀ): the symmetric systems.
    Cholesky,
    /// LU with partial pivoting.
    PartialLu,
    /// LU with full pivoting, after the partial pivoting's residual failed.
    FullLu,
}

/// The iterate (y, z) that satisfies the equations of the sets `states` (with the slip
/// directions `sign`), and how its system was solved.
pub fn target(
    pb: &StepProblem,
    states: &[State],
    sign: &[f64],
) -> Result<(Vec<f64>, Vec<f64>, Factorisation), Diagnosis> {
    let n = pb.len();
    let g = pb.couplings;
    let a: Vec<usize> = (0..n).filter(|&q| states[q] != State::Open).collect();
    let stick: Vec<usize> = (0..n).filter(|&q| states[q] == State::Stick).collect();
    let slip: Vec<usize> = (0..n).filter(|&q| states[q] == State::Slip).collect();
    let (dn, dt) = match pb.imposition {
        Imposition::Exact => (0.0, 0.0),
        Imposition::Penalty { epsilon, epsilon_t } => (epsilon, epsilon_t),
    };
    // Coulomb: z_L = μ σ y_L, a column factor on y's columns; Tresca: known z_L.
    let (mu, known_z): (f64, Vec<f64>) = match pb.bound {
        Bound::Coulomb(mu) => (mu, vec![0.0; n]),
        Bound::Tresca(th) => (
            0.0,
            (0..n)
                .map(|q| {
                    if states[q] == State::Slip {
                        sign[q] * pb.weight[q] * th[q]
                    } else {
                        0.0
                    }
                })
                .collect(),
        ),
    };
    let slip_factor = |q: usize| {
        if states[q] == State::Slip {
            mu * sign[q]
        } else {
            0.0
        }
    };
    let (na, m) = (a.len(), a.len() + stick.len());
    let mut mat = Mat::<f64>::zeros(m, m);
    let mut rhs = Mat::<f64>::zeros(m, 1);
    for (i, &p) in a.iter().enumerate() {
        for (j, &q) in a.iter().enumerate() {
            mat[(i, j)] = g.g_nn[(p, q)] - slip_factor(q) * g.g_nt[(p, q)];
        }
        mat[(i, i)] += dn / pb.weight[p];
        for (k, &q) in stick.iter().enumerate() {
            mat[(i, na + k)] = -g.g_nt[(p, q)];
        }
        rhs[(i, 0)] = pb.d[p] + slip.iter().map(|&q| g.g_nt[(p, q)] * known_z[q]).sum::<f64>();
    }
    for (k, &p) in stick.iter().enumerate() {
        for (j, &q) in a.iter().enumerate() {
            // (G_tn)_pq = (G_nt)_qp.
            mat[(na + k, j)] = -g.g_nt[(q, p)] + slip_factor(q) * g.g_tt[(p, q)];
        }
        for (l, &q) in stick.iter().enumerate() {
            mat[(na + k, na + l)] = g.g_tt[(p, q)];
        }
        mat[(na + k, na + k)] += dt / pb.weight[p];
        rhs[(na + k, 0)] = pb.shift + pb.anchor[p]
            - pb.e[p]
            - slip.iter().map(|&q| g.g_tt[(p, q)] * known_z[q]).sum::<f64>();
    }
    let symmetric = mu == 0.0 || slip.is_empty();
    let (x, how) = solve(&mat, &rhs, symmetric)?;
    let (mut y, mut z) = (vec![0.0; n], vec![0.0; n]);
    for (i, &p) in a.iter().enumerate() {
        y[p] = x[(i, 0)];
    }
    for (k, &p) in stick.iter().enumerate() {
        z[p] = x[(na + k, 0)];
    }
    for &q in &slip {
        z[q] = known_z[q] + slip_factor(q) * y[q];
    }
    Ok((y, z, how))
}

/// Solve M x = b: Cholesky for a `symmetric` M, else LU with partial, then full pivoting,
/// each LU solution checked by its residual.
pub fn solve(
    mat: &Mat<f64>,
    rhs: &Mat<f64>,
    symmetric: bool,
) -> Result<(Mat<f64>, Factorisation), Diagnosis> {
    if mat.nrows() == 0 {
        return Ok((Mat::zeros(0, 1), Factorisation::Cholesky));
    }
    if symmetric {
        let x = match mat.llt(Side::Lower) {
            Ok(llt) => llt.solve(rhs),
            // 𝔾 + D is positive semi-definite: only round-off (or a kernel) can get here.
            Err(_) => mat.lblt(Side::Lower).solve(rhs),
        };
        return Ok((x, Factorisation::Cholesky));
    }
    let fits = |x: &Mat<f64>| {
        let r = mat * x - rhs;
        let scale = mat.norm_max() * x.norm_max() + rhs.norm_max();
        x.norm_max().is_finite() && r.norm_max() <= LU_TOLERANCE * scale
    };
    let x = mat.partial_piv_lu().solve(rhs);
    if fits(&x) {
        return Ok((x, Factorisation::PartialLu));
    }
    let x = mat.full_piv_lu().solve(rhs);
    if fits(&x) {
        return Ok((x, Factorisation::FullLu));
    }
    Err(Diagnosis::CoulombSingular)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::ContactPoints;
    use crate::contact::friction::FrictionTrace;
    use crate::contact::friction::law::Couplings;
    use crate::discretization::Discretization;
    use crate::scenario::Scenario;
    use std::sync::Arc;

    fn couplings() -> (Discretization, Arc<Couplings>, Vec<f64>) {
        let scenario = Scenario::load(std::path::Path::new("scenarios/hertz-paper-full.toml")).unwrap();
        let disc = scenario.discretize(0, scenario.element).unwrap();
        let rule = crate::contact::Rule::Trapezoid;
        let points = ContactPoints::on(&disc, rule);
        let trace = FrictionTrace::of(&disc).unwrap();
        let c = trace.couplings(&disc, rule, &points);
        let w = points.points.iter().map(|q| q.weight).collect();
        (disc, c, w)
    }

    /// Coulomb's system with slipping points is unsymmetric, and the LU's solution satisfies
    /// the sets' equations (s = 0 on A, v = 0 on S, z = μσy on L) to 1e-12; Tresca's is
    /// symmetric positive definite (Cholesky succeeds) and satisfies its own.
    #[test]
    fn coulomb_system_is_unsymmetric_and_lu_solves_it() {
        let (_disc, c, w) = couplings();
        let n = w.len();
        let d: Vec<f64> = (0..n)
            .map(|q| 0.01 * (1.0 - (q as f64 / n as f64 - 0.5).abs() * 4.0))
            .collect();
        let zero = vec![0.0; n];
        let states: Vec<State> = (0..n)
            .map(|q| match d[q] {
                v if v <= 0.0 => State::Open,
                _ if (q as f64 - n as f64 / 2.0).abs() < 2.0 => State::Stick,
                _ => State::Slip,
            })
            .collect();
        let sign: Vec<f64> = (0..n).map(|q| if q < n / 2 { -1.0 } else { 1.0 }).collect();
        let thresholds = vec![3.0; n];
        for (bound, mu) in [(Bound::Coulomb(0.3), 0.3), (Bound::Tresca(&thresholds), 0.0)] {
            let pb = StepProblem {
                couplings: &c,
                d: &d,
                e: &zero,
                weight: &w,
                bound,
                imposition: Imposition::Exact,
                shift: 0.002,
                anchor: &zero,
            };
            let (y, z, how) = target(&pb, &states, &sign).unwrap();
            let [s, r, _, _] = pb.displacements(&y, &z);
            let scale_s = d.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
            for q in 0..n {
                match states[q] {
                    State::Open => assert!(y[q] == 0.0 && z[q] == 0.0),
                    State::Stick => {
                        assert!(s[q].abs() <= 1e-12 * scale_s);
                        assert!(r[q].abs() <= 1e-12 * scale_s);
                    }
                    State::Slip => {
                        assert!(s[q].abs() <= 1e-12 * scale_s);
                        let b = match bound {
                            Bound::Coulomb(mu) => mu * y[q],
                            Bound::Tresca(g) => w[q] * g[q],
                        };
                        assert!((z[q] - sign[q] * b).abs() <= 1e-12 * b.abs().max(1e-300));
                    }
                }
            }
            if mu > 0.0 {
                assert_eq!(how, Factorisation::PartialLu);
            } else {
                assert_eq!(how, Factorisation::Cholesky);
            }
        }
    }
}
