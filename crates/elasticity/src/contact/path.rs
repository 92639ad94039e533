//! Load paths with memory on the thick body: a sequence of load states solved quasi-statically,
//! each from the previous state, friction acting on the slip increment of each step.

use std::time::Instant;

use capstan_friction::FrictionLaw;
use capstan_solvers::{Observer, SilentObserver};

use crate::contact::boundary_solver::BoundarySolver;
use crate::contact::error::ContactError;
use crate::contact::full_system::{FullSystemSettings, FullSystemSolver};
use crate::contact::loads::EndLoads;
use crate::contact::model::ContactModel;
use crate::contact::operator::ContactOperator;
use crate::contact::solution::ContactSolution;
use crate::discretisation::ContactNode;
use crate::error::ElasticityError;

/// Which contact solver runs the steps of a load path.
#[derive(Debug)]
pub enum PathSolver<'s, 'm, D, L: FrictionLaw<f64>> {
    /// The condensed solver, whose factorisation and condensation serve every step (the fast
    /// path: a step costs dense `m x m` Newton work and one sparse solve for the field).
    /// Regularised laws on bilateral contact only.
    Condensed(&'s BoundarySolver<'m, D, L>),
    /// The full-system Newton (sparse LU or another backend each step): every law, unilateral
    /// contact and exact (nonsmooth) friction.
    FullSystem(Box<FullSystemSettings>),
}

/// One solved load state of a path.
#[derive(Debug, Clone, PartialEq)]
pub struct PathStep {
    /// The solution of the step: its displacement is the total one, and its contact profile's
    /// `slip` and `state` are those of the slip increment over the step (what the law saw).
    pub solution: ContactSolution,
    /// Energy dissipated by friction over the step (per unit length of the prism in plane
    /// strain), `>= 0`.
    pub dissipation: f64,
    /// Physical tangential displacement `sqrt(g_22) v^2` of the contact node at the
    /// `theta_max` end (a 3-D body: on its middle `x1` line).
    pub end_displacement: f64,
    /// Wall time of the step's solve, seconds.
    pub seconds: f64,
}

/// Solves the load states `path` in order, the first from rest, each later one from the
/// state before it, with friction on the slip increment of each step
/// ([`ContactModel::with_slip_reference`]). Every Newton iterate goes to `observer`.
///
/// # Math
/// Step `n` solves the discrete equilibrium under the loads `b(tau^n)` with the law's slip
/// measured from the state `v^{n-1}` (`v^0 = 0`):
/// ```text
/// A v^n - b(tau^n) - sum_k w_k e_{row_k} t_k(F_k (x_k^n - x_k^{n-1}), sigma_k(v^n)) = 0
/// ```
/// (backward Euler in pseudo-time of the rate form of the law). Stick means no further slip,
/// so the stick/slip pattern and the displacement depend on the history: unloading leaves a
/// stuck zone with the tractions it carried, and a reverse-slip zone grows from the loaded
/// end. The friction work of the step on the slip increment `Delta u = F (x^n - x^{n-1})`,
/// ```text
/// D^n = - int t(v^n) . Delta u dS  >= 0      (trapezoidal rule on the contact nodes)
/// ```
/// is the energy dissipated (the traction opposes the slip increment under every Coulomb-type
/// law; backward Euler: the traction at the end of the step, so `D` converges at first order
/// in the load step). The first step is the static solve from rest, exactly (the model without a
/// reference, the solver's own start). With regularised Coulomb the stick branch has the
/// compliance `eps / (mu |sigma_n|)` per step (the law is a rate law), so loading in `N`
/// steps differs from one step by `O(N eps)`; exact Coulomb has none.
///
/// # Errors
/// [`ElasticityError::InvalidParameter`] naming `path` when it is empty;
/// [`ContactError::Unsupported`] for a matrix-free or distributed model; a failing step as
/// [`ContactError::PathStep`] with its number (from 1) and the solver's error.
pub fn solve_path<D: ContactOperator, L: FrictionLaw<f64> + Clone>(
    model: &ContactModel<D, L>,
    solver: PathSolver<'_, '_, D, L>,
    path: &[EndLoads],
    observer: &mut dyn Observer<f64>,
) -> Result<Vec<PathStep>, ContactError> {
    if path.is_empty() {
        return Err(ElasticityError::InvalidParameter {
            field: "path",
            value: 0.0,
            allowed: "at least one load state",
        }
        .into());
    }
    if model.is_matrix_free() || model.is_distributed() {
        return Err(ContactError::Unsupported {
            field: "solver.linear",
            message: "a load path needs the assembled bulk on one process (`lu`, `multigrid`); matrix-free and distributed solves run single load states",
        });
    }
    let mut steps: Vec<PathStep> = Vec::with_capacity(path.len());
    for (n, &loads) in path.iter().enumerate() {
        let at_step = |source: ContactError| ContactError::PathStep {
            step: n + 1,
            source: Box::new(source),
        };
        let started = Instant::now();
        let previous = steps.last().map(|s| &s.solution);
        // the first step is the model as built: today's static solve from rest
        let stepped = match previous {
            Some(p) => Some(
                model
                    .with_slip_reference(Some(p.displacement.clone()))
                    .map_err(at_step)?,
            ),
            None => None,
        };
        let step_model = stepped.as_ref().unwrap_or(model);
        let solution = match &solver {
            PathSolver::Condensed(base) => {
                let solver = match &stepped {
                    Some(m) => Some(base.with_model(m).map_err(at_step)?),
                    None => None,
                };
                let solver = solver.as_ref().unwrap_or(base);
                let guess = previous.map(|p| p.unknowns.as_slice());
                solver.solve_from_observed(loads, guess, observer)
            }
            PathSolver::FullSystem(settings) => {
                let solver = FullSystemSolver::new(step_model, **settings).map_err(at_step)?;
                match previous {
                    Some(p) => solver.solve_from_observed(loads, &p.displacement, observer),
                    None => solver.solve_observed(loads, observer),
                }
            }
        }
        .map_err(at_step)?;
        let dissipation = friction_work(step_model, &solution);
        let end_displacement = end_displacement(step_model, &solution);
        steps.push(PathStep {
            solution,
            dissipation,
            end_displacement,
            seconds: started.elapsed().as_secs_f64(),
        });
    }
    Ok(steps)
}

/// [`solve_path`] with no observer.
///
/// # Errors
/// See [`solve_path`].
pub fn solve_path_silent<D: ContactOperator, L: FrictionLaw<f64> + Clone>(
    model: &ContactModel<D, L>,
    solver: PathSolver<'_, '_, D, L>,
    path: &[EndLoads],
) -> Result<Vec<PathStep>, ContactError> {
    solve_path(model, solver, path, &mut SilentObserver)
}

/// `D = - int t . Delta u dS` over the contact surface: the work of the friction traction on
/// the body over the step's slip increment, with the sign of dissipation, by the trapezoidal
/// rule on the contact nodes (`dS = sqrt(g_22) dx2` per unit length in plane strain,
/// `sqrt(g_11) sqrt(g_22) dx1 dx2` on a 3-D body's face).
fn friction_work<D, L: FrictionLaw<f64>>(
    model: &ContactModel<D, L>,
    solution: &ContactSolution,
) -> f64 {
    // the sites in profile order: runs of entries with the same site
    let mut sites: Vec<Vec<&ContactNode>> = Vec::new();
    for node in model.contact_nodes() {
        match sites.last_mut() {
            Some(last) if last[0].site == node.site => last.push(node),
            _ => sites.push(vec![node]),
        }
    }
    let p = &solution.contact;
    let weights = |coordinates: Vec<f64>| -> Vec<(f64, f64)> {
        let mut x = coordinates;
        x.sort_by(f64::total_cmp);
        x.dedup();
        let n = x.len();
        (0..n)
            .map(|i| {
                let left = if i > 0 { x[i - 1] } else { x[i] };
                let right = if i + 1 < n { x[i + 1] } else { x[i] };
                (x[i], 0.5 * (right - left))
            })
            .collect()
    };
    let along = weights(p.x2.clone());
    let across = p.solid.as_ref().map(|s| weights(s.x1.clone()));
    let weight_of = |table: &[(f64, f64)], x: f64| -> f64 {
        let i = table.partition_point(|&(c, _)| c < x);
        table.get(i).map_or(0.0, |&(_, w)| w)
    };
    let mut work = 0.0;
    for (k, entries) in sites.iter().enumerate() {
        let area: f64 = entries.iter().map(|e| e.sqrt_g22).product();
        let mut w = weight_of(&along, p.x2[k]) * area;
        let mut power = p.friction_traction[k] * p.slip[k];
        if let (Some(s), Some(table)) = (p.solid.as_ref(), across.as_ref()) {
            w *= weight_of(table, s.x1[k]);
            power += s.friction_traction_1[k] * s.slip_1[k];
        }
        work -= w * power;
    }
    work
}

/// `sqrt(g_22) v^2` at the contact node of largest `x2` (a 3-D body: of those on the middle
/// `x1` line, the one of largest `x2`).
fn end_displacement<D, L: FrictionLaw<f64>>(
    model: &ContactModel<D, L>,
    solution: &ContactSolution,
) -> f64 {
    let v = &solution.displacement;
    let along_x2 = model.contact_nodes().iter().filter(|n| n.component == 2);
    let mut x1: Vec<f64> = along_x2.clone().map(|n| n.x1).collect();
    x1.sort_by(f64::total_cmp);
    x1.dedup();
    let middle = x1.get(x1.len() / 2).copied().unwrap_or(0.0);
    along_x2
        .filter(|n| n.x1 == middle)
        .max_by(|a, b| a.x2.total_cmp(&b.x2))
        .map_or(0.0, |n| n.sqrt_g22 * v[n.tangential_dof])
}
