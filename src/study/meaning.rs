//! What makes a study's numbers mean something: its errors are relative to the
//! reference's norms (‖p_ref‖₀ on Γ_C, ‖u_ref‖₁ of (7), P_ref), so a reference whose norms are
//! zero (no contact: the obstacle does not reach the body) or not finite gives no study at
//! all, and a row is `ok` only when every number it reports is finite.

use super::{Reference, Status, StudyRow};
use crate::error::{InputFault, SolveError};
use crate::scenario::Scenario;

/// Refuse a study of `scenario` before anything is solved when its obstacle does not reach
/// the body (depth ≤ 0: the lowest point of the obstacle at or above the top; the body is
/// then free of load, u = 0 and p = 0).
///
/// # Errors
///
/// The obstacle does not reach the body ([`SolveError::Input`]).
pub fn check_contact(scenario: &Scenario) -> Result<(), SolveError> {
    let depth = scenario.obstacle.depth();
    if depth > 0.0 {
        return Ok(());
    }
    Err(InputFault::NoContact { depth }.into())
}

impl Reference {
    /// The reference as a measure of the rows' errors: its norms and load finite and > 0.
    ///
    /// # Errors
    ///
    /// A norm or the load that is zero or not finite.
    pub fn check_meaningful(&self) -> Result<(), SolveError> {
        let norms = [self.p_norm, self.u_norm, self.load];
        if norms.iter().any(|v| !v.is_finite()) {
            return Err(InputFault::InfiniteReference {
                p_norm: self.p_norm,
                u_norm: self.u_norm,
                load: self.load,
            }
            .into());
        }
        if norms.iter().any(|&v| v <= 0.0) {
            return Err(InputFault::ZeroReference {
                p_norm: self.p_norm,
                u_norm: self.u_norm,
                load: self.load,
            }
            .into());
        }
        Ok(())
    }
}

impl StudyRow {
    /// A row with a result stays `ok` only when its load and errors are finite numbers;
    /// otherwise it is `failed` and says why.
    pub(super) fn certify(&mut self) {
        if self.status != Status::Ok {
            return;
        }
        let finite = self.load.is_none_or(f64::is_finite)
            && self.errors.is_none_or(|e| e.values().all(f64::is_finite));
        if !finite {
            self.status = Status::Failed;
            self.reason = Some("its load or its errors against the reference are not finite numbers".into());
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::study::{Errors, ReferenceFields, ReferenceMesh};

    fn reference(scale: f64) -> Reference {
        let s = Scenario::paper();
        let grid = ReferenceMesh::uniform(&s, 0);
        let (n_u, n_p) = grid.lengths();
        let fields = ReferenceFields {
            u: vec![scale; n_u],
            p: vec![scale; n_p],
            t: Vec::new(),
            load: scale,
            n_dofs: n_u,
            ms: 1.0,
            source: Default::default(),
        };
        Reference::from_fields(&s, &grid, &fields)
    }

    /// Zero norms (no contact) and overflowing ones are refused; ordinary ones pass.
    #[test]
    fn a_reference_without_contact_or_with_infinite_norms_is_refused() {
        assert_eq!(reference(1.0).check_meaningful(), Ok(()));
        let zero = reference(0.0).check_meaningful().unwrap_err();
        assert_eq!(
            zero,
            SolveError::Input(InputFault::ZeroReference {
                p_norm: 0.0,
                u_norm: 0.0,
                load: 0.0
            })
        );
        assert!(
            zero.to_string().starts_with("the reference has no contact"),
            "{zero}"
        );
        assert!(zero.is_input());
        // 1e200 squared overflows: its norms are infinite.
        let huge = reference(1e200).check_meaningful().unwrap_err();
        assert!(
            matches!(huge, SolveError::Input(InputFault::InfiniteReference { p_norm, .. }) if p_norm == f64::INFINITY),
            "{huge}"
        );
        let mut s = Scenario::paper();
        assert_eq!(check_contact(&s), Ok(()));
        s.obstacle = s.obstacle.with_depth(-0.5);
        assert_eq!(
            check_contact(&s),
            Err(SolveError::Input(InputFault::NoContact { depth: -0.5 }))
        );
    }

    /// A row whose errors are NaN is not `ok`.
    #[test]
    fn a_row_with_a_nan_error_is_failed() {
        let s = Scenario::paper();
        let r = reference(1.0);
        let m = (crate::contact::Method::Penalty, 1e-6);
        let scheme = (crate::mesh::Element::Q1, crate::contact::Rule::Gauss1);
        let err = SolveError::Cancelled;
        let (mut row, _) = StudyRow::new(&r, &s, scheme, 0, m, Err(&err));
        row.status = Status::Ok;
        row.errors = Some(Errors {
            p: f64::NAN,
            pbar: 0.1,
            u: 0.1,
            load: 0.1,
            tbar: None,
            tangential_load: None,
        });
        row.certify();
        assert_eq!(row.status, Status::Failed);
        assert!(row.reason.unwrap().contains("not finite"));
    }
}
