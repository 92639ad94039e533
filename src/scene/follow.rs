//! Defaults that follow other keys: the discretisation follows the body's dimension, the grid
//! follows the discretisation.
//!
//! The built-in defaults are for the paper's plane-strain body (`fd`, 250 x 41 nodes). A key
//! the scene does not give (neither in the file nor by `--set` / `Scene.set` in this
//! resolve) and whose built-in value the other keys refuse is moved to the nearest value they
//! accept; a value that was given is never changed (it is refused with the usual error
//! instead), and a value that is accepted is never changed:
//! - `discretisation.method`: `fd` with `body.dimension = 3` becomes `fem-q1` (finite
//!   differences are plane strain only; Q1 hexahedra are the cheapest 3-D element).
//! - `grid.n1` (3-D), `grid.n2`, `grid.n3`: the node count nearest the given one (ties down)
//!   that the method accepts (`DiscretisationScheme::admissible_nodes`: odd for `fem-q2`,
//!   `p e + 1` for `fem-qp` of order `p`, the graded partition's counts when graded), e.g.
//!   250 -> 249 for `fem-q2` or `fem-qp` of order 4.

use capstan_elasticity::finite_element::DiscretisationMethod;
use capstan_elasticity::registration::DiscretisationSettings;

use super::Scene;
use super::origins::Origins;

impl Scene {
    /// Applies the defaults that follow other keys (see the module docs); `origins` says which
    /// keys this resolve was given.
    pub(super) fn follow_defaults(&mut self, origins: &Origins) {
        if self.body.dimension == 3
            && self.discretisation.method == DiscretisationMethod::Fd
            && !origins.given("discretisation.method")
        {
            self.discretisation.method = DiscretisationMethod::FemQ1;
        }
        let d = &self.discretisation;
        let Ok(grading) = d.grading() else {
            return; // refused with its key by validation
        };
        let settings = DiscretisationSettings {
            order: d.order,
            volumetric: d.volumetric,
            grading,
            ..Default::default()
        };
        let Ok(scheme) = d.method.scheme(&settings) else {
            return; // refused with its key by validation
        };
        let dimension = self.body.dimension;
        let g = &mut self.grid;
        for (key, n) in [
            ("grid.n1", &mut g.n1),
            ("grid.n2", &mut g.n2),
            ("grid.n3", &mut g.n3),
        ] {
            if (key != "grid.n1" || dimension == 3) && !origins.given(key) {
                *n = scheme.admissible_nodes(*n);
            }
        }
    }
}
