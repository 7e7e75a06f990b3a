//! Degrees of freedom: two per node (u_x, u_y), numbered node by node; the Dirichlet
//! dofs of Γ_D (and of the symmetry line of a half model) are removed, leaving V_h of (5).

use crate::mesh::Mesh;

/// Marks a constrained dof in [`DofMap::free`].
const CONSTRAINED: usize = usize::MAX;

/// How a body is held on its support Γ_D, the bottom row of its mesh (docs/design.md §1).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Support {
    /// u = 0: the model's clamped base.
    #[default]
    Clamped,
    /// u_y = 0 and u_x free, but for the one u_x that removes the rigid slide (the symmetry
    /// line's of a half model, else the support's first node's): with free sides, a uniform
    /// compression is exact (the contact patch test).
    Roller,
    /// Free but for the one point that removes the vertical translation: the support's first
    /// node's u (on a half model's symmetry line, which holds the horizontal translation and
    /// the rotation) — a body whose load is balanced by its contact alone (a pressure on the
    /// upper body's top, docs/design.md §12). A half model's only: on a full one the rotation
    /// about that node stays free.
    Free,
}

impl Support {
    /// The support's name in scenario files and the outputs.
    pub fn name(self) -> &'static str {
        match self {
            Support::Clamped => "clamped",
            Support::Roller => "roller",
            Support::Free => "free",
        }
    }
}

/// The numbering of the free dofs among the 2 · nodes global ones.
#[derive(Clone, Debug)]
pub struct DofMap {
    /// For each global dof 2·node + component: its index among the free dofs, or CONSTRAINED.
    free: Vec<usize>,
    n_free: usize,
}

impl DofMap {
    /// Free dofs are all but those for which `constrained(node, component)` holds.
    pub fn new(n_nodes: usize, constrained: impl Fn(usize, usize) -> bool) -> Self {
        let mut free = vec![CONSTRAINED; 2 * n_nodes];
        let mut n_free = 0;
        for (g, slot) in free.iter_mut().enumerate() {
            if !constrained(g / 2, g % 2) {
                *slot = n_free;
                n_free += 1;
            }
        }
        DofMap { free, n_free }
    }

    /// The model's constraints (docs/design.md §1): the bottom clamped, u_x = 0 on the left side
    /// of a half model, and on the right side of a mesh with a roller wall there.
    pub fn model(mesh: &Mesh) -> Self {
        Self::supported(mesh, Support::Clamped)
    }

    /// As [`DofMap::model`] with the bottom held by `support`.
    pub fn supported(mesh: &Mesh, support: Support) -> Self {
        let nnx = mesh.nnx();
        let (symmetric, roller) = (mesh.symmetric_left, mesh.roller_right);
        let held_base = |node: usize, comp: usize| match support {
            Support::Clamped => true,
            Support::Roller => comp == 1 || node == 0,
            Support::Free => node == 0,
        };
        let map = Self::new(mesh.n_nodes(), |node, comp| {
            (node < nnx && held_base(node, comp))
                || (symmetric && comp == 0 && node % nnx == 0)
                || (roller && comp == 0 && node % nnx == nnx - 1)
        });
        debug_assert!(
            roller || map.n_free == Self::count_supported(nnx, mesh.node_y.len(), symmetric, support)
        );
        map
    }

    /// [`DofMap::count`] with the bottom held by `support`: a roller frees the u_x of every
    /// support node but one, [`Support::Free`] both components of every node but one.
    pub fn count_supported(nnx: usize, nny: usize, symmetric_left: bool, support: Support) -> usize {
        Self::count(nnx, nny, symmetric_left)
            + match support {
                Support::Clamped => 0,
                Support::Roller => nnx - 1,
                Support::Free => 2 * nnx - 2,
            }
    }

    /// The number of free dofs of [`DofMap::model`] on a grid of `nnx` × `nny` nodes without a
    /// roller wall, counted without building it: two per node above the clamped bottom row,
    /// less u_x on the symmetry line of a half model (`symmetric_left`) above the bottom.
    pub fn count(nnx: usize, nny: usize, symmetric_left: bool) -> usize {
        let above = nny - 1;
        2 * nnx * above - if symmetric_left { above } else { 0 }
    }

    /// The number of free dofs (the dimension of V_h).
    pub fn n_free(&self) -> usize {
        self.n_free
    }
    /// The free dof of u_n = u_y at each Γ_C node of `mesh`, ascending x: the trace that every
    /// factorisation orders last ([`super::condense`]). Γ_C is never on a clamped side, so a
    /// constrained one is a caller's error, and panics.
    pub fn contact_dofs(&self, mesh: &Mesh) -> Vec<usize> {
        mesh.top_nodes()
            .iter()
            .map(|&n| {
                self.free_index(2 * n + 1)
                    .expect("Γ_C is not on the clamped side")
            })
            .collect()
    }

    /// The free dof of u_t = u_x at each Γ_C node of `mesh`, ascending x: the tangential
    /// trace that friction adds to the normal one ([`crate::contact::friction`]). None when
    /// one of them is held (a half model's symmetry line, a roller wall).
    pub fn tangential_dofs(&self, mesh: &Mesh) -> Option<Vec<usize>> {
        mesh.top_nodes().iter().map(|&n| self.free_index(2 * n)).collect()
    }

    /// The free index of global dof `g`, if it is free.
    pub fn free_index(&self, g: usize) -> Option<usize> {
        let f = self.free[g];
        (f != CONSTRAINED).then_some(f)
    }

    /// Global vector from free values, with `fixed` (by global dof) on the constrained dofs.
    pub fn expand(&self, u_free: &[f64], fixed: impl Fn(usize) -> f64) -> Vec<f64> {
        (0..self.free.len())
            .map(|g| self.free_index(g).map_or_else(|| fixed(g), |f| u_free[f]))
            .collect()
    }

    /// Free values of a global vector.
    pub fn restrict(&self, global: &[f64]) -> Vec<f64> {
        let mut out = vec![0.0; self.n_free];
        for (g, &v) in global.iter().enumerate() {
            if let Some(f) = self.free_index(g) {
                out[f] = v;
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Element;

    /// The count agrees with the map, and both with a hand count: Q2 on 2 × 1 cells has 5 × 3
    /// nodes; 10 above the bottom row have 20 dofs, less 2 u_x on the symmetry line.
    #[test]
    fn count_matches_the_model_map() {
        assert_eq!(DofMap::count(5, 3, true), 18);
        assert_eq!(DofMap::count(5, 3, false), 20);
        // On rollers the base's 5 u_x are free but one: 4 more.
        assert_eq!(DofMap::count_supported(5, 3, true, Support::Roller), 22);
        // Free, the base's 10 dofs are free but its first node's 2: 8 more.
        assert_eq!(DofMap::count_supported(5, 3, true, Support::Free), 26);
        for element in Element::ALL {
            for (nx, ny) in [(1, 1), (2, 1), (3, 5)] {
                for symmetric in [false, true] {
                    let mesh = Mesh::uniform(element, (0.0, 1.0, nx), (0.0, 1.0, ny), symmetric);
                    assert_eq!(
                        DofMap::model(&mesh).n_free(),
                        DofMap::count(mesh.nnx(), mesh.node_y.len(), symmetric),
                        "{element:?} {nx}×{ny} symmetric {symmetric}"
                    );
                    for support in [Support::Roller, Support::Free] {
                        assert_eq!(
                            DofMap::supported(&mesh, support).n_free(),
                            DofMap::count_supported(mesh.nnx(), mesh.node_y.len(), symmetric, support),
                            "{element:?} {nx}×{ny} symmetric {symmetric} {support:?}"
                        );
                    }
                }
            }
        }
    }
}
