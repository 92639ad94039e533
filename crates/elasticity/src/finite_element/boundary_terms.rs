//! Natural boundary terms (tractions and stresses on the sides) of the element operators.

use capstan_geometry::ShellPoint;

use crate::boundary::{Component, ComponentCondition, Side, SideCondition};
use crate::continuum::{FaceData, face_flux};
use crate::error::ElasticityError;

/// Adds the natural boundary term of one quadrature point `at` of `side` (chart point `p`) to
/// `load`: for every component `c` with a natural condition and every `(node index, N)` of
/// `shape`, `load[2 node + c] += N phi_c w J` with the flux of [`face_flux`]
/// ```text
/// phi_c = sqrt(g) sqrt(g^aa) t_c(s)   (traction),   phi_c = +-sqrt(g) T_c(s)   (stress)
/// ```
/// `a` the side's normal index, `s` the coordinate along the side, `[w, J]` the rule's weight
/// and the Jacobian of the edge (applied in that order).
///
/// # Errors
/// [`ElasticityError::NonFinite`] for a non-finite `phi_c`.
pub(crate) fn add_side_point_load(
    load: &mut [f64],
    cond: &SideCondition,
    side: Side,
    p: &ShellPoint<f64>,
    at: [f64; 2],
    [w, jacobian]: [f64; 2],
    shape: impl Iterator<Item = (usize, f64)> + Clone,
) -> Result<(), ElasticityError> {
    let a = side.normal_index();
    let s = if a == 2 { at[0] } else { at[1] };
    for c in Component::ALL {
        let data = match cond.component(c) {
            ComponentCondition::Displacement(_) => continue,
            ComponentCondition::Traction(f) => FaceData::Traction(f.eval(s)),
            ComponentCondition::Stress(f) => FaceData::Stress(f.eval(s)),
        };
        let flux = face_flux(p, a, side.sign(), data, at)?;
        for (node, n) in shape.clone() {
            load[2 * node + c.index()] += n * flux * w * jacobian;
        }
    }
    Ok(())
}
