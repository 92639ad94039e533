//! One load step of the membrane with a nonsmooth friction law: semismooth Newton on the
//! augmented-Lagrangian (projection) form, with the active set reported per iteration.

use capstan_geometry::ProfileCurve;

use capstan_solvers::{Flow, NewtonDirection, NewtonIterate, NewtonSystem, newton_drive};

use crate::error::{FrictionError, check};
use crate::membrane_displacement::{
    EndCondition, MembraneDisplacementProblem, MembraneGrid, membrane_policy, spent, thomas,
};
use crate::nonsmooth_law::{FrictionState, NonsmoothFrictionLaw};

use super::step::{MembraneState, MembraneStep, SemismoothIteration, SemismoothSettings};

/// Iterations in a row with every free node sliding (and no convergence) after which the
/// membrane is taken to slide as a whole: no static equilibrium.
const RIGID_SLIDING_ITERATIONS: usize = 10;

/// The pieces of one residual evaluation.
struct Evaluation {
    /// Equilibrium rows `E_i` (force; a displacement end: `w - W`).
    equilibrium: Vec<f64>,
    /// Friction rows `F_i = t_i - P(t_i - r_i dw_i)` (force per unit length).
    friction: Vec<f64>,
    /// `dt/dt*` of the projection at each node.
    d_trial: Vec<f64>,
    /// `dt/dsigma_n` of the projection at each node.
    d_pressure: Vec<f64>,
    /// `|t| / |t*|` of the projection (1 in stick, `g/|t*|` in slip): how near to sticking.
    closeness: Vec<f64>,
    /// The projection's state at each node.
    states: Vec<FrictionState>,
    /// Node tensions.
    tension: Vec<f64>,
    /// `max(|E_i|, |l_i F_i|)`.
    norm: f64,
}

/// The step solver: the discrete membrane of [`crate::membrane_displacement`] with the friction
/// force per unit length `t_i` as a second unknown at each node.
pub(super) struct StepSolver<'a, L: NonsmoothFrictionLaw<f64>> {
    pub law: &'a L,
    pub params: &'a L::Params,
    pub grid: MembraneGrid,
    pub problem: MembraneDisplacementProblem,
}

impl<L: NonsmoothFrictionLaw<f64>> StepSolver<'_, L> {
    /// The grid of `problem` on `profile`.
    pub(super) fn grid<C: ProfileCurve<f64> + ?Sized>(
        profile: &C,
        problem: &MembraneDisplacementProblem,
    ) -> Result<MembraneGrid, FrictionError> {
        MembraneGrid::new(profile, problem)
    }

    fn is_fixed(&self, i: usize) -> bool {
        let n = self.grid.theta.len();
        (i == 0 && matches!(self.problem.start, EndCondition::Displacement(_)))
            || (i == n - 1 && matches!(self.problem.end, EndCondition::Displacement(_)))
    }

    /// The length `l_i` a node's friction acts on: `d J_i`, half at the ends.
    fn cell(&self, i: usize) -> f64 {
        let n = self.grid.theta.len();
        let full = self.grid.d * self.grid.nodes[i].0;
        if i == 0 || i == n - 1 {
            0.5 * full
        } else {
            full
        }
    }

    /// The augmentation `r_i`: the setting, or the membrane's stiffness per unit length at the
    /// node, `k / (d J_i)^2` (of the order of the tridiagonal operator's diagonal per cell).
    fn augmentation(&self, i: usize, settings: &SemismoothSettings) -> f64 {
        settings.augmentation.unwrap_or_else(|| {
            let dj = self.grid.d * self.grid.nodes[i].0;
            self.problem.stiffness / (dj * dj)
        })
    }

    /// `dE_i/dw` as `[lower, diag, upper]` and `dT_i/dw` likewise (zero at tension ends).
    fn rows(&self, i: usize) -> ([f64; 3], [f64; 3]) {
        let (n, c) = (self.grid.theta.len(), &self.grid.c);
        if i == 0 {
            ([0.0, -c[0], c[0]], [0.0; 3])
        } else if i == n - 1 {
            ([c[n - 2], -c[n - 2], 0.0], [0.0; 3])
        } else {
            (
                [c[i - 1], -c[i - 1] - c[i], c[i]],
                [-0.5 * c[i - 1], 0.5 * (c[i - 1] - c[i]), 0.5 * c[i]],
            )
        }
    }

    fn evaluate(
        &self,
        w: &[f64],
        t: &[f64],
        previous: &MembraneState,
        settings: &SemismoothSettings,
    ) -> Result<Evaluation, FrictionError> {
        let (n, c) = (w.len(), &self.grid.c);
        let half = |i: usize| c[i] * (w[i + 1] - w[i]);
        let mut e = Evaluation {
            equilibrium: vec![0.0; n],
            friction: vec![0.0; n],
            d_trial: vec![0.0; n],
            d_pressure: vec![0.0; n],
            closeness: vec![1.0; n],
            states: vec![FrictionState::Stick; n],
            tension: vec![0.0; n],
            norm: 0.0,
        };
        for i in 0..n {
            let kappa = self.grid.nodes[i].1;
            let bc = if i == 0 {
                Some(self.problem.start)
            } else if i == n - 1 {
                Some(self.problem.end)
            } else {
                None
            };
            let (ei, ti) = match bc {
                Some(EndCondition::Displacement(x)) => (w[i] - x, f64::NAN),
                Some(EndCondition::Tension(te)) => {
                    let l = self.cell(i);
                    let ei = if i == 0 {
                        half(0) - te + l * t[i]
                    } else {
                        te - half(n - 2) + l * t[i]
                    };
                    (ei, te)
                }
                None => (
                    half(i) - half(i - 1) + self.cell(i) * t[i],
                    0.5 * (half(i - 1) + half(i)),
                ),
            };
            e.equilibrium[i] = ei;
            e.norm = e.norm.max(ei.abs());
            if ti.is_nan() {
                // a displacement end: no friction unknown (t = 0), the state follows the motion
                e.friction[i] = t[i];
                e.states[i] = if w[i] == previous.displacement[i] {
                    FrictionState::Stick
                } else {
                    FrictionState::Slip
                };
                e.tension[i] = ti;
                continue;
            }
            e.tension[i] = ti;
            let trial = t[i] - self.augmentation(i, settings) * (w[i] - previous.displacement[i]);
            let p = self.law.project([0.0, trial], -kappa * ti, self.params)?;
            e.friction[i] = t[i] - p.traction[1];
            e.d_trial[i] = p.d_trial[1][1];
            e.d_pressure[i] = p.d_pressure[1];
            e.closeness[i] = if trial == 0.0 {
                1.0
            } else {
                (p.traction[1] / trial).abs()
            };
            e.states[i] = p.state;
            e.norm = e.norm.max((self.cell(i) * e.friction[i]).abs());
        }
        if !e.norm.is_finite() {
            e.norm = f64::INFINITY;
        }
        Ok(e)
    }

    /// Solves one load step from `previous` (see the module docs of [`super`]).
    pub(super) fn solve(
        &self,
        previous: &MembraneState,
        settings: &SemismoothSettings,
        progress: &mut dyn FnMut(&SemismoothIteration),
    ) -> Result<MembraneStep, FrictionError> {
        check(
            "max_iterations",
            settings.max_iterations as f64,
            "[1, inf)",
            |v| v >= 1.0,
        )?;
        check("tolerance", settings.tolerance, "(0, 1)", |v| {
            v > 0.0 && v < 1.0
        })?;
        if let Some(r) = settings.augmentation {
            check("augmentation", r, "(0, inf)", |v| v > 0.0)?;
        }
        let n = self.grid.theta.len();
        check(
            "previous state",
            previous.displacement.len() as f64,
            "one value per node",
            |v| v == n as f64 && previous.friction.len() == n,
        )?;
        let wp = &previous.displacement;
        let (mut w, mut t) = match (settings.sweep, self.problem.start, self.problem.end) {
            (true, EndCondition::Tension(t0), EndCondition::Tension(te)) => {
                self.sweep(previous, t0, te)
            }
            _ => (wp.clone(), previous.friction.clone()),
        };
        if let EndCondition::Displacement(v) = self.problem.start {
            w[0] = v;
        }
        if let EndCondition::Displacement(v) = self.problem.end {
            w[n - 1] = v;
        }
        let mut u = w;
        u.append(&mut t);
        // backtracking on the residual's max norm
        let policy = membrane_policy(
            settings.max_iterations,
            settings.tolerance * self.grid.scale,
            1e-3,
        );
        let mut system = SemismoothSystem {
            solver: self,
            previous,
            settings,
            progress,
            c_max: self.grid.c.iter().fold(0.0f64, |m, x| m.max(*x)),
            last: None,
            current: None,
            changes: 0,
            sliding: 0,
        };
        let result = newton_drive(&mut system, &mut u, &policy);
        let (changes, current) = (system.changes, system.current);
        let iterations = match result {
            Ok(done) => done.iterations,
            Err(failure) => {
                let (iterations, residual) = spent(failure, self.problem.theta0)?;
                return Err(FrictionError::SemismoothNotConverged {
                    iterations,
                    residual,
                    changes,
                });
            }
        };
        let t = u.split_off(n);
        let ev = current.ok_or(FrictionError::NonFinite {
            what: "semismooth Newton evaluation",
            angle: self.problem.theta0,
        })?;
        Ok(self.finish(u, t, wp, ev, iterations))
    }

    /// The capstan sweep: the start of a step between two tension ends `t0`, `te`. From the
    /// loaded end inward the half-cell tensions follow the discrete slip balance with the
    /// slip direction `sigma = sign(te - te_old)`,
    /// `T_{i-1/2} = T_{i+1/2} (1 - sigma a_i)/(1 + sigma a_i)`, `a_i = l_i mu kappa_i / 2`
    /// (`mu` read from the law: the projection of a large trial), until they meet the
    /// previous state's tensions; inward of that the tensions are the previous ones (stick).
    /// Then `w` from the tensions (`w_0` kept) and `t` from the equilibrium rows. On a single
    /// slip zone growing from the loaded end (loading, unloading, reloading of a belt) this
    /// is the discrete solution up to the node where the zones meet.
    fn sweep(&self, previous: &MembraneState, t0: f64, te: f64) -> (Vec<f64>, Vec<f64>) {
        let (n, c) = (self.grid.theta.len(), &self.grid.c);
        let wp = &previous.displacement;
        let old: Vec<f64> = (0..n - 1).map(|i| c[i] * (wp[i + 1] - wp[i])).collect();
        let te_old = old[n - 2] - self.cell(n - 1) * previous.friction[n - 1];
        let sigma = if te > te_old {
            1.0
        } else if te < te_old {
            -1.0
        } else {
            return (wp.clone(), previous.friction.clone());
        };
        // mu kappa_i: the limit of the projection of a trial beyond any bound, at sigma_n = -1
        let mu_kappa = |i: usize| -> Option<f64> {
            let kappa = self.grid.nodes[i].1;
            let p = self.law.project([0.0, 1e100], -kappa, self.params).ok()?;
            Some(p.traction[1].abs())
        };
        let mut half = old.clone();
        let Some(g_end) = mu_kappa(n - 1) else {
            return (wp.clone(), previous.friction.clone());
        };
        let mut current = te * (1.0 - sigma * self.cell(n - 1) * g_end);
        for j in (0..n - 1).rev() {
            if sigma * (current - old[j]) <= 0.0 {
                break;
            }
            half[j] = current;
            if j == 0 {
                break;
            }
            let Some(g) = mu_kappa(j) else { break };
            let a = 0.5 * self.cell(j) * g;
            current *= (1.0 - sigma * a) / (1.0 + sigma * a);
        }
        let mut w = vec![wp[0]; n];
        for i in 1..n {
            w[i] = w[i - 1] + half[i - 1] / c[i - 1];
        }
        let t = (0..n)
            .map(|i| {
                let (left, right) = match i {
                    0 => (t0, half[0]),
                    i if i == n - 1 => (half[n - 2], te),
                    i => (half[i - 1], half[i]),
                };
                -(right - left) / self.cell(i)
            })
            .collect();
        (w, t)
    }

    /// The semismooth Newton step `(dw, dt)`: the friction rows eliminated node by node, a
    /// tridiagonal system in `dw`, then `dt` from the equilibrium rows.
    fn newton_step(
        &self,
        ev: &Evaluation,
        settings: &SemismoothSettings,
    ) -> Result<(Vec<f64>, Vec<f64>), FrictionError> {
        let n = self.grid.theta.len();
        let mut jac = vec![[0.0; 3]; n];
        // Every free node sliding leaves the membrane free to translate (a singular system)
        // unless that is the solution: an intermediate iterate takes the stick branch at the
        // node nearest to sticking, so that the step is defined.
        let anchor = if (0..n).all(|i| self.is_fixed(i) || ev.states[i] != FrictionState::Stick) {
            (0..n)
                .filter(|&i| !self.is_fixed(i))
                .max_by(|&i, &j| ev.closeness[i].total_cmp(&ev.closeness[j]))
        } else {
            None
        };
        let mut rhs = vec![0.0; n];
        for i in 0..n {
            if self.is_fixed(i) {
                jac[i] = [0.0, 1.0, 0.0];
                rhs[i] = -ev.equilibrium[i];
                continue;
            }
            // F linearised: (1 - D) dt + D r dw_i + S kappa dT = -F; with dt from E:
            // (1 - D) A.dw - l S kappa B.dw - l D r dw_i = -(1 - D) E + l F
            let (ar, b) = self.rows(i);
            let (dd, s) = if anchor == Some(i) {
                (1.0, 0.0)
            } else {
                (ev.d_trial[i], ev.d_pressure[i])
            };
            let (l, kappa, r) = (
                self.cell(i),
                self.grid.nodes[i].1,
                self.augmentation(i, settings),
            );
            for k in 0..3 {
                jac[i][k] = (1.0 - dd) * ar[k] - l * s * kappa * b[k];
            }
            jac[i][1] -= l * dd * r;
            rhs[i] = -(1.0 - dd) * ev.equilibrium[i] + l * ev.friction[i];
        }
        if thomas(&jac, &mut rhs).is_none() {
            let sliding = (0..n)
                .filter(|&i| !self.is_fixed(i))
                .all(|i| ev.states[i] != FrictionState::Stick);
            return Err(if sliding {
                FrictionError::RigidSliding {
                    theta0: self.problem.theta0,
                    theta1: self.problem.theta1,
                }
            } else {
                FrictionError::NonFinite {
                    what: "semismooth Newton step (singular tridiagonal system)",
                    angle: self.problem.theta0,
                }
            });
        }
        let dw = rhs;
        let dt = (0..n)
            .map(|i| {
                if self.is_fixed(i) {
                    return -ev.friction[i];
                }
                let (a, _) = self.rows(i);
                let adw = a[0] * if i > 0 { dw[i - 1] } else { 0.0 }
                    + a[1] * dw[i]
                    + a[2] * if i + 1 < n { dw[i + 1] } else { 0.0 };
                (-ev.equilibrium[i] - adw) / self.cell(i)
            })
            .collect();
        Ok((dw, dt))
    }

    fn finish(
        &self,
        w: Vec<f64>,
        t: Vec<f64>,
        previous: &[f64],
        ev: Evaluation,
        iterations: usize,
    ) -> MembraneStep {
        let n = w.len();
        let c = &self.grid.c;
        let half: Vec<f64> = (0..n - 1).map(|i| c[i] * (w[i + 1] - w[i])).collect();
        let mut tension = ev.tension;
        if self.is_fixed(0) {
            tension[0] = 1.5 * half[0] - 0.5 * half[1];
        }
        if self.is_fixed(n - 1) {
            tension[n - 1] = 1.5 * half[n - 2] - 0.5 * half[n - 3];
        }
        let slip: Vec<f64> = w.iter().zip(previous).map(|(a, b)| a - b).collect();
        // A node left on the limit by an earlier slip and not moving now sticks: its trial is
        // on the limit to the round-off of the tensions (differences of w), which the
        // projection may read either way; the step's own slip increment decides.
        let noise = 64.0 * f64::EPSILON * w.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let mut states = ev.states;
        for (state, du) in states.iter_mut().zip(&slip) {
            if *state == FrictionState::Slip && du.abs() <= noise {
                *state = FrictionState::Stick;
            }
        }
        let dissipation = (0..n)
            .filter(|&i| !self.is_fixed(i))
            .map(|i| -self.cell(i) * t[i] * slip[i])
            .sum();
        let reaction = tension
            .iter()
            .zip(&self.grid.nodes)
            .map(|(t, (_, kappa))| kappa * t)
            .collect();
        MembraneStep {
            theta: self.grid.theta.clone(),
            displacement: w,
            slip_increment: slip,
            friction: t,
            tension,
            reaction,
            states,
            iterations,
            residual: ev.norm,
            dissipation,
        }
    }
}

/// One load step as a problem of the Newton driver: the unknowns `(w, t)` in one vector, the
/// residual `(E_i, l_i F_i)` (its max norm the step's residual), the semismooth Newton step,
/// the active set reported and the rigid sliding detected after every accepted iterate.
struct SemismoothSystem<'s, 'a, 'p, L: NonsmoothFrictionLaw<f64>> {
    solver: &'s StepSolver<'a, L>,
    previous: &'s MembraneState,
    settings: &'s SemismoothSettings,
    progress: &'p mut dyn FnMut(&SemismoothIteration),
    /// `max_i c_{i+1/2}`.
    c_max: f64,
    /// The evaluation of the last residual (a trial point).
    last: Option<Evaluation>,
    /// The evaluation of the accepted iterate.
    current: Option<Evaluation>,
    /// Nodes whose state changed in the last accepted step.
    changes: usize,
    /// Iterations in a row at which every free node slides.
    sliding: usize,
}

impl<L: NonsmoothFrictionLaw<f64>> NewtonSystem for SemismoothSystem<'_, '_, '_, L> {
    type Error = FrictionError;

    fn residual(&mut self, u: &[f64], r: &mut [f64]) -> Result<(), FrictionError> {
        let n = u.len() / 2;
        let ev = self
            .solver
            .evaluate(&u[..n], &u[n..], self.previous, self.settings)?;
        for i in 0..n {
            r[i] = ev.equilibrium[i];
            // a displacement end has no friction row
            r[n + i] = if ev.tension[i].is_nan() {
                0.0
            } else {
                self.solver.cell(i) * ev.friction[i]
            };
        }
        self.last = Some(ev);
        Ok(())
    }

    fn direction(
        &mut self,
        _at: &NewtonIterate<'_>,
        d: &mut [f64],
    ) -> Result<NewtonDirection, FrictionError> {
        let ev = self.current.as_ref().ok_or(FrictionError::NonFinite {
            what: "semismooth Newton evaluation",
            angle: self.solver.problem.theta0,
        })?;
        let (dw, dt) = self.solver.newton_step(ev, self.settings)?;
        let n = dw.len();
        d[..n].copy_from_slice(&dw);
        d[n..].copy_from_slice(&dt);
        Ok(NewtonDirection::default())
    }

    /// The round-off floor of the residual: differences `c (w_{i+1} - w_i)` of large terms.
    fn floor(&self, u: &[f64]) -> f64 {
        let w = &u[..u.len() / 2];
        100.0 * f64::EPSILON * self.c_max * w.iter().fold(0.0f64, |m, x| m.max(x.abs()))
    }

    fn accepted(&mut self, at: &NewtonIterate<'_>) -> Result<Flow, FrictionError> {
        let ev = self.last.take().ok_or(FrictionError::NonFinite {
            what: "semismooth Newton evaluation",
            angle: self.solver.problem.theta0,
        })?;
        if let Some(old) = &self.current {
            self.changes = ev
                .states
                .iter()
                .zip(&old.states)
                .filter(|(a, b)| a != b)
                .count();
        }
        let count = |k: FrictionState| ev.states.iter().filter(|&&x| x == k).count();
        (self.progress)(&SemismoothIteration {
            iteration: at.iteration,
            residual: ev.norm,
            step: at.step,
            stick: count(FrictionState::Stick),
            slip: count(FrictionState::Slip),
            separated: count(FrictionState::Separated),
            changes: self.changes,
        });
        let solver = self.solver;
        let free_sliding = (0..ev.states.len())
            .all(|i| solver.is_fixed(i) || ev.states[i] != FrictionState::Stick);
        self.current = Some(ev);
        if at.iteration > 0 {
            if free_sliding {
                self.sliding += 1;
                if self.sliding == RIGID_SLIDING_ITERATIONS {
                    return Err(FrictionError::RigidSliding {
                        theta0: solver.problem.theta0,
                        theta1: solver.problem.theta1,
                    });
                }
            } else {
                self.sliding = 0;
            }
        }
        Ok(Flow::Continue)
    }
}
