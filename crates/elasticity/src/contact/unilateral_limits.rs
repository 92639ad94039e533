//! The limiting range of a plane body under unilateral contact: the tension ratios at which
//! the whole contact slides along the rigid sliding mode (a circular obstacle), with the
//! contact set an unknown of the full-slip solve.

use capstan_friction::FrictionLaw;
use capstan_solvers::{BackendKind, BoxedLinearSolver, LinearBackend};

use crate::contact::error::ContactError;
use crate::contact::full_system::FullSystemSolver;
use crate::contact::load_continuation::LoadSteps;
use crate::contact::loads::EndLoads;
use crate::contact::model::ContactModel;
use crate::contact::model::slide_along;
use crate::contact::operator::ContactOperator;
use crate::contact::solution::SolveStats;

/// Newton iterations of one full-slip solve ([`FullSystemSolver::full_slip_ratio`]): the
/// equations are affine in `(v, r)` for a fixed contact set (a Coulomb-type law), so each
/// iteration after the first only corrects the contact set.
pub const FULL_SLIP_NEWTON_ITERATIONS: usize = 50;

/// Largest defect `1 - kappa x_p` of the pinned Jacobian (see
/// [`FullSystemSolver::full_slip_ratio`]) for which the body counts as having a rigid sliding
/// mode: `0` exactly when the Jacobian at full slip is singular along a mode that moves the
/// pinned entry. (Measured: below `2e-13` in size on the circle, FD 21 x 5 to 250 x 41;
/// `2.4e-2` on the ellipse with semi-axes 2 and 1, 41 x 9 and 250 x 41, which has no rigid
/// mode.)
pub const RIGID_MODE_DEFECT: f64 = 1e-6;

/// The full-slip state of a body sliding rigidly one way: the ratio that balances the loads
/// along the rigid mode, and the equilibrium there.
#[derive(Debug, Clone)]
pub struct FullSlip {
    /// `tau_max / tau0` of the balance (may be `<= 0` or non-finite: no bound that way).
    pub ratio: f64,
    /// The equilibrium displacement at `ratio`, with the amplitude along the rigid mode fixed
    /// by `v_p = 0` at the middle contact entry.
    pub displacement: Vec<f64>,
    /// The rigid sliding mode `z` (`J z = 0`, largest entry 1), oriented so that the contact
    /// slides toward `+x2` along it: `displacement + a z` is the same full-slip equilibrium
    /// for every amplitude `a` with the slip `direction a z` beyond the law's saturation at
    /// every site. Empty when no balance was solved (no rigid mode, or an undriven one).
    pub rigid_mode: Vec<f64>,
    /// Contact nodes separated from the obstacle at the full slip (0 on a bilateral model).
    pub separated: usize,
    /// Newton iterations (one sparse factorisation each).
    pub iterations: usize,
    /// The defect `1 - kappa x_p` of the pinned Jacobian: near `0` (below
    /// [`RIGID_MODE_DEFECT`]) when the full-slip Jacobian is singular along a rigid mode.
    pub rigid_mode_defect: f64,
}

/// One end of the limiting range ([`FullSystemSolver::limiting_end`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FullSlipEnd {
    /// The ratio, `+inf` / `-inf` when friction holds every ratio that way.
    pub ratio: f64,
    /// Contact nodes separated at the full slip.
    pub separated: usize,
    /// Newton iterations of the full-slip solve.
    pub iterations: usize,
}

/// The limiting range of tension ratios of a body under unilateral contact
/// ([`FullSystemSolver::limiting_ratios`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LimitingRange {
    /// The smallest ratio friction holds (full slip toward `-x2`), `-inf` if unbounded.
    pub lower: f64,
    /// The largest ratio friction holds (full slip toward `+x2`), `+inf` if unbounded.
    pub upper: f64,
    /// Contact nodes separated at the full slip `[lower, upper]`.
    pub separated: [usize; 2],
    /// Newton iterations of both full-slip solves.
    pub iterations: usize,
}

impl LimitingRange {
    /// The range of the two ends.
    pub fn from_ends(lower: FullSlipEnd, upper: FullSlipEnd) -> Self {
        Self {
            lower: lower.ratio.min(upper.ratio),
            upper: lower.ratio.max(upper.ratio),
            separated: [lower.separated, upper.separated],
            iterations: lower.iterations + upper.iterations,
        }
    }

    /// Whether `ratio` lies outside `[lower, upper]` (relative tolerance `1e-9`, as the
    /// condensed solver's check).
    pub fn excludes(&self, ratio: f64) -> bool {
        let tol = 1e-9 * ratio.abs().max(1.0);
        ratio > self.upper + tol || ratio < self.lower - tol
    }
}

impl<D: ContactOperator, L: FrictionLaw<f64>> FullSystemSolver<'_, D, L> {
    /// The limiting range `[lower, upper]` at `tau0`: [`FullSystemSolver::limiting_end`] each
    /// way. `None` when the body has no rigid sliding mode.
    ///
    /// # Errors
    /// See [`FullSystemSolver::full_slip_ratio`].
    pub fn limiting_ratios(&self, tau0: f64) -> Result<Option<LimitingRange>, ContactError> {
        let (Some(lower), Some(upper)) = (
            self.limiting_end(tau0, -1.0)?,
            self.limiting_end(tau0, 1.0)?,
        ) else {
            return Ok(None);
        };
        Ok(Some(LimitingRange::from_ends(lower, upper)))
    }

    /// One end of the limiting range at `tau0` ([`FullSystemSolver::full_slip_ratio`] in
    /// `direction`): the balance, or `direction * inf` when it is not positive and finite
    /// (no bound that way, as the condensed solver's [`crate::contact::SlidingMode`]). `None`
    /// when the body has no rigid sliding mode (a defect above [`RIGID_MODE_DEFECT`]).
    ///
    /// # Errors
    /// See [`FullSystemSolver::full_slip_ratio`].
    pub fn limiting_end(
        &self,
        tau0: f64,
        direction: f64,
    ) -> Result<Option<FullSlipEnd>, ContactError> {
        let slip = self.full_slip_ratio(tau0, direction)?;
        if !has_rigid_mode(slip.rigid_mode_defect) {
            return Ok(None);
        }
        let ratio = if slip.ratio.is_finite() && slip.ratio > 0.0 {
            slip.ratio
        } else {
            direction * f64::INFINITY
        };
        Ok(Some(FullSlipEnd {
            ratio,
            separated: slip.separated,
            iterations: slip.iterations,
        }))
    }

    /// The tension ratio at which the whole contact slides rigidly in `direction` (`+1`:
    /// toward `+x2`, the `tau_max` end; `-1` the other way), for `tau0`: the limiting
    /// equilibrium, solved with the ratio and the contact set as unknowns.
    ///
    /// # Math
    /// At full slip the friction traction is saturated: `t_k = t(u_sat, p_k)` with the slip
    /// `u_sat = direction 1e6 eps` along `x2` at every site (for a Coulomb-type law
    /// `mu p_k`, opposing the slide), independent of the tangential displacement; the law
    /// reads `p_k = max(min(sigma_n, 0), -cap_k)` where the node is in contact (the
    /// unilateral cap on the contact reaction, [`crate::contact::ContactKind`]) and nothing
    /// where it has separated. The residual
    /// ```text
    /// F(v, r) = A v - b(tau0, r tau0) - sum_k w_k e_row_k t_k(u_sat, p_k(v))   (tangential rows)
    ///           d_k min(v^3_k + g_k, lambda_k(v))                            (normal rows)
    /// ```
    /// is then singular along the rigid sliding mode `z` (the circle's rotation: `A z = 0`,
    /// `v^3` unchanged), and equilibrium fixes the ratio: `y . F = 0` for the left null
    /// vector `y` is the balance of loads and friction along the mode. With the amplitude
    /// along `z` pinned by `v_p = 0` (the middle contact entry's tangential dof), semismooth
    /// Newton on `(v, r)`:
    /// ```text
    /// [J   F_r] [dv]     [F  ]      J = dF/dv (generalised: the contact set of the iterate),
    /// [e_p^T 0] [dr] = - [v_p]      F_r = F(v, r + 1) - F(v, r)
    /// ```
    /// by bordering on `M = J + kappa e_p e_p^T` (non-singular; `kappa = |A_pp|`): `a = -M^{-1}
    /// F`, `b = -M^{-1} F_r`, `dr = -(v_p + a_p) / b_p`, `dv = a + dr b` (the spring term
    /// `kappa v_p` vanishes once `v_p = 0`, so a converged iterate solves `F = 0`). Singular
    /// along `z` means `M (z / (kappa z_p)) = e_p`, so `x = M^{-1} e_p` has `kappa x_p = 1`:
    /// the defect `1 - kappa x_p` tells a rigid mode from a body without one (no sliding
    /// mode: the pin would hold the body, and the ratio would mean nothing).
    ///
    /// On a bilateral model (`p_k = sigma_n`, no normal rows) this is the condensed solver's
    /// full-slip balance ([`crate::contact::BoundarySolver::sliding`]) on the full system,
    /// without its test of friction pushing along the slip.
    ///
    /// # Errors
    /// [`ContactError::Unsupported`] naming `body.dimension` on a body with two tangential
    /// entries per site (3-D), and naming `friction.law` for exact friction;
    /// [`ContactError::NotConverged`] after [`FULL_SLIP_NEWTON_ITERATIONS`] (load factor 0:
    /// no state reached); linear solver failures (a singular `M`).
    pub fn full_slip_ratio(&self, tau0: f64, direction: f64) -> Result<FullSlip, ContactError> {
        let model = self.model();
        if (0..model.site_count()).any(|j| model.site_members(j).len() != 1) {
            return Err(ContactError::Unsupported {
                field: "body.dimension",
                message: "the full-slip limiting range is computed for plane bodies (one tangential entry per contact site)",
            });
        }
        if model.is_exact_friction() {
            return Err(ContactError::Unsupported {
                field: "friction.law",
                message: "the full-slip limiting range reads a regularised law's saturated traction",
            });
        }
        EndLoads::new(tau0, tau0).check()?;
        let n = model.dof_count();
        let ext = model.extended();
        let pin = model.active().len() / 2;
        let pin_node = model.active_node(pin);
        let (pin_dof, pin_slot) = (pin_node.tangential_dof, ext.tangential_slot[pin]);
        let pin_row = pin_node.tangential_row.expect("active nodes have a row");
        let kappa = {
            let mut a = vec![0.0; ext.pattern.nnz()];
            for (k, &x) in model.system().values.iter().enumerate() {
                a[ext.a_slot[k]] += x;
            }
            let d = a[pin_slot].abs();
            if d > 0.0 && d.is_finite() { d } else { 1.0 }
        };
        let slips = full_slips(model, direction);
        let residual = |v: &[f64], r: f64| -> Vec<f64> {
            let rhs = model.rhs(EndLoads::new(tau0, tau0 * r));
            let mut out = vec![0.0; n];
            full_slip_residual(model, &rhs, v, &slips, &mut out);
            out
        };
        // the Newton backend, or sparse LU for a stationary sweep (slow on the stiff rows,
        // and no convergence promised on the bordered matrix)
        let linear = self.settings().newton.linear;
        let mut lu: BoxedLinearSolver = match linear.kind() {
            BackendKind::Direct | BackendKind::Krylov => self.backend(linear, false)?,
            _ => self.backend(LinearBackend::LU, false)?,
        };
        lu.analyse(&ext.pattern)?;
        let mut values = vec![0.0; ext.pattern.nnz()];
        let mut r = 1.0;
        let mut stats = SolveStats {
            method: "full-slip",
            newton_iterations: 0,
            continuation_steps: 0,
            residual: 0.0,
            linear_iterations: 0,
            factorisations: 0,
        };
        let mut v = LoadSteps::stuck_start(self, EndLoads::new(tau0, tau0 * r), &mut stats)?;
        let b_norm = norm(&model.rhs(EndLoads::new(tau0, tau0 * 2.0))).max(1.0);
        let tolerance = self.settings().continuation.tolerance * b_norm;
        let mut last = f64::INFINITY;
        let mut defect = f64::NAN;
        for iteration in 0..=FULL_SLIP_NEWTON_ITERATIONS {
            let f = residual(&v, r);
            last = norm(&f);
            let rhs = model.rhs(EndLoads::new(tau0, tau0 * r));
            full_slip_jacobian(model, &rhs, &v, &slips, &mut values);
            values[pin_slot] += kappa;
            lu.factor(&values)?;
            if iteration == 0 {
                // the rigid-mode test: x = M^{-1} e_p has kappa x_p = 1 along a rigid mode
                let mut x = vec![0.0; n];
                x[pin_row] = 1.0;
                lu.solve_in_place(&mut x)?;
                defect = 1.0 - kappa * x[pin_dof];
                if !has_rigid_mode(defect) {
                    return Ok(FullSlip {
                        ratio: f64::NAN,
                        displacement: v,
                        rigid_mode: Vec::new(),
                        separated: 0,
                        iterations: 0,
                        rigid_mode_defect: defect,
                    });
                }
            }
            if iteration > 0 && last <= tolerance && v[pin_dof].abs() <= tolerance / kappa {
                let separated = model.unilateral().map_or(0, |u| {
                    u.contact_set(&v, &rhs).iter().filter(|c| !**c).count()
                });
                // z = M^{-1} e_p on the factorisation at the solution (see # Math)
                let mut z = vec![0.0; n];
                z[pin_row] = 1.0;
                lu.solve_in_place(&mut z)?;
                let toward_x2: f64 = (0..model.site_count())
                    .map(|j| {
                        model.site_frame_slip(j, 1.0, |k| z[model.active_node(k).tangential_dof])[1]
                    })
                    .sum();
                let size = z.iter().fold(0.0f64, |m, x| m.max(x.abs())) * toward_x2.signum();
                z.iter_mut().for_each(|x| *x /= size);
                return Ok(FullSlip {
                    ratio: r,
                    displacement: v,
                    rigid_mode: z,
                    separated,
                    iterations: iteration,
                    rigid_mode_defect: defect,
                });
            }
            if iteration == FULL_SLIP_NEWTON_ITERATIONS {
                break;
            }
            let f_r: Vec<f64> = residual(&v, r + 1.0)
                .iter()
                .zip(&f)
                .map(|(a, b)| a - b)
                .collect();
            // the spring term of M: M v differs from J v by kappa v_p on the pinned row
            let mut a: Vec<f64> = f.iter().map(|x| -x).collect();
            a[pin_row] -= kappa * v[pin_dof];
            lu.solve_in_place(&mut a)?;
            let mut b: Vec<f64> = f_r.iter().map(|x| -x).collect();
            lu.solve_in_place(&mut b)?;
            let dr = -(v[pin_dof] + a[pin_dof]) / b[pin_dof];
            if !dr.is_finite() {
                // the loads do not drive the mode: no ratio balances it
                return Ok(FullSlip {
                    ratio: direction * f64::INFINITY,
                    displacement: v,
                    rigid_mode: Vec::new(),
                    separated: 0,
                    iterations: iteration + 1,
                    rigid_mode_defect: defect,
                });
            }
            v.iter_mut()
                .zip(a.iter().zip(&b))
                .for_each(|(x, (ai, bi))| *x += ai + dr * bi);
            r += dr;
        }
        Err(ContactError::NotConverged {
            iterations: FULL_SLIP_NEWTON_ITERATIONS,
            residual: last / b_norm,
            load_factor: 0.0,
        })
    }
}

/// Whether a defect `1 - kappa x_p` shows a rigid mode (`|defect| <= RIGID_MODE_DEFECT`;
/// a NaN defect does not).
fn has_rigid_mode(defect: f64) -> bool {
    defect.abs() <= RIGID_MODE_DEFECT
}

/// The 2-norm.
fn norm(x: &[f64]) -> f64 {
    x.iter().map(|a| a * a).sum::<f64>().sqrt()
}

/// The saturated slip of every site: `direction 1e6 eps` along the site's frame (toward
/// `+x2` for `direction = 1`).
fn full_slips<D, L: FrictionLaw<f64>>(model: &ContactModel<D, L>, direction: f64) -> Vec<[f64; 2]> {
    let size = 1e6 * model.slip_threshold();
    (0..model.site_count())
        .map(|j| {
            let w = model.site_frame_slip(j, 1.0, |_| 1.0);
            slide_along(w, direction, size)
        })
        .collect()
}

/// The law at site `j` at the full slip `slip` where the site is in contact (`None` where it
/// has separated), with the site's capping row when the reaction cap holds, and whether the
/// law's normal stress is frozen at zero (`min(sigma_n, 0)` with `sigma_n > 0`).
fn site_at_full_slip<D, L: FrictionLaw<f64>>(
    model: &ContactModel<D, L>,
    j: usize,
    slip: [f64; 2],
    v: &[f64],
    rhs: &[f64],
    contact: Option<&[bool]>,
) -> Option<(crate::contact::SiteTraction, Option<usize>, bool)> {
    if let (Some(contact), Some(u)) = (contact, model.unilateral())
        && let Some(row) = u.site_row[j]
        && !contact[row]
    {
        return None;
    }
    let (pressure, capped) = model.friction_normal_stress(j, v, rhs);
    let first = model.active_node(model.site_members(j)[0]);
    let frozen =
        model.unilateral().is_some() && capped.is_none() && first.normal_stress.dot(v) > 0.0;
    Some((
        model.site_traction_at_slip(j, slip, pressure),
        capped,
        frozen,
    ))
}

/// `F(v, r)` of [`FullSystemSolver::full_slip_ratio`] for the right-hand side `rhs` of `r`
/// (without the pin's spring).
fn full_slip_residual<D, L: FrictionLaw<f64>>(
    model: &ContactModel<D, L>,
    rhs: &[f64],
    v: &[f64],
    slips: &[[f64; 2]],
    out: &mut [f64],
) {
    let system = model.system();
    system.pattern.matvec(&system.values, v, out);
    out.iter_mut().zip(rhs).for_each(|(o, b)| *o -= b);
    let contact = model.unilateral().map(|u| u.contact_set(v, rhs));
    for (j, slip) in slips.iter().enumerate() {
        let Some((st, _, _)) = site_at_full_slip(model, j, *slip, v, rhs, contact.as_deref())
        else {
            continue;
        };
        for (e, &k) in model.site_members(j).iter().enumerate() {
            let node = model.active_node(k);
            let row = node.tangential_row.expect("active nodes have a row");
            out[row] -= node.traction_weight * st.covariant[e];
        }
    }
    if let Some(u) = model.unilateral() {
        u.residual_into(v, rhs, out);
    }
}

/// `dF/dv` of [`FullSystemSolver::full_slip_ratio`] on the extended pattern: `A`, the
/// unilateral rows' generalised Jacobian, and the friction's dependence on the normal stress
/// (or on the capping reaction); the slip is fixed, so no tangential term.
fn full_slip_jacobian<D, L: FrictionLaw<f64>>(
    model: &ContactModel<D, L>,
    rhs: &[f64],
    v: &[f64],
    slips: &[[f64; 2]],
    values: &mut [f64],
) {
    let ext = model.extended();
    values.iter_mut().for_each(|x| *x = 0.0);
    for (k, &a) in model.system().values.iter().enumerate() {
        values[ext.a_slot[k]] += a;
    }
    let unilateral = model.unilateral();
    let contact = unilateral.map(|u| u.contact_set(v, rhs));
    if let Some(u) = unilateral {
        u.jacobian_into(v, rhs, &ext.a_slot, values);
    }
    for (j, slip) in slips.iter().enumerate() {
        let Some((st, capped, frozen)) =
            site_at_full_slip(model, j, *slip, v, rhs, contact.as_deref())
        else {
            continue;
        };
        if frozen {
            continue;
        }
        let members = model.site_members(j);
        let first_weight = model.active_node(members[0]).traction_weight;
        for (e, &k) in members.iter().enumerate() {
            let node = model.active_node(k);
            let w = node.traction_weight;
            if let (Some(row), Some(u)) = (capped, unilateral) {
                // the law reads -cap: d t / d v = -(dt/dsigma) d cap / d v
                let tangential = node.tangential_row.expect("active nodes have a row");
                for (c, g) in u.rows[row].friction_cap_gradient(first_weight) {
                    if let Some(slot) = ext.pattern.slot(tangential, c) {
                        values[slot] += w * st.d_normal_stress[e] * g;
                    }
                }
                continue;
            }
            for (c, &slot) in node.normal_stress.values.iter().zip(&ext.normal_slots[k]) {
                values[slot] -= w * st.d_normal_stress[e] * c;
            }
        }
    }
}
