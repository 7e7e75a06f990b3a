//! What a cache entry must mean before it is believed: a checksum only says the
//! bytes are the ones written. An entry's fields are checked against what the reference is,
//! independently of the solver that made them: its sizes are the mesh's, every number is
//! finite, its load P is I(p, 1) of its own pressure (`contact::pressure::load`), and its
//! displacement is in equilibrium with that load: the vertical reaction of the clamped bottom,
//! Σ (K u)_y with K applied cell by cell ([`crate::fem::apply`]), equals P (the body carries
//! no other load); with friction its horizontal reaction Σ (K u)_x balances its tangential
//! load Q = I(t, 1) (docs/design.md §11: the traction on the body is +t in x). Consistency is
//! not enough: u, p, t and the load of a solution all scaled by one factor, or a true solution
//! of another depth written under this key, pass those checks; so the entry must also solve
//! its own obstacle's contact (4) at Simpson's points on Γ_C: u_n ≤ g, p ≥ 0 and
//! p (u_n − g) = 0, u_n read from its displacement and g from the scenario's obstacle. An entry
//! that fails any check is recomputed and replaced.

use crate::contact::ContactPoints;
use crate::contact::pressure::load;
use crate::fem::{Form, apply};
use crate::scenario::Scenario;
use crate::study::{REFERENCE_SCHEME, ReferenceFields, ReferenceMesh};
use crate::text::num;

/// The relative agreement asked of the load and I(p, 1) (the same sum, up to its order).
const LOAD_TOLERANCE: f64 = 1e-9;

/// The relative agreement asked of the bottom's reaction and the load (the exact method's
/// Newton stops at a residual far below this; tests/numerics/contact.rs finds 1e-9).
const REACTION_TOLERANCE: f64 = 1e-6;

/// The relative agreement asked of the contact conditions (4) at the points: u_n − g at most
/// this share of the displacement's scale above 0, p at most this share of its largest value
/// below 0, and p (u_n − g) at most this share of their product of scales (the exact method
/// solves G_AA y_A = d_A: u_n − g is round-off on its active points, p is 0 off them).
const CONTACT_TOLERANCE: f64 = 1e-6;

/// Why a cached reference is not believed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum Meaningless {
    /// Its sizes are not the mesh's.
    #[error(
        "its sizes {found:?} (displacements, pressures and tangential tractions, dofs) are not the mesh's {expected:?}"
    )]
    Sizes {
        /// (displacements, pressures and tangential tractions, dofs) it holds.
        found: (usize, usize, usize),
        /// (displacements, pressures and tangential tractions, dofs) of the mesh.
        expected: (usize, usize, usize),
    },
    /// A number that is not finite, or a negative time.
    #[error("it holds a number that is not finite (or a negative time)")]
    NotFinite,
    /// Its load is not I(p, 1) of its pressure.
    #[error("its load {} is not I(p, 1) = {} of its pressure", num(*load), num(*integral))]
    Load {
        /// The load it holds.
        load: f64,
        /// I(p, 1) of its pressure.
        integral: f64,
    },
    /// Its displacement's reaction at the bottom is not its load.
    #[error("its displacement's reaction {} is not its load {}", num(*reaction), num(*load))]
    Reaction {
        /// The bottom's reaction of its displacement.
        reaction: f64,
        /// The load it holds.
        load: f64,
    },
    /// With friction, its displacement's horizontal reaction at the bottom does not balance
    /// its tangential load.
    #[error(
        "its displacement's horizontal reaction {} does not balance its tangential load {}",
        num(*reaction),
        num(*load)
    )]
    Tangential {
        /// The bottom's horizontal reaction of its displacement.
        reaction: f64,
        /// Its tangential load Q = I(t, 1).
        load: f64,
    },
    /// Its displacement and pressure do not satisfy its own obstacle's contact conditions (4)
    /// at a point of Γ_C: a penetration, a tension, or a pressure across a gap.
    #[error(
        "at x = {} on Γ_C its u_n − g is {} with p = {}: not the contact of its obstacle (u_n ≤ g, p ≥ 0, p (u_n − g) = 0)",
        num(*x),
        num(*gap),
        num(*p)
    )]
    Contact {
        /// The point's x.
        x: f64,
        /// u_n − g there (−∞ where the obstacle does not reach).
        gap: f64,
        /// p there.
        p: f64,
    },
}

/// Why `fields` cannot be the reference of `scenario` on `grid`, if it cannot.
pub fn check(scenario: &Scenario, grid: &ReferenceMesh, fields: &ReferenceFields) -> Result<(), Meaningless> {
    let (n_u, n_p) = grid.lengths();
    let n_dofs = grid.n_dofs(scenario);
    // With friction a tangential traction at each pressure's point.
    let n_t = if scenario.friction.is_on() { n_p } else { 0 };
    let traction = fields.p.len() + fields.t.len();
    if (fields.u.len(), fields.p.len(), fields.t.len(), fields.n_dofs) != (n_u, n_p, n_t, n_dofs) {
        return Err(Meaningless::Sizes {
            found: (fields.u.len(), traction, fields.n_dofs),
            expected: (n_u, n_p + n_t, n_dofs),
        });
    }
    let finite = [fields.load, fields.ms]
        .iter()
        .chain(&fields.u)
        .chain(&fields.p)
        .chain(&fields.t)
        .all(|v| v.is_finite());
    if !finite || fields.ms < 0.0 {
        return Err(Meaningless::NotFinite);
    }
    let mesh = grid.mesh(scenario);
    let points = ContactPoints::new(
        REFERENCE_SCHEME.1,
        &mesh.node_x[..mesh.nnx()],
        REFERENCE_SCHEME.0.order(),
    );
    let integral = load(&points, &fields.p);
    let scale = points
        .points
        .iter()
        .zip(&fields.p)
        .map(|(q, p)| (q.weight * p).abs())
        .sum::<f64>()
        .max(f64::MIN_POSITIVE);
    if (fields.load - integral).abs() > LOAD_TOLERANCE * scale {
        return Err(Meaningless::Load {
            load: fields.load,
            integral,
        });
    }
    let ku = apply(
        &mesh,
        Form::Elasticity(scenario.material, scenario.integration),
        &fields.u,
    );
    let reaction: f64 = (0..mesh.nnx()).map(|i| ku[2 * mesh.node(i, 0) + 1]).sum();
    if !reaction.is_finite() || (reaction - fields.load).abs() > REACTION_TOLERANCE * scale {
        return Err(Meaningless::Reaction {
            reaction,
            load: fields.load,
        });
    }
    contact(scenario, &mesh, &points, fields)?;
    if !fields.t.is_empty() {
        let q = load(&points, &fields.t);
        let horizontal: f64 = (0..mesh.nnx()).map(|i| ku[2 * mesh.node(i, 0)]).sum();
        if !horizontal.is_finite() || (horizontal + q).abs() > REACTION_TOLERANCE * scale {
            return Err(Meaningless::Tangential {
                reaction: horizontal,
                load: q,
            });
        }
    }
    Ok(())
}

/// Whether `fields` satisfy the contact conditions (4) of `scenario`'s obstacle at `points`:
/// u_n ≤ g, p ≥ 0 and p (u_n − g) = 0 within [`CONTACT_TOLERANCE`] of the scales of u_n
/// (the largest |u_n| or the depth) and of p (its largest |p|).
fn contact(
    scenario: &Scenario,
    mesh: &crate::mesh::Mesh,
    points: &ContactPoints,
    fields: &ReferenceFields,
) -> Result<(), Meaningless> {
    let top: Vec<f64> = mesh.top_nodes().iter().map(|&n| fields.u[2 * n + 1]).collect();
    let un = points.trace_of(&top);
    let length = un
        .iter()
        .fold(scenario.obstacle.depth().abs(), |m, v| m.max(v.abs()))
        .max(f64::MIN_POSITIVE);
    let force = fields
        .p
        .iter()
        .fold(0.0_f64, |m, v| m.max(v.abs()))
        .max(f64::MIN_POSITIVE);
    let tol = CONTACT_TOLERANCE;
    for ((q, &un), &p) in points.points.iter().zip(&un).zip(&fields.p) {
        let gap = un - scenario.obstacle.gap(q.x);
        let penetrates = gap > tol * length;
        let pulls = p < -tol * force;
        // Where the obstacle does not reach (g = +∞) nothing may press.
        let across = if gap.is_finite() {
            p > 0.0 && p * -gap > tol * force * length
        } else {
            p > tol * force
        };
        if penetrates || pulls || across {
            return Err(Meaningless::Contact { x: q.x, gap, p });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A solved reference passes; its pressure ×1.5, a load of 1e308, n_dofs = 2⁶⁴ − 1, a NaN
    /// time, its pressure ×1.5 with its load, everything ×1.5 (u, p and the load: consistent,
    /// but not its obstacle's contact), or another depth's true solution each fail.
    #[test]
    fn only_a_reference_that_means_what_it_says_is_believed() {
        let s = Scenario::paper();
        let grid = ReferenceMesh::uniform(&s, 1);
        let good = ReferenceFields::solve_on(&s, &grid).unwrap();
        assert_eq!(check(&s, &grid, &good), Ok(()));
        let bad = |f: &dyn Fn(&mut ReferenceFields)| {
            let mut fields = good.clone();
            f(&mut fields);
            check(&s, &grid, &fields).unwrap_err()
        };
        let load = |e: Meaningless| matches!(e, Meaningless::Load { .. });
        assert!(load(bad(&|f| f.p.iter_mut().for_each(|p| *p *= 1.5))));
        assert!(load(bad(&|f| f.load = 1e308)));
        assert!(matches!(
            bad(&|f| f.n_dofs = usize::MAX),
            Meaningless::Sizes { .. }
        ));
        assert_eq!(bad(&|f| f.ms = f64::NAN), Meaningless::NotFinite);
        assert!(load(bad(&|f| f.p[3] = 1e200)));
        let scaled = bad(&|f| {
            f.p.iter_mut().for_each(|p| *p *= 1.5);
            f.load *= 1.5;
        });
        assert!(matches!(scaled, Meaningless::Reaction { .. }), "{scaled}");
        // Everything ×1.5 (u, p and the load): consistent, but u_n = 1.5 g where it presses.
        let all = bad(&|f| {
            f.u.iter_mut().for_each(|u| *u *= 1.5);
            f.p.iter_mut().for_each(|p| *p *= 1.5);
            f.load *= 1.5;
        });
        assert!(matches!(all, Meaningless::Contact { .. }), "{all}");
        // A true solution of depth 0.7 read for depth 0.8: 0.1 short of the obstacle.
        let mut shallower = s.clone();
        shallower.obstacle = s.obstacle.with_depth(0.7);
        let other = ReferenceFields::solve_on(&shallower, &grid).unwrap();
        assert_eq!(check(&shallower, &grid, &other), Ok(()));
        let e = check(&s, &grid, &other).unwrap_err();
        assert!(matches!(e, Meaningless::Contact { gap, .. } if gap > 0.09), "{e}");
    }

    /// With friction (μ = 0.3, a shift) a solved reference passes, its bottom balancing Q; u,
    /// p, t and the load all ×1.5, its t ×1.5, a t missing, or a frictionless entry read for
    /// friction each fail.
    #[test]
    fn a_friction_reference_balances_its_tangential_load() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/scenarios/hertz-paper-full.toml");
        let plain = Scenario::load(std::path::Path::new(path)).unwrap();
        let mut s = plain.clone();
        s.friction = crate::contact::friction::Friction {
            law: crate::contact::friction::Law::Coulomb { mu: 0.3 },
            shift: 0.05,
            steps: 2,
            epsilon_t: None,
            press: crate::contact::friction::Press::WithFriction,
        };
        let grid = ReferenceMesh::uniform(&s, 0);
        let good = ReferenceFields::solve_on(&s, &grid).unwrap();
        assert_eq!(check(&s, &grid, &good), Ok(()));
        assert!(good.t.iter().any(|&t| t > 0.0));
        let mut all = good.clone();
        for v in all.u.iter_mut().chain(&mut all.p).chain(&mut all.t) {
            *v *= 1.5;
        }
        all.load *= 1.5;
        assert!(matches!(check(&s, &grid, &all), Err(Meaningless::Contact { .. })));
        let mut scaled = good.clone();
        scaled.t.iter_mut().for_each(|t| *t *= 1.5);
        assert!(matches!(
            check(&s, &grid, &scaled),
            Err(Meaningless::Tangential { .. })
        ));
        let frictionless = ReferenceFields::solve_on(&plain, &grid).unwrap();
        assert!(frictionless.t.is_empty());
        assert!(matches!(
            check(&s, &grid, &frictionless),
            Err(Meaningless::Sizes { .. })
        ));
        assert!(matches!(
            check(&plain, &grid, &good),
            Err(Meaningless::Sizes { .. })
        ));
    }
}
