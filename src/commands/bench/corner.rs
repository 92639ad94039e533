//! The `fem-qpP-corner` rows of `capstan bench work-precision` on `paper`: the Qp elements
//! on the mesh refined toward the four corners only
//! ([`capstan_elasticity::finite_element::CornerRefinedNavier`]): `12 x 2` coarse cells (about square in physical length), each
//! corner cell cut into `n` geometric layers (ratio [`CORNER_RATIO`]) of two trapezoids, `n`
//! growing along the series. Time and error as for the graded rows (`high_order.rs`): build,
//! condensation and skeleton assembly, analyse + factor + solve + interior recovery; error
//! against the graded reference by Gauss quadrature over the run's own elements.

use std::time::Instant;

use capstan_elasticity::finite_element::{CornerRefinedNavier, CornerSettings};
use capstan_elasticity::samples::PaperEllipse;
use capstan_elasticity::solvers::SparseCholesky;
use capstan_elasticity::studies::paper_parts;
use capstan_elasticity::verification::GridLevel;

use super::{Problem, REPEAT_RULE, Reference, Run, reset_peak, status_kib};
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
        if use_vmhwm {
            reset_peak();
        }
        let base = status_kib("VmRSS:").unwrap_or(0.0);
        let start = Instant::now();
        // the grid only gives the rectangle
        let parts = paper_parts(&PaperEllipse::default(), GridLevel { n2: 3, n3: 3 })?;
        let op = CornerRefinedNavier::new(parts, corner_settings(p, layers))?;
        let t_setup = start.elapsed().as_secs_f64();
        let t = Instant::now();
        let condensed = op.condensed_system()?;
        let t_assemble = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let u = condensed.system.solve(&mut SparseCholesky::default())?;
        let v = op.recover(&condensed, &u)?;
        let t_solve = t.elapsed().as_secs_f64();
        let total = start.elapsed().as_secs_f64();
        let peak_mib = if use_vmhwm {
            (status_kib("VmHWM:").unwrap_or(0.0) - base).max(0.0) / 1024.0
        } else {
            (12.0 * condensed.system.pattern.nnz() as f64 + 40.0 * op.dof_count() as f64)
                / 1_048_576.0
        };
        let e = op.displacement_errors(&v, reference)?;
        let name = capstan_elasticity::finite_element::high_order::order_name(p);
        Ok(Run {
            problem: Problem::Paper.name(),
            method: format!("{name}-corner"),
            backend: "cholesky".to_owned(),
            n2: op.element_count(),
            n3: layers,
            dofs: op.dof_count(),
            threads: rayon::current_num_threads(),
            setup_seconds: t_setup,
            assemble_seconds: t_assemble,
            solve_seconds: t_solve,
            seconds: total,
            error: e.l2 / e.l2_exact,
            peak_mib,
        })
    })
}
