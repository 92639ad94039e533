//! Manufactured solutions of the 3-D body: a smooth field on any chart, its forcing and
//! tractions, and the convergence study on cones and prisms.

use std::sync::Arc;

use capstan_geometry::{
    ExpressionProfile, GeneralCone, GeneralPrism, Obstacle, Scalar, ShellChart, ShellPoint,
    Surface, ad,
};

use super::samples::manufactured_forcing;
use crate::continuum::{SOLID, mixed_stress_of};
use crate::error::ElasticityError;
use crate::finite_element::{ElementOrder, VolumetricIntegration};
use crate::material::Material;
use crate::shell_geometry::ShellGeometry;
use crate::solid::BoxGrid;
use crate::solid::HexElement;
use crate::solid::{Face, FaceComponent, FaceCondition, FaceFunction, SolidBoundary};
use crate::solid::{SolidForce, SolidMatrixFree, SolidNavier};

/// The chart of the 3-D sample problems (as `crate::studies::SampleChart`).
type SampleChart = ShellChart<Obstacle>;
use crate::verification::{GridLevel, Study, StudyPoint};

/// A smooth 3-D displacement field `x -> [v^1, v^2, v^3]`, written once for every scalar:
/// its derivatives follow exactly by forward-mode AD through [`SolidField::value`].
pub trait SolidField: Send + Sync {
    /// `[v^1, v^2, v^3]` at `x`.
    fn value<S: Scalar<f64>>(&self, x: [S; 3]) -> [S; 3];

    /// `([v^1, v^2, v^3], gradient)` at `x`, `gradient[p][c] = d_p v^c` (by AD).
    fn displacement(&self, x: [f64; 3]) -> ([f64; 3], [[f64; 3]; 3]) {
        ad::value_and_gradient(|y| self.value(y), x)
    }

    /// The twelve inputs `[v^c, d_1 v^c, d_2 v^c, d_3 v^c]` of [`SOLID`] (at dual `x` they
    /// carry their own derivatives).
    fn inputs<S: Scalar<f64>>(&self, x: [S; 3]) -> [S; 12] {
        let (v, g) = ad::value_and_gradient(|y| self.value(y), x);
        core::array::from_fn(|k| {
            if k < 3 {
                v[k]
            } else {
                g[(k - 3) / 3][(k - 3) % 3]
            }
        })
    }
}

/// The field of the 3-D studies (`v^3 = 0` on `x3 = 0`):
///
/// ```text
/// v^1 = 0.04 sin(1.1 x1 + 0.3) cos(0.7 x2) (1 + x3/2)
/// v^2 = 0.05 sin(1.3 x2 + 0.2) (1 + x3/2 + x3^2/4) (1 + x1/5)
/// v^3 = 0.1 sin(1.2 x3) (1 + cos(0.8 x2)/2) (1 + 0.3 sin x1)
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SolidTrigonometricField;

impl SolidField for SolidTrigonometricField {
    fn value<S: Scalar<f64>>(&self, [x1, x2, x3]: [S; 3]) -> [S; 3] {
        let q = x3 * 0.5 + x3 * x3 * 0.25 + 1.0;
        let w = (x2 * 0.8).cos() * 0.5 + 1.0;
        [
            (x1 * 1.1 + 0.3).sin() * (x2 * 0.7).cos() * (x3 * 0.5 + 1.0) * 0.04,
            (x2 * 1.3 + 0.2).sin() * q * (x1 * 0.2 + 1.0) * 0.05,
            (x3 * 1.2).sin() * w * (x1.sin() * 0.3 + 1.0) * 0.1,
        ]
    }
}

/// Stresses, tractions and the forcing of a 3-D manufactured field, pointwise on a chart.
pub struct SolidExact<G, F> {
    /// The chart.
    pub chart: G,
    /// The material.
    pub material: Material,
    /// The field.
    pub field: F,
}

impl<G: ShellGeometry, F: SolidField> SolidExact<G, F> {
    fn point(&self, x: [f64; 3]) -> Result<ShellPoint<f64>, ElasticityError> {
        Ok(self.chart.shell_point(x)?)
    }

    /// `T^i_j` of the exact field at `x`.
    ///
    /// # Errors
    /// Geometry failures.
    pub fn mixed_stress(&self, x: [f64; 3]) -> Result<[[f64; 3]; 3], ElasticityError> {
        Ok(mixed_stress_of(
            &self.point(x)?,
            &SOLID,
            &self.material,
            &self.field.inputs(x),
        ))
    }

    /// The traction `t_j = n_i T^i_j` on `face` at `x`.
    ///
    /// # Errors
    /// Geometry failures.
    pub fn traction(&self, face: Face, x: [f64; 3]) -> Result<[f64; 3], ElasticityError> {
        let p = self.point(x)?;
        let a = face.normal_index();
        let t = mixed_stress_of(&p, &SOLID, &self.material, &self.field.inputs(x));
        let n = face.sign() / p.inverse_metric[a][a].sqrt();
        Ok([0, 1, 2].map(|j| n * t[a][j]))
    }
}

impl<Surf: Surface<f64>, F: SolidField> SolidExact<ShellChart<Surf>, F> {
    /// The forcing `f_j = -nabla_i T^i_j` of the exact field, exact to round-off.
    ///
    /// # Math
    /// ```text
    /// nabla_i T^i_j = (1/sqrt(g)) d_a (sqrt(g) T^a_j) - Gamma^k_ij T^i_k      (a = 1, 2, 3)
    /// ```
    /// `d_a (sqrt(g) T^a_j)` by forward-mode AD, as in the 2-D samples
    /// ([`crate::samples::ExactSolution::forcing`]).
    ///
    /// # Errors
    /// Geometry failures.
    pub fn forcing(&self, x: [f64; 3]) -> Result<[f64; 3], ElasticityError> {
        manufactured_forcing(&self.chart, &self.material, &SOLID, x, &[0, 1, 2], |y| {
            self.field.inputs(y)
        })
    }
}

/// A 3-D manufactured-solution problem: the field of [`SolidTrigonometricField`] on the box
/// of a chart, Dirichlet data on the `x1` and `x2` faces, tractions on the `x3` faces.
#[derive(Debug, Clone)]
pub struct SolidMms {
    /// The obstacle.
    pub obstacle: Obstacle,
    /// The material.
    pub material: Material,
    /// `[x1a, x1b]`.
    pub x1: [f64; 2],
    /// `[x2a, x2b]`.
    pub x2: [f64; 2],
    /// The thickness `h`.
    pub thickness: f64,
    /// What the problem shows, for reports.
    pub name: &'static str,
}

/// The exact solution of the 3-D studies.
pub type SolidTrigonometricExact = SolidExact<SampleChart, SolidTrigonometricField>;

impl SolidMms {
    /// An elliptical cone `x1 (1, 0.6 sin x2, 0.4 cos x2)` for `x1 in [1, 1.5]`: its chart has
    /// `g_12 = x1 (ubar ubar' + vbar vbar') != 0` (not orthogonally parametrised).
    ///
    /// # Panics
    /// Never: the expressions are fixed and valid.
    pub fn elliptical_cone() -> Self {
        let profile =
            ExpressionProfile::parse("0.6 * sin(t)", "0.4 * cos(t)").expect("a valid profile");
        Self {
            obstacle: Obstacle::Cone(GeneralCone::new(profile)),
            material: Material::new(10.0, 0.3).expect("a valid material"),
            x1: [1.0, 1.5],
            x2: [-0.6, 0.6],
            thickness: 0.15,
            name: "elliptical cone (g_12 != 0)",
        }
    }

    /// A right circular cone of half-aperture `atan(0.5)` (orthogonal chart) for
    /// `x1 in [1, 1.5]`.
    ///
    /// # Panics
    /// Never: the expressions are fixed and valid.
    pub fn circular_cone() -> Self {
        let profile =
            ExpressionProfile::parse("0.5 * sin(t)", "0.5 * cos(t)").expect("a valid profile");
        Self {
            obstacle: Obstacle::Cone(GeneralCone::new(profile)),
            name: "right circular cone",
            ..Self::elliptical_cone()
        }
    }

    /// The expression prism `(3 sin t - 0.2 sin 3t, 2 cos t + 0.1 t^2)` of the 2-D studies,
    /// `x1 in [0, 0.5]`.
    ///
    /// # Panics
    /// Never: the expressions are fixed and valid.
    pub fn expression_prism() -> Self {
        let profile =
            ExpressionProfile::parse("3 * sin(t) - 0.2 * sin(3 * t)", "2 * cos(t) + 0.1 * t^2")
                .expect("a valid profile");
        Self {
            obstacle: Obstacle::Prism(GeneralPrism::new(profile)),
            x1: [0.0, 0.5],
            x2: [-0.5, 0.5],
            thickness: 0.3,
            name: "expression prism",
            ..Self::elliptical_cone()
        }
    }

    /// The exact solution.
    pub fn exact(&self) -> Arc<SolidTrigonometricExact> {
        Arc::new(SolidExact {
            chart: ShellChart::new(self.obstacle.clone()),
            material: self.material,
            field: SolidTrigonometricField,
        })
    }

    /// The boundary conditions (the exact field on the `x1`, `x2` faces, its tractions on the
    /// `x3` faces) and the body force of the problem.
    pub fn boundary(&self) -> (SolidBoundary, SolidForce) {
        let exact = self.exact();
        let dirichlet = || {
            FaceCondition([0, 1, 2].map(|c| {
                let ex = exact.clone();
                FaceComponent::Displacement(FaceFunction::new(move |x| {
                    ex.field.displacement(x).0[c]
                }))
            }))
        };
        let traction = |face: Face| {
            FaceCondition([0, 1, 2].map(|c| {
                let ex = exact.clone();
                FaceComponent::Traction(FaceFunction::new(move |x| {
                    ex.traction(face, x).map_or(f64::NAN, |t| t[c])
                }))
            }))
        };
        let boundary = SolidBoundary {
            faces: [
                dirichlet(),
                dirichlet(),
                dirichlet(),
                dirichlet(),
                traction(Face::X3Min),
                traction(Face::X3Max),
            ],
            periodic_x2: false,
            pinned: vec![],
        };
        let ex = exact.clone();
        let force: SolidForce = Arc::new(move |x| ex.forcing(x).unwrap_or([f64::NAN; 3]));
        (boundary, force)
    }

    /// The operator on an `n = [n1, n2, n3]` grid with elements of `order`.
    ///
    /// # Errors
    /// Grid, geometry or element-count errors.
    pub fn operator(
        &self,
        n: [usize; 3],
        order: impl Into<HexElement>,
    ) -> Result<SolidNavier<SampleChart>, ElasticityError> {
        self.operator_with_force(n, order, |f| f)
    }

    /// [`SolidMms::operator`] with the exact covariant forcing handed through `force` first
    /// (e.g. to a physical-component [`crate::contact::BodyForceField`] and back: a test of
    /// that path against the manufactured solution).
    ///
    /// # Errors
    /// As [`SolidMms::operator`].
    pub fn operator_with_force(
        &self,
        n: [usize; 3],
        order: impl Into<HexElement>,
        force: impl FnOnce(SolidForce) -> SolidForce,
    ) -> Result<SolidNavier<SampleChart>, ElasticityError> {
        let grid = BoxGrid::new(self.x1, self.x2, self.thickness, n, false)?;
        let (boundary, force0) = self.boundary();
        let force = force(force0);
        SolidNavier::new(
            ShellChart::new(self.obstacle.clone()),
            self.material,
            grid,
            &boundary,
            Some(&force),
            order,
            VolumetricIntegration::Full,
        )
    }

    /// The matrix-free operator of the same problem ([`SolidMatrixFree`]).
    ///
    /// # Errors
    /// See [`SolidMms::operator`].
    pub fn matrix_free(
        &self,
        n: [usize; 3],
        order: impl Into<HexElement>,
    ) -> Result<SolidMatrixFree<SampleChart>, ElasticityError> {
        let grid = BoxGrid::new(self.x1, self.x2, self.thickness, n, false)?;
        let (boundary, force) = self.boundary();
        SolidMatrixFree::new(
            ShellChart::new(self.obstacle.clone()),
            self.material,
            grid,
            &boundary,
            Some(&force),
            order,
            VolumetricIntegration::Full,
        )
    }

    /// `(h, relative L2 error)` on the grid with `m` elements per direction (`dx3` as `h`).
    ///
    /// # Errors
    /// See [`SolidMms::operator`]; solver failures.
    pub fn relative_error(
        &self,
        m: usize,
        order: impl Into<HexElement>,
    ) -> Result<(f64, f64), ElasticityError> {
        let order = order.into();
        let k = order.degree();
        let n = k * m + 1;
        let op = self.operator([n, n, n], order)?;
        let v = op.solve(&mut capstan_solvers::SparseCholesky::default())?;
        let exact = self.exact();
        let (e, u) = op.l2_errors(&v, &|x| exact.field.displacement(x).0)?;
        Ok((self.thickness / (k * m) as f64, e / u))
    }
}

/// A 3-D manufactured-solution study for `capstan verify`: grids of `m = 2, 4, 8, 16`
/// elements per direction (`GridLevel { n2: n, n3: n }` stands for `n x n x n` nodes).
#[derive(Debug, Clone)]
pub struct SolidStudy {
    /// The problem.
    pub mms: SolidMms,
    /// The elements.
    pub order: ElementOrder,
}

impl Study for SolidStudy {
    fn name(&self) -> String {
        format!("3-D manufactured solution, {}", self.mms.name)
    }
    fn geometry(&self) -> String {
        format!(
            "x1 in {:?}, x2 in {:?}, h = {} (n x n x n nodes)",
            self.mms.x1, self.mms.x2, self.mms.thickness
        )
    }
    fn discretisation(&self) -> &'static str {
        match self.order {
            ElementOrder::Q1 => "solid-q1",
            ElementOrder::Q2 => "solid-q2",
        }
    }
    fn expected_order(&self) -> f64 {
        (self.order.degree() + 1) as f64
    }
    fn levels(&self) -> Vec<GridLevel> {
        let k = self.order.degree();
        [2, 4, 8, 16]
            .map(|m| GridLevel {
                n2: k * m + 1,
                n3: k * m + 1,
            })
            .to_vec()
    }
    fn run_level(&self, level: GridLevel) -> Result<StudyPoint, ElasticityError> {
        let n = level.n2;
        let op = self.mms.operator([n, n, n], self.order)?;
        let v = op.solve(&mut capstan_solvers::SparseCholesky::default())?;
        let exact = self.mms.exact();
        let (l2, _) = op.l2_errors(&v, &|x| exact.field.displacement(x).0)?;
        let grid = op.grid();
        let mut max = 0.0f64;
        for m in 0..grid.node_count() {
            let x = grid.coordinates(grid.node(m));
            let p = exact.chart.shell_point(x)?;
            let u = exact.field.displacement(x).0;
            let e: [f64; 3] = core::array::from_fn(|c| v[3 * m + c] - u[c]);
            let norm2 = crate::solid::length_squared(&p.metric, e);
            max = max.max(norm2.sqrt());
        }
        Ok(StudyPoint {
            level,
            h: self.mms.thickness / (n - 1) as f64,
            max_error: max,
            l2_error: l2,
        })
    }
}
