//! The Galerkin discretisation of the plane-strain curvilinear Navier operator with Q1/Q2
//! Lagrange elements on the parameter rectangle: the operator and its trait implementation;
//! the geometry cache, boundary terms, nodal recovery, assembly and error norms are its
//! submodules.

mod assembly;
pub(crate) mod boundary_terms;
mod geometry_cache;
pub(super) mod norms;
mod recovery;

use capstan_geometry::ShellPoint;

use super::element::{ElementOrder, lumped_weight};
use super::volumetric::VolumetricIntegration;
use crate::continuum::kinematics::{contravariant_stress, mixed_stress_coefficients};
use crate::continuum::{
    PLANE_STRAIN, check_plane_strain, divergence_coefficients, energy_matrix, mixed_strains,
};
use crate::discretisation::{ContactNode, Discretisation, LinearSystem};
use crate::error::ElasticityError;
use crate::fields::NodalFields;
use crate::material::Material;
use crate::plane_problem::PlaneProblem;
use crate::plane_strain_operator::{plane_strain_numbering, setup_accessors};
use crate::shell_geometry::ShellGeometry;
use capstan_solvers::SparsityPattern;

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
/// let op = FiniteElementNavier::new(problem, ElementOrder::Q2).unwrap();
/// let v = op.solve(&mut SparseCholesky::default()).unwrap(); // symmetric positive definite
/// // equal end tensions: the tangential displacement is odd in x2
/// let (left, right) = (v[op.dof([0, 4], Component::X2)], v[op.dof([24, 4], Component::X2)]);
/// assert!(left < 0.0 && (left + right).abs() < 1e-10);
/// ```
pub struct FiniteElementNavier<G> {
    /// The problem, without its body force (integrated into `load`).
    problem: PlaneProblem<G>,
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
        self.problem
            .debug_fields(f, "FiniteElementNavier", Some(("order", &self.order)))
    }
}

/// [`energy_matrix`] of the plane-strain inputs with the material's Lamé constants, packed.
fn packed_stiffness(p: &ShellPoint<f64>, material: &Material, scale: f64) -> [f64; 21] {
    packed_energy(p, material.lambda(), material.mu(), scale)
}

/// [`energy_matrix`] of the plane-strain inputs, packed (upper triangle, [`PACK`] order):
/// `lambda = 0` leaves the shear part `2 mu sqrt(g) tr(M_k M_l)` of selective reduced
/// integration.
fn packed_energy(p: &ShellPoint<f64>, lambda: f64, mu: f64, scale: f64) -> [f64; 21] {
    let k = energy_matrix(p, &PLANE_STRAIN, lambda, mu, scale);
    let mut packed = [0.0; 21];
    for (a, row) in k.iter().enumerate() {
        for (b, x) in row.iter().enumerate().skip(a) {
            packed[PACK[a][b]] = *x;
        }
    }
    packed
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
    pub fn new(problem: PlaneProblem<G>, order: ElementOrder) -> Result<Self, ElasticityError> {
        Self::with_volumetric(problem, order, VolumetricIntegration::Full)
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
    ///     ElementOrder, FiniteElementNavier, VolumetricIntegration,
    /// };
    /// use capstan_elasticity::studies::lame_parts;
    /// use capstan_elasticity::samples::{LameCylinder, ManufacturedField};
    /// use capstan_elasticity::verification::GridLevel;
    /// use capstan_elasticity::{Discretisation, Material};
    /// use capstan_solvers::SparseCholesky;
    /// // the Lamé cylinder at nu = 0.4999: Q1 locks, Q1 with SRI does not
    /// let lame = LameCylinder { material: Material::new(10.0, 0.4999).unwrap(), ..Default::default() };
    /// let exact = lame.field();
    /// let error = |volumetric| {
    ///     let p = lame_parts(&lame, GridLevel { n2: 32, n3: 9 }).unwrap();
    ///     let op = FiniteElementNavier::with_volumetric(p, ElementOrder::Q1, volumetric).unwrap();
    ///     let v = op.solve(&mut SparseCholesky::default()).unwrap();
    ///     let e = op.displacement_errors(&v, &|x| exact.displacement(x).value).unwrap();
    ///     e.l2 / e.l2_exact
    /// };
    /// let (full, reduced) = (error(VolumetricIntegration::Full), error(VolumetricIntegration::Reduced));
    /// assert!(reduced < 1e-2 && full > 10.0 * reduced, "full {full}, reduced {reduced}");
    /// ```
    pub fn with_volumetric(
        mut problem: PlaneProblem<G>,
        order: ElementOrder,
        volumetric: VolumetricIntegration,
    ) -> Result<Self, ElasticityError> {
        let grid = problem.grid;
        problem.boundary.check_grid(&grid)?;
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
        let body_force = problem.body_force.take();
        let mut op = Self {
            problem,
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
        op.dirichlet = op.problem.dirichlet_values(|node| grid.coordinates(node))?;
        op.shape = op.reference_shape();
        op.cache_geometry(body_force.as_ref())?;
        if volumetric == VolumetricIntegration::Reduced {
            op.cache_reduced_divergence()?;
        }
        op.add_boundary_loads()?;
        op.contact = (0..grid.n2())
            .map(|i| {
                let p = op.point(grid.x2(i), 0.0)?;
                let c = mixed_stress_coefficients(&p, &op.problem.material);
                let mut coef: Coefficients =
                    core::array::from_fn(|e| core::array::from_fn(|q| c[q][2][e + 1]));
                if volumetric == VolumetricIntegration::Reduced {
                    // T^3_3 = lambda tr M + 2 mu M^3_3: only the shear part is pointwise, the
                    // divergence comes from the reduced points (see `contact_rows`)
                    let two_mu = 2.0 * op.problem.material.mu();
                    coef[1] = mixed_strains(&p, &PLANE_STRAIN).map(|m| two_mu * m[2][2]);
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

    setup_accessors!();

    /// Number of elements `[in x2, in x3]`.
    pub fn element_counts(&self) -> [usize; 2] {
        self.elements
    }

    fn point(&self, x2: f64, x3: f64) -> Result<ShellPoint<f64>, ElasticityError> {
        let at = [0.0, x2, x3];
        let p = self.problem.chart.shell_point(at)?;
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
        [k * self.problem.grid.dx2(), k * self.problem.grid.dx3()]
    }

    /// Node numbers of element `e`, local node `a = a2 (k + 1) + a3`.
    fn element_nodes(&self, e: usize, out: &mut [usize; 9]) {
        let (k, np) = (self.order.degree(), self.order.nodes_per_direction());
        let (e2, e3) = (e / self.elements[1], e % self.elements[1]);
        let n2 = self.problem.grid.n2();
        for a2 in 0..np {
            let i2 = (k * e2 + a2) % n2; // wraps only on a periodic grid
            for a3 in 0..np {
                out[a2 * np + a3] = self.problem.grid.node_index([i2, k * e3 + a3]);
            }
        }
    }

    /// Lower-left corner `(x2, x3)` of element `e`.
    fn element_origin(&self, e: usize) -> [f64; 2] {
        let k = self.order.degree();
        let (e2, e3) = (e / self.elements[1], e % self.elements[1]);
        [self.problem.grid.x2(k * e2), self.problem.grid.x3(k * e3)]
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
}

impl<G: ShellGeometry + Sync> Discretisation for FiniteElementNavier<G> {
    fn method(&self) -> &'static str {
        self.order.method_name()
    }

    /// Nested dissection along element boundaries ([`ElementOrder::cholesky_ordering`]).
    fn lu_ordering(&self) -> capstan_solvers::ColumnOrdering {
        self.order.cholesky_ordering(&self.problem.grid)
    }

    plane_strain_numbering!();

    fn entries(&self) -> Result<Vec<(usize, usize)>, ElasticityError> {
        Ok(self.pattern.entries().collect())
    }

    fn fill_values(
        &self,
        add: &mut dyn FnMut(usize, f64),
        rhs: &mut [f64],
    ) -> Result<(), ElasticityError> {
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
        let g = &self.problem.grid;
        let n2 = g.n2();
        (0..n2)
            .map(|i| {
                let (_, [sqrt_g, s33, sqrt_g22]) = self.contact[i];
                // int N_i dx2 on x3 = 0: row sums of the 1-D boundary mass matrix
                let length = lumped_weight(self.order, i, n2, g.dx2(), g.is_periodic());
                Ok(ContactNode::at(
                    self,
                    i,
                    &self.dirichlet,
                    sqrt_g * s33 * length,
                    sqrt_g22,
                    self.contact_rows(i),
                ))
            })
            .collect()
    }

    fn fields(&self, v: &[f64]) -> Result<NodalFields, ElasticityError> {
        ElasticityError::check_length("displacement", self.dof_count(), v.len())?;
        NodalFields::from_nodes(self.problem.grid, &self.problem.chart, |node, p| {
            let u = self.local(node, v);
            let mut stress = contravariant_stress(p, &self.problem.material, &u);
            if self.volumetric == VolumetricIntegration::Reduced {
                // T^ij = lambda g^ij div v + 2 mu E^ij: the divergence from the reduced points
                let inputs = u.to_inputs();
                let t = divergence_coefficients(p, &PLANE_STRAIN);
                let pointwise: f64 = (0..6).map(|q| t[q] * inputs[q]).sum();
                let reduced: f64 = self
                    .reduced_divergence_terms(node)
                    .iter()
                    .map(|&(d, w)| w * v[d])
                    .sum();
                let jump = self.problem.material.lambda() * (reduced - pointwise);
                for (row, gi) in stress.iter_mut().zip(&p.inverse_metric) {
                    for (x, g) in row.iter_mut().zip(gi) {
                        *x += jump * g;
                    }
                }
            }
            Ok((u, stress))
        })
    }
}

#[cfg(test)]
mod tests;
