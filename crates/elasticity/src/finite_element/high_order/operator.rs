//! The operator type of the tensor-product elements Qp: setup (nodes, geometry at the
//! quadrature points, loads, Dirichlet data) and the per-node recovery the contact rows and
//! output fields share.

use std::sync::OnceLock;

use rayon::prelude::*;

use super::gll::{gauss_legendre, gll_rule};
use super::kernel::ElementTables;
use super::mesh::{Grading, QpSettings};
use super::nodal_recovery::NodalRecovery;
use super::skeleton::Skeleton;
use crate::boundary::Side;
use crate::continuum::{PLANE_STRAIN, check_plane_strain, divergence_coefficients, energy_matrix};
use crate::error::ElasticityError;
use crate::finite_element::assembly::ElementAssembly;
use crate::finite_element::boundary_terms::add_side_point_load;
use crate::finite_element::element::ElementOrder;
use crate::finite_element::volumetric::VolumetricIntegration;
use crate::plane_problem::{BodyForce, PlaneProblem, body_force_load};
use crate::plane_strain_operator::setup_accessors;
use crate::shell_geometry::ShellGeometry;

/// The orders the Qp elements accept (`discretisation.order`).
pub const ORDERS: core::ops::RangeInclusive<usize> = 1..=10;

/// Method names per order, for reports (`fem-qp1` ... `fem-qp10`).
const NAMES: [&str; 11] = [
    "fem-qp0", "fem-qp1", "fem-qp2", "fem-qp3", "fem-qp4", "fem-qp5", "fem-qp6", "fem-qp7",
    "fem-qp8", "fem-qp9", "fem-qp10",
];

/// The report name of order `p` (`"fem-qp4"`).
///
/// # Panics
/// For `p` outside [`ORDERS`].
#[track_caller]
pub fn order_name(p: usize) -> &'static str {
    assert!(ORDERS.contains(&p), "order {p} outside 1..=10");
    NAMES[p]
}

/// Checks `discretisation.order`.
///
/// # Errors
/// [`ElasticityError::InvalidParameter`] naming `discretisation.order` outside [`ORDERS`].
pub fn check_order(p: usize) -> Result<(), ElasticityError> {
    if ORDERS.contains(&p) {
        Ok(())
    } else {
        Err(ElasticityError::InvalidParameter {
            field: "discretisation.order",
            value: p as f64,
            allowed: "1..=10",
        })
    }
}

/// The plane-strain curvilinear Navier operator by tensor-product Lagrange elements of any
/// order `p` (Qp) with Gauss–Lobatto–Legendre nodes, on the element partition of a
/// [`Grid`](crate::Grid): `n2 = p e2 + 1` (periodic: `p e2`), `n3 = p e3 + 1` nodes.
///
/// # Math
/// Weak form on the parameter rectangle `Omega = [theta0, theta1] x [0, h]` (per unit `x1`):
/// ```text
/// a(v, w) = int_Omega T^i_j(v) nabla_i w^j sqrt(g) dx2 dx3
///         = int_Omega A^ijkl E_kl(v) E_ij(w) sqrt(g) dx2 dx3            (symmetric)
/// l(w)    = int_Omega f_j w^j sqrt(g) dx2 dx3 + int_{sides} phi_j w^j ds
/// nabla_i w^j = d_i w^j + Gamma^j_im w^m                              (d_1 = 0, w^1 = 0)
/// ```
/// with the boundary flux `phi_j = sqrt(g) sqrt(g^aa) t_j` for a traction
/// (`t_j = n_i T^i_j`, `dS = sqrt(g) sqrt(g^aa) ds` per unit `x1`) and `phi_j = s sqrt(g) f`
/// for a stress condition `T^a_j = f` (`s = +-1` the outward sign), exactly the fluxes of the
/// finite differences. In the six local inputs `u = [v^2, v^3, d_2 v^2, d_2 v^3, d_3 v^2,
/// d_3 v^3]` the integrand is `u^T K_q w` with `K_q` the symmetric 6 x 6 energy matrix
/// ([`energy_matrix`]), evaluated from the chart once per quadrature point and reused by
/// every refill (Newton steps, sweeps).
///
/// Element `(e2, e3)` is the parameter rectangle of the grid's element boundaries (every
/// `p`-th node line of the uniform grid); inside it node `(a2, a3)` sits at the GLL points
/// `xi_a2`, `xi_a3` of [`gll_rule`]:
/// ```text
/// x2(p e2 + a2) = theta0 + (e2 + (1 + xi_a2) / 2) L2,   x3(p e3 + a3) = (e3 + (1 + xi_a3) / 2) L3
/// ```
/// so grid node `(i2, i3)` is **not** at the uniform grid's `grid.coordinates` for `p >= 3`
/// (for `p = 1, 2` the GLL points `-1, 1` and `-1, 0, 1` are the uniform ones): use
/// [`HighOrderNavier::node_coordinates`] (the contact entries, output fields and error norms
/// do). The basis is the Lagrange basis through the GLL nodes; the stiffness uses the
/// `(p + 1)^2` Gauss–Legendre rule (exact for the constant-coefficient integrand; the
/// quadrature error `O(h^(2p+2))` stays below the `O(h^(p+1))` L2 error with the smooth
/// curvilinear coefficients), and the element matrix is formed by sum factorisation
/// ([`super::kernel::add_element_matrix`], `O(p^5)`), or for `p <= 2` by the direct loop
/// ([`super::kernel::add_element_matrix_direct`], faster at these sizes). Element matrices
/// are computed in parallel in batches and scattered in element order, so the values are
/// bitwise reproducible.
///
/// Dirichlet conditions are imposed strongly and symmetrically
/// ([`crate::finite_element::ElementAssembly`]): the row and column of a prescribed dof keep
/// only the diagonal `K_dd`, the column's contribution `K_rc g_c` moves to the right-hand side
/// and the row becomes `K_dd v_d = K_dd g_d`. The matrix is symmetric (bitwise) and, with
/// enough Dirichlet conditions to stop the rigid motions, positive definite, so
/// [`capstan_solvers::SparseCholesky`] applies; LU works too. Corner rules are those of
/// [`crate::FiniteDifferenceNavier`] (a displacement on either side wins; pinned dofs first).
///
/// Selective reduced integration ([`VolumetricIntegration::Reduced`]): the volumetric part
/// `lambda sqrt(g) (div v)(div w)` with the `p x p` Gauss rule, the shear part with the full
/// rule (Q1: one point, Q2: 2 x 2).
///
/// # Contact rows and fields
/// [`crate::ContactNode::traction_weight`] is the lumped boundary weight
/// `sqrt(g) sqrt(g^33) int N_i dx2` at the node; the stresses `T^3_3`, `T^3_2` at the node
/// and the output fields are recovered from the nodal values as [`NodalRecovery`] says
/// (`Element` for `fem-qp`, `Differences` for `fem-q1`, `fem-q2`).
///
/// # Unknowns and solves
/// [`crate::Discretisation`] sees every node (`dof = 2 node_index + c`, the numbering of the
/// other operators), so the contact solvers, which factorise `system()` once and condense
/// onto the contact boundary, work unchanged. [`crate::Discretisation::solve`] instead
/// condenses the element interiors statically (see [`super::CondensedElement`]): the global
/// factorisation is of the skeleton system on the element edges only, and the interior values
/// are recovered element by element ([`HighOrderNavier::condensed_system`],
/// [`HighOrderNavier::recover`]).
///
/// # Example
/// ```
/// use capstan_elasticity::{BoundaryConditions, Component, Discretisation, Grid, Material};
/// use capstan_elasticity::finite_element::HighOrderNavier;
/// use capstan_elasticity::PlaneProblem;
/// use capstan_geometry::{EllipticalPrism, ShellChart};
/// use capstan_solvers::SparseCholesky;
/// let problem = PlaneProblem {
///     chart: ShellChart::new(EllipticalPrism::new(2.0, 2.0).unwrap()),
///     material: Material::new(1e3, 0.25).unwrap(),
///     // p = 4: 6 x 1 elements
///     grid: Grid::new([-1.5707963, 1.5707963], 1.0, 25, 5, false).unwrap(),
///     boundary: BoundaryConditions::paper_clamped(1.0, 1.0),
///     body_force: None,
/// };
/// let op = HighOrderNavier::new(problem, 4).unwrap();
/// let v = op.solve(&mut SparseCholesky::default()).unwrap(); // condensed
/// let (left, right) = (v[op.dof([0, 4], Component::X2)], v[op.dof([24, 4], Component::X2)]);
/// assert!(left < 0.0 && (left + right).abs() < 1e-10); // odd in x2
/// ```
pub struct HighOrderNavier<G> {
    /// The problem, without its body force (integrated into `load`).
    pub(super) problem: PlaneProblem<G>,
    /// The order `p`.
    pub(super) degree: usize,
    pub(super) volumetric: VolumetricIntegration,
    /// Elements in `x2` and `x3`.
    pub(super) elements: [usize; 2],
    /// The element boundaries in `x2` (`e2 + 1`) and `x3` (`e3 + 1`).
    pub(super) breaks: [Vec<f64>; 2],
    /// How they are spaced.
    pub(super) grading: Grading,
    /// GLL nodes on `[-1, 1]`.
    pub(super) gll: Vec<f64>,
    /// GLL weights.
    pub(super) gll_weights: Vec<f64>,
    /// `x2` of each node line `i2`, `x3` of each node line `i3`.
    pub(super) x2: Vec<f64>,
    pub(super) x3: Vec<f64>,
    /// Basis tables at the full rule, on the reference element `[-1, 1]^2` (the element sizes
    /// are in `kq`, see [`scale_to_element`]).
    pub(super) tables: ElementTables,
    /// Basis tables at the reduced rule (SRI), reference element.
    pub(super) reduced_tables: Option<ElementTables>,
    /// `l_j'(xi_i)` at the GLL nodes, index `j n + i`.
    pub(super) derivative_at_nodes: Vec<f64>,
    /// Pointwise energy matrix times weights, scaled to the reference element, index
    /// `e nq^2 + q`.
    pub(super) kq: Vec<[[f64; 6]; 6]>,
    /// Volumetric part at the reduced points (SRI), index `e nr^2 + r`.
    pub(super) kv: Vec<[[f64; 6]; 6]>,
    /// The divergence coefficients `t_k = tr M_k` at the reduced points (SRI), index
    /// `e nr^2 + r`, for the reduced-point divergence of [`NodalRecovery::Differences`].
    pub(super) reduced_divergence: Vec<[f64; 6]>,
    /// How nodal values and gradients are recovered (contact rows, output fields).
    pub(super) recovery: NodalRecovery,
    pub(super) dirichlet: Vec<Option<f64>>,
    pub(super) load: Vec<f64>,
    /// The full pattern, built on first use.
    pub(super) full: OnceLock<ElementAssembly>,
    /// The skeleton pattern and numbering, built on first use.
    pub(super) skeleton: OnceLock<Skeleton>,
}

impl<G> core::fmt::Debug for HighOrderNavier<G> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        self.problem
            .debug_fields(f, "HighOrderNavier", Some(("degree", &self.degree)))
    }
}

impl<G: ShellGeometry + Sync> HighOrderNavier<G> {
    /// Builds the operator of order `p` with full integration: nodes, geometry and load.
    ///
    /// # Errors
    /// [`ElasticityError::InvalidParameter`] for `p` outside [`ORDERS`] (field
    /// `discretisation.order`) or a grid that is not a whole number of elements (`n - 1`,
    /// periodic `n`, a multiple of `p`; at least two elements around a periodic direction), and
    /// naming `recovery` for [`NodalRecovery::Differences`] with `p > 2` or graded elements;
    /// [`ElasticityError::InconsistentBoundary`] if periodicity of grid and conditions differ
    /// or a pinned node is outside the grid; [`ElasticityError::Geometry`] where the chart
    /// cannot be evaluated; [`ElasticityError::NotPlaneStrain`] for a chart that is not
    /// `x1`-invariant; [`ElasticityError::NonFinite`] for non-finite boundary data or body
    /// force.
    pub fn new(problem: PlaneProblem<G>, p: usize) -> Result<Self, ElasticityError> {
        Self::with_volumetric(problem, p, VolumetricIntegration::Full)
    }

    /// As [`HighOrderNavier::new`], with the volumetric part integrated as `volumetric` says
    /// (`Reduced`: `p x p` Gauss points for `lambda (div v)(div w)`).
    ///
    /// # Errors
    /// See [`HighOrderNavier::new`].
    pub fn with_volumetric(
        problem: PlaneProblem<G>,
        p: usize,
        volumetric: VolumetricIntegration,
    ) -> Result<Self, ElasticityError> {
        let settings = QpSettings {
            volumetric,
            ..QpSettings::order(p)
        };
        Self::with_settings(problem, settings)
    }

    /// The Q1 or Q2 element (`fem-q1`, `fem-q2`): order 1 or 2 on uniform elements with the
    /// volumetric part integrated as `volumetric` says and the nodal-difference recovery
    /// ([`QpSettings::element`], [`NodalRecovery::Differences`]).
    ///
    /// # Errors
    /// See [`HighOrderNavier::new`].
    ///
    /// # Example
    /// ```
    /// use capstan_elasticity::{BoundaryConditions, Component, Discretisation, Grid, Material};
    /// use capstan_elasticity::finite_element::{ElementOrder, HighOrderNavier, VolumetricIntegration};
    /// use capstan_elasticity::PlaneProblem;
    /// use capstan_geometry::{EllipticalPrism, ShellChart};
    /// use capstan_solvers::SparseCholesky;
    /// let problem = PlaneProblem {
    ///     chart: ShellChart::new(EllipticalPrism::new(2.0, 2.0).unwrap()),
    ///     material: Material::new(1e3, 0.25).unwrap(),
    ///     grid: Grid::new([-1.5707963, 1.5707963], 1.0, 25, 5, false).unwrap(),
    ///     boundary: BoundaryConditions::paper_clamped(1.0, 1.0),
    ///     body_force: None,
    /// };
    /// let q2 = ElementOrder::Q2;
    /// let op = HighOrderNavier::with_element(problem, q2, VolumetricIntegration::Full).unwrap();
    /// assert_eq!(op.method(), "fem-q2");
    /// let v = op.solve(&mut SparseCholesky::default()).unwrap(); // symmetric positive definite
    /// // equal end tensions: the tangential displacement is odd in x2
    /// let (left, right) = (v[op.dof([0, 4], Component::X2)], v[op.dof([24, 4], Component::X2)]);
    /// assert!(left < 0.0 && (left + right).abs() < 1e-10);
    /// ```
    pub fn with_element(
        problem: PlaneProblem<G>,
        order: ElementOrder,
        volumetric: VolumetricIntegration,
    ) -> Result<Self, ElasticityError> {
        let settings = QpSettings {
            volumetric,
            ..QpSettings::element(order)
        };
        Self::with_settings(problem, settings)
    }

    /// As [`HighOrderNavier::with_volumetric`], with the element boundaries spaced as
    /// `settings.grading` says ([`Grading`]: geometric layers toward both ends of `x2`, unless
    /// periodic, and of `x3`). The grid still fixes the element counts (`n = p e + 1`); its
    /// uniform positions are not the nodes' ([`HighOrderNavier::node_coordinates`]).
    ///
    /// # Errors
    /// See [`HighOrderNavier::new`].
    pub fn with_settings(
        mut problem: PlaneProblem<G>,
        settings: QpSettings,
    ) -> Result<Self, ElasticityError> {
        let QpSettings {
            order: p,
            volumetric,
            grading,
            recovery,
        } = settings;
        check_order(p)?;
        recovery.check(p, grading.is_uniform())?;
        let grid = problem.grid;
        problem.boundary.check_grid(&grid)?;
        let periodic = grid.is_periodic();
        let count = |field: &'static str, n: usize, periodic: bool| {
            let intervals = if periodic { n } else { n - 1 };
            if intervals.is_multiple_of(p) && intervals / p >= if periodic { 2 } else { 1 } {
                Ok(intervals / p)
            } else {
                Err(ElasticityError::InvalidParameter {
                    field,
                    value: n as f64,
                    allowed: "p e + 1 nodes for e elements (periodic: p e, e >= 2)",
                })
            }
        };
        let elements = [
            count("grid.n2", grid.n2(), periodic)?,
            count("grid.n3", grid.n3(), false)?,
        ];
        let breaks = [
            grading.breaks("grid.n2", grid.theta(), elements[0], periodic, |j| {
                grid.x2(p * j)
            })?,
            grading.breaks(
                "grid.n3",
                [0.0, grid.thickness()],
                elements[1],
                false,
                |j| grid.x3(p * j),
            )?,
        ];
        let (gll, gll_weights) = gll_rule(p);
        // element ends exactly on the boundaries, GLL points inside
        let line = |breaks: &[f64], n: usize| -> Vec<f64> {
            (0..n)
                .map(|i| {
                    let (e, a) = (i / p, i % p);
                    if a == 0 {
                        breaks[e]
                    } else {
                        breaks[e] + 0.5 * (1.0 + gll[a]) * (breaks[e + 1] - breaks[e])
                    }
                })
                .collect()
        };
        let x2 = line(&breaks[0], grid.n2());
        let x3 = line(&breaks[1], grid.n3());
        let (gq, _) = gauss_legendre(p + 1);
        let reference = [2.0, 2.0];
        let tables = ElementTables::new(&gll, &gq, reference);
        let reduced_tables = (volumetric == VolumetricIntegration::Reduced)
            .then(|| ElementTables::new(&gll, &gauss_legendre(p).0, reference));
        let (_, dn) = super::gll::basis_tables(&gll, &gll);
        let body_force = problem.body_force.take();
        let mut op = Self {
            problem,
            degree: p,
            volumetric,
            elements,
            breaks,
            grading,
            gll,
            gll_weights,
            x2,
            x3,
            tables,
            reduced_tables,
            derivative_at_nodes: dn.into_iter().flatten().collect(),
            kq: vec![],
            kv: vec![],
            reduced_divergence: vec![],
            recovery,
            dirichlet: vec![],
            load: vec![],
            full: OnceLock::new(),
            skeleton: OnceLock::new(),
        };
        op.dirichlet = op
            .problem
            .dirichlet_values(|node| op.node_coordinates(node))?;
        op.load = vec![0.0; 2 * grid.node_count()];
        op.cache_geometry(body_force.as_ref())?;
        op.add_boundary_loads()?;
        Ok(op)
    }

    setup_accessors!();

    /// The order `p`.
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// How nodal values and gradients are recovered for the contact rows and output fields.
    pub fn recovery(&self) -> NodalRecovery {
        self.recovery
    }

    /// The settings the operator was built with.
    pub fn settings(&self) -> QpSettings {
        QpSettings {
            order: self.degree,
            volumetric: self.volumetric,
            grading: self.grading,
            recovery: self.recovery,
        }
    }

    /// How the volumetric part is integrated.
    pub fn volumetric(&self) -> VolumetricIntegration {
        self.volumetric
    }

    /// Number of elements `[in x2, in x3]`.
    pub fn element_counts(&self) -> [usize; 2] {
        self.elements
    }

    /// `(x2, x3)` of grid node `(i2, i3)`: GLL points inside each element.
    ///
    /// # Panics
    /// If the node is outside the grid.
    #[track_caller]
    pub fn node_coordinates(&self, node: [usize; 2]) -> [f64; 2] {
        [self.x2[node[0]], self.x3[node[1]]]
    }

    /// Nodes per element direction, `p + 1`.
    pub(super) fn np(&self) -> usize {
        self.degree + 1
    }

    /// Grid node numbers of element `e = e2 e3count + e3`, local node `a = a2 (p + 1) + a3`.
    pub(super) fn element_nodes(&self, e: usize) -> Vec<usize> {
        let (p, np) = (self.degree, self.np());
        let (e2, e3) = (e / self.elements[1], e % self.elements[1]);
        let n2 = self.problem.grid.n2();
        let mut out = Vec::with_capacity(np * np);
        for a2 in 0..np {
            let i2 = (p * e2 + a2) % n2;
            for a3 in 0..np {
                out.push(self.problem.grid.node_index([i2, p * e3 + a3]));
            }
        }
        out
    }

    /// How the element boundaries are spaced.
    pub fn grading(&self) -> Grading {
        self.grading
    }

    /// The element boundaries `[x2 (e2 + 1 values), x3 (e3 + 1 values)]`.
    pub fn element_breaks(&self) -> &[Vec<f64>; 2] {
        &self.breaks
    }

    /// Start and length of element `e` of direction `axis` (`0`: `x2` column, `1`: `x3` row).
    pub(super) fn span(&self, axis: usize, e: usize) -> (f64, f64) {
        let b = &self.breaks[axis];
        (b[e], b[e + 1] - b[e])
    }

    /// Lower-left corner and size `[L2, L3]` of element `e = e2 e3count + e3`.
    pub(super) fn element_box(&self, e: usize) -> ([f64; 2], [f64; 2]) {
        let (x0, l2) = self.span(0, e / self.elements[1]);
        let (y0, l3) = self.span(1, e % self.elements[1]);
        ([x0, y0], [l2, l3])
    }

    /// Evaluates the chart at the tensor points `gp` of every element (one chart column per
    /// `x2` abscissa, element columns in parallel) and calls `visit(point, x, weight, size)`
    /// with `weight = w_q2 w_q3 det J`, `det J = L2 L3 / 4`, and the element's `[L2, L3]`;
    /// the result has `nq^2` entries per element, index `e nq^2 + q2 nq + q3`.
    fn walk_points<T: Send + Clone + Default>(
        &self,
        gp: &[f64],
        gw: &[f64],
        visit: impl Fn(
            &capstan_geometry::ShellPoint<f64>,
            [f64; 2],
            f64,
            [f64; 2],
        ) -> Result<T, ElasticityError>
        + Sync,
    ) -> Result<Vec<T>, ElasticityError> {
        let [ne2, ne3] = self.elements;
        let nq = gp.len();
        let heights: Vec<f64> = (0..ne3)
            .flat_map(|e3| {
                let (y0, l3) = self.span(1, e3);
                gp.iter().map(move |&eta| y0 + 0.5 * (eta + 1.0) * l3)
            })
            .collect();
        let mut out = vec![T::default(); ne2 * ne3 * nq * nq];
        out.par_chunks_mut(ne3 * nq * nq).enumerate().try_for_each(
            |(e2, column)| -> Result<(), ElasticityError> {
                let (x0, l2) = self.span(0, e2);
                let mut points = Vec::with_capacity(heights.len());
                for (q2, &xi) in gp.iter().enumerate() {
                    let x2 = x0 + 0.5 * (xi + 1.0) * l2;
                    self.problem
                        .visit_column(x2, &heights, &mut points, |idx, p, x3| {
                            let (e3, q3) = (idx / nq, idx % nq);
                            let l3 = self.span(1, e3).1;
                            let w = gw[q2] * gw[q3] * 0.25 * l2 * l3;
                            column[e3 * nq * nq + q2 * nq + q3] = visit(p, [x2, x3], w, [l2, l3])?;
                            Ok(())
                        })?;
                }
                Ok(())
            },
        )?;
        Ok(out)
    }

    /// The energy matrices at the quadrature points (and at the reduced points with SRI) and
    /// the body-force load `int f_j N_a sqrt(g) dA`.
    fn cache_geometry(&mut self, body_force: Option<&BodyForce>) -> Result<(), ElasticityError> {
        let (gp, gw) = gauss_legendre(self.degree + 1);
        let (lambda, mu) = (self.problem.material.lambda(), self.problem.material.mu());
        let full_lambda = if self.volumetric == VolumetricIntegration::Full {
            lambda
        } else {
            0.0
        };
        let points = self.walk_points(&gp, &gw, |p, x, w, size| {
            let k = scale_to_element(energy_matrix(p, &PLANE_STRAIN, full_lambda, mu, w), size);
            let f = body_force_load(body_force, x, p.sqrt_g, w)?;
            Ok((k, f))
        })?;
        if body_force.is_some() {
            let (np, nq) = (self.np(), gp.len());
            let t = &self.tables;
            for e in 0..self.elements[0] * self.elements[1] {
                let nodes = self.element_nodes(e);
                for q2 in 0..nq {
                    for q3 in 0..nq {
                        let f = points[e * nq * nq + q2 * nq + q3].1;
                        for a2 in 0..np {
                            for a3 in 0..np {
                                let n = t.value[a2 * nq + q2] * t.value[a3 * nq + q3];
                                let d = 2 * nodes[a2 * np + a3];
                                self.load[d] += n * f[0];
                                self.load[d + 1] += n * f[1];
                            }
                        }
                    }
                }
            }
        }
        self.kq = points.into_iter().map(|(k, _)| k).collect();
        if self.volumetric == VolumetricIntegration::Reduced {
            let (rp, rw) = gauss_legendre(self.degree);
            let points = self.walk_points(&rp, &rw, |p, _, w, size| {
                let t = divergence_coefficients(p, &PLANE_STRAIN);
                let c = lambda * p.sqrt_g * w;
                let k = core::array::from_fn(|a| core::array::from_fn(|b| c * t[a] * t[b]));
                Ok((scale_to_element(k, size), t))
            })?;
            (self.kv, self.reduced_divergence) = points.into_iter().unzip();
        }
        Ok(())
    }

    /// Adds `int phi_j N_a ds` over every side with a natural condition (Gauss rule of
    /// `p + 1` points along each boundary edge).
    fn add_boundary_loads(&mut self) -> Result<(), ElasticityError> {
        let (gp, gw) = gauss_legendre(self.degree + 1);
        let (p, np) = (self.degree, self.np());
        let (n2, n3) = (self.problem.grid.n2(), self.problem.grid.n3());
        // the shape functions at the edge's Gauss points, the same on every edge
        let shapes: Vec<Vec<f64>> = gp
            .iter()
            .map(|&xi| super::gll::lagrange_basis(&self.gll, xi).0)
            .collect();
        for side in Side::ALL {
            let Some(cond) = self.problem.boundary.side(side).cloned() else {
                continue; // periodic x2
            };
            let a = side.normal_index();
            let along_x2 = a == 2;
            let axis = usize::from(!along_x2);
            for e in 0..self.elements[axis] {
                let (origin, length) = self.span(axis, e);
                for ((&xi, &w), shape) in gp.iter().zip(&gw).zip(&shapes) {
                    let along = origin + 0.5 * (xi + 1.0) * length;
                    let (x, nodes): ([f64; 2], Vec<[usize; 2]>) = if along_x2 {
                        let i3 = if side == Side::X3Min { 0 } else { n3 - 1 };
                        (
                            [along, self.x3[i3]],
                            (0..np).map(|b| [(p * e + b) % n2, i3]).collect(),
                        )
                    } else {
                        let i2 = if side == Side::X2Min { 0 } else { n2 - 1 };
                        (
                            [self.x2[i2], along],
                            (0..np).map(|b| [i2, p * e + b]).collect(),
                        )
                    };
                    let at = [0.0, x[0], x[1]];
                    let pt = self.problem.chart.shell_point(at)?;
                    check_plane_strain(&pt, at)?;
                    let grid = &self.problem.grid;
                    let shape = nodes
                        .iter()
                        .zip(shape)
                        .map(|(m, n)| (grid.node_index(*m), *n));
                    let weight = [w, 0.5 * length];
                    add_side_point_load(&mut self.load, &cond, side, &pt, x, weight, shape)?;
                }
            }
        }
        Ok(())
    }

    /// The elements along one direction containing node line `i`: `(element, local index)`.
    pub(super) fn elements_along(
        &self,
        i: usize,
        count: usize,
        periodic: bool,
    ) -> Vec<(usize, usize)> {
        super::gll::elements_along(self.degree, i, count, periodic)
    }

    /// The nodal value and derivatives at grid node `node` as weights of nodal values:
    /// `(node index, [value, d_2, d_3])`, the derivatives of the element polynomials at the
    /// node averaged over the elements sharing it (one-sided limits at element edges).
    ///
    /// # Math
    /// ```text
    /// d_2 v (node) = (1 / #E2) sum_(e2 in E2) (2 / L2) sum_b l_b'(xi_a) v(p e2 + b, i3)
    /// ```
    /// and likewise in `x3`: exact for polynomials of degree `p` in the direction.
    pub(super) fn node_terms(&self, node: [usize; 2]) -> Vec<(usize, [f64; 3])> {
        self.node_terms_weighted(node, |_, _| 1.0)
    }

    /// [`Self::node_terms`] with the one-sided `x2` derivatives of the elements sharing the
    /// node weighted as the contact face's quadrature weighs them: `w_a L2_e / 2` (the GLL
    /// weight of the node in element `e` times its half-length), normalised. A contact
    /// traction linear in `T^3_j` then sums over the face to the elementwise GLL quadrature
    /// of the one-sided traction,
    /// ```text
    /// sum_e w_a (L2_e / 2) t(T_e) = (sum_e w_a L2_e / 2) t(sum_e theta_e T_e),
    /// theta_e = w_a L2_e / sum_f w_a L2_f
    /// ```
    /// where the plain average (`theta_e = 1 / #E2`) weighs a small element's one-sided stress
    /// as much as its large neighbour's and so misplaces `(theta_e - 1 / 2) [T] L2` of
    /// traction at every node between elements of unequal size (graded meshes).
    pub(super) fn contact_node_terms(&self, node: [usize; 2]) -> Vec<(usize, [f64; 3])> {
        self.node_terms_weighted(node, |e2, a2| self.gll_weights[a2] * self.span(0, e2).1)
    }

    /// [`Self::node_terms`] with the elements along `x2` weighted by `weight(e2, a2)`
    /// (normalised to sum 1).
    fn node_terms_weighted(
        &self,
        [i2, i3]: [usize; 2],
        weight: impl Fn(usize, usize) -> f64,
    ) -> Vec<(usize, [f64; 3])> {
        let (p, np) = (self.degree, self.np());
        let n2 = self.problem.grid.n2();
        let mut terms = vec![(self.problem.grid.node_index([i2, i3]), [1.0, 0.0, 0.0])];
        let along2 = self.elements_along(i2, self.elements[0], self.problem.grid.is_periodic());
        let total: f64 = along2.iter().map(|&(e2, a2)| weight(e2, a2)).sum();
        for (e2, a2) in along2 {
            let w2 = weight(e2, a2) / total;
            for b in 0..np {
                let d = self.derivative_at_nodes[b * np + a2] * 2.0 / self.span(0, e2).1 * w2;
                terms.push((
                    self.problem.grid.node_index([(p * e2 + b) % n2, i3]),
                    [0.0, d, 0.0],
                ));
            }
        }
        let along3 = self.elements_along(i3, self.elements[1], false);
        let w3 = 1.0 / along3.len() as f64;
        for (e3, a3) in along3 {
            for b in 0..np {
                let d = self.derivative_at_nodes[b * np + a3] * 2.0 / self.span(1, e3).1 * w3;
                terms.push((
                    self.problem.grid.node_index([i2, p * e3 + b]),
                    [0.0, 0.0, d],
                ));
            }
        }
        terms
    }
}

/// The energy matrix `k` of an element of size `[L2, L3]` on the reference element: the
/// inputs `d_2` (`k = 2, 3`) and `d_3` (`k = 4, 5`) are the reference derivatives times
/// `2 / L2` and `2 / L3`, so with reference tables (`d_xi`, `d_eta`)
/// ```text
/// k'[a][b] = s_a k[a][b] s_b,   s = (1, 1, 2 / L2, 2 / L2, 2 / L3, 2 / L3)
/// ```
/// reproduces the element matrix of tables scaled to the element; elements of any size then
/// share one set of tables.
fn scale_to_element(mut k: [[f64; 6]; 6], [l2, l3]: [f64; 2]) -> [[f64; 6]; 6] {
    let s = [1.0, 1.0, 2.0 / l2, 2.0 / l2, 2.0 / l3, 2.0 / l3];
    for (a, row) in k.iter_mut().enumerate() {
        for (b, x) in row.iter_mut().enumerate() {
            *x *= s[a] * s[b];
        }
    }
    k
}
