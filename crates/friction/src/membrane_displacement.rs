//! The membrane as a displacement problem: a 1-D elastic membrane in bilateral contact with a
//! prism, a pointwise friction law on the contact, solved by Newton on the tangential
//! displacement. Its full-slip limit is the capstan profile of [`crate::membrane`].
//!
//! # Math
//! The membrane lies on the profile `(u(t), v(t))` of a prism for `t in [theta0, theta1]`
//! (arclength `s`, `ds = J dt`, `J = sqrt(a_22)`, curvature `kappa = Psi'/J > 0`). Bilateral
//! contact: the normal displacement is zero and the only unknown is the tangential
//! displacement `w(t)` (physical length along the curve). The linear membrane strain of a
//! displacement `w t + w_n N` along a curve is `eps_22 = dw/ds - kappa w_n`; with `w_n = 0`
//! it is `dw/ds`, with no curvature term. Hence
//! ```text
//! T     = k dw/ds                    k = E h l (zero Poisson's ratio, Theorem 1)
//!                                    k = E h / (1 - nu^2) per unit width (Corollary 1)
//! p     = kappa T - q.N              normal reaction per unit length (no loads here: q = 0)
//! dT/ds + t(w, -p) = 0               tangential balance, t from the friction law
//! ```
//! `t` is the law's traction with slip `(0, w)` and normal stress `sigma_n = -p`, so for
//! regularised Coulomb `t = -mu p w / max(|w|, eps)` and wherever `|w| >= eps` the balance is
//! the capstan equation `dT/ds = mu kappa T sign(w)`. The ends carry a tension or a
//! displacement ([`EndCondition`]).
//!
//! # Discretisation
//! `n` nodes uniform in `t` (spacing `d`), tensions on the half nodes,
//! `T_{i+1/2} = k (w_{i+1} - w_i) / (d J_{i+1/2})`; node balance
//! `T_{i+1/2} - T_{i-1/2} + d J_i t_i = 0` with `p_i = kappa_i (T_{i-1/2} + T_{i+1/2})/2`;
//! at an end with tension `T_e` a half cell `+-(T_e - T_{1/2}) + (d/2) J t(w, -kappa T_e) = 0`;
//! at an end with displacement `W` the row `w - W = 0`. The Jacobian is tridiagonal
//! (consistent tangent from [`FrictionLaw::traction_derivatives`]); Newton with a
//! backtracking line search, Thomas elimination.
//!
//! # Limit eps -> 0
//! In a full-slip state (every `|w| >= eps`) the regularised-Coulomb solution *is* the capstan
//! profile for every `eps`; only the grid error (second order) remains. The smooth
//! regularisation differs from Coulomb by `O(eps^2/w^2)`, so its full-slip profile converges at
//! second order in `eps`. With the low-tension end anchored (`w(theta0) = 0`) a stick layer of
//! length `delta = eps k / T(theta0)` forms there and `T(theta0)` exceeds the capstan value by
//! `mu kappa delta / 2` relative: first order in `eps` (`docs/models.md` has the numbers).
//!
//! # References
//! Paper section 2 (Theorem 1, Corollary 1: `T = h l E eps_22`, `tau = E/(1 - nu^2) eps_22`),
//! section 3 (eq. CoulombOden).

use capstan_geometry::ProfileCurve;

use capstan_solvers::{
    Flow, Merit, NewtonDirection, NewtonFailure, NewtonIterate, NewtonPolicy, NewtonSystem,
    ResidualNorm, ShortStep, StepControl, newton_drive,
};

use crate::error::{FrictionError, check, check_wrap};
use crate::friction_law::{ContactState, FrictionLaw};
use crate::membrane::ProfilePoint;

/// What holds one end of the membrane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum EndCondition {
    /// A given tension (force; stress for [`MembraneDisplacement`] with `k = E h/(1 - nu^2)`).
    Tension(f64),
    /// A given tangential displacement (physical length).
    Displacement(f64),
}

/// Settings of the Newton iteration.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MembraneNewton {
    /// Largest number of Newton steps.
    pub max_iterations: usize,
    /// Converged when `max |R_i| <= tolerance * scale` (`scale`: the largest end tension, or
    /// `k |W| / length` for displacement ends), or below the round-off floor
    /// `100 eps_mach max_i(k / (d J)) max|w|`.
    pub tolerance: f64,
}

impl Default for MembraneNewton {
    fn default() -> Self {
        Self {
            max_iterations: 100,
            tolerance: 1e-12,
        }
    }
}

/// A membrane displacement problem on `[theta0, theta1]` of a prism profile.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MembraneDisplacementProblem {
    /// Start of the contact interval (`membrane.theta0`).
    pub theta0: f64,
    /// End of the contact interval (`membrane.theta_max`).
    pub theta1: f64,
    /// Nodes (`>= 3`).
    pub nodes: usize,
    /// Axial stiffness `k` (`E h l`, or `E h/(1 - nu^2)`).
    pub stiffness: f64,
    /// Condition at `theta0`.
    pub start: EndCondition,
    /// Condition at `theta1`.
    pub end: EndCondition,
}

/// The solved membrane.
#[derive(Debug, Clone, PartialEq)]
pub struct MembraneDisplacementSolution {
    /// Node angles.
    pub theta: Vec<f64>,
    /// Tangential displacement `w` at the nodes.
    pub displacement: Vec<f64>,
    /// Tension at the nodes (ends: the given tension, or second-order extrapolation).
    pub tension: Vec<f64>,
    /// Normal reaction `p = kappa T` per unit length at the nodes.
    pub reaction: Vec<f64>,
    /// Newton iterations.
    pub iterations: usize,
    /// Final `max |R_i|`.
    pub residual: f64,
}

impl MembraneDisplacementSolution {
    /// `T(theta1) / T(theta0)`.
    ///
    /// # Panics
    /// Never for solutions built here (at least three nodes).
    pub fn tension_ratio(&self) -> f64 {
        self.tension.last().expect("nodes") / self.tension[0]
    }
    /// Stick/slip per node: `+1` if `w >= eps`, `-1` if `w <= -eps`, else `0`.
    pub fn states(&self, eps: f64) -> Vec<i8> {
        self.displacement
            .iter()
            .map(|&w| {
                if w >= eps {
                    1
                } else if w <= -eps {
                    -1
                } else {
                    0
                }
            })
            .collect()
    }
    /// The paper's Slip: the mean of [`MembraneDisplacementSolution::states`].
    pub fn slip_fraction(&self, eps: f64) -> f64 {
        let s = self.states(eps);
        s.iter().map(|&x| f64::from(x)).sum::<f64>() / s.len() as f64
    }
}

/// The membrane on a prism profile with a pointwise friction law (see the module docs).
///
/// # Example
/// ```
/// use capstan_friction::membrane_displacement::{EndCondition, MembraneDisplacement,
///     MembraneDisplacementProblem};
/// use capstan_friction::{RegularisedCoulomb, RegularisedCoulombParams};
/// use capstan_geometry::CircularCylinder;
/// let circle = CircularCylinder::new(1.0).unwrap();
/// let params = RegularisedCoulombParams::new(0.3, 1e-6).unwrap();
/// let problem = MembraneDisplacementProblem {
///     theta0: 0.0, theta1: std::f64::consts::PI, nodes: 801, stiffness: 100.0,
///     start: EndCondition::Tension(1.0), end: EndCondition::Displacement(1.0),
/// };
/// let m = MembraneDisplacement::new(&circle, RegularisedCoulomb, params);
/// let sol = m.solve(&problem, None, Default::default()).unwrap();
/// // fully slipping: the capstan ratio exp(mu pi), to the grid error
/// assert!((sol.tension_ratio() / (0.3 * std::f64::consts::PI).exp() - 1.0).abs() < 1e-5);
/// ```
#[derive(Debug, Clone)]
pub struct MembraneDisplacement<'a, C: ?Sized, L: FrictionLaw<f64>> {
    profile: &'a C,
    law: L,
    params: L::Params,
}

/// Geometry at one point: `J = sqrt(a_22)` and `kappa`.
pub(crate) fn local<C: ProfileCurve<f64> + ?Sized>(
    profile: &C,
    t: f64,
) -> Result<(f64, f64), FrictionError> {
    let p = ProfilePoint::from_jet(profile.profile_jet(t));
    let j = p.a22.sqrt();
    let kappa = p.turning_rate / j;
    if !(j > 0.0 && kappa.is_finite()) {
        return Err(FrictionError::NonFinite {
            what: "profile metric or curvature",
            angle: t,
        });
    }
    if kappa <= 0.0 {
        return Err(FrictionError::NonPositiveCurvature {
            angle: t,
            mean_curvature: 0.5 * kappa,
        });
    }
    Ok((j, kappa))
}

/// The discrete membrane of a problem: node angles, geometry, half-cell stiffnesses.
#[derive(Debug, Clone)]
pub(crate) struct MembraneGrid {
    /// Node angles.
    pub theta: Vec<f64>,
    /// `(J, kappa)` at the nodes.
    pub nodes: Vec<(f64, f64)>,
    /// `c_{i+1/2} = k / (d J_{i+1/2})`.
    pub c: Vec<f64>,
    /// The angle step `d`.
    pub d: f64,
    /// The residual scale: the largest end tension, or `k |W| / length` for displacement ends
    /// (1 when all are zero).
    pub scale: f64,
}

impl MembraneGrid {
    /// Validates `pr` and builds its grid on `profile`.
    pub(crate) fn new<C: ProfileCurve<f64> + ?Sized>(
        profile: &C,
        pr: &MembraneDisplacementProblem,
    ) -> Result<Self, FrictionError> {
        check_wrap(pr.theta0, pr.theta1, pr.nodes, (3.0, 1e8, "[3, 10^8]"))?;
        check("membrane.stiffness", pr.stiffness, "(0, inf)", |v| v > 0.0)?;
        for e in [pr.start, pr.end] {
            let (EndCondition::Tension(x) | EndCondition::Displacement(x)) = e;
            check("membrane.t0", x, "finite values", |_| true)?;
        }
        let n = pr.nodes;
        let d = (pr.theta1 - pr.theta0) / (n - 1) as f64;
        let theta: Vec<f64> = (0..n)
            .map(|i| {
                if i + 1 == n {
                    pr.theta1
                } else {
                    pr.theta0 + d * i as f64
                }
            })
            .collect();
        let nodes: Vec<(f64, f64)> = theta
            .iter()
            .map(|&t| local(profile, t))
            .collect::<Result<_, _>>()?;
        // c_{i+1/2} = k / (d J_{i+1/2})
        let c: Vec<f64> = (0..n - 1)
            .map(|i| Ok(pr.stiffness / (d * local(profile, theta[i] + 0.5 * d)?.0)))
            .collect::<Result<_, FrictionError>>()?;
        let length: f64 = c.iter().map(|ci| pr.stiffness / ci).sum();
        let mut scale: f64 = 0.0;
        for e in [pr.start, pr.end] {
            scale = scale.max(match e {
                EndCondition::Tension(t) => t.abs(),
                EndCondition::Displacement(w) => pr.stiffness * w.abs() / length,
            });
        }
        let scale = if scale > 0.0 { scale } else { 1.0 };
        Ok(Self {
            theta,
            nodes,
            c,
            d,
            scale,
        })
    }
}

impl<'a, C: ProfileCurve<f64> + ?Sized, L: FrictionLaw<f64>> MembraneDisplacement<'a, C, L> {
    /// The membrane on `profile` with friction `law` and its parameters.
    pub fn new(profile: &'a C, law: L, params: L::Params) -> Self {
        Self {
            profile,
            law,
            params,
        }
    }

    /// Solves the problem from `initial` (default: the straight line through a displacement
    /// end with the slope of the end tension, or zero).
    ///
    /// # Errors
    /// [`FrictionError::InvalidParameter`] naming `membrane.theta0`, `membrane.theta_max`,
    /// `membrane.samples` (nodes) or `membrane.stiffness`;
    /// [`FrictionError::NonPositiveCurvature`] on a non-convex interval;
    /// [`FrictionError::NonFinite`] for a singular Jacobian (e.g. two tension ends at a
    /// ratio a sliding membrane cannot hold); [`FrictionError::RootNotConverged`] when Newton
    /// does not converge.
    pub fn solve(
        &self,
        problem: &MembraneDisplacementProblem,
        initial: Option<&[f64]>,
        newton: MembraneNewton,
    ) -> Result<MembraneDisplacementSolution, FrictionError> {
        self.solve_observed(problem, initial, newton, &mut |_, _, _| {})
    }

    /// As [`MembraneDisplacement::solve`], calling `progress(iteration, residual, step)` after
    /// the initial residual (iteration 0, step 0) and after every Newton step (the residual
    /// max-norm, the line-search step length). The facade forwards these to its `Observer`
    /// (stage `membrane`); this crate knows no solver types, so a closure is the hook.
    ///
    /// # Errors
    /// As [`MembraneDisplacement::solve`].
    pub fn solve_observed(
        &self,
        problem: &MembraneDisplacementProblem,
        initial: Option<&[f64]>,
        newton: MembraneNewton,
        progress: &mut dyn FnMut(usize, f64, f64),
    ) -> Result<MembraneDisplacementSolution, FrictionError> {
        self.solve_from(problem, None, initial, newton, progress)
    }

    /// As [`MembraneDisplacement::solve_observed`], with the friction law acting on the slip
    /// measured from `reference` (`u = w - w_ref`; a load step from a state in which the
    /// friction traction vanishes, e.g. the membrane wrapped at a uniform tension). `None`:
    /// from `w = 0`.
    ///
    /// # Errors
    /// As [`MembraneDisplacement::solve`]; [`FrictionError::InvalidParameter`] naming
    /// `reference` if its length is not `problem.nodes`.
    pub fn solve_from(
        &self,
        problem: &MembraneDisplacementProblem,
        reference: Option<&[f64]>,
        initial: Option<&[f64]>,
        newton: MembraneNewton,
        progress: &mut dyn FnMut(usize, f64, f64),
    ) -> Result<MembraneDisplacementSolution, FrictionError> {
        let pr = problem;
        let MembraneGrid {
            theta,
            nodes,
            c,
            d,
            scale,
        } = MembraneGrid::new(self.profile, pr)?;
        let n = pr.nodes;
        let origin = match reference {
            Some(w) => {
                check("reference", w.len() as f64, "problem.nodes values", |v| {
                    v == pr.nodes as f64
                })?;
                w.to_vec()
            }
            None => vec![0.0; n],
        };
        let mut w = match initial {
            Some(w0) if w0.len() == n => w0.to_vec(),
            _ => self.initial_guess(pr, &c),
        };
        let policy = membrane_policy(newton.max_iterations, newton.tolerance * scale, 1e-10);
        let mut system = DisplacementSystem {
            membrane: self,
            problem: pr,
            nodes: &nodes,
            c: &c,
            d,
            origin: &origin,
            jac: vec![[0.0; 3]; n],
            r: vec![0.0; n],
            c_max: c.iter().fold(0.0f64, |m, x| m.max(*x)),
            progress,
        };
        let (iterations, norm) = match newton_drive(&mut system, &mut w, &policy) {
            Ok(done) => (done.iterations, done.residuals[done.iterations]),
            Err(failure) => {
                let (iterations, residual) = spent(failure, pr.theta0)?;
                return Err(FrictionError::NewtonNotConverged {
                    iterations,
                    residual,
                });
            }
        };
        // Node tensions and reactions.
        let half: Vec<f64> = (0..n - 1).map(|i| c[i] * (w[i + 1] - w[i])).collect();
        let mut tension = vec![0.0; n];
        for i in 1..n - 1 {
            tension[i] = 0.5 * (half[i - 1] + half[i]);
        }
        tension[0] = match pr.start {
            EndCondition::Tension(t) => t,
            EndCondition::Displacement(_) => 1.5 * half[0] - 0.5 * half[1],
        };
        tension[n - 1] = match pr.end {
            EndCondition::Tension(t) => t,
            EndCondition::Displacement(_) => 1.5 * half[n - 2] - 0.5 * half[n - 3],
        };
        let reaction = tension
            .iter()
            .zip(&nodes)
            .map(|(t, (_, kappa))| kappa * t)
            .collect();
        Ok(MembraneDisplacementSolution {
            theta,
            displacement: w,
            tension,
            reaction,
            iterations,
            residual: norm,
        })
    }

    /// The start's straight line (see [`MembraneDisplacement::solve`]).
    fn initial_guess(&self, pr: &MembraneDisplacementProblem, c: &[f64]) -> Vec<f64> {
        let n = c.len() + 1;
        let mut w = vec![0.0; n];
        // The slope of the first tension end, integrated from the first displacement end.
        let slope = match (pr.start, pr.end) {
            (EndCondition::Tension(t), _) | (_, EndCondition::Tension(t)) => t,
            _ => 0.0,
        };
        for i in 1..n {
            w[i] = w[i - 1] + slope / c[i - 1];
        }
        let shift = match (pr.start, pr.end) {
            (EndCondition::Displacement(a), _) => a - w[0],
            (_, EndCondition::Displacement(b)) => b - w[n - 1],
            _ => 0.0,
        };
        w.iter_mut().for_each(|x| *x += shift);
        if let (EndCondition::Displacement(a), EndCondition::Displacement(b)) = (pr.start, pr.end) {
            for (i, x) in w.iter_mut().enumerate() {
                *x = a + (b - a) * i as f64 / (n - 1) as f64;
            }
        }
        w
    }

    /// Residual (returns `max |R|`) and, if asked, the tridiagonal Jacobian `[lower, diag, upper]`.
    #[allow(clippy::too_many_arguments)] // the discrete problem's pieces, kept apart for clarity
    fn assemble(
        &self,
        pr: &MembraneDisplacementProblem,
        nodes: &[(f64, f64)],
        c: &[f64],
        d: f64,
        origin: &[f64],
        w: &[f64],
        r: &mut [f64],
        mut jac: Option<&mut [[f64; 3]]>,
    ) -> f64 {
        let n = w.len();
        let half = |i: usize| c[i] * (w[i + 1] - w[i]);
        // friction force t(w, -p) per unit length, dt/dw, dt/dsigma
        let friction = |wi: f64, p: f64| {
            let state = ContactState::new([0.0, wi], -p);
            let t = self.law.traction(&state, &self.params)[1];
            let dt = self.law.traction_derivatives(&state, &self.params);
            (t, dt.d_slip[1][1], dt.d_pressure[1])
        };
        let mut norm: f64 = 0.0;
        for i in 0..n {
            let (j, kappa) = nodes[i];
            let (mut lo, mut up) = (0.0, 0.0);
            let di;
            let ri = if i == 0 || i == n - 1 {
                let bc = if i == 0 { pr.start } else { pr.end };
                match bc {
                    EndCondition::Displacement(x) => {
                        di = 1.0;
                        w[i] - x
                    }
                    EndCondition::Tension(te) => {
                        // start: T_{1/2} - T_e + (d/2) J t = 0; end: T_e - T_{n-3/2} + (d/2) J t = 0
                        let (t, dtw, _) = friction(w[i] - origin[i], kappa * te);
                        if i == 0 {
                            di = -c[0] + 0.5 * d * j * dtw;
                            up = c[0];
                            half(0) - te + 0.5 * d * j * t
                        } else {
                            di = -c[n - 2] + 0.5 * d * j * dtw;
                            lo = c[n - 2];
                            te - half(n - 2) + 0.5 * d * j * t
                        }
                    }
                }
            } else {
                let (tm, tp) = (half(i - 1), half(i));
                let ti = 0.5 * (tm + tp);
                let (t, dtw, dts) = friction(w[i] - origin[i], kappa * ti);
                // sigma = -kappa T_i, T_i = (T_{i-1/2} + T_{i+1/2})/2
                let g = d * j * dts * (-kappa) * 0.5;
                lo = c[i - 1] + g * (-c[i - 1]);
                up = c[i] + g * c[i];
                di = -c[i] - c[i - 1] + d * j * dtw + g * (c[i - 1] - c[i]);
                tp - tm + d * j * t
            };
            r[i] = ri;
            norm = norm.max(ri.abs());
            if let Some(jac) = jac.as_deref_mut() {
                jac[i] = [lo, di, up];
            }
        }
        if norm.is_finite() {
            norm
        } else {
            f64::INFINITY
        }
    }
}

/// Thomas elimination of the tridiagonal system `[lower, diag, upper]` in place; `None` on a
/// zero or non-finite pivot.
pub(crate) fn thomas(jac: &[[f64; 3]], rhs: &mut [f64]) -> Option<()> {
    let n = rhs.len();
    let mut cp = vec![0.0; n];
    let mut denom = jac[0][1];
    if denom == 0.0 || !denom.is_finite() {
        return None;
    }
    cp[0] = jac[0][2] / denom;
    rhs[0] /= denom;
    for i in 1..n {
        denom = jac[i][1] - jac[i][0] * cp[i - 1];
        if denom == 0.0 || !denom.is_finite() {
            return None;
        }
        cp[i] = jac[i][2] / denom;
        rhs[i] = (rhs[i] - jac[i][0] * rhs[i - 1]) / denom;
    }
    for i in (0..n - 1).rev() {
        rhs[i] -= cp[i] * rhs[i + 1];
    }
    rhs.iter().all(|x| x.is_finite()).then_some(())
}

/// The membrane models' Newton policy: the residual's max norm, a strict decrease of it by
/// `1e-4 alpha` relative, the trial taken once `alpha < min_step`, converged below
/// `tolerance` (or the problem's round-off floor).
pub(crate) fn membrane_policy(
    max_iterations: usize,
    tolerance: f64,
    min_step: f64,
) -> NewtonPolicy {
    NewtonPolicy {
        max_iterations,
        absolute_tolerance: tolerance,
        relative_tolerance: 0.0,
        norm: ResidualNorm::Max,
        step: StepControl::Backtracking {
            merit: Merit::Norm { armijo: 1e-4 },
            min_step,
            short_step: ShortStep::Take,
        },
        divergence_limit: None,
        step_stagnation: false,
        check_finite: false,
    }
}

/// `(iterations, residual)` of a membrane Newton solve that spent its budget; the problem's
/// own error, or a non-finite step (on the interval from `theta0`), as errors.
///
/// # Errors
/// Those two.
pub(crate) fn spent(
    failure: NewtonFailure<FrictionError>,
    theta0: f64,
) -> Result<(usize, f64), FrictionError> {
    match failure {
        NewtonFailure::Problem(e) => Err(e),
        NewtonFailure::NotConverged {
            iterations,
            residual,
        }
        | NewtonFailure::LineSearch {
            iterations,
            residual,
            ..
        }
        | NewtonFailure::Stagnated {
            iterations,
            residual,
        }
        | NewtonFailure::Diverged {
            iteration: iterations,
            residual,
        } => Ok((iterations, residual)),
        NewtonFailure::Interrupted { .. } | NewtonFailure::NonFinite { .. } => {
            Err(step_failed(theta0))
        }
    }
}

/// The error of a Newton step that could not be computed.
fn step_failed(theta0: f64) -> FrictionError {
    FrictionError::NonFinite {
        what: "Newton step (singular tridiagonal Jacobian)",
        angle: theta0,
    }
}

/// [`MembraneDisplacement::solve_from`]'s problem for the Newton driver: the node residuals,
/// the tridiagonal Jacobian by Thomas elimination, the round-off floor of the residual.
struct DisplacementSystem<'m, 'a, 'p, C: ?Sized, L: FrictionLaw<f64>> {
    membrane: &'m MembraneDisplacement<'a, C, L>,
    problem: &'m MembraneDisplacementProblem,
    nodes: &'m [(f64, f64)],
    c: &'m [f64],
    d: f64,
    origin: &'m [f64],
    jac: Vec<[f64; 3]>,
    r: Vec<f64>,
    /// `max_i c_{i+1/2}`.
    c_max: f64,
    progress: &'p mut dyn FnMut(usize, f64, f64),
}

impl<C: ProfileCurve<f64> + ?Sized, L: FrictionLaw<f64>> NewtonSystem
    for DisplacementSystem<'_, '_, '_, C, L>
{
    type Error = FrictionError;

    fn residual(&mut self, w: &[f64], r: &mut [f64]) -> Result<(), FrictionError> {
        let (pr, nodes, c) = (self.problem, self.nodes, self.c);
        self.membrane
            .assemble(pr, nodes, c, self.d, self.origin, w, r, None);
        Ok(())
    }

    fn direction(
        &mut self,
        at: &NewtonIterate<'_>,
        dw: &mut [f64],
    ) -> Result<NewtonDirection, FrictionError> {
        let (pr, nodes, c) = (self.problem, self.nodes, self.c);
        self.membrane.assemble(
            pr,
            nodes,
            c,
            self.d,
            self.origin,
            at.u,
            &mut self.r,
            Some(&mut self.jac),
        );
        for (d, r) in dw.iter_mut().zip(&self.r) {
            *d = -r;
        }
        thomas(&self.jac, dw).ok_or_else(|| step_failed(pr.theta0))?;
        Ok(NewtonDirection::default())
    }

    /// Round-off floor of the residual: differences `c (w_{i+1} - w_i)` of large terms.
    fn floor(&self, w: &[f64]) -> f64 {
        100.0 * f64::EPSILON * self.c_max * w.iter().fold(0.0f64, |m, x| m.max(x.abs()))
    }

    fn accepted(&mut self, at: &NewtonIterate<'_>) -> Result<Flow, FrictionError> {
        (self.progress)(at.iteration, at.norm, at.step);
        Ok(Flow::Continue)
    }
}
