//! Grid sequencing (nested iteration) of the 3-D matrix-free Newton: the body solved on the
//! grids of its V-cycle's coarse levels first, each solution prolonged as the next finer
//! grid's Newton start.

use capstan_friction::FrictionLaw;
use capstan_geometry::{ShellChart, Surface};
use capstan_solvers::{Observer, Progress, SolveStage};

use crate::contact::error::{ContactError, ContactErrorKind};
use crate::contact::loads::EndLoads;
use crate::contact::matrix_free_newton::{MatrixFreeNewton, MatrixFreeSettings};
use crate::contact::model::ContactModel;
use crate::contact::operator::ContactOperator;
use crate::contact::solid_matrix_free::SolidMatrixFreeBody;
use crate::contact::solution::ContactSolution;
use crate::error::ElasticityError;
use crate::finite_element::ElementOrder;
use crate::solid::{HexElement, SolidBody, SolidMultigridParams, cell_sizes, coarse_level_nodes};

/// The coarsest grid of [`SolidBody::solve_matrix_free_sequenced`] by default: the sequence
/// stops at the first grid of at most this many unknowns (its stuck start then costs
/// little).
pub const SEQUENCE_COARSEST_UNKNOWNS: usize = 20_000;

/// The result of [`SolidBody::solve_matrix_free_sequenced`]: the body's own model and
/// solution, and the grids solved on the way.
pub struct MatrixFreeSequenced<D, L: FrictionLaw<f64>> {
    /// The contact model on the body's own grid.
    pub model: ContactModel<D, L>,
    /// Its solution (statistics of the finest level only; see `levels`).
    pub solution: ContactSolution,
    /// `(nodes [n1, n2, n3], Newton steps, Krylov iterations)` of every level solved,
    /// coarsest first (the last is the body's own grid; a skipped level is not listed).
    pub levels: Vec<([usize; 3], usize, usize)>,
}

impl<S: Surface<f64> + Clone + Send + Sync + 'static> SolidBody<S> {
    /// The body on the grid of its matrix-free V-cycle's assembled coarse level (Q1 hexahedra
    /// on [`coarse_level_nodes`]: the element vertices for `p > 1`, one semi-coarsening step
    /// for Q1), `None` when that is the body itself (no direction can be halved).
    ///
    /// # Errors
    /// Grid or geometry errors ([`cell_sizes`]).
    pub fn sequence_coarser(&self) -> Result<Option<Self>, ElasticityError> {
        let degree = self.order.degree();
        let chart = ShellChart::new(self.surface.clone());
        let nodes = coarse_level_nodes(self.nodes, degree, cell_sizes(&chart, &self.grid()?)?);
        if degree == 1 && nodes == self.nodes {
            return Ok(None);
        }
        let mut coarse = self.clone();
        coarse.nodes = nodes;
        coarse.order = HexElement::Uniform(ElementOrder::Q1);
        Ok(Some(coarse))
    }

    /// The matrix-free Newton ([`MatrixFreeNewton`]) with grid sequencing: the bodies of
    /// [`SolidBody::sequence_coarser`] down to the first of at most `coarsest_unknowns`
    /// unknowns, or to the last one of at most a quarter of the unknowns of the one above it
    /// (a semi-coarsening step that halves one direction only ends the sequence: its level
    /// would cost half the finer one's solve, and save less), the coarsest solved from its
    /// stuck start, each finer one by Newton from the
    /// coarser solution prolonged by its V-cycle's `P`
    /// ([`crate::contact::MatrixFreeBulk::prolongation`]: trilinear on the halved grid, or
    /// the Q1-to-Qp interpolation).
    ///
    /// # Math
    /// ```text
    /// bodies B_0 (coarsest) .. B_m (this body),  B_{k-1} = sequence_coarser(B_k)
    /// v_0 = MatrixFreeNewton(B_0) from the stuck start
    /// v_k = MatrixFreeNewton(B_k) from P_k v_{k-1}
    /// unknowns(B_{k-1}) <= unknowns(B_k) / 4     (work of all coarse levels <= 1/3 of the finest's)
    /// ```
    /// The prolonged start is within `O(h^2)` of the fine solution but for the nodes whose
    /// stick/slip state changes, so the fine grid, where every step costs most, takes a few
    /// Newton steps instead of those a stuck start takes; its stuck start (a penalised solve
    /// whose Krylov count grows with the grid) is never made. The answer is the fine
    /// problem's (the same residual and tolerance; only the start differs), and a level
    /// whose Newton fails from its start falls back to the stuck start and load continuation;
    /// a coarse level that does not converge at all is skipped (the next one starts from its
    /// stuck start), so a coarse level's non-convergence never fails the solve.
    ///
    /// Every level reports to `observer`: its solver's iterations, then one
    /// [`SolveStage::GridLevel`] event (`iteration` the level, coarsest 0; `residual_norm`
    /// the level's final Newton residual; `step_length` its unknowns).
    ///
    /// # Errors
    /// [`ElasticityError::InvalidParameter`] naming `solver.coarsest_unknowns` for
    /// `coarsest_unknowns == 0`; model and solver errors of any level.
    #[allow(clippy::too_many_arguments)]
    pub fn solve_matrix_free_sequenced<L: FrictionLaw<f64> + Clone>(
        &self,
        law: L,
        params: L::Params,
        slip_threshold: f64,
        multigrid: SolidMultigridParams,
        settings: MatrixFreeSettings,
        coarsest_unknowns: usize,
        loads: EndLoads,
        observer: &mut dyn Observer<f64>,
    ) -> Result<MatrixFreeSequenced<SolidMatrixFreeBody<ShellChart<S>>, L>, ContactError>
    where
        L::Params: Clone,
    {
        self.solve_sequenced_with(
            |body: &Self| {
                body.matrix_free_model(law.clone(), params.clone(), slip_threshold, multigrid)
            },
            settings,
            coarsest_unknowns,
            loads,
            observer,
        )
    }

    /// [`SolidBody::solve_matrix_free_sequenced`] with the matrix-free model of each level
    /// built by `model` (e.g. boxed as [`crate::contact::BodyOperator`]).
    ///
    /// # Errors
    /// See [`SolidBody::solve_matrix_free_sequenced`].
    pub fn solve_sequenced_with<D, L, F>(
        &self,
        model: F,
        settings: MatrixFreeSettings,
        coarsest_unknowns: usize,
        loads: EndLoads,
        observer: &mut dyn Observer<f64>,
    ) -> Result<MatrixFreeSequenced<D, L>, ContactError>
    where
        D: ContactOperator,
        L: FrictionLaw<f64>,
        F: Fn(&Self) -> Result<ContactModel<D, L>, ContactError>,
    {
        if coarsest_unknowns == 0 {
            return Err(ContactError::from(ElasticityError::InvalidParameter {
                field: "solver.coarsest_unknowns",
                value: 0.0,
                allowed: "[1, inf)",
            }));
        }
        let unknowns = |b: &Self| 3 * b.nodes.iter().product::<usize>();
        let mut bodies = vec![self.clone()];
        while let Some(last) = bodies.last()
            && unknowns(last) > coarsest_unknowns
            && let Some(c) = last.sequence_coarser()?
            && 4 * unknowns(&c) <= unknowns(last)
        {
            bodies.push(c);
        }
        bodies.reverse();
        let mut levels = Vec::with_capacity(bodies.len());
        let mut previous: Option<Vec<f64>> = None;
        let mut last = None;
        for (k, body) in bodies.iter().enumerate() {
            let model = model(body)?;
            let solver = MatrixFreeNewton::new(&model, settings)?;
            let solution = match previous.take() {
                None => match solver.solve_observed(loads, observer) {
                    Ok(solution) => solution,
                    // a coarse level that does not converge is skipped: the next level
                    // starts from its own stuck start
                    Err(e)
                        if k + 1 < bodies.len() && e.kind() == ContactErrorKind::NotConverged =>
                    {
                        continue;
                    }
                    Err(e) => return Err(e),
                },
                Some(coarse) => {
                    let p = model
                        .matrix_free_bulk()
                        .ok_or(ContactError::Unsupported {
                            field: "solver.linear",
                            message: "grid sequencing of the 3-D Newton needs a matrix-free model",
                        })?
                        .prolongation();
                    if p.ncols() != coarse.len() {
                        return Err(ContactError::from(ElasticityError::InconsistentBoundary {
                            what: "the sequence's coarser grid is not the V-cycle's coarse level",
                        }));
                    }
                    let mut start = vec![0.0; model.dof_count()];
                    p.mul_vec(&coarse, &mut start);
                    drop(coarse);
                    solver.solve_from_observed(loads, &start, observer)?
                }
            };
            observer.iteration(&Progress::new(
                SolveStage::GridLevel,
                k,
                solution.stats.residual,
                unknowns(body) as f64,
            ));
            levels.push((
                body.nodes,
                solution.stats.newton_iterations,
                solution.stats.linear_iterations,
            ));
            if k + 1 < bodies.len() {
                previous = Some(solution.displacement);
            } else {
                last = Some((model, solution));
            }
        }
        let (model, solution) = last.expect("at least the body's own level");
        Ok(MatrixFreeSequenced {
            model,
            solution,
            levels,
        })
    }
}
