//! The `fem-qpP-corner` rows of `capstan bench work-precision` on `paper`: the Qp elements
//! on the mesh refined toward the four corners only
//! ([`capstan_elasticity::finite_element::CornerRefinedNavier`]): `12 x 2` coarse cells (about square in physical length), each
//! corner cell cut into `n` geometric layers (ratio [`CORNER_RATIO`]) of two trapezoids, `n`
//! growing along the series. Time and error as for the graded rows (`high_order.rs`): build,
//! condensation and skeleton assembly, analyse + factor + solve + interior recovery; error
//! against the graded reference by Gauss quadrature over the run's own elements.

use capstan_elasticity::finite_element::{CornerRefinedNavier, CornerSettings};
use capstan_elasticity::samples::PaperEllipse;
use capstan_elasticity::studies::paper_parts;
use capstan_elasticity::verification::GridLevel;

use super::high_order::timed_condensed;
use super::{Problem, REPEAT_RULE, Reference, Run};
use crate::error::CliError;

/// Ratio of successive corner layers (measured on `paper`, docs/high-order.md).
pub const CORNER_RATIO: f64 = 0.3;

/// Coarse cells `[x2, x3]` of the corner series.
const CELLS: [usize; 2] = [12, 2];

/// Layers per corner along a series.
const LAYERS: [usize; 9] = [1, 2, 3, 4, 5, 6, 8, 10, 12];

/// The corner series' layer counts (`--quick`: the first three).
pub(super) fn corner_layers(quick: bool) -> &'static [usize] {
    if quick { &LAYERS[..3] } else { &LAYERS[..] }
}

/// The settings of the run of order `p` with `n` layers.
pub fn corner_settings(p: usize, n: usize) -> CornerSettings {
    CornerSettings {
        order: p,
        cells: CELLS,
        layers: n,
        ratio: CORNER_RATIO,
    }
}

/// One `fem-qpP-corner` run on `paper`, the fastest of [`REPEAT_RULE`].
pub(super) fn run_corner(
    p: usize,
    layers: usize,
    reference: Reference<'_>,
    use_vmhwm: bool,
) -> Result<Run, CliError> {
    REPEAT_RULE.fastest(|| {
        let (op, t) = timed_condensed(use_vmhwm, reference, || {
            // the grid only gives the rectangle
            let parts = paper_parts(&PaperEllipse::default(), GridLevel { n2: 3, n3: 3 })?;
            Ok(CornerRefinedNavier::new(parts, corner_settings(p, layers))?)
        })?;
        let name = capstan_elasticity::finite_element::high_order::order_name(p);
        Ok(t.run(
            Problem::Paper,
            format!("{name}-corner"),
            [op.element_count(), layers],
            op.dof_count(),
        ))
    })
}
