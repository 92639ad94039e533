//! A converged contact solution: displacement, contact profile, stick/slip classification.

use capstan_friction::FrictionLaw;

use crate::contact::loads::EndLoads;
use crate::contact::model::{ContactModel, add_slip};
use crate::contact::operator::{ContactOperator, Extremum};
use crate::discretisation::ContactNode;

/// The state of a contact node that has lifted off the obstacle (unilateral contact): neither
/// stick (`0`) nor slip (`+-1`).
pub const SEPARATED: i8 = 2;

/// A maximal run of contact nodes in one state, with interpolated ends.
///
/// # Math
/// `nodes` are the `x2` of the first and last node of the run. `from`, `to` are where the
/// piecewise-linear slip `u(x2)` crosses `+-eps` between the run and its neighbours (the node
/// itself at an end of the contact surface): a grid-independent description of the region.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct StateInterval {
    /// `+1` positive slip, `-1` negative slip, `0` stick, [`SEPARATED`] lifted off.
    pub state: i8,
    /// Interpolated start.
    pub from: f64,
    /// Interpolated end.
    pub to: f64,
    /// `[x2 of the first node, x2 of the last node]`.
    pub nodes: [f64; 2],
    /// Number of nodes in the run.
    pub count: usize,
}

/// The fields on the contact surface `x3 = 0`, one entry per contact node.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct ContactProfile {
    /// `x2` of the nodes.
    pub x2: Vec<f64>,
    /// `v^2` (radians on an angular chart).
    pub v2: Vec<f64>,
    /// `v^3` (zero: bilateral contact).
    pub v3: Vec<f64>,
    /// `sigma_n = T^3_3` (negative in compression).
    pub normal_stress: Vec<f64>,
    /// `T^3_2` (covariant shear; the tangential traction on the body is `t_2 = -T^3_2`).
    pub shear_stress: Vec<f64>,
    /// Physical tangential displacement `u = sqrt(g_22) v^2`: the slip the law sees (on a load
    /// path, [`ContactModel::with_slip_reference`], its increment over the step).
    pub slip: Vec<f64>,
    /// Physical friction traction on the body, `t_2 / sqrt(g_22)`, from the law.
    pub friction_traction: Vec<f64>,
    /// `+1` where `u >= eps`, `-1` where `u <= -eps`, `0` otherwise (a 3-D body: `0` where
    /// `|u| < eps`, else the sign of the `e_2` component of the slip, `+1` when it is zero);
    /// [`SEPARATED`] where the node has lifted off (unilateral contact).
    pub state: Vec<i8>,
    /// Unilateral contact: whether each node has lifted off the obstacle (`None`, and absent
    /// from JSON, for bilateral contact).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub separated: Option<Vec<bool>>,
    /// The `x1` components of a 3-D body (`None` in plane strain).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub solid: Option<SolidContactProfile>,
}

/// The fields of a 3-D body's contact surface that plane strain does not have, one entry per
/// contact node (the order of [`ContactProfile`]). In a 3-D body [`ContactProfile::slip`] and
/// [`ContactProfile::friction_traction`] are the `e_2` components in the orthonormal frame
/// `e_1 = a_1/|a_1|`, `e_2 = a^2/|a^2|` of the tangent plane.
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize)]
pub struct SolidContactProfile {
    /// `x1` of the nodes.
    pub x1: Vec<f64>,
    /// `v^1`.
    pub v1: Vec<f64>,
    /// `T^3_1`.
    pub shear_stress_1: Vec<f64>,
    /// Physical slip along `e_1`.
    pub slip_1: Vec<f64>,
    /// Physical friction traction on the body along `e_1`.
    pub friction_traction_1: Vec<f64>,
}

/// How a solution was computed.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct SolveStats {
    /// `condensed` (boundary-only Newton) or `full-newton` / `full-jacobi-newton`.
    pub method: &'static str,
    /// Newton iterations in total (over all continuation steps).
    pub newton_iterations: usize,
    /// Load-continuation steps (1 when plain Newton converged).
    pub continuation_steps: usize,
    /// Relative max-norm residual of the full system `R(v)` at the solution.
    pub residual: f64,
    /// Inner linear iterations (Jacobi–Newton), 0 for direct solvers.
    pub linear_iterations: usize,
    /// Sparse factorisations done for this solve.
    pub factorisations: usize,
}

/// A converged contact solution.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct ContactSolution {
    /// The loads.
    pub loads: EndLoads,
    /// The nodal displacement vector (the discretisation's numbering).
    #[serde(skip)]
    pub displacement: Vec<f64>,
    /// The condensed contact unknowns `s_k = t_2,k + c_k v^2_k` (empty for the full-system
    /// solvers): a warm start for [`crate::contact::BoundarySolver::solve_from`].
    #[serde(skip)]
    pub unknowns: Vec<f64>,
    /// The contact surface fields.
    pub contact: ContactProfile,
    /// The paper's Slip: mean of the states over the contact nodes.
    pub slip_fraction: f64,
    /// The longest stick run (interpolated ends), if any node sticks.
    pub stick_interval: Option<StateInterval>,
    /// All runs of equal state, in increasing `x2`.
    pub intervals: Vec<StateInterval>,
    /// `v^2` of largest magnitude over the body.
    pub max_azimuthal_displacement: Extremum,
    /// `v^3` of largest magnitude over the body.
    pub max_radial_displacement: Extremum,
    /// Contact nodes with `sigma_n > 0` (tension on a bilateral contact: the regularised law
    /// then drives rather than resists the slip; under unilateral contact only the nodes in
    /// contact are counted).
    pub tensile_contact_nodes: usize,
    /// Unilateral contact: the runs of lifted-off nodes (along the middle `x1` line of a 3-D
    /// body), ends midway to the neighbouring node in contact; `None` (absent from JSON) for
    /// bilateral contact.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lift_off_intervals: Option<Vec<StateInterval>>,
    /// Solver statistics.
    pub stats: SolveStats,
}

impl ContactSolution {
    /// Assembles the solution report from the displacement `v`.
    ///
    /// # Errors
    /// The residual's gather on a distributed model ([`ContactModel::residual_into`]).
    pub fn new<D: ContactOperator, L: FrictionLaw<f64>>(
        model: &ContactModel<D, L>,
        loads: EndLoads,
        v: Vec<f64>,
        mut stats: SolveStats,
    ) -> Result<Self, capstan_solvers::SolverError> {
        let disc = model.discretisation();
        let eps = model.slip_threshold();
        let nodes = model.contact_nodes();
        // the sites in order: runs of entries with the same site
        let mut sites: Vec<Vec<&ContactNode>> = Vec::new();
        for node in nodes {
            match sites.last_mut() {
                Some(last) if last[0].site == node.site => last.push(node),
                _ => sites.push(vec![node]),
            }
        }
        let n = sites.len();
        let solid = sites.iter().any(|s| s.len() == 2);
        let mut p = ContactProfile {
            x2: Vec::with_capacity(n),
            v2: Vec::with_capacity(n),
            v3: Vec::with_capacity(n),
            normal_stress: Vec::with_capacity(n),
            shear_stress: Vec::with_capacity(n),
            slip: Vec::with_capacity(n),
            friction_traction: Vec::with_capacity(n),
            state: Vec::with_capacity(n),
            separated: None,
            solid: solid.then(|| SolidContactProfile {
                x1: Vec::with_capacity(n),
                v1: Vec::with_capacity(n),
                shear_stress_1: Vec::with_capacity(n),
                slip_1: Vec::with_capacity(n),
                friction_traction_1: Vec::with_capacity(n),
            }),
        };
        let rhs = model.rhs(loads);
        let separated_dof: Option<std::collections::HashMap<usize, bool>> = model
            .separated_nodes(&rhs, &v)
            .map(|rows| rows.into_iter().collect());
        let mut separated = separated_dof.as_ref().map(|_| Vec::with_capacity(n));
        // exact friction: the state and traction of the projection, by site
        let exact = model.exact_friction().map(|x| {
            let r = model.free_residual(&rhs, &v);
            x.profile(model, &v, &r, model.separated_sites(&rhs, &v).as_deref())
        });
        let cap_row = model.unilateral().map(|u| {
            let rows: std::collections::HashMap<usize, usize> = u
                .rows
                .iter()
                .enumerate()
                .map(|(r, row)| (row.dof, r))
                .collect();
            (u, rows)
        });
        for entries in &sites {
            let lifted = separated_dof
                .as_ref()
                .and_then(|m| m.get(&entries[0].normal_dof).copied())
                .unwrap_or(false);
            if let Some(s) = separated.as_mut() {
                s.push(lifted);
            }
            let mut u = [0.0; 2];
            for e in entries {
                add_slip(
                    &mut u,
                    1.0,
                    e.frame,
                    v[e.tangential_dof] - model.reference_of(e.tangential_dof),
                );
            }
            let first = entries[0];
            let sigma = first.normal_stress.dot(&v);
            // unilateral: min(sigma_n, 0) capped by the contact reaction (the residual's law)
            let cap = cap_row
                .as_ref()
                .and_then(|(u, rows)| {
                    rows.get(&first.normal_dof).map(|&r| {
                        u.rows[r]
                            .friction_cap(&v, &rhs, first.traction_weight)
                            .max(0.0)
                    })
                })
                .unwrap_or(f64::INFINITY);
            let mut st = model.entries_traction(
                entries,
                u,
                if separated_dof.is_some() {
                    sigma.min(0.0).max(-cap)
                } else {
                    sigma
                },
            );
            st.normal_stress = sigma;
            if lifted {
                // friction acts only where the node is in contact
                st.traction = [0.0; 2];
                st.covariant = [0.0; 2];
            }
            let along = entries.iter().position(|e| e.component == 2).unwrap_or(0);
            let x2_entry = entries[along];
            p.x2.push(first.x2);
            p.v2.push(v[x2_entry.tangential_dof]);
            p.v3.push(v[first.normal_dof]);
            p.normal_stress.push(st.normal_stress);
            p.shear_stress.push(x2_entry.shear_stress.dot(&v));
            if let [entry] = entries[..] {
                // plane strain: u = sqrt(g22) v^2, t = t_2 / sqrt(g22)
                p.slip.push(st.slip[1]);
                p.friction_traction.push(st.covariant[0] / entry.sqrt_g22);
                p.state.push(classify(st.slip[1], eps));
            } else {
                p.slip.push(st.slip[1]);
                p.friction_traction.push(st.traction[1]);
                let size = (u[0] * u[0] + u[1] * u[1]).sqrt();
                p.state.push(if size < eps {
                    0
                } else if u[1] >= 0.0 {
                    1
                } else {
                    -1
                });
            }
            if lifted {
                *p.state.last_mut().expect("pushed above") = SEPARATED;
            }
            if let Some(sp) = p.solid.as_mut() {
                let x1_entry = entries.iter().find(|e| e.component == 1);
                sp.x1.push(first.x1);
                sp.v1.push(x1_entry.map_or(0.0, |e| v[e.tangential_dof]));
                sp.shear_stress_1
                    .push(x1_entry.map_or(0.0, |e| e.shear_stress.dot(&v)));
                sp.slip_1.push(st.slip[0]);
                sp.friction_traction_1.push(st.traction[0]);
            }
            if let Some(&(state, traction)) = exact.as_ref().and_then(|m| m.get(&first.site)) {
                *p.state.last_mut().expect("pushed above") = state;
                *p.friction_traction.last_mut().expect("pushed above") = traction[1];
                if let Some(sp) = p.solid.as_mut() {
                    *sp.friction_traction_1.last_mut().expect("pushed above") = traction[0];
                }
            }
        }
        p.separated = separated;
        // the paper's Slip over the nodes in contact
        let touching = p.state.iter().filter(|&&s| s != SEPARATED).count();
        let slip_fraction = p
            .state
            .iter()
            .filter(|&&s| s != SEPARATED)
            .map(|&s| f64::from(s))
            .sum::<f64>()
            / touching.max(1) as f64;
        // a 3-D body: the runs along the middle x1 line of the contact face
        let line: Vec<usize> = if solid {
            let mut rows: Vec<usize> = sites.iter().map(|s| s[0].i1).collect();
            rows.dedup();
            let middle = rows[rows.len() / 2];
            (0..n).filter(|&k| sites[k][0].i1 == middle).collect()
        } else {
            (0..n).collect()
        };
        let pick = |f: &[f64]| line.iter().map(|&k| f[k]).collect::<Vec<f64>>();
        let states: Vec<i8> = line.iter().map(|&k| p.state[k]).collect();
        // exact friction: stick is zero slip, so a run ends at its last sticking node
        let level = if model.is_exact_friction() { 0.0 } else { eps };
        let intervals = state_intervals(&pick(&p.x2), &pick(&p.slip), &states, level);
        let stick_interval = intervals
            .iter()
            .filter(|i| i.state == 0)
            .max_by_key(|i| i.count)
            .copied();
        let [max_azimuthal_displacement, max_radial_displacement] = disc.extremes(&v);
        stats.residual = model.relative_residual(loads, &v)?;
        let tensile_contact_nodes = p
            .normal_stress
            .iter()
            .zip(&p.state)
            .filter(|&(&s, &state)| s > 0.0 && state != SEPARATED)
            .count();
        let lift_off_intervals = p.separated.as_ref().map(|_| {
            intervals
                .iter()
                .filter(|i| i.state == SEPARATED)
                .copied()
                .collect()
        });
        Ok(Self {
            loads,
            displacement: v,
            unknowns: Vec::new(),
            contact: p,
            slip_fraction,
            stick_interval,
            intervals,
            max_azimuthal_displacement,
            max_radial_displacement,
            tensile_contact_nodes,
            lift_off_intervals,
            stats,
        })
    }

    /// The slip intervals (runs with state `+-1`).
    pub fn slip_intervals(&self) -> impl Iterator<Item = &StateInterval> {
        self.intervals
            .iter()
            .filter(|i| i.state == 1 || i.state == -1)
    }

    /// Whether every contact node slides in the positive direction (state `+1`; on a 3-D body
    /// the sign of the slip's `e_2` component).
    pub fn fully_slipping(&self) -> bool {
        self.contact.state.iter().all(|&s| s == 1 || s == SEPARATED)
    }

    /// Whether every contact node slides (`|u| >= eps`, state `+-1`), in any direction. On a
    /// 3-D body of finite width the edge nodes can slide sideways with a small backward `e_2`
    /// component, so [`ContactSolution::fully_slipping`] may never hold; this is the threshold
    /// criterion of the thin-limit study on a cone (docs/models.md). It is not one for a band
    /// that slides sideways at any load (a band along a circle of a cone, pulled towards the
    /// apex: every node slides already at ratio 1).
    pub fn every_node_slipping(&self) -> bool {
        self.contact.state.iter().all(|&s| s != 0)
    }
}

/// `+1` if `u >= eps`, `-1` if `u <= -eps`, else `0`.
pub fn classify(u: f64, eps: f64) -> i8 {
    if u >= eps {
        1
    } else if u <= -eps {
        -1
    } else {
        0
    }
}

/// Runs of equal state with interpolated ends (see [`StateInterval`]).
pub fn state_intervals(x2: &[f64], slip: &[f64], state: &[i8], eps: f64) -> Vec<StateInterval> {
    let n = state.len();
    let mut out = Vec::new();
    let mut start = 0;
    while start < n {
        let mut end = start;
        while end + 1 < n && state[end + 1] == state[start] {
            end += 1;
        }
        // Crossing between node a (outside) and node b (inside the run) of the level that
        // separates their states.
        let crossing = |a: usize, b: usize| -> f64 {
            let (sa, sb) = (state[a], state[b]);
            if sa == SEPARATED || sb == SEPARATED {
                // lift-off: no slip level separates the states
                return 0.5 * (x2[a] + x2[b]);
            }
            let level = if sa == 1 || sb == 1 {
                eps
            } else if sa == -1 || sb == -1 {
                -eps
            } else {
                0.0
            };
            let (ua, ub) = (slip[a], slip[b]);
            if (ub - ua).abs() < f64::MIN_POSITIVE {
                return 0.5 * (x2[a] + x2[b]);
            }
            let s = ((level - ua) / (ub - ua)).clamp(0.0, 1.0);
            x2[a] + s * (x2[b] - x2[a])
        };
        let from = if start == 0 {
            x2[0]
        } else {
            crossing(start - 1, start)
        };
        let to = if end == n - 1 {
            x2[n - 1]
        } else {
            crossing(end + 1, end)
        };
        out.push(StateInterval {
            state: state[start],
            from,
            to,
            nodes: [x2[start], x2[end]],
            count: end - start + 1,
        });
        start = end + 1;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn classify_uses_closed_thresholds() {
        assert_eq!(classify(1e-5, 1e-5), 1);
        assert_eq!(classify(-1e-5, 1e-5), -1);
        assert_eq!(classify(0.99e-5, 1e-5), 0);
    }

    #[test]
    fn intervals_interpolate_the_eps_crossings() {
        let x2 = [0.0, 1.0, 2.0, 3.0];
        let slip = [-3.0, -0.5, 0.5, 3.0];
        let state: Vec<i8> = slip.iter().map(|&u| classify(u, 1.0)).collect();
        let runs = state_intervals(&x2, &slip, &state, 1.0);
        assert_eq!(runs.len(), 3);
        assert_eq!(runs[1].state, 0);
        assert!((runs[1].from - 0.8).abs() < 1e-12); // -3 + 2.5 s = -1 at s = 0.8
        assert!((runs[1].to - 2.2).abs() < 1e-12);
        assert_eq!(runs[0].from, 0.0);
        assert_eq!(runs[2].to, 3.0);
    }
}
