//! `i`: the stiffness's volumetric integration, full ↔ selective ([`Integration`]), the lab's
//! way to show volumetric locking as ν → ½ (scenarios/near-incompressible.toml) and its cure
//! by reduced integration, the idea behind the paper's references 2–4.

use crate::fem::Integration;
use crate::mesh::Element;

use super::{App, Notice};

impl App {
    /// Switch the integration of the next solve and say what it set (and where it changes
    /// nothing: a P1 triangle's strains are constant).
    pub(super) fn switch_integration(&mut self) {
        let s = &mut self.settings;
        s.integration = match s.integration {
            Integration::Full => Integration::Selective,
            Integration::Selective => Integration::Full,
        };
        // One status row at 80 columns beside the key hint, p1's remark on a second.
        let what = match s.integration {
            Integration::Full => "full: λ div u exact (Q1 locks as ν → ½",
            Integration::Selective => "selective: λ div u reduced (no locking",
        };
        let nu = self.scenario.material.poisson;
        let p1 = if s.element == Element::P1 {
            "; p1's strains are constant: it changes nothing"
        } else {
            ""
        };
        self.notice = Some(Notice::info(format!("integration {what}; ν = {nu}){p1}")));
    }
}
