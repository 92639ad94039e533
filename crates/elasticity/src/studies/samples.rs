//! Reference problems shared by tests, benches and the `capstan verify` command: manufactured
//! solutions on prisms, the Lamé thick cylinder and the paper's section 3 ellipse.

use std::sync::Arc;

use capstan_geometry::ad::{self, Dual1};
use capstan_geometry::{
    CircularCylinder, EllipticalPrism, ExpressionProfile, GeneralPrism, Obstacle, Scalar,
    ShellChart, ShellPoint, Surface,
};

use super::column_forcing::{ColumnCache, ForcingColumn};
use super::parts::ProblemParts;
use crate::boundary::{
    BoundaryConditions, BoundaryFunction, Component, ComponentCondition, PinnedDof, Side,
    SideCondition, X2Ends,
};
use crate::continuum::kinematics::{LocalDisplacement, christoffel_contraction, mixed_stress};
use crate::continuum::{InputLayout, mixed_stress_of};
use crate::discretisation::Discretisation;
use crate::error::ElasticityError;
use crate::finite_difference::FiniteDifferenceNavier;
use crate::grid::Grid;
use crate::material::Material;
use crate::plane_problem::BodyForce;
use crate::shell_geometry::ShellGeometry;
use crate::verification::{GridLevel, Study, StudyPoint};

/// The chart type of the samples.
pub use super::parts::SampleChart;

/// A smooth displacement field `(x2, x3) -> [v^2, v^3]`, written once for every scalar: its
/// derivatives (the gradient in the boundary data and the errors, the second derivatives in
/// the forcing) follow exactly by forward-mode AD through [`ManufacturedField::value`].
pub trait ManufacturedField: Send + Sync {
    /// `[v^2, v^3]` at `(x2, x3)`.
    fn value<S: Scalar<f64>>(&self, x: [S; 2]) -> [S; 2];

    /// The six inputs `[v^2, v^3, d_2 v^2, d_2 v^3, d_3 v^2, d_3 v^3]` of
    /// [`PLANE_STRAIN`](crate::continuum::PLANE_STRAIN) at `(x2, x3)`, by AD through [`ManufacturedField::value`] (at dual
    /// `x` they carry their own derivatives).
    fn inputs<S: Scalar<f64>>(&self, x: [S; 2]) -> [S; 6] {
        let (v, g) = ad::value_and_gradient(|y| self.value(y), x);
        [v[0], v[1], g[0][0], g[0][1], g[1][0], g[1][1]]
    }

    /// `v^2, v^3` and their `x2`, `x3` derivatives at `(x2, x3)`.
    fn displacement(&self, x: [f64; 2]) -> LocalDisplacement {
        let [v2, v3, d22, d23, d32, d33] = self.inputs(x);
        LocalDisplacement {
            value: [v2, v3],
            gradient: [[d22, d23], [d32, d33]],
        }
    }
}

/// The manufactured field of the convergence studies (zero `v^3` on `x3 = 0`, so it also
/// satisfies bilateral contact):
///
/// ```text
/// v^2 = 0.05 sin(1.3 x2 + 0.2) (1 + x3/2 + x3^2/4)
/// v^3 = 0.1 sin(1.2 x3) (1 + cos(0.8 x2)/2)
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct TrigonometricField;

impl ManufacturedField for TrigonometricField {
    fn value<S: Scalar<f64>>(&self, [x2, x3]: [S; 2]) -> [S; 2] {
        let q = x3 * 0.5 + x3 * x3 * 0.25 + 1.0;
        let w = (x2 * 0.8).cos() * 0.5 + 1.0;
        [
            (x2 * 1.3 + 0.2).sin() * q * 0.05,
            (x3 * 1.2).sin() * w * 0.1,
        ]
    }
}

/// A manufactured field with more variation than [`TrigonometricField`] (about three times
/// its frequencies, trigonometric in both directions, zero `v^3` on `x3 = 0`), for the studies
/// of high-order elements: its interpolation error dominates the geometry's, so the observed
/// orders settle at `p + 1` on grids whose errors are well above round-off.
///
/// ```text
/// v^2 = 0.05 sin(3.7 x2 + 0.2) cos(2.9 x3 - 0.3)
/// v^3 = 0.1 sin(4.1 x3) (1 + cos(3.3 x2)/2)
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct OscillatoryField;

impl ManufacturedField for OscillatoryField {
    fn value<S: Scalar<f64>>(&self, [x2, x3]: [S; 2]) -> [S; 2] {
        let w = (x2 * 3.3).cos() * 0.5 + 1.0;
        [
            (x2 * 3.7 + 0.2).sin() * (x3 * 2.9 - 0.3).cos() * 0.05,
            (x3 * 4.1).sin() * w * 0.1,
        ]
    }
}

/// The field of a prism study ([`PrismMms::field`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum PrismField {
    /// [`TrigonometricField`], of the finite-difference and Q1/Q2 studies.
    #[default]
    Trigonometric,
    /// [`OscillatoryField`], of the high-order (Qp) studies.
    Oscillatory,
}

impl ManufacturedField for PrismField {
    fn value<S: Scalar<f64>>(&self, x: [S; 2]) -> [S; 2] {
        match self {
            Self::Trigonometric => TrigonometricField.value(x),
            Self::Oscillatory => OscillatoryField.value(x),
        }
    }
}

/// The exact radial field of the Lamé cylinder: `v^2 = 0`, `v^3 = A r + B/r`, `r = R + x3`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RadialField {
    /// `R`, radius of the inner surface.
    pub radius: f64,
    /// `A`.
    pub a: f64,
    /// `B`.
    pub b: f64,
}

impl ManufacturedField for RadialField {
    fn value<S: Scalar<f64>>(&self, [_, x3]: [S; 2]) -> [S; 2] {
        let r = x3 + self.radius;
        [S::zero(), r * self.a + r.recip() * self.b]
    }
}

/// The forcing `f_j = -nabla_i T^i_j` (`j = 1, 2, 3`) of a manufactured field given by its
/// `layout` inputs, at `x` on a shell chart, exactly: the fluxes are differentiated by
/// forward-mode AD along the coordinate `axes`.
///
/// # Math
/// ```text
/// nabla_i T^i_j = (1/sqrt(g)) d_a (sqrt(g) T^a_j) - Gamma^k_ij T^i_k     (a in axes)
/// d_a (sqrt(g) T^a_j): sqrt(g) T^a_j evaluated at x + eps e_a (dual numbers through sigma,
///                      the shell point and the field); the eps part
/// ```
/// `inputs(y)` are the field's inputs at the dual point `y`.
///
/// # Errors
/// Geometry failures.
pub(crate) fn manufactured_forcing<Surf: Surface<f64>, const N: usize>(
    chart: &ShellChart<Surf>,
    material: &Material,
    layout: &InputLayout<N>,
    x: [f64; 3],
    axes: &[usize],
    inputs: impl Fn([Dual1<f64>; 3]) -> [Dual1<f64>; N],
) -> Result<[f64; 3], ElasticityError> {
    let p = chart.point(x)?;
    let mut div = [0.0; 3];
    let mut stress = [[0.0; 3]; 3];
    for &a in axes {
        let y = core::array::from_fn(|i| ad::seed(x[i], if i == a { 1.0 } else { 0.0 }));
        let q = chart.point_over(y)?;
        let t = mixed_stress_of(&q, layout, material, &inputs(y));
        for (j, d) in div.iter_mut().enumerate() {
            *d += ad::derivative_part(q.sqrt_g * t[a][j]);
        }
        stress = t.map(|row| row.map(ad::value_part));
    }
    Ok(core::array::from_fn(|j| {
        -(div[j] / p.sqrt_g - christoffel_contraction(&p, &stress, j))
    }))
}

/// Stresses, tractions and the forcing of a manufactured field, pointwise on a chart.
pub struct ExactSolution<G, M> {
    /// The chart.
    pub chart: G,
    /// The material.
    pub material: Material,
    /// The field.
    pub field: M,
}

impl<G: ShellGeometry, M: ManufacturedField> ExactSolution<G, M> {
    fn point(&self, x: [f64; 2]) -> Result<ShellPoint<f64>, ElasticityError> {
        Ok(self.chart.shell_point([0.0, x[0], x[1]])?)
    }

    /// `T^i_j` of the exact field at `x`.
    ///
    /// # Errors
    /// Geometry failures.
    pub fn mixed_stress(&self, x: [f64; 2]) -> Result<[[f64; 3]; 3], ElasticityError> {
        Ok(mixed_stress(
            &self.point(x)?,
            &self.material,
            &self.field.displacement(x),
        ))
    }

    /// The traction `t_j = n_i T^i_j` on `side` at `x`.
    ///
    /// # Errors
    /// Geometry failures.
    pub fn traction(&self, side: Side, x: [f64; 2]) -> Result<[f64; 2], ElasticityError> {
        let p = self.point(x)?;
        let a = side.normal_index();
        let t = mixed_stress(&p, &self.material, &self.field.displacement(x));
        let n = side.sign() / p.inverse_metric[a][a].sqrt();
        Ok([n * t[a][1], n * t[a][2]])
    }
}

impl<Surf: Surface<f64>, M: ManufacturedField> ExactSolution<ShellChart<Surf>, M> {
    /// The forcing `f_j = -nabla_i T^i_j` (`j = 2, 3`) of the exact field, exact to round-off.
    ///
    /// # Math
    /// ```text
    /// nabla_i T^i_j = (1/sqrt(g)) d_a (sqrt(g) T^a_j) - Gamma^k_ij T^i_k     (a = 2, 3)
    /// ```
    /// `d_a (sqrt(g) T^a_j)` by forward-mode AD, both directions from one evaluation: the
    /// shell point at nested dual coordinates (`x2` inner, `x3` outer; [`ForcingColumn`]: the
    /// dual frame of the column `x2`, fourth derivatives of `sigma`) and the field's inputs at
    /// the same coordinates ([`ManufacturedField::inputs`], second derivatives of the field).
    ///
    /// # Errors
    /// Geometry failures.
    pub fn forcing(&self, x: [f64; 2]) -> Result<[f64; 2], ElasticityError> {
        self.forcing_in(&ForcingColumn::new(&self.chart, x[0])?, x[1])
    }

    /// [`ExactSolution::forcing`] at `(x2, x3)` with the column of `x2` from `cache` (built
    /// once per column and thread while the points come column by column, as the quadrature
    /// loops visit them): the same numbers.
    ///
    /// # Errors
    /// Geometry failures.
    pub fn cached_forcing(
        &self,
        cache: &ColumnCache,
        x: [f64; 2],
    ) -> Result<[f64; 2], ElasticityError> {
        cache.with(&self.chart, x[0], |column| self.forcing_in(column, x[1]))
    }

    /// The forcing at height `x3` of `column`.
    fn forcing_in(&self, column: &ForcingColumn, x3: f64) -> Result<[f64; 2], ElasticityError> {
        column.forcing(&self.material, x3, |y| self.field.inputs(y))
    }
}

/// The exact solution of the prism studies (the field of [`PrismMms::field`]).
pub type TrigonometricExact = ExactSolution<SampleChart, PrismField>;

/// Which conditions a manufactured-solution study imposes (all data from the exact field).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum MmsBoundaries {
    /// Dirichlet at both `x2` ends; traction on `x3 = 0` (the contact side) and on `x3 = h`.
    TractionContact,
    /// Bilateral contact on `x3 = 0` (`v^3 = 0` and a traction in `j = 2`), traction on
    /// `x3 = h`, stress `T^2_j` at `x2 = theta0` (the paper's end condition), Dirichlet at
    /// `x2 = theta1`.
    BilateralContact,
}

impl MmsBoundaries {
    /// Name used in reports.
    pub fn name(self) -> &'static str {
        match self {
            Self::TractionContact => "traction-contact",
            Self::BilateralContact => "bilateral-contact",
        }
    }
}

/// A manufactured-solution study on a prism: a [`PrismField`] ([`TrigonometricField`] unless
/// set) on `[theta0, theta1] x [0, h]`, forcing and boundary data from the exact field.
#[derive(Debug, Clone)]
pub struct PrismMms {
    /// Short name of the geometry, e.g. `ellipse b/a=0.5`.
    pub geometry: String,
    /// The obstacle.
    pub obstacle: Obstacle,
    /// `[theta0, theta1]`.
    pub theta: [f64; 2],
    /// Thickness `h`.
    pub thickness: f64,
    /// The material.
    pub material: Material,
    /// The boundary conditions.
    pub boundaries: MmsBoundaries,
    /// The manufactured field.
    pub field: PrismField,
}

fn material(young: f64, poisson: f64) -> Material {
    Material::new(young, poisson).expect("sample material is valid")
}

impl PrismMms {
    /// The elliptical prism `(x1, a sin t, b cos t)` with `a = 1` and `b = b_over_a`.
    ///
    /// # Panics
    /// If `b_over_a` is not positive.
    #[track_caller]
    pub fn ellipse(b_over_a: f64, boundaries: MmsBoundaries) -> Self {
        Self {
            geometry: format!("ellipse a=1 b={b_over_a}"),
            obstacle: Obstacle::Ellipse(
                EllipticalPrism::new(1.0, b_over_a).expect("positive radii"),
            ),
            theta: [-1.2, 1.0],
            thickness: 0.5,
            material: material(10.0, 0.3),
            boundaries,
            field: PrismField::Trigonometric,
        }
    }

    /// The expression-defined prism `u = 2 sin(t) + 0.2 sin(2t)`, `v = 1.5 cos(t)`.
    pub fn expression_prism(boundaries: MmsBoundaries) -> Self {
        let profile = ExpressionProfile::parse("2*sin(t) + 0.2*sin(2*t)", "1.5*cos(t)")
            .expect("sample expressions parse");
        Self {
            geometry: "prism u=2*sin(t)+0.2*sin(2*t) v=1.5*cos(t)".to_owned(),
            obstacle: Obstacle::Prism(GeneralPrism::new(profile)),
            theta: [-1.0, 1.1],
            thickness: 0.4,
            material: material(10.0, 0.3),
            boundaries,
            field: PrismField::Trigonometric,
        }
    }

    fn exact(&self) -> Arc<TrigonometricExact> {
        Arc::new(ExactSolution {
            chart: ShellChart::new(self.obstacle.clone()),
            material: self.material,
            field: self.field,
        })
    }

    /// The problem's parts on an `n2 x n3` grid (any discretisation builds from them), with
    /// its exact solution.
    ///
    /// # Errors
    /// Grid or geometry errors.
    pub fn parts(
        &self,
        level: GridLevel,
    ) -> Result<(ProblemParts, Arc<TrigonometricExact>), ElasticityError> {
        let exact = self.exact();
        let grid = Grid::new(self.theta, self.thickness, level.n2, level.n3, false)?;
        let traction = |side: Side, c: Component| {
            let ex = exact.clone();
            ComponentCondition::Traction(BoundaryFunction::new(move |s| {
                ex.traction(side, side.point(&grid, s))
                    .map_or(f64::NAN, |t| t[c.index()])
            }))
        };
        let stress = |side: Side, c: Component| {
            let ex = exact.clone();
            ComponentCondition::Stress(BoundaryFunction::new(move |s| {
                ex.mixed_stress(side.point(&grid, s))
                    .map_or(f64::NAN, |t| t[side.normal_index()][c.index() + 1])
            }))
        };
        let dirichlet = |side: Side, c: Component| {
            let ex = exact.clone();
            ComponentCondition::Displacement(BoundaryFunction::new(move |s| {
                ex.field.displacement(side.point(&grid, s)).value[c.index()]
            }))
        };
        let both = |f: &dyn Fn(Side, Component) -> ComponentCondition, side| {
            SideCondition([f(side, Component::X2), f(side, Component::X3)])
        };
        let boundary = match self.boundaries {
            MmsBoundaries::TractionContact => BoundaryConditions {
                x2: X2Ends::Sides {
                    min: both(&dirichlet, Side::X2Min),
                    max: both(&dirichlet, Side::X2Max),
                },
                x3_min: both(&traction, Side::X3Min),
                x3_max: both(&traction, Side::X3Max),
                pinned: vec![],
            },
            MmsBoundaries::BilateralContact => BoundaryConditions {
                x2: X2Ends::Sides {
                    min: both(&stress, Side::X2Min),
                    max: both(&dirichlet, Side::X2Max),
                },
                x3_min: SideCondition([
                    traction(Side::X3Min, Component::X2),
                    ComponentCondition::fixed(),
                ]),
                x3_max: both(&traction, Side::X3Max),
                pinned: vec![],
            },
        };
        let (ex, cache) = (exact.clone(), ColumnCache::default());
        let force: BodyForce =
            Arc::new(move |x| ex.cached_forcing(&cache, x).unwrap_or([f64::NAN; 2]));
        let parts = ProblemParts {
            chart: ShellChart::new(self.obstacle.clone()),
            material: self.material,
            grid,
            boundary,
            body_force: Some(force),
        };
        Ok((parts, exact))
    }

    /// The finite-difference operator on an `n2 x n3` grid, with its exact solution.
    ///
    /// # Errors
    /// Grid or geometry errors.
    pub fn operator(
        &self,
        level: GridLevel,
    ) -> Result<(FiniteDifferenceNavier<SampleChart>, Arc<TrigonometricExact>), ElasticityError>
    {
        let (parts, exact) = self.parts(level)?;
        Ok((parts.finite_difference()?, exact))
    }
}

/// Max and L2 (trapezoidal RMS over the parameter rectangle) norms of the error of the
/// Cartesian displacement, `|U_h - U| = sqrt(g_22 e^2 e^2 + g_33 e^3 e^3)` (orthogonal charts).
///
/// # Errors
/// Geometry failures.
pub fn displacement_error<D: Discretisation, M: ManufacturedField>(
    op: &D,
    v: &[f64],
    field: &M,
) -> Result<[f64; 2], ElasticityError> {
    let fields = op.fields(v)?;
    let grid = *op.grid();
    let (mut max, mut sum, mut weight) = (0.0f64, 0.0, 0.0);
    for k in 0..grid.node_count() {
        let node = grid.node(k);
        let exact = field.displacement(grid.coordinates(node)).value;
        let (d, s) = (fields.displacement[k], fields.scale[k]);
        let e = ((s[1] * (d[0] - exact[0])).powi(2) + (s[2] * (d[1] - exact[1])).powi(2)).sqrt();
        let w = grid.quadrature_weight(node);
        max = max.max(e);
        sum += w * e * e;
        weight += w;
    }
    Ok([max, (sum / weight).sqrt()])
}

/// The errors of `op`'s sparse-LU solution against `field` on `level` (`h = dx3`).
///
/// # Errors
/// The solve's and [`displacement_error`]'s.
fn lu_study_point<D: Discretisation, M: ManufacturedField>(
    level: GridLevel,
    op: &D,
    field: &M,
) -> Result<StudyPoint, ElasticityError> {
    let v = op.solve(&mut capstan_solvers::SparseLu::default())?;
    let [max_error, l2_error] = displacement_error(op, &v, field)?;
    Ok(StudyPoint {
        level,
        h: op.grid().dx3(),
        max_error,
        l2_error,
    })
}

impl Study for PrismMms {
    fn name(&self) -> String {
        let field = match self.field {
            PrismField::Trigonometric => "",
            PrismField::Oscillatory => " oscillatory field",
        };
        format!("mms {} {}{field}", self.geometry, self.boundaries.name())
    }
    fn geometry(&self) -> String {
        self.geometry.clone()
    }
    fn discretisation(&self) -> &'static str {
        "fd"
    }
    fn expected_order(&self) -> f64 {
        2.0 // the second-order central differences
    }
    fn levels(&self) -> Vec<GridLevel> {
        [12, 24, 48, 96]
            .map(|m| GridLevel {
                n2: 2 * m + 1,
                n3: m + 1,
            })
            .to_vec()
    }
    fn run_level(&self, level: GridLevel) -> Result<StudyPoint, ElasticityError> {
        let (op, exact) = self.operator(level)?;
        lu_study_point(level, &op, &exact.field)
    }
}

/// The Lamé thick cylinder: a circular tube `R <= r <= R + h` under internal pressure `p`,
/// free outside, in plane strain, over a full wrap (periodic `x2`), with `v^2 = 0` pinned at
/// one node to remove the rigid rotation.
///
/// # Math
/// ```text
/// u_r = A r + B/r,   sigma_rr = 2 (lambda + mu) A - 2 mu B / r^2
/// sigma_rr(R) = -p,  sigma_rr(R + h) = 0
/// => B = p / (2 mu (1/R^2 - 1/(R+h)^2)),   A = mu B / ((lambda + mu) (R+h)^2)
/// ```
/// On `x3 = 0` the traction is `t_3 = n_i T^i_3 = -T^3_3 = p`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LameCylinder {
    /// Inner radius `R`.
    pub radius: f64,
    /// Wall thickness `h`.
    pub thickness: f64,
    /// Internal pressure `p`.
    pub pressure: f64,
    /// The material.
    pub material: Material,
}

impl Default for LameCylinder {
    fn default() -> Self {
        Self {
            radius: 1.0,
            thickness: 1.0,
            pressure: 1.0,
            material: material(10.0, 0.3),
        }
    }
}

impl LameCylinder {
    /// The exact solution.
    pub fn field(&self) -> RadialField {
        let (l, m) = (self.material.lambda(), self.material.mu());
        let (r1, r2) = (self.radius, self.radius + self.thickness);
        let b = self.pressure / (2.0 * m * (1.0 / (r1 * r1) - 1.0 / (r2 * r2)));
        let a = m * b / ((l + m) * r2 * r2);
        RadialField {
            radius: self.radius,
            a,
            b,
        }
    }

    /// The cylinder's parts on an `n2 x n3` periodic grid, `v^2 = 0` pinned on `x3 = 0` at the
    /// nodes `pins` along `x2` (exact: the solution has `v^2 = 0` everywhere; one pin stops the
    /// rotation, more stop the rigid translations too).
    ///
    /// # Errors
    /// Grid or geometry errors.
    pub fn parts_pinned(
        &self,
        level: GridLevel,
        pins: &[usize],
    ) -> Result<ProblemParts, ElasticityError> {
        let grid = Grid::new(
            [0.0, 2.0 * core::f64::consts::PI],
            self.thickness,
            level.n2,
            level.n3,
            true,
        )?;
        let boundary = BoundaryConditions {
            x2: X2Ends::Periodic,
            x3_min: SideCondition([
                ComponentCondition::free(),
                ComponentCondition::Traction(BoundaryFunction::constant(self.pressure)),
            ]),
            x3_max: SideCondition::free(),
            pinned: pins
                .iter()
                .map(|&i2| PinnedDof {
                    node: [i2, 0],
                    component: Component::X2,
                    value: 0.0,
                })
                .collect(),
        };
        Ok(ProblemParts {
            chart: ShellChart::new(Obstacle::Cylinder(CircularCylinder::new(self.radius)?)),
            material: self.material,
            grid,
            boundary,
            body_force: None,
        })
    }

    /// The finite-difference operator on an `n2 x n3` periodic grid (the rotation pinned at
    /// `x2 = 0`).
    ///
    /// # Errors
    /// Grid or geometry errors.
    pub fn operator(
        &self,
        level: GridLevel,
    ) -> Result<FiniteDifferenceNavier<SampleChart>, ElasticityError> {
        self.parts_pinned(level, &[0])?.finite_difference()
    }
}

impl Study for LameCylinder {
    fn name(&self) -> String {
        "lame cylinder full wrap".to_owned()
    }
    fn geometry(&self) -> String {
        format!(
            "circle R={} h={} p={}",
            self.radius, self.thickness, self.pressure
        )
    }
    fn discretisation(&self) -> &'static str {
        "fd"
    }
    fn expected_order(&self) -> f64 {
        2.0 // the second-order central differences
    }
    fn levels(&self) -> Vec<GridLevel> {
        [8, 16, 32, 64]
            .map(|m| GridLevel {
                n2: 4 * m,
                n3: m + 1,
            })
            .to_vec()
    }
    fn run_level(&self, level: GridLevel) -> Result<StudyPoint, ElasticityError> {
        lu_study_point(level, &self.operator(level)?, &self.field())
    }
}

/// The paper's section 3 body on the ellipse `a = b = 2`, `h = 1`, `x2 in [-pi/2, pi/2]`,
/// `E = 1e3`, `nu = 1/4`, end tensions `tau0 = 1`, `tau_max = 2`, free outer surface, and
/// `v^2 = v^3 = 0` on `x3 = 0` as a linear stand-in for the contact (the benchmark problem).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PaperEllipse {
    /// Horizontal radius `a`.
    pub a: f64,
    /// Vertical radius `b`.
    pub b: f64,
    /// Thickness `h`.
    pub thickness: f64,
    /// Traction at `x2 = -pi/2`.
    pub tau0: f64,
    /// Traction at `x2 = pi/2`.
    pub tau_max: f64,
    /// The material.
    pub material: Material,
}

impl Default for PaperEllipse {
    fn default() -> Self {
        Self {
            a: 2.0,
            b: 2.0,
            thickness: 1.0,
            tau0: 1.0,
            tau_max: 2.0,
            material: material(1e3, 0.25),
        }
    }
}

impl PaperEllipse {
    /// The problem's parts on an `n2 x n3` grid.
    ///
    /// # Errors
    /// Grid or geometry errors.
    pub fn parts(&self, level: GridLevel) -> Result<ProblemParts, ElasticityError> {
        let half = core::f64::consts::FRAC_PI_2;
        Ok(ProblemParts {
            chart: ShellChart::new(Obstacle::Ellipse(EllipticalPrism::new(self.a, self.b)?)),
            material: self.material,
            grid: Grid::new([-half, half], self.thickness, level.n2, level.n3, false)?,
            boundary: BoundaryConditions::paper_clamped(self.tau0, self.tau_max),
            body_force: None,
        })
    }

    /// The finite-difference operator on an `n2 x n3` grid.
    ///
    /// # Errors
    /// Grid or geometry errors.
    pub fn operator(
        &self,
        level: GridLevel,
    ) -> Result<FiniteDifferenceNavier<SampleChart>, ElasticityError> {
        self.parts(level)?.finite_difference()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::continuum::PLANE_STRAIN;

    /// The forcing from one nested-dual evaluation per point on a column frame equals the one
    /// direction at a time of [`manufactured_forcing`] (two dual chart points per point) to
    /// round-off, on the ellipse and the expression prism, at both fields.
    #[test]
    fn column_forcing_equals_the_forcing_one_direction_at_a_time() {
        for mms in [
            PrismMms::ellipse(2.0, MmsBoundaries::TractionContact),
            PrismMms {
                field: PrismField::Oscillatory,
                ..PrismMms::expression_prism(MmsBoundaries::BilateralContact)
            },
        ] {
            let exact = mms.exact();
            for x in [[-1.1, 0.0], [-0.3, 0.21], [0.4, 0.5], [0.97, 0.33]] {
                let column = exact.forcing(x).unwrap();
                let axes = manufactured_forcing(
                    &exact.chart,
                    &exact.material,
                    &PLANE_STRAIN,
                    [0.0, x[0], x[1]],
                    &[1, 2],
                    |y| exact.field.inputs([y[1], y[2]]),
                )
                .unwrap();
                for j in 0..2 {
                    let scale = axes[1].abs().max(axes[2].abs());
                    assert!(
                        (column[j] - axes[j + 1]).abs() <= 1e-14 * scale,
                        "{} {x:?} j {j}: {} against {}",
                        mms.geometry,
                        column[j],
                        axes[j + 1]
                    );
                }
            }
        }
    }
}
