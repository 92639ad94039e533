//! The Galerkin discretisation of the plane-strain curvilinear Navier operator with Q1/Q2
//! Lagrange elements on the parameter rectangle.

use capstan_geometry::ShellPoint;
use rayon::prelude::*;

use super::element::{ElementOrder, gauss_rule};
use super::volumetric::VolumetricIntegration;
use crate::boundary::{BoundaryConditions, Component, ComponentCondition, Side};
use crate::discretisation::{ContactNode, Discretisation, LinearSystem, SparseRow};
use crate::error::ElasticityError;
use crate::fields::NodalFields;
use crate::finite_difference::BodyForce;
use crate::grid::Grid;
use crate::kinematics::{
    LocalDisplacement, contravariant_stress, mixed_stress_coefficients, strain,
};
use crate::material::Material;
use crate::shell_geometry::ShellGeometry;
use capstan_solvers::SparsityPattern;

/// Relative tolerance of the plane-strain check on the chart (as the finite differences).
const PLANE_STRAIN_TOLERANCE: f64 = 1e-10;

/// No slot: the local entry is dropped (Dirichlet row) or lifted to the right-hand side
/// (Dirichlet column).
const NO_SLOT: u32 = u32::MAX;

/// Elements whose local matrices are computed in parallel before one sequential scatter.
const BATCH: usize = 2048;

/// Coefficients of `[T^3_2, T^3_3]` in the six local inputs (see [`LocalDisplacement`]).
type Coefficients = [[f64; 6]; 2];

/// Index of `(k, l)`, `k <= l`, in the packed upper triangle of a symmetric 6 x 6 matrix.
const PACK: [[usize; 6]; 6] = {
    let mut p = [[0; 6]; 6];
    let mut idx = 0;
    let mut k = 0;
    while k < 6 {
        let mut l = k;
        while l < 6 {
            p[k][l] = idx;
            p[l][k] = idx;
            idx += 1;
            l += 1;
        }
        k += 1;
    }
    p
};

/// The plane-strain curvilinear Navier operator by Q1 or Q2 finite elements on the
/// `n2 x n3` grid of the finite differences (same nodes, same dof numbering).
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
/// finite differences. By linearity `T^i_j = sum_k u_k C_k^i_j` and
/// `nabla_i w^j = sum_l w_l D_l^i_j` in the six local inputs
/// `u = [v^2, v^3, d_2 v^2, d_2 v^3, d_3 v^2, d_3 v^3]`, so the integrand is `u^T K_q w` with
/// `K_q[k][l] = sqrt(g) sum_ij C_k^i_j D_l^i_j`, a symmetric 6 x 6 matrix cached at every
/// quadrature point (packed upper triangle, times the quadrature weight and `det J`): the
/// geometry is evaluated once per discretisation and reused by every refill (Newton steps,
/// sweeps). Element matrices are computed in parallel (rayon) in batches and scattered
/// sequentially in element order, so the values are bitwise reproducible.
///
/// Dirichlet conditions are imposed strongly and symmetrically: the row and column of a
/// prescribed dof are removed from the pattern (except the diagonal), the column's
/// contribution `K_rc g_c` moves to the right-hand side, and the row becomes
/// `K_dd v_d = K_dd g_d` with the assembled diagonal `K_dd`. The matrix is symmetric
/// (bitwise: element matrices are symmetrised) and, with enough Dirichlet conditions to stop
/// the rigid motions, positive definite, so [`capstan_solvers::SparseCholesky`] applies; LU
/// works too. Corner rules are those of [`crate::FiniteDifferenceNavier`] (a displacement on
/// either side wins; pinned dofs first).
///
/// # Contact rows
/// [`ContactNode::traction_weight`] is the lumped boundary weight
/// `sqrt(g) sqrt(g^33) int N_i dx2` at the node (row sums of the boundary mass matrix:
/// trapezoid for Q1, Simpson's `1/3, 4/3` pattern for Q2), so a nodal friction traction
/// enters as in the finite differences. [`ContactNode::normal_stress`] and
/// [`ContactNode::shear_stress`] recover `T^3_3`, `T^3_2` at the node from the nodal values
/// with second-order differences (central in `x2`, one-sided `(-3, 4, -1)/(2 dx3)` in `x3`;
/// for Q2 the `x3` rule is the element's own derivative at its face). The recovery is second
/// order for both elements (the Q2 displacement is third order in L2, its gradient second
/// order), and uses the same stencil as the finite differences, so both paths feed the
/// friction law the same kind of data.
///
/// With [`VolumetricIntegration::Reduced`] the normal stress splits (mixed components,
/// `T^i_j = lambda delta^i_j div v + 2 mu M^i_j`, `M = g^-1 E`):
/// ```text
/// T^3_3 = lambda div_h v (node) + 2 mu M^3_3 (node)        T^3_2 = 2 mu M^3_2 (node)
/// ```
/// The shear parts keep the pointwise recovery above; `div_h` is the divergence SRI controls,
/// the reduced-point values of the boundary elements extrapolated to the node and averaged
/// over the elements sharing it:
/// ```text
/// div_h v (node) = (1 / #E) sum_(e in E(node)) sum_(r, s) l_r(xi_node) l_s(eta_node) div v(xi_r, eta_s)
/// ```
/// with the curvilinear `div v = nabla_i v^i` of the stiffness at the reduced points and
/// `l_r` the Lagrange basis of degree `k - 1` through them: Q1 `l_0 = 1` (the element-centre
/// value); Q2 `l_(0,1)(s) = (1 -+ sqrt(3) s) / 2`, so `(1 +- sqrt(3)) / 2` on the contact edge
/// `eta = -1` and at the end nodes of an element, `(1/2, 1/2)` at its mid node. The
/// extrapolation is exact for a divergence of degree `k - 1`. The pointwise `lambda div v`
/// carries the unpenalised checkerboard of SRI amplified by `lambda / mu` (node-to-node
/// oscillation of `T^3_3` 18-19 times its mean on the paper's contact case, errors growing
/// like `1 / (1 - 2 nu)` on the Lamé cylinder); `div_h` converges uniformly in `nu`.
/// [`Discretisation::fields`] reports the stress `T^ij = lambda g^ij div_h v + 2 mu E^ij` the
/// same way at every node (the strain `E_ij` stays the pointwise recovery), so its `T^33 g_33`
/// on `x3 = 0` is the contact row's `T^3_3`. With the full rule nothing changes.
///
/// # Errors
/// See [`FiniteElementNavier::new`].
///
/// # Example
/// ```
/// use capstan_elasticity::{BoundaryConditions, Component, Discretisation, Grid, Material};
/// use capstan_elasticity::finite_element::{ElementOrder, FiniteElementNavier};
/// use capstan_geometry::{EllipticalPrism, ShellChart};
/// use capstan_solvers::SparseCholesky;
/// let chart = ShellChart::new(EllipticalPrism::new(2.0, 2.0).unwrap());
/// let grid = Grid::new([-1.5707963, 1.5707963], 1.0, 25, 5, false).unwrap();
/// let bc = BoundaryConditions::paper_clamped(1.0, 1.0);
/// let m = Material::new(1e3, 0.25).unwrap();
/// let op = FiniteElementNavier::new(chart, m, grid, bc, None, ElementOrder::Q2).unwrap();
/// let v = op.solve(&mut SparseCholesky::default()).unwrap(); // symmetric positive definite
/// // equal end tensions: the tangential displacement is odd in x2
/// let (left, right) = (v[op.dof([0, 4], Component::X2)], v[op.dof([24, 4], Component::X2)]);
/// assert!(left < 0.0 && (left + right).abs() < 1e-10);
/// ```
pub struct FiniteElementNavier<G> {
    chart: G,
    material: Material,
    grid: Grid,
    boundary: BoundaryConditions,
    order: ElementOrder,
    /// Elements in `x2` and `x3`.
    elements: [usize; 2],
    /// `[N_a, d_2 N_a, d_3 N_a]` at reference quadrature point `q`, index `q nen + a`.
    shape: Vec<[f64; 3]>,
    /// Packed `K_q` times weight and `det J`, index `e nq + q` (the shear part only when the
    /// volumetric part is integrated separately).
    stiffness: Vec<[f64; 21]>,
    /// How the volumetric part is integrated.
    volumetric: VolumetricIntegration,
    /// Reduced rule: `[N_a, d_2 N_a, d_3 N_a]` at reduced point `r`, index `r nen + a`.
    reduced_shape: Vec<[f64; 3]>,
    /// Reduced rule: `[lambda sqrt(g) w det J, tr M_0, ..., tr M_5]`, index `e nr + r`.
    reduced_divergence: Vec<[f64; 7]>,
    /// Prescribed value of each dof.
    dirichlet: Vec<Option<f64>>,
    /// Right-hand side from the body force and the natural boundary data.
    load: Vec<f64>,
    /// The compressed-column pattern of the system (`entries()` is its slots in order).
    pattern: SparsityPattern,
    /// Slot in `pattern` of each local entry `(I, J)` of each element, `NO_SLOT` if none.
    local_slots: Vec<u32>,
    /// Slot in `pattern` of the diagonal of each dof.
    diagonal_slots: Vec<usize>,
    /// `[T^3_2, T^3_3]` coefficients and `[sqrt(g), sqrt(g^33), sqrt(g_22)]` on `x3 = 0`
    /// (with [`VolumetricIntegration::Reduced`], of `T^3_3` only the shear part `2 mu M^3_3`).
    contact: Vec<(Coefficients, [f64; 3])>,
}

impl<G> core::fmt::Debug for FiniteElementNavier<G> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("FiniteElementNavier")
            .field("order", &self.order)
            .field("material", &self.material)
            .field("grid", &self.grid)
            .field("boundary", &self.boundary)
            .finish_non_exhaustive()
    }
}

fn check_plane_strain(p: &ShellPoint<f64>, at: [f64; 3]) -> Result<(), ElasticityError> {
    let gscale = 1.0
        + p.metric
            .iter()
            .flatten()
            .fold(0.0f64, |m, x| m.max(x.abs()));
    if p.metric[0][1].abs() > PLANE_STRAIN_TOLERANCE * gscale
        || p.metric[0][2].abs() > PLANE_STRAIN_TOLERANCE * gscale
    {
        return Err(ElasticityError::NotPlaneStrain {
            what: "g_12 or g_13 is not zero",
            at,
        });
    }
    let cscale = 1.0
        + p.christoffel
            .iter()
            .flatten()
            .flatten()
            .fold(0.0f64, |m, x| m.max(x.abs()));
    let index_one = (0..3).any(|i| {
        (0..3).any(|j| {
            p.christoffel[0][i][j].abs() > PLANE_STRAIN_TOLERANCE * cscale
                || p.christoffel[i][0][j].abs() > PLANE_STRAIN_TOLERANCE * cscale
        })
    });
    if index_one {
        return Err(ElasticityError::NotPlaneStrain {
            what: "a Christoffel symbol with index 1 is not zero",
            at,
        });
    }
    Ok(())
}

/// The symmetric 6 x 6 matrix `K_q[k][l] = sqrt(g) sum_ij C_k^i_j D_l^i_j`, packed, times
/// `scale`.
///
/// # Math
/// `C_k^i_j = T^i_j(u_k)` and `D_l^i_j = nabla_i w^j` for the unit inputs `u_k`, `w_l`; as
/// `T^ij` is symmetric, `T^i_j nabla_i w^j = T^ij E_ij(w)`, the energy form:
/// ```text
/// N_k[i][n] = nabla_i v^n      Gamma^n_{i m} for the value v^m (k = m - 1),
///                              delta_i^p delta^n_c for d_p v^c (k = 2 (p - 1) + (c - 1))
/// E_k[i][l] = (N_k[i][n] g_nl + N_k[l][n] g_ni) / 2       covariant strain
/// M_k = g^-1 E_k                                           mixed strain E^i_l
/// K[k][l] = sqrt(g) (lambda tr M_k tr M_l + 2 mu tr(M_k M_l))
/// ```
/// symmetric by construction; equal to the contraction with the mixed stress coefficients of
/// [`mixed_stress_coefficients`] to round-off (tested), at a fifth of the cost.
fn point_stiffness(p: &ShellPoint<f64>, material: &Material, scale: f64) -> [f64; 21] {
    point_energy(p, material.lambda(), material.mu(), scale)
}

/// [`point_stiffness`] with given Lamé constants: `lambda = 0` leaves the shear part
/// `2 mu sqrt(g) tr(M_k M_l)` of selective reduced integration.
#[allow(clippy::needless_range_loop)] // index loops mirror the tensor formulas
fn point_energy(p: &ShellPoint<f64>, lambda: f64, mu: f64, scale: f64) -> [f64; 21] {
    let mixed = mixed_strains(p);
    let trace = mixed.map(|m| m[0][0] + m[1][1] + m[2][2]);
    let two_mu = 2.0 * mu;
    let w = p.sqrt_g * scale;
    let mut packed = [0.0; 21];
    for a in 0..6 {
        for b in a..6 {
            let mut s = 0.0;
            for i in 0..3 {
                for l in 0..3 {
                    s += mixed[a][i][l] * mixed[b][l][i];
                }
            }
            packed[PACK[a][b]] = (lambda * trace[a] * trace[b] + two_mu * s) * w;
        }
    }
    packed
}

/// The traces `tr M_k = nabla_i v^i` of the mixed strains of the six unit inputs: the
/// divergence is `sum_k u_k tr M_k` (`tr M_k = Gamma^i_im` for the value `v^m`, `delta_pc`
/// for `d_p v^c`).
fn divergence_coefficients(p: &ShellPoint<f64>) -> [f64; 6] {
    mixed_strains(p).map(|m| m[0][0] + m[1][1] + m[2][2])
}

/// The mixed strains `M_k = g^-1 E_k` of the six unit inputs (see [`point_stiffness`]).
#[allow(clippy::needless_range_loop)] // index loops mirror the tensor formulas
fn mixed_strains(p: &ShellPoint<f64>) -> [[[f64; 3]; 3]; 6] {
    let (g, gi, gamma) = (&p.metric, &p.inverse_metric, &p.christoffel);
    let mut mixed = [[[0.0f64; 3]; 3]; 6];
    for (k, mk) in mixed.iter_mut().enumerate() {
        // h[i][l] = N_k[i][n] g_nl
        let mut h = [[0.0f64; 3]; 3];
        if k < 2 {
            let m = k + 1;
            for i in 0..3 {
                for l in 0..3 {
                    h[i][l] = gamma[0][i][m] * g[0][l]
                        + gamma[1][i][m] * g[1][l]
                        + gamma[2][i][m] * g[2][l];
                }
            }
        } else {
            let (dir, comp) = (k / 2, k % 2 + 1);
            h[dir] = g[comp];
        }
        let mut e = [[0.0f64; 3]; 3];
        for i in 0..3 {
            for l in 0..3 {
                e[i][l] = 0.5 * (h[i][l] + h[l][i]);
            }
        }
        for i in 0..3 {
            for l in 0..3 {
                mk[i][l] = gi[i][0] * e[0][l] + gi[i][1] * e[1][l] + gi[i][2] * e[2][l];
            }
        }
    }
    mixed
}

/// Second-order nodal difference weights `(index, weight)` along a grid direction.
fn difference_stencil(i: usize, n: usize, h: f64, periodic: bool) -> [(usize, f64); 3] {
    let w = 0.5 / h;
    if periodic {
        [((i + n - 1) % n, -w), ((i + 1) % n, w), (i, 0.0)]
    } else if i == 0 {
        [(0, -3.0 * w), (1, 4.0 * w), (2, -w)]
    } else if i == n - 1 {
        [(n - 1, 3.0 * w), (n - 2, -4.0 * w), (n - 3, w)]
    } else {
        [(i - 1, -w), (i + 1, w), (i, 0.0)]
    }
}

/// The Lagrange basis `l_r(s) = prod_(q != r) (s - x_q) / (x_r - x_q)` through `points`, at
/// `s` (one point: the constant `1`).
fn lagrange_weights(points: &[f64], s: f64) -> Vec<f64> {
    points
        .iter()
        .enumerate()
        .map(|(r, &xr)| {
            points
                .iter()
                .enumerate()
                .filter(|&(q, _)| q != r)
                .map(|(_, &xq)| (s - xq) / (xr - xq))
                .product()
        })
        .collect()
}

/// Errors of a discrete displacement against an exact one.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct DisplacementErrors {
    /// Max over the nodes of `|U_h - U|` (Cartesian displacement error).
    pub max: f64,
    /// RMS over the parameter rectangle, `sqrt(int |U_h - U|^2 dx2 dx3 / area)` (the
    /// verification norm of the finite differences, integrated exactly instead of by the
    /// nodal trapezoid rule).
    pub rms: f64,
    /// Physical L2 norm `sqrt(int |U_h - U|^2 dA)` (per unit `x1`, `dA = sqrt(g) dx2 dx3`).
    pub l2: f64,
    /// `sqrt(int |U|^2 dA)`, for relative errors.
    pub l2_exact: f64,
}

impl<G: ShellGeometry + Sync> FiniteElementNavier<G> {
    /// Builds the discretisation: caches the geometry at the quadrature points, the load
    /// vector and the sparsity pattern.
    ///
    /// # Errors
    /// [`ElasticityError::InvalidParameter`] if the grid is not a whole number of elements
    /// (Q2: odd `n2` and `n3`, even `n2` when periodic); [`ElasticityError::InconsistentBoundary`]
    /// if periodicity of grid and conditions differ or a pinned node is outside the grid;
    /// [`ElasticityError::Geometry`] where the chart cannot be evaluated;
    /// [`ElasticityError::NotPlaneStrain`] for a chart that is not `x1`-invariant;
    /// [`ElasticityError::NonFinite`] for non-finite boundary data or body force.
    pub fn new(
        chart: G,
        material: Material,
        grid: Grid,
        boundary: BoundaryConditions,
        body_force: Option<BodyForce>,
        order: ElementOrder,
    ) -> Result<Self, ElasticityError> {
        Self::with_volumetric(
            chart,
            material,
            grid,
            boundary,
            body_force,
            order,
            VolumetricIntegration::Full,
        )
    }

    /// As [`FiniteElementNavier::new`], with the volumetric part of the stiffness integrated
    /// as `volumetric` says ([`VolumetricIntegration::Reduced`]: selective reduced
    /// integration, the remedy for volumetric locking as `nu -> 1/2`).
    ///
    /// # Errors
    /// See [`FiniteElementNavier::new`].
    ///
    /// # Example
    /// ```
    /// use capstan_elasticity::finite_element::{
    ///     ElementOrder, FiniteElementNavier, VolumetricIntegration, lame_parts,
    /// };
    /// use capstan_elasticity::samples::{LameCylinder, ManufacturedField};
    /// use capstan_elasticity::verification::GridLevel;
    /// use capstan_elasticity::{Discretisation, Material};
    /// use capstan_solvers::SparseCholesky;
    /// // the Lamé cylinder at nu = 0.4999: Q1 locks, Q1 with SRI does not
    /// let lame = LameCylinder { material: Material::new(10.0, 0.4999).unwrap(), ..Default::default() };
    /// let exact = lame.field();
    /// let error = |volumetric| {
    ///     let p = lame_parts(&lame, GridLevel { n2: 32, n3: 9 }).unwrap();
    ///     let op = FiniteElementNavier::with_volumetric(
    ///         p.chart, p.material, p.grid, p.boundary, p.body_force, ElementOrder::Q1, volumetric,
    ///     )
    ///     .unwrap();
    ///     let v = op.solve(&mut SparseCholesky::default()).unwrap();
    ///     let e = op.displacement_errors(&v, &|x| exact.displacement(x).value).unwrap();
    ///     e.l2 / e.l2_exact
    /// };
    /// let (full, reduced) = (error(VolumetricIntegration::Full), error(VolumetricIntegration::Reduced));
    /// assert!(reduced < 1e-2 && full > 10.0 * reduced, "full {full}, reduced {reduced}");
    /// ```
    pub fn with_volumetric(
        chart: G,
        material: Material,
        grid: Grid,
        boundary: BoundaryConditions,
        body_force: Option<BodyForce>,
        order: ElementOrder,
        volumetric: VolumetricIntegration,
    ) -> Result<Self, ElasticityError> {
        if grid.is_periodic() != boundary.is_periodic() {
            return Err(ElasticityError::InconsistentBoundary {
                what: "the grid and the x2 conditions must both be periodic or both not",
            });
        }
        if boundary
            .pinned
            .iter()
            .any(|p| p.node[0] >= grid.n2() || p.node[1] >= grid.n3())
        {
            return Err(ElasticityError::InconsistentBoundary {
                what: "a pinned node is outside the grid",
            });
        }
        order.check_nodes("grid.n2", grid.n2(), grid.is_periodic())?;
        order.check_nodes("grid.n3", grid.n3(), false)?;
        let k = order.degree();
        let elements = [
            if grid.is_periodic() {
                grid.n2() / k
            } else {
                (grid.n2() - 1) / k
            },
            (grid.n3() - 1) / k,
        ];
        let mut op = Self {
            chart,
            material,
            grid,
            boundary,
            order,
            elements,
            shape: vec![],
            stiffness: vec![],
            volumetric,
            reduced_shape: vec![],
            reduced_divergence: vec![],
            dirichlet: vec![],
            load: vec![],
            pattern: SparsityPattern::from_compressed_columns(0, 0, vec![0], vec![])
                .expect("the empty pattern"),
            local_slots: vec![],
            diagonal_slots: vec![],
            contact: vec![],
        };
        op.dirichlet = (0..op.dof_count())
            .map(|d| op.dirichlet_value(grid.node(d / 2), Component::ALL[d % 2]))
            .collect::<Result<_, _>>()?;
        op.shape = op.reference_shape();
        op.cache_geometry(body_force.as_ref())?;
        if volumetric == VolumetricIntegration::Reduced {
            op.cache_reduced_divergence()?;
        }
        op.add_boundary_loads()?;
        op.contact = (0..grid.n2())
            .map(|i| {
                let p = op.point(grid.x2(i), 0.0)?;
                let c = mixed_stress_coefficients(&p, &op.material);
                let mut coef: Coefficients =
                    core::array::from_fn(|e| core::array::from_fn(|q| c[q][2][e + 1]));
                if volumetric == VolumetricIntegration::Reduced {
                    // T^3_3 = lambda tr M + 2 mu M^3_3: only the shear part is pointwise, the
                    // divergence comes from the reduced points (see `contact_rows`)
                    let two_mu = 2.0 * op.material.mu();
                    coef[1] = mixed_strains(&p).map(|m| two_mu * m[2][2]);
                }
                Ok((
                    coef,
                    [
                        p.sqrt_g,
                        p.inverse_metric[2][2].sqrt(),
                        p.metric[1][1].sqrt(),
                    ],
                ))
            })
            .collect::<Result<_, ElasticityError>>()?;
        op.build_pattern();
        Ok(op)
    }

    /// The element order.
    pub fn order(&self) -> ElementOrder {
        self.order
    }

    /// How the volumetric part of the stiffness is integrated.
    pub fn volumetric(&self) -> VolumetricIntegration {
        self.volumetric
    }

    /// The material.
    pub fn material(&self) -> &Material {
        &self.material
    }

    /// The boundary conditions.
    pub fn boundary(&self) -> &BoundaryConditions {
        &self.boundary
    }

    /// The chart.
    pub fn chart(&self) -> &G {
        &self.chart
    }

    /// Number of elements `[in x2, in x3]`.
    pub fn element_counts(&self) -> [usize; 2] {
        self.elements
    }

    fn point(&self, x2: f64, x3: f64) -> Result<ShellPoint<f64>, ElasticityError> {
        let at = [0.0, x2, x3];
        let p = self.chart.shell_point(at)?;
        check_plane_strain(&p, at)?;
        Ok(p)
    }

    fn nodes_per_element(&self) -> usize {
        self.order.nodes_per_element()
    }

    fn quadrature_points(&self) -> usize {
        self.order.nodes_per_direction().pow(2)
    }

    /// Element lengths `[L2, L3]` in parameter space.
    fn element_size(&self) -> [f64; 2] {
        let k = self.order.degree() as f64;
        [k * self.grid.dx2(), k * self.grid.dx3()]
    }

    /// Node numbers of element `e`, local node `a = a2 (k + 1) + a3`.
    fn element_nodes(&self, e: usize, out: &mut [usize; 9]) {
        let (k, np) = (self.order.degree(), self.order.nodes_per_direction());
        let (e2, e3) = (e / self.elements[1], e % self.elements[1]);
        let n2 = self.grid.n2();
        for a2 in 0..np {
            let i2 = (k * e2 + a2) % n2; // wraps only on a periodic grid
            for a3 in 0..np {
                out[a2 * np + a3] = self.grid.node_index([i2, k * e3 + a3]);
            }
        }
    }

    /// Lower-left corner `(x2, x3)` of element `e`.
    fn element_origin(&self, e: usize) -> [f64; 2] {
        let k = self.order.degree();
        let (e2, e3) = (e / self.elements[1], e % self.elements[1]);
        [self.grid.x2(k * e2), self.grid.x3(k * e3)]
    }

    fn reference_shape(&self) -> Vec<[f64; 3]> {
        self.shape_table(&self.order.gauss_1d().0)
    }

    /// `[N_a, d_2 N_a, d_3 N_a]` at the tensor points `gp x gp`, index `q nen + a`.
    fn shape_table(&self, gp: &[f64]) -> Vec<[f64; 3]> {
        let [l2, l3] = self.element_size();
        let np = self.order.nodes_per_direction();
        let mut out = Vec::with_capacity(gp.len() * gp.len() * self.nodes_per_element());
        for &xi in gp {
            for &eta in gp {
                let (n2, d2) = self.order.shape_1d(xi);
                let (n3, d3) = self.order.shape_1d(eta);
                for a2 in 0..np {
                    for a3 in 0..np {
                        out.push([
                            n2[a2] * n3[a3],
                            d2[a2] * n3[a3] * 2.0 / l2,
                            n2[a2] * d3[a3] * 2.0 / l3,
                        ]);
                    }
                }
            }
        }
        out
    }

    /// `x3` of every Gauss point `gp` (reference abscissae) of a column of elements, element
    /// by element: index `e3 nqd + j`.
    fn column_heights(&self, gp: &[f64]) -> Vec<f64> {
        let [_, l3] = self.element_size();
        let k = self.order.degree();
        (0..self.elements[1])
            .flat_map(|e3| {
                let y0 = self.grid.x3(k * e3);
                gp.iter().map(move |&eta| y0 + 0.5 * (eta + 1.0) * l3)
            })
            .collect()
    }

    /// Walks the tensor Gauss points `gp x gp` of the column of elements `e2`, one chart column
    /// ([`ShellGeometry::shell_column`]) per `x2` abscissa: `visit(i, e3, j, point, [x2, x3])`
    /// with `i`, `j` the point's indices along `x2`, `x3` inside element `(e2, e3)`; the point
    /// is checked for the plane-strain reduction first.
    fn walk_column(
        &self,
        e2: usize,
        gp: &[f64],
        heights: &[f64],
        mut visit: impl FnMut(
            usize,
            usize,
            usize,
            &ShellPoint<f64>,
            [f64; 2],
        ) -> Result<(), ElasticityError>,
    ) -> Result<(), ElasticityError> {
        let [l2, _] = self.element_size();
        let x0 = self.grid.x2(self.order.degree() * e2);
        let nqd = gp.len();
        let mut points = Vec::with_capacity(heights.len());
        for (i, &xi) in gp.iter().enumerate() {
            let x2 = x0 + 0.5 * (xi + 1.0) * l2;
            points.clear();
            self.chart.shell_column([0.0, x2], heights, &mut points)?;
            for (idx, (p, &x3)) in points.iter().zip(heights).enumerate() {
                check_plane_strain(p, [0.0, x2, x3])?;
                visit(i, idx / nqd, idx % nqd, p, [x2, x3])?;
            }
        }
        Ok(())
    }

    /// Evaluates the geometry at every quadrature point and adds the body force: one column
    /// of points ([`ShellGeometry::shell_column`], one surface jet) per `x2` abscissa of each
    /// column of elements, the columns in parallel.
    fn cache_geometry(&mut self, body_force: Option<&BodyForce>) -> Result<(), ElasticityError> {
        let (gp, gw) = self.order.gauss_1d();
        let [l2, l3] = self.element_size();
        let det = 0.25 * l2 * l3;
        let (nq, nen) = (self.quadrature_points(), self.nodes_per_element());
        let [ne2, ne3] = self.elements;
        let nqd = gp.len();
        let heights = self.column_heights(&gp);
        let mut stiffness = vec![[0.0; 21]; ne2 * ne3 * nq];
        let mut local_loads = vec![
            0.0;
            if body_force.is_some() {
                ne2 * ne3 * 2 * nen
            } else {
                0
            }
        ];
        let this = &*self;
        // one column of elements: stiffness `kq` (ne3 nq) and loads (ne3 2 nen, if any)
        let compute = |e2: usize,
                       kq: &mut [[f64; 21]],
                       mut load: Option<&mut [f64]>|
         -> Result<(), ElasticityError> {
            this.walk_column(e2, &gp, &heights, |i, e3, j, p, [x2, x3]| {
                let q = i * nqd + j;
                let w = gw[i] * gw[j] * det;
                kq[e3 * nq + q] = match this.volumetric {
                    VolumetricIntegration::Full => point_stiffness(p, &this.material, w),
                    // the shear part only: the volumetric part is at the reduced points
                    VolumetricIntegration::Reduced => point_energy(p, 0.0, this.material.mu(), w),
                };
                if let (Some(f), Some(load)) = (body_force, load.as_deref_mut()) {
                    let x = [x2, x3];
                    let fx = f(x);
                    if !(fx[0].is_finite() && fx[1].is_finite()) {
                        return Err(ElasticityError::NonFinite {
                            what: "body force",
                            at: x,
                        });
                    }
                    let load = &mut load[e3 * 2 * nen..(e3 + 1) * 2 * nen];
                    for a in 0..nen {
                        let n = this.shape[q * nen + a][0] * p.sqrt_g * w;
                        load[2 * a] += n * fx[0];
                        load[2 * a + 1] += n * fx[1];
                    }
                }
                Ok(())
            })
        };
        if body_force.is_some() {
            stiffness
                .par_chunks_mut(ne3 * nq)
                .zip(local_loads.par_chunks_mut(ne3 * 2 * nen))
                .enumerate()
                .try_for_each(|(e2, (kq, load))| compute(e2, kq, Some(load)))?;
        } else {
            stiffness
                .par_chunks_mut(ne3 * nq)
                .enumerate()
                .try_for_each(|(e2, kq)| compute(e2, kq, None))?;
        }
        self.stiffness = stiffness;
        self.load = vec![0.0; self.dof_count()];
        if body_force.is_some() {
            let mut nodes = [0; 9];
            for e in 0..ne2 * ne3 {
                self.element_nodes(e, &mut nodes);
                for a in 0..nen {
                    for c in 0..2 {
                        self.load[2 * nodes[a] + c] += local_loads[e * 2 * nen + 2 * a + c];
                    }
                }
            }
        }
        Ok(())
    }

    /// The volumetric part at the reduced `k x k` Gauss points of every element (selective
    /// reduced integration): shape functions, `lambda sqrt(g) w det J` and the divergence
    /// coefficients `tr M_k`, one column of points per `x2` abscissa as in
    /// [`Self::cache_geometry`].
    fn cache_reduced_divergence(&mut self) -> Result<(), ElasticityError> {
        let (gp, gw) = gauss_rule(self.order.degree());
        self.reduced_shape = self.shape_table(&gp);
        let [l2, l3] = self.element_size();
        let det = 0.25 * l2 * l3;
        let [ne2, ne3] = self.elements;
        let nqd = gp.len();
        let nr = nqd * nqd;
        let heights = self.column_heights(&gp);
        let lambda = self.material.lambda();
        let mut out = vec![[0.0; 7]; ne2 * ne3 * nr];
        let this = &*self;
        out.par_chunks_mut(ne3 * nr)
            .enumerate()
            .try_for_each(|(e2, column)| {
                this.walk_column(e2, &gp, &heights, |i, e3, j, p, _| {
                    let t = divergence_coefficients(p);
                    let c = lambda * p.sqrt_g * gw[i] * gw[j] * det;
                    column[e3 * nr + i * nqd + j] = [c, t[0], t[1], t[2], t[3], t[4], t[5]];
                    Ok(())
                })
            })?;
        self.reduced_divergence = out;
        Ok(())
    }

    /// Adds `int phi_j N_a ds` over every side with a natural condition (Gauss rule of the
    /// element along each boundary edge).
    fn add_boundary_loads(&mut self) -> Result<(), ElasticityError> {
        let (gp, gw) = self.order.gauss_1d();
        let (k, np) = (self.order.degree(), self.order.nodes_per_direction());
        let [l2, l3] = self.element_size();
        let (n2, n3) = (self.grid.n2(), self.grid.n3());
        for side in Side::ALL {
            let Some(cond) = self.boundary.side(side).cloned() else {
                continue; // periodic x2
            };
            let along_x2 = side.normal_index() == 2;
            let (count, length) = if along_x2 {
                (self.elements[0], l2)
            } else {
                (self.elements[1], l3)
            };
            for e in 0..count {
                for (&xi, &w) in gp.iter().zip(&gw) {
                    let (shape, _) = self.order.shape_1d(xi);
                    let (x, nodes): ([f64; 2], Vec<[usize; 2]>) = if along_x2 {
                        let i3 = if side == Side::X3Min { 0 } else { n3 - 1 };
                        let x2 = self.grid.x2(k * e) + 0.5 * (xi + 1.0) * length;
                        (
                            [x2, self.grid.x3(i3)],
                            (0..np).map(|a| [(k * e + a) % n2, i3]).collect(),
                        )
                    } else {
                        let i2 = if side == Side::X2Min { 0 } else { n2 - 1 };
                        let x3 = self.grid.x3(k * e) + 0.5 * (xi + 1.0) * length;
                        (
                            [self.grid.x2(i2), x3],
                            (0..np).map(|a| [i2, k * e + a]).collect(),
                        )
                    };
                    let s = if along_x2 { x[0] } else { x[1] };
                    let p = self.point(x[0], x[1])?;
                    let a = side.normal_index();
                    for c in Component::ALL {
                        let flux = match cond.component(c) {
                            ComponentCondition::Displacement(_) => continue,
                            ComponentCondition::Traction(f) => {
                                p.sqrt_g * p.inverse_metric[a][a].sqrt() * f.eval(s)
                            }
                            ComponentCondition::Stress(f) => side.sign() * p.sqrt_g * f.eval(s),
                        };
                        if !flux.is_finite() {
                            return Err(ElasticityError::NonFinite {
                                what: "boundary traction",
                                at: x,
                            });
                        }
                        for (node, n) in nodes.iter().zip(shape) {
                            let d = 2 * self.grid.node_index(*node) + c.index();
                            self.load[d] += n * flux * w * 0.5 * length;
                        }
                    }
                }
            }
        }
        Ok(())
    }

    /// The value prescribed at a node and component, if any ([`BoundaryConditions::dirichlet_value`]).
    fn dirichlet_value(
        &self,
        node: [usize; 2],
        c: Component,
    ) -> Result<Option<f64>, ElasticityError> {
        self.boundary.dirichlet_value(&self.grid, node, c)
    }

    /// Elements containing grid index `i` along one direction.
    fn elements_along(&self, i: usize, count: usize, periodic: bool) -> Vec<usize> {
        let k = self.order.degree();
        if !i.is_multiple_of(k) {
            return vec![i / k];
        }
        let mut out = Vec::with_capacity(2);
        if periodic {
            out.push((i / k) % count);
            out.push((i / k + count - 1) % count);
        } else {
            if i / k < count {
                out.push(i / k);
            }
            if i > 0 {
                out.push(i / k - 1);
            }
        }
        out.sort_unstable();
        out.dedup();
        out
    }

    /// The gradient-recovery stencil at a node: `(node, [value, d_2, d_3])` weights.
    fn node_stencil(&self, [i, j]: [usize; 2]) -> Vec<([usize; 2], [f64; 3])> {
        let mut out = Vec::with_capacity(7);
        out.push(([i, j], [1.0, 0.0, 0.0]));
        let g = &self.grid;
        for (ii, w) in difference_stencil(i, g.n2(), g.dx2(), g.is_periodic()) {
            out.push(([ii, j], [0.0, w, 0.0]));
        }
        for (jj, w) in difference_stencil(j, g.n3(), g.dx3(), false) {
            out.push(([i, jj], [0.0, 0.0, w]));
        }
        out
    }

    /// The contact rows `[T^3_2, T^3_3]` at node `(i, 0)`: the recovery stencil applied to the
    /// pointwise coefficients; with [`VolumetricIntegration::Reduced`], `T^3_3` adds
    /// `lambda` times the reduced-point divergence of [`Self::reduced_divergence_terms`] to
    /// its pointwise shear part.
    fn contact_rows(&self, i: usize) -> [SparseRow; 2] {
        let (coef, _) = &self.contact[i];
        let st = self.node_stencil([i, 0]);
        [0, 1].map(|e| {
            let mut terms = Vec::with_capacity(2 * st.len());
            for (node, w) in &st {
                for c in 0..2 {
                    let a = coef[e][c] * w[0] + coef[e][2 + c] * w[1] + coef[e][4 + c] * w[2];
                    terms.push((self.dof(*node, Component::ALL[c]), a));
                }
            }
            if e == 1 && self.volumetric == VolumetricIntegration::Reduced {
                let lambda = self.material.lambda();
                terms.extend(
                    self.reduced_divergence_terms([i, 0])
                        .into_iter()
                        .map(|(d, w)| (d, lambda * w)),
                );
            }
            SparseRow::from_terms(&mut terms)
        })
    }

    /// The divergence at a node recovered from the reduced points of the elements around it
    /// (selective reduced integration only): `(dof, weight)` terms of `v -> div_h v (node)`,
    /// duplicates allowed. Its columns are those of the elements around the node, already in
    /// the pattern of the node's rows.
    ///
    /// # Math
    /// SRI controls the divergence only at the `k x k` reduced Gauss points `(xi_r, eta_s)` of
    /// each element (the pressure `lambda div v` of the equivalent mixed element: Q1-P0,
    /// Q2-Q1 discontinuous); between them, and at the nodes, the pointwise `div v` of the
    /// displacement carries the spurious (checkerboard) modes that `lambda` no longer
    /// penalises. The nodal value is the element's reduced-point field extrapolated with the
    /// tensor Lagrange interpolant of degree `k - 1` through those points,
    /// ```text
    /// div_e(xi, eta) = sum_(r, s) l_r(xi) l_s(eta) div v(xi_r, eta_s)
    /// div v(xi_r, eta_s) = sum_(a, c) v^c_a (t_c N_a + t_(2+c) d_2 N_a + t_(4+c) d_3 N_a)
    /// ```
    /// (`t_k = tr M_k` at the point, the curvilinear `nabla_i v^i = d_i v^i + Gamma^i_im v^m`
    /// of the stiffness), averaged over the elements containing the node:
    /// ```text
    /// div_h(node) = (1 / #E(node)) sum_(e in E(node)) div_e(xi_node, eta_node)
    /// ```
    /// Q1: `l_0 = 1`, the element-centre value, averaged over the two elements on either side
    /// of the node in each direction; at a boundary node (one element that way) the centre
    /// values of the two nearest element rows extrapolated linearly, `1.5 c_near - 0.5 c_far`
    /// (centres at `dx/2` and `3 dx/2`): second order where the divergence varies normal to the
    /// boundary, as on the contact surface (ellipse manufactured solution: order 1.78, errors
    /// 15.7x smaller than the first-row centre value at `dx3 = 1/64`). Q2: `l_0(s) = (1 - sqrt(3) s) / 2`, `l_1(s) = (1 + sqrt(3) s) / 2`
    /// through `-+1/sqrt(3)`, so on the bottom edge `eta = -1` the weights are
    /// `(1 +- sqrt(3)) / 2` and at the node abscissa `xi in {-1, 0, 1}` they are
    /// `((1 +- sqrt(3)) / 2, (1 -+ sqrt(3)) / 2)`, `(1/2, 1/2)`. Both reproduce a divergence of
    /// degree `k - 1` exactly, so the recovered pressure is `O(h^k)` where the reduced-point
    /// pressure is.
    ///
    /// # Panics
    /// If the volumetric part is integrated with the full rule (no reduced points cached).
    #[track_caller]
    fn reduced_divergence_terms(&self, [i2, i3]: [usize; 2]) -> Vec<(usize, f64)> {
        assert_eq!(
            self.volumetric,
            VolumetricIntegration::Reduced,
            "reduced points are cached with selective reduced integration only"
        );
        let g = &self.grid;
        let (k, nen) = (self.order.degree(), self.nodes_per_element());
        let (gp, _) = gauss_rule(k);
        let nr = k * k;
        let local = |a: usize| -1.0 + 2.0 * a as f64 / k as f64;
        // per direction: (element, weights of its reduced points along that direction)
        let direction = |i: usize, n: usize, count: usize, periodic: bool| {
            let along = self.elements_along(i, count, periodic);
            if k == 1 && !periodic && along.len() == 1 && count >= 2 {
                // Q1 at a boundary node: the centre values of the two nearest element rows,
                // extrapolated linearly (centres at dx/2 and 3 dx/2 from the node)
                let (near, far) = if i == 0 {
                    (0, 1)
                } else {
                    (count - 1, count - 2)
                };
                return vec![(near, vec![1.5]), (far, vec![-0.5])];
            }
            let share = 1.0 / along.len() as f64;
            along
                .into_iter()
                .map(|e| {
                    // local node number (k in the last element of a periodic grid at i = 0)
                    let l = lagrange_weights(&gp, local((i + n - k * e) % n));
                    (e, l.into_iter().map(|w| share * w).collect::<Vec<f64>>())
                })
                .collect::<Vec<_>>()
        };
        let along2 = direction(i2, g.n2(), self.elements[0], g.is_periodic());
        let along3 = direction(i3, g.n3(), self.elements[1], false);
        let mut terms = Vec::with_capacity(along2.len() * along3.len() * nr * 2 * nen);
        let mut nodes = [0; 9];
        for (e2, l2) in &along2 {
            for (e3, l3) in &along3 {
                let e = e2 * self.elements[1] + e3;
                self.element_nodes(e, &mut nodes);
                for (ri, w2) in l2.iter().enumerate() {
                    for (rj, w3) in l3.iter().enumerate() {
                        let r = ri * k + rj; // the order of `shape_table`
                        let w = w2 * w3;
                        let [_, t @ ..] = self.reduced_divergence[e * nr + r];
                        let phi = &self.reduced_shape[r * nen..(r + 1) * nen];
                        for (a, f) in phi.iter().enumerate() {
                            for c in 0..2 {
                                let d = t[c] * f[0] + t[2 + c] * f[1] + t[4 + c] * f[2];
                                terms.push((2 * nodes[a] + c, w * d));
                            }
                        }
                    }
                }
            }
        }
        terms
    }

    /// Builds the row-wise pattern and the slot of every local element entry.
    fn build_pattern(&mut self) {
        let g = self.grid;
        let n2 = g.n2();
        let ndof = self.dof_count();
        let nen = self.nodes_per_element();
        // contact extras: the columns of T^3_j in each free tangential row on x3 = 0
        let mut extras: Vec<Vec<usize>> = vec![vec![]; n2];
        for (i, extra) in extras.iter_mut().enumerate() {
            let d = self.dof([i, 0], Component::X2);
            if self.dirichlet[d].is_none() {
                let rows = self.contact_rows(i);
                extra.extend(rows.iter().flat_map(|r| r.columns.iter().copied()));
            }
        }
        let rows: Vec<Vec<usize>> = (0..g.node_count())
            .into_par_iter()
            .map(|node| {
                let [i2, i3] = g.node(node);
                let mut neighbours = Vec::with_capacity(25);
                for e2 in self.elements_along(i2, self.elements[0], g.is_periodic()) {
                    for e3 in self.elements_along(i3, self.elements[1], false) {
                        let mut nn = [0; 9];
                        self.element_nodes(e2 * self.elements[1] + e3, &mut nn);
                        neighbours.extend_from_slice(&nn[..nen]);
                    }
                }
                neighbours.sort_unstable();
                neighbours.dedup();
                let mut cols = Vec::with_capacity(2 * neighbours.len());
                for m in neighbours {
                    for c in 0..2 {
                        if self.dirichlet[2 * m + c].is_none() {
                            cols.push(2 * m + c);
                        }
                    }
                }
                cols
            })
            .collect();
        let mut row_ptr = Vec::with_capacity(ndof + 1);
        let mut columns = Vec::with_capacity(ndof * 20);
        row_ptr.push(0);
        for d in 0..ndof {
            let node = d / 2;
            if self.dirichlet[d].is_some() {
                columns.push(d);
            } else {
                let start = columns.len();
                columns.extend_from_slice(&rows[node]);
                let [i2, i3] = g.node(node);
                if i3 == 0 && d % 2 == 0 {
                    columns.extend_from_slice(&extras[i2]);
                }
                columns[start..].sort_unstable();
                let mut w = start;
                for r in start..columns.len() {
                    if r == start || columns[r] != columns[w - 1] {
                        columns[w] = columns[r];
                        w += 1;
                    }
                }
                columns.truncate(w);
            }
            row_ptr.push(columns.len());
        }
        let slot = |r: usize, c: usize| -> Option<usize> {
            let row = &columns[row_ptr[r]..row_ptr[r + 1]];
            row.binary_search(&c).ok().map(|p| row_ptr[r] + p)
        };
        let ne = self.elements[0] * self.elements[1];
        let l = 2 * nen;
        let mut local_slots = vec![NO_SLOT; ne * l * l];
        // in parallel over elements; one search per (row, element node): the node's two
        // columns are neighbours in the sorted row (one of them absent if prescribed)
        let (row_ptr_ref, columns_ref, dirichlet) = (&row_ptr, &columns, &self.dirichlet);
        local_slots
            .par_chunks_mut(l * l)
            .enumerate()
            .for_each(|(e, out)| {
                let mut nodes = [0; 9];
                self.element_nodes(e, &mut nodes);
                for a in 0..l {
                    let r = 2 * nodes[a / 2] + a % 2;
                    let base = row_ptr_ref[r];
                    let row = &columns_ref[base..row_ptr_ref[r + 1]];
                    let out = &mut out[a * l..(a + 1) * l];
                    for (bn, &m) in nodes[..nen].iter().enumerate() {
                        let first = 2 * m;
                        let pos = row.partition_point(|&c| c < first);
                        for d in 0..2 {
                            let c = first + d;
                            let keep = if dirichlet[r].is_some() {
                                r == c
                            } else {
                                dirichlet[c].is_none()
                            };
                            if keep {
                                let p = if row.get(pos) == Some(&c) {
                                    pos
                                } else {
                                    pos + 1
                                };
                                assert!(row.get(p) == Some(&c), "element entry in the pattern");
                                out[2 * bn + d] = (base + p) as u32;
                            }
                        }
                    }
                }
            });
        // the compressed columns: the row-wise pattern transposed by a counting pass (rows come
        // out increasing in each column), and every row-wise slot mapped to its column slot
        let mut col_ptr = vec![0usize; ndof + 1];
        for &c in &columns {
            col_ptr[c + 1] += 1;
        }
        for c in 0..ndof {
            col_ptr[c + 1] += col_ptr[c];
        }
        let mut next = col_ptr[..ndof].to_vec();
        let mut row_idx = vec![0usize; columns.len()];
        let mut column_slot = vec![0u32; columns.len()];
        for r in 0..ndof {
            for k in row_ptr[r]..row_ptr[r + 1] {
                let c = columns[k];
                row_idx[next[c]] = r;
                column_slot[k] = next[c] as u32;
                next[c] += 1;
            }
        }
        local_slots.par_iter_mut().for_each(|s| {
            if *s != NO_SLOT {
                *s = column_slot[*s as usize];
            }
        });
        self.diagonal_slots = (0..ndof)
            .map(|d| column_slot[slot(d, d).expect("diagonal in the pattern")] as usize)
            .collect();
        self.pattern = SparsityPattern::from_compressed_columns(ndof, ndof, col_ptr, row_idx)
            .expect("rows increase in each column by construction");
        self.local_slots = local_slots;
    }

    /// The element matrix of element `e` into `out` (`2 nen x 2 nen`, row-major, local dof
    /// `2 a + c`), exactly symmetric.
    fn element_matrix(&self, e: usize, out: &mut [f64]) {
        let (nq, nen) = (self.quadrature_points(), self.nodes_per_element());
        let l = 2 * nen;
        out.iter_mut().for_each(|x| *x = 0.0);
        let mut kb = [[[0.0f64; 2]; 6]; 9];
        for q in 0..nq {
            let packed = &self.stiffness[e * nq + q];
            let kq: [[f64; 6]; 6] =
                core::array::from_fn(|r| core::array::from_fn(|s| packed[PACK[r][s]]));
            let phi = &self.shape[q * nen..(q + 1) * nen];
            for (b, kbb) in kb.iter_mut().enumerate().take(nen) {
                let f = phi[b];
                for (row, kr) in kbb.iter_mut().enumerate() {
                    for (d, x) in kr.iter_mut().enumerate() {
                        *x = kq[row][d] * f[0] + kq[row][2 + d] * f[1] + kq[row][4 + d] * f[2];
                    }
                }
            }
            for a in 0..nen {
                let f = phi[a];
                for c in 0..2 {
                    let row = &mut out[(2 * a + c) * l..(2 * a + c + 1) * l];
                    for (b, kbb) in kb.iter().enumerate().take(nen) {
                        for d in 0..2 {
                            row[2 * b + d] +=
                                f[0] * kbb[c][d] + f[1] * kbb[2 + c][d] + f[2] * kbb[4 + c][d];
                        }
                    }
                }
            }
        }
        if self.volumetric == VolumetricIntegration::Reduced {
            // lambda (div v)(div w) sqrt(g) at the reduced points: a rank-one update per point
            // with the discrete divergence d_(a c) = t_c N_a + t_(2+c) d_2 N_a + t_(4+c) d_3 N_a
            let nr = self.order.degree().pow(2);
            let mut d = [0.0f64; 18];
            for r in 0..nr {
                let [c, t @ ..] = self.reduced_divergence[e * nr + r];
                let phi = &self.reduced_shape[r * nen..(r + 1) * nen];
                for (a, f) in phi.iter().enumerate() {
                    for comp in 0..2 {
                        d[2 * a + comp] = t[comp] * f[0] + t[2 + comp] * f[1] + t[4 + comp] * f[2];
                    }
                }
                for i in 0..l {
                    let ci = c * d[i];
                    for (x, dj) in out[i * l..(i + 1) * l].iter_mut().zip(&d[..l]) {
                        *x += ci * dj;
                    }
                }
            }
        }
        for i in 0..l {
            for j in i + 1..l {
                let s = 0.5 * (out[i * l + j] + out[j * l + i]);
                out[i * l + j] = s;
                out[j * l + i] = s;
            }
        }
    }

    /// The assembled values (in `pattern` order, that of `entries()`) and right-hand side.
    fn assemble(&self, rhs: &mut [f64]) -> Vec<f64> {
        let nen = self.nodes_per_element();
        let l = 2 * nen;
        let ne = self.elements[0] * self.elements[1];
        let mut values = vec![0.0; self.pattern.nnz()];
        rhs.copy_from_slice(&self.load);
        let mut buffer = vec![0.0; BATCH.min(ne) * l * l];
        let mut nodes = [0; 9];
        for start in (0..ne).step_by(BATCH) {
            let end = (start + BATCH).min(ne);
            let buf = &mut buffer[..(end - start) * l * l];
            buf.par_chunks_mut(l * l)
                .enumerate()
                .for_each(|(i, out)| self.element_matrix(start + i, out));
            for e in start..end {
                let local = &buf[(e - start) * l * l..(e - start + 1) * l * l];
                let slots = &self.local_slots[e * l * l..(e + 1) * l * l];
                self.element_nodes(e, &mut nodes);
                for (idx, (&s, &x)) in slots.iter().zip(local).enumerate() {
                    if s != NO_SLOT {
                        values[s as usize] += x;
                    } else {
                        let (a, b) = (idx / l, idx % l);
                        let r = 2 * nodes[a / 2] + a % 2;
                        let c = 2 * nodes[b / 2] + b % 2;
                        if let (None, Some(g)) = (self.dirichlet[r], self.dirichlet[c]) {
                            rhs[r] -= x * g;
                        }
                    }
                }
            }
        }
        for (d, g) in self.dirichlet.iter().enumerate() {
            if let Some(g) = g {
                rhs[d] = values[self.diagonal_slots[d]] * g;
            }
        }
        values
    }

    /// Interpolates the discrete displacement `[v^2, v^3]` and the exact one over every
    /// element with a `(k + 2)`-point Gauss rule per direction and returns the error norms.
    ///
    /// # Errors
    /// [`ElasticityError::DimensionMismatch`] for a wrong length; geometry failures.
    pub fn displacement_errors(
        &self,
        v: &[f64],
        exact: &(dyn Fn([f64; 2]) -> [f64; 2] + Sync),
    ) -> Result<DisplacementErrors, ElasticityError> {
        if v.len() != self.dof_count() {
            return Err(ElasticityError::DimensionMismatch {
                quantity: "displacement",
                expected: self.dof_count(),
                found: v.len(),
            });
        }
        let norm2 = |p: &ShellPoint<f64>, e: [f64; 2]| {
            let g = &p.metric;
            g[1][1] * e[0] * e[0] + 2.0 * g[1][2] * e[0] * e[1] + g[2][2] * e[1] * e[1]
        };
        let max = (0..self.grid.node_count())
            .into_par_iter()
            .map(|k| -> Result<f64, ElasticityError> {
                let [x2, x3] = self.grid.coordinates(self.grid.node(k));
                let p = self.chart.shell_point([0.0, x2, x3])?;
                let u = exact([x2, x3]);
                Ok(norm2(&p, [v[2 * k] - u[0], v[2 * k + 1] - u[1]]).sqrt())
            })
            .try_reduce(|| 0.0, |a, b| Ok(a.max(b)))?;
        let (gp, gw) = gauss_rule(self.order.nodes_per_direction() + 1);
        let [l2, l3] = self.element_size();
        let det = 0.25 * l2 * l3;
        let np = self.order.nodes_per_direction();
        let ne = self.elements[0] * self.elements[1];
        let sums = (0..ne)
            .into_par_iter()
            .map(|e| -> Result<[f64; 3], ElasticityError> {
                let mut nodes = [0; 9];
                self.element_nodes(e, &mut nodes);
                let [x0, y0] = self.element_origin(e);
                let mut s = [0.0; 3];
                for (i, &xi) in gp.iter().enumerate() {
                    let (n2, _) = self.order.shape_1d(xi);
                    for (j, &eta) in gp.iter().enumerate() {
                        let (n3, _) = self.order.shape_1d(eta);
                        let x = [x0 + 0.5 * (xi + 1.0) * l2, y0 + 0.5 * (eta + 1.0) * l3];
                        let mut uh = [0.0; 2];
                        for a2 in 0..np {
                            for a3 in 0..np {
                                let node = nodes[a2 * np + a3];
                                let n = n2[a2] * n3[a3];
                                uh[0] += n * v[2 * node];
                                uh[1] += n * v[2 * node + 1];
                            }
                        }
                        let p = self.chart.shell_point([0.0, x[0], x[1]])?;
                        let u = exact(x);
                        let w = gw[i] * gw[j] * det;
                        let err2 = norm2(&p, [uh[0] - u[0], uh[1] - u[1]]);
                        s[0] += w * err2;
                        s[1] += w * p.sqrt_g * err2;
                        s[2] += w * p.sqrt_g * norm2(&p, u);
                    }
                }
                Ok(s)
            })
            .collect::<Result<Vec<_>, _>>()?;
        // sequential sum in element order: reproducible
        let s = sums.iter().fold([0.0; 3], |acc, x| {
            [acc[0] + x[0], acc[1] + x[1], acc[2] + x[2]]
        });
        let [t0, t1] = self.grid.theta();
        let area = (t1 - t0) * self.grid.thickness();
        Ok(DisplacementErrors {
            max,
            rms: (s[0] / area).sqrt(),
            l2: s[1].sqrt(),
            l2_exact: s[2].sqrt(),
        })
    }

    /// The local displacement at a node by the recovery stencil.
    fn local(&self, node: [usize; 2], v: &[f64]) -> LocalDisplacement {
        let mut u = [0.0; 6];
        for (n, w) in self.node_stencil(node) {
            for c in 0..2 {
                let x = v[self.dof(n, Component::ALL[c])];
                u[c] += w[0] * x;
                u[2 + c] += w[1] * x;
                u[4 + c] += w[2] * x;
            }
        }
        LocalDisplacement {
            value: [u[0], u[1]],
            gradient: [[u[2], u[3]], [u[4], u[5]]],
        }
    }
}

impl<G: ShellGeometry + Sync> Discretisation for FiniteElementNavier<G> {
    fn method(&self) -> &'static str {
        self.order.method_name()
    }

    /// Nested dissection along element boundaries ([`ElementOrder::cholesky_ordering`]).
    fn lu_ordering(&self) -> capstan_solvers::ColumnOrdering {
        self.order.cholesky_ordering(&self.grid)
    }

    fn grid(&self) -> &Grid {
        &self.grid
    }

    fn dof_count(&self) -> usize {
        2 * self.grid.node_count()
    }

    #[track_caller]
    fn dof(&self, node: [usize; 2], component: Component) -> usize {
        assert!(
            node[0] < self.grid.n2() && node[1] < self.grid.n3(),
            "node {node:?} outside the grid"
        );
        2 * self.grid.node_index(node) + component.index()
    }

    fn entries(&self) -> Result<Vec<(usize, usize)>, ElasticityError> {
        Ok(self.pattern.entries().collect())
    }

    fn fill(
        &self,
        add: &mut dyn FnMut(usize, f64),
        rhs: &mut [f64],
    ) -> Result<(), ElasticityError> {
        if rhs.len() != self.dof_count() {
            return Err(ElasticityError::DimensionMismatch {
                quantity: "rhs",
                expected: self.dof_count(),
                found: rhs.len(),
            });
        }
        for (k, x) in self.assemble(rhs).into_iter().enumerate() {
            add(k, x);
        }
        Ok(())
    }

    /// The pattern built with the discretisation (no `entries()` and sort), the values
    /// assembled straight into its slots; equal to the default (tested).
    fn system(&self) -> Result<LinearSystem, ElasticityError> {
        let mut rhs = vec![0.0; self.dof_count()];
        let values = self.assemble(&mut rhs);
        LinearSystem::from_parts(self.pattern.clone(), values, rhs)
    }

    fn contact_nodes(&self) -> Result<Vec<ContactNode>, ElasticityError> {
        let g = &self.grid;
        let (n2, k) = (g.n2(), self.order.degree());
        (0..n2)
            .map(|i| {
                let node = [i, 0];
                let (_, [sqrt_g, s33, sqrt_g22]) = self.contact[i];
                // int N_i dx2 on x3 = 0: row sums of the 1-D boundary mass matrix
                let interior = match (k, i % 2) {
                    (1, _) => g.dx2(),
                    (_, 0) => 2.0 * g.dx2() / 3.0,
                    _ => 4.0 * g.dx2() / 3.0,
                };
                let end = !g.is_periodic() && (i == 0 || i == n2 - 1);
                let length = if end { 0.5 * interior } else { interior };
                let [shear, normal] = self.contact_rows(i);
                let tangential_dof = self.dof(node, Component::X2);
                Ok(ContactNode {
                    node,
                    x2: g.x2(i),
                    tangential_row: self.dirichlet[tangential_dof]
                        .is_none()
                        .then_some(tangential_dof),
                    tangential_dof,
                    normal_dof: self.dof(node, Component::X3),
                    traction_weight: sqrt_g * s33 * length,
                    sqrt_g22,
                    normal_stress: normal,
                    shear_stress: shear,
                })
            })
            .collect()
    }

    fn fields(&self, v: &[f64]) -> Result<NodalFields, ElasticityError> {
        if v.len() != self.dof_count() {
            return Err(ElasticityError::DimensionMismatch {
                quantity: "displacement",
                expected: self.dof_count(),
                found: v.len(),
            });
        }
        let n = self.grid.node_count();
        let mut out = NodalFields {
            grid: self.grid,
            displacement: Vec::with_capacity(n),
            strain: Vec::with_capacity(n),
            stress: Vec::with_capacity(n),
            scale: Vec::with_capacity(n),
            cartesian_displacement: Vec::with_capacity(n),
        };
        for k in 0..n {
            let node = self.grid.node(k);
            let [x2, x3] = self.grid.coordinates(node);
            let p = self.chart.shell_point([0.0, x2, x3])?;
            let u = self.local(node, v);
            out.displacement.push(u.value);
            out.strain.push(strain(&p, &u));
            let mut stress = contravariant_stress(&p, &self.material, &u);
            if self.volumetric == VolumetricIntegration::Reduced {
                // T^ij = lambda g^ij div v + 2 mu E^ij: the divergence from the reduced points
                let inputs = u.to_inputs();
                let t = divergence_coefficients(&p);
                let pointwise: f64 = (0..6).map(|q| t[q] * inputs[q]).sum();
                let reduced: f64 = self
                    .reduced_divergence_terms(node)
                    .iter()
                    .map(|&(d, w)| w * v[d])
                    .sum();
                let jump = self.material.lambda() * (reduced - pointwise);
                for (row, gi) in stress.iter_mut().zip(&p.inverse_metric) {
                    for (x, g) in row.iter_mut().zip(gi) {
                        *x += jump * g;
                    }
                }
            }
            out.stress.push(stress);
            out.scale.push([0, 1, 2].map(|i| p.metric[i][i].sqrt()));
            let g = &p.covariant_basis;
            out.cartesian_displacement
                .push([0, 1, 2].map(|a| u.value[0] * g[1][a] + u.value[1] * g[2][a]));
        }
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use capstan_geometry::{EllipticalPrism, ExpressionProfile, GeneralPrism, ShellChart};

    /// `K_q` by the definition: the mixed stress coefficients `C_k^i_j` contracted with
    /// `D_l^i_j = nabla_i w^j`, then symmetrised.
    #[allow(clippy::needless_range_loop)] // index loops mirror the tensor formulas
    fn stiffness_by_definition(p: &ShellPoint<f64>, material: &Material, scale: f64) -> [f64; 21] {
        let c = mixed_stress_coefficients(p, material);
        let mut k = [[0.0; 6]; 6];
        for trial in 0..6 {
            for test in 0..6 {
                k[trial][test] = if test < 2 {
                    let m = test + 1;
                    let mut s = 0.0;
                    for i in 0..3 {
                        for j in 0..3 {
                            s += c[trial][i][j] * p.christoffel[j][i][m];
                        }
                    }
                    s
                } else {
                    c[trial][test / 2][test % 2 + 1]
                };
            }
        }
        let mut packed = [0.0; 21];
        for a in 0..6 {
            for b in a..6 {
                packed[PACK[a][b]] = 0.5 * (k[a][b] + k[b][a]) * p.sqrt_g * scale;
            }
        }
        packed
    }

    fn energy_form_equals_definition<G: ShellGeometry>(chart: &G) {
        let material = Material::new(7.0, 0.3).unwrap();
        for x2 in [-2.0, -0.7, 0.0, 0.4, 1.3] {
            for x3 in [0.0, 0.15, 0.6] {
                let p = chart.shell_point([0.0, x2, x3]).unwrap();
                let fast = point_stiffness(&p, &material, 0.37);
                let reference = stiffness_by_definition(&p, &material, 0.37);
                let size = reference.iter().fold(0.0f64, |m, x| m.max(x.abs()));
                for (a, b) in fast.iter().zip(&reference) {
                    // the same sums in another order: round-off only
                    assert!((a - b).abs() <= 1e-13 * size, "x2 {x2} x3 {x3}: {a} vs {b}");
                }
            }
        }
    }

    /// The pattern by brute force: every pair of nodes of an element (a prescribed row keeps
    /// its diagonal only, a prescribed column is dropped) and the contact columns of every free
    /// tangential row on `x3 = 0`, through `SparsityPattern::from_entries` (the sort).
    fn pattern_by_definition<G: ShellGeometry + Sync>(
        op: &FiniteElementNavier<G>,
    ) -> SparsityPattern {
        let nen = op.nodes_per_element();
        let mut entries = vec![];
        let mut nodes = [0; 9];
        for e in 0..op.elements[0] * op.elements[1] {
            op.element_nodes(e, &mut nodes);
            for &a in &nodes[..nen] {
                for &b in &nodes[..nen] {
                    for (r, c) in (0..4).map(|k| (2 * a + k / 2, 2 * b + k % 2)) {
                        let keep = match op.dirichlet[r] {
                            Some(_) => r == c,
                            None => op.dirichlet[c].is_none(),
                        };
                        if keep {
                            entries.push((r, c));
                        }
                    }
                }
            }
        }
        for i in 0..op.grid.n2() {
            let d = op.dof([i, 0], Component::X2);
            if op.dirichlet[d].is_none() {
                for row in op.contact_rows(i) {
                    entries.extend(row.columns.iter().map(|&c| (d, c)));
                }
            }
        }
        let n = op.dof_count();
        SparsityPattern::from_entries(n, n, &entries).unwrap().0
    }

    #[test]
    fn direct_pattern_and_system_equal_the_entries_path() {
        use crate::finite_element::{lame_parts, paper_parts};
        use crate::samples::{LameCylinder, PaperEllipse};
        use crate::verification::GridLevel;
        for order in [ElementOrder::Q1, ElementOrder::Q2] {
            let parts = [
                lame_parts(&LameCylinder::default(), GridLevel { n2: 16, n3: 5 }).unwrap(),
                paper_parts(&PaperEllipse::default(), GridLevel { n2: 17, n3: 5 }).unwrap(),
            ];
            for parts in parts {
                let op = parts.finite_element(order).unwrap();
                assert_eq!(op.pattern, pattern_by_definition(&op), "{order:?}");
                // the default `system()`: entries, sort, fill through the slots
                let entries = op.entries().unwrap();
                let mut reference = LinearSystem::from_entries(op.dof_count(), &entries).unwrap();
                op.refill(&mut reference).unwrap();
                let direct = op.system().unwrap();
                assert_eq!(direct.pattern, reference.pattern);
                // the same sums in the same order: bitwise equal
                assert_eq!(direct.values, reference.values);
                assert_eq!(direct.rhs, reference.rhs);
            }
        }
    }

    #[test]
    fn element_nested_dissection_solution_equals_amd() {
        use crate::finite_element::lame_parts;
        use crate::samples::LameCylinder;
        use crate::verification::GridLevel;
        use capstan_solvers::{ColumnOrdering, DirectParams, SparseCholesky};
        for order in [ElementOrder::Q1, ElementOrder::Q2] {
            let level = GridLevel { n2: 48, n3: 13 };
            let op = lame_parts(&LameCylinder::default(), level)
                .unwrap()
                .finite_element(order)
                .unwrap();
            let system = op.system().unwrap();
            let solve = |ordering| {
                let mut chol = SparseCholesky::new(DirectParams {
                    ordering,
                    ..Default::default()
                })
                .unwrap();
                let v = system.solve(&mut chol).unwrap();
                (v, chol.factor_values())
            };
            let (amd, _) = solve(ColumnOrdering::Amd);
            let (nd, fill) = solve(order.cholesky_ordering(op.grid()));
            assert!(fill > 0);
            let scale = amd.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            for (a, b) in amd.iter().zip(&nd) {
                // two backward-stable factorisations of a well-conditioned system
                assert!((a - b).abs() <= 1e-12 * scale, "{order:?}: {a} vs {b}");
            }
        }
    }

    #[test]
    fn point_stiffness_splits_into_shear_and_divergence_parts() {
        // the split of selective reduced integration: K = K(lambda = 0) + lambda sqrt(g) t t^T
        let chart = ShellChart::new(EllipticalPrism::new(1.0, 2.0).unwrap());
        let material = Material::new(7.0, 0.3).unwrap();
        let p = chart.shell_point([0.0, 0.4, 0.3]).unwrap();
        let full = point_stiffness(&p, &material, 0.37);
        let shear = point_energy(&p, 0.0, material.mu(), 0.37);
        let t = divergence_coefficients(&p);
        let size = full.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        for a in 0..6 {
            for b in a..6 {
                let vol = material.lambda() * p.sqrt_g * 0.37 * t[a] * t[b];
                let k = PACK[a][b];
                assert!((full[k] - shear[k] - vol).abs() <= 1e-14 * size); // round-off
            }
        }
        // d_2 v^2 and d_3 v^3 enter the divergence with weight 1, d_3 v^2 and d_2 v^3 not
        for (x, want) in [t[2], t[3], t[4], t[5]].iter().zip([1.0, 0.0, 0.0, 1.0]) {
            assert!((x - want).abs() < 1e-14, "{t:?}"); // g^22 g_22 = 1 to round-off
        }
    }

    #[test]
    fn lagrange_weights_extrapolate_from_the_gauss_points() {
        assert_eq!(lagrange_weights(&[0.0], -1.0), vec![1.0]);
        let (gp, _) = gauss_rule(2);
        let s3 = 3.0f64.sqrt();
        for (s, want) in [
            (-1.0, [0.5 * (1.0 + s3), 0.5 * (1.0 - s3)]),
            (0.0, [0.5, 0.5]),
            (1.0, [0.5 * (1.0 - s3), 0.5 * (1.0 + s3)]),
        ] {
            let w = lagrange_weights(&gp, s);
            for (a, b) in w.iter().zip(want) {
                assert!((a - b).abs() < 1e-15, "{s}: {w:?}"); // closed form: round-off
            }
        }
    }

    /// A smooth, non-polynomial displacement at the nodes (the recovery sees only nodal
    /// values).
    fn wavy<G: ShellGeometry + Sync>(op: &FiniteElementNavier<G>) -> Vec<f64> {
        let g = op.grid();
        (0..op.dof_count())
            .map(|d| {
                let [x2, x3]: [f64; 2] = g.coordinates(g.node(d / 2));
                if d % 2 == 0 {
                    0.01 * (1.3 * x2 + 2.0 * x3).sin() + 0.002 * x3 * x3
                } else {
                    0.02 * (0.7 * x2).cos() * (1.0 + x3) - 0.003 * x2 * x3
                }
            })
            .collect()
    }

    #[test]
    fn contact_normal_stress_is_the_nodal_field_stress_for_both_volumetric_rules() {
        // fields() and the contact rows recover T^3_3 = T^33 g_33 on x3 = 0 the same way
        // (g_23 = 0 on the shell chart); with SRI both take lambda div v from the reduced points
        let chart = ShellChart::new(EllipticalPrism::new(2.0, 1.0).unwrap());
        let material = Material::new(1e3, 0.49).unwrap();
        for order in [ElementOrder::Q1, ElementOrder::Q2] {
            let mut values = vec![];
            for volumetric in VolumetricIntegration::ALL {
                let grid = Grid::new([-1.2, 1.3], 0.4, 13, 5, false).unwrap();
                let bc = BoundaryConditions::paper_clamped(1.0, 1.0);
                let op = FiniteElementNavier::with_volumetric(
                    chart.clone(),
                    material,
                    grid,
                    bc,
                    None,
                    order,
                    volumetric,
                )
                .unwrap();
                let v = wavy(&op);
                let fields = op.fields(&v).unwrap();
                let mut row = vec![];
                for node in op.contact_nodes().unwrap() {
                    let k = op.grid().node_index(node.node);
                    let t33 = fields.stress[k][2][2] * fields.scale[k][2].powi(2);
                    let own = node.normal_stress.dot(&v);
                    // the same sums in another order, times lambda / mu = 49: round-off
                    assert!(
                        (own - t33).abs() < 1e-11 * (1.0 + t33.abs()),
                        "{own} vs {t33}"
                    );
                    // the shear row is pointwise for both rules
                    let t32 = fields.stress[k][2][1] * fields.scale[k][1].powi(2);
                    assert!((node.shear_stress.dot(&v) - t32).abs() < 1e-11 * (1.0 + t32.abs()));
                    row.push(own);
                }
                values.push(row);
            }
            // the rules differ only by lambda (div_h - div) at the node: not by round-off
            let diff = values[0]
                .iter()
                .zip(&values[1])
                .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
            assert!(diff > 1e-3, "{order:?}: {diff}");
        }
    }

    #[test]
    fn point_stiffness_equals_stress_coefficient_contraction() {
        energy_form_equals_definition(&ShellChart::new(EllipticalPrism::new(1.0, 2.0).unwrap()));
        energy_form_equals_definition(&ShellChart::new(EllipticalPrism::new(2.0, 0.5).unwrap()));
        let profile =
            ExpressionProfile::parse("3 * sin(t) - 0.2 * sin(3 * t)", "2 * cos(t) + 0.1 * t^2")
                .unwrap();
        energy_form_equals_definition(&ShellChart::new(GeneralPrism::new(profile)));
    }
}
