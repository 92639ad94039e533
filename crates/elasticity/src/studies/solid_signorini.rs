//! A manufactured Signorini (unilateral contact) problem on a 3-D body with a known, curved
//! contact/separation boundary on the contact face: the exact solution is the smooth field of
//! [`SolidMms`], the data (a normal load on the contact face and the initial gap) make it the
//! solution of a Signorini problem that touches the obstacle on `x2 < c(x1)` and has lifted
//! off on `x2 > c(x1)` (the 3-D counterpart of [`super::SignoriniMms`]).

use std::sync::Arc;

use capstan_friction::Frictionless;
use capstan_geometry::ShellChart;

use super::solid::{SolidField, SolidMms, SolidTrigonometricExact};
use crate::contact::{ContactError, ContactModel, EndLoads, FullSystemSettings, Gap, SEPARATED};
use crate::error::ElasticityError;
use crate::finite_element::{ElementOrder, VolumetricIntegration};
use crate::shell_geometry::ShellGeometry;
use crate::solid::{
    BoxGrid, Face, FaceComponent, FaceCondition, FaceFunction, SolidBoundary, SolidForce,
    SolidNavier,
};

/// The chart of the 3-D sample problems.
type SampleChart = ShellChart<capstan_geometry::Obstacle>;

/// The frictionless unilateral contact model of [`SolidSignoriniMms`].
pub type SolidSignoriniModel = ContactModel<SolidNavier<SampleChart>, Frictionless>;

/// A frictionless manufactured Signorini problem on the body of a [`SolidMms`] (the right
/// circular cone by default), split along the curve `x2 = c(x1)` of the contact face.
///
/// # Math
/// `U` is the field of [`super::solid::SolidTrigonometricField`] (`U^3 = 0` on `x3 = 0`),
/// `f = -nabla . T(U)` its forcing, Dirichlet data from `U` on the `x1` and `x2` faces, the
/// traction of `U` on `x3 = h` and its tangential tractions `t_1`, `t_2` on `x3 = 0`. With
/// ```text
/// c(x1)   = c0 + c1 (x1 - xm) + c2 (x1 - xm)^2        (xm the middle of [x1a, x1b])
/// phi     = x2 - c(x1)
/// p       = P max(-phi, 0)^2     (contact pressure of the exact solution)
/// d       = D max(phi, 0)^2      (its opening)
/// ```
/// the contact face carries the applied normal traction `t_3 = n_i T^i_3(U) - p` and the
/// obstacle sits at the initial gap `g = d - U^3(x1, x2, 0)`. Signorini holds for `U`: where
/// `phi < 0` the opening `U^3 + g = d = 0` and the reaction is `p > 0` (contact); where
/// `phi > 0` the opening is `d > 0` and the reaction `p = 0` (separated). `p` and `d` are
/// `C^1` across the curve, so the discrete solution converges at the element's order; the
/// separated part of the face is `{x2 > c(x1)}`, of parametric area
/// `A = (x2b - c0) w - c2 w^3 / 12` (`w = x1b - x1a`; the linear term integrates to zero).
#[derive(Debug, Clone)]
pub struct SolidSignoriniMms {
    /// The body, field and material (its contact-face conditions are replaced as above).
    pub mms: SolidMms,
    /// `[c0, c1, c2]` of the split curve `c(x1)`.
    pub split: [f64; 3],
    /// `P` (traction per squared length).
    pub pressure: f64,
    /// `D` (per length).
    pub opening: f64,
}

impl Default for SolidSignoriniMms {
    /// The right circular cone of the 3-D studies (`x1 in [1, 1.5]`, `x2 in [-0.6, 0.6]`,
    /// `h = 0.15`, `E = 10`, `nu = 0.3`), split along
    /// `c(x1) = 0.1 + 0.4 (x1 - 1.25) + 1.6 (x1 - 1.25)^2` (from `0.075` to `0.3`), `P = 2`,
    /// `D = 0.05` (the 2-D problem's).
    fn default() -> Self {
        Self {
            mms: SolidMms::circular_cone(),
            split: [0.1, 0.4, 1.6],
            pressure: 2.0,
            opening: 0.05,
        }
    }
}

/// The errors of one [`SolidSignoriniMms`] solve.
#[derive(Debug, Clone, PartialEq)]
pub struct SolidSignoriniPoint {
    /// Nodes `[n1, n2, n3]`.
    pub nodes: [usize; 3],
    /// `dx2` (the spacing of the nodes along the direction the split is located in).
    pub h: f64,
    /// Relative L2 error of the displacement over the body.
    pub l2_error: f64,
    /// Max over the nodes of the physical displacement error `sqrt(g_ij e^i e^j)`.
    pub max_error: f64,
    /// Max over the `x1` lines of the contact face of `|s_h(x1) - c(x1)|`, `s_h` the
    /// midpoint between the last contact node and the first separated one along `x2`.
    pub split_error: f64,
    /// Whether on every `x1` line the nodes are in contact up to one node and separated
    /// from the next on (one switch), with `c(x1)` within one spacing of that pair.
    pub split_bracketed: bool,
    /// The located separated area `sum_i W1_i (x2b - s_h(x1_i))` (trapezoid weights `W1`).
    pub separated_area: f64,
    /// `|separated_area - A|`.
    pub area_error: f64,
    /// Newton iterations.
    pub newton_iterations: usize,
}

impl SolidSignoriniMms {
    /// `c(x1)`, the split curve.
    pub fn split_at(&self, x1: f64) -> f64 {
        let y = x1 - 0.5 * (self.mms.x1[0] + self.mms.x1[1]);
        let [c0, c1, c2] = self.split;
        c0 + c1 * y + c2 * y * y
    }

    /// `phi(x1, x2) = x2 - c(x1)`: negative in contact, positive where separated.
    fn level(&self, x1: f64, x2: f64) -> f64 {
        x2 - self.split_at(x1)
    }

    /// `p`, the contact pressure of the exact solution.
    pub fn contact_pressure(&self, x1: f64, x2: f64) -> f64 {
        self.pressure * (-self.level(x1, x2)).max(0.0).powi(2)
    }

    /// `d`, the opening of the exact solution.
    pub fn exact_opening(&self, x1: f64, x2: f64) -> f64 {
        self.opening * self.level(x1, x2).max(0.0).powi(2)
    }

    /// The exact parametric area of the separated part `{x2 > c(x1)}` of the contact face.
    pub fn separated_area(&self) -> f64 {
        let w = self.mms.x1[1] - self.mms.x1[0];
        (self.mms.x2[1] - self.split[0]) * w - self.split[2] * w.powi(3) / 12.0
    }

    /// The initial gap `g = d - U^3(x1, x2, 0)`.
    fn gap(&self, exact: &Arc<SolidTrigonometricExact>) -> Gap {
        let (ex, this) = (Arc::clone(exact), self.clone());
        Gap::new(move |x: [f64; 2]| {
            this.exact_opening(x[0], x[1]) - ex.field.displacement([x[0], x[1], 0.0]).0[2]
        })
    }

    /// The face conditions and body force, all data times `s`.
    fn boundary(
        &self,
        exact: &Arc<SolidTrigonometricExact>,
        s: f64,
    ) -> (SolidBoundary, SolidForce) {
        let dirichlet = || {
            FaceCondition([0, 1, 2].map(|c| {
                let ex = Arc::clone(exact);
                FaceComponent::Displacement(FaceFunction::new(move |x| {
                    s * ex.field.displacement(x).0[c]
                }))
            }))
        };
        let traction = |face: Face, pressure: bool| {
            FaceCondition([0, 1, 2].map(|c| {
                let (ex, this) = (Arc::clone(exact), self.clone());
                FaceComponent::Traction(FaceFunction::new(move |x| {
                    let t = ex.traction(face, x).map_or(f64::NAN, |t| t[c]);
                    let p = if pressure && c == 2 {
                        this.contact_pressure(x[0], x[1])
                    } else {
                        0.0
                    };
                    s * (t - p)
                }))
            }))
        };
        let boundary = SolidBoundary {
            faces: [
                dirichlet(),
                dirichlet(),
                dirichlet(),
                dirichlet(),
                traction(Face::X3Min, true),
                traction(Face::X3Max, false),
            ],
            periodic_x2: false,
            pinned: vec![],
        };
        let ex = Arc::clone(exact);
        let force: SolidForce =
            Arc::new(move |x| ex.forcing(x).map_or([f64::NAN; 3], |f| f.map(|y| s * y)));
        (boundary, force)
    }

    /// The frictionless unilateral contact model on `nodes` (`[n1, n2, n3]`) with elements of
    /// `order`, and the exact solution: all data in the first load (solve with
    /// `EndLoads::new(1.0, 0.0)`), the second load zero.
    ///
    /// # Errors
    /// Grid, geometry and element-count errors; those of
    /// [`ContactModel::into_unilateral`].
    pub fn model(
        &self,
        nodes: [usize; 3],
        order: ElementOrder,
    ) -> Result<(SolidSignoriniModel, Arc<SolidTrigonometricExact>), ContactError> {
        let exact = self.mms.exact();
        let grid = BoxGrid::new(self.mms.x1, self.mms.x2, self.mms.thickness, nodes, false)?;
        let build = |m: &[f64]| -> Result<SolidNavier<SampleChart>, ElasticityError> {
            let (boundary, force) = self.boundary(&exact, m[0]);
            SolidNavier::new(
                ShellChart::new(self.mms.obstacle.clone()),
                self.mms.material,
                grid,
                &boundary,
                Some(&force),
                order,
                VolumetricIntegration::Full,
            )
        };
        let model =
            ContactModel::with_loads(build, &["mms.data", "mms.zero"], Frictionless, (), 1.0)?;
        let model = model.into_unilateral(&self.gap(&exact))?;
        Ok((model, exact))
    }

    /// Solves on `nodes` with the full-system (semismooth) Newton and measures the errors.
    ///
    /// # Errors
    /// See [`SolidSignoriniMms::model`]; solver failures.
    pub fn run(
        &self,
        nodes: [usize; 3],
        order: ElementOrder,
    ) -> Result<SolidSignoriniPoint, ContactError> {
        use crate::contact::FullSystemSolver;
        let (model, exact) = self.model(nodes, order)?;
        let solution = FullSystemSolver::new(&model, FullSystemSettings::default())?
            .solve(EndLoads::new(1.0, 0.0))?;
        let op = model.discretisation();
        let v = &solution.displacement;
        let field = |x: [f64; 3]| exact.field.displacement(x).0;
        let (l2, norm) = op.l2_errors(v, &field)?;
        let grid = op.grid();
        let mut max_error = 0.0f64;
        for m in 0..grid.node_count() {
            let node = grid.node(m);
            let x = grid.coordinates(node);
            let g = exact
                .chart
                .shell_point(x)
                .map_err(ElasticityError::from)?
                .metric;
            let u = field(x);
            let e: [f64; 3] = core::array::from_fn(|c| v[op.dof(node, c)] - u[c]);
            let mut q = 0.0;
            for i in 0..3 {
                for j in 0..3 {
                    q += g[i][j] * e[i] * e[j];
                }
            }
            max_error = max_error.max(q.max(0.0).sqrt());
        }
        let [n1, n2, _] = grid.counts();
        let [d1, d2, _] = grid.spacing();
        let profile = &solution.contact;
        let separated: Vec<bool> = profile
            .separated
            .clone()
            .unwrap_or_else(|| profile.state.iter().map(|&s| s == SEPARATED).collect());
        let x1 = profile.solid.as_ref().map_or(&profile.x2, |s| &s.x1);
        let (mut split_error, mut bracketed, mut area) = (0.0f64, true, 0.0);
        for i1 in 0..n1 {
            // the contact profile lists the face nodes x1-line by x1-line (site i1 n2 + i2)
            let line = i1 * n2..(i1 + 1) * n2;
            let states = &separated[line.clone()];
            let xs = &profile.x2[line.clone()];
            let at = x1[line.start];
            let exact_split = self.split_at(at);
            let switches = states.windows(2).filter(|w| w[0] != w[1]).count();
            let located = match states.iter().position(|&s| s) {
                Some(i) if i > 0 && switches == 1 => {
                    let (last, first) = (xs[i - 1], xs[i]);
                    if !(last <= exact_split + d2 && first >= exact_split - d2) {
                        bracketed = false;
                    }
                    0.5 * (last + first)
                }
                _ => {
                    bracketed = false;
                    f64::NAN
                }
            };
            split_error = split_error.max((located - exact_split).abs());
            let w1 = if i1 == 0 || i1 == n1 - 1 {
                0.5 * d1
            } else {
                d1
            };
            area += w1 * (self.mms.x2[1] - located);
        }
        let split_error = if bracketed {
            split_error
        } else {
            f64::INFINITY
        };
        Ok(SolidSignoriniPoint {
            nodes,
            h: d2,
            l2_error: l2 / norm,
            max_error,
            split_error,
            split_bracketed: bracketed,
            separated_area: area,
            area_error: (area - self.separated_area()).abs(),
            newton_iterations: solution.stats.newton_iterations,
        })
    }
}
