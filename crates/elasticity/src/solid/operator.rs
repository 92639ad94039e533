//! The 3-D curvilinear Navier operator by Q1/Q2/Qp hexahedral finite elements on the box.

use capstan_solvers::LinearSolver;
use rayon::prelude::*;

use super::boundary::SolidBoundary;
use super::element::{ElementRule, HexElement};
use super::grid::BoxGrid;
use super::setup::{COMPONENTS, SolidSetup};
use crate::continuum::{SOLID, divergence_coefficients, energy_matrix};
use crate::discretisation::LinearSystem;
use crate::error::ElasticityError;
use crate::finite_element::ElementAssembly;
use crate::finite_element::VolumetricIntegration;
use crate::material::Material;
use crate::shell_geometry::ShellGeometry;

pub use super::setup::SolidForce;

/// The curvilinear Navier operator of a 3-D body on the parametric box
/// `[x1a, x1b] x [x2a, x2b] x [0, h]` of a shell chart `sigma + x3 N`, by Q1, Q2 or Qp
/// Lagrange hexahedra ([`HexElement`]; Qp with GLL nodes), assembled from the chart alone.
///
/// # Math
/// ```text
/// a(v, w) = int_B A^ijkl E_kl(v) E_ij(w) sqrt(g) dx1 dx2 dx3
///         = int_B u(v)^T K w(w) dx,    K = energy_matrix(SOLID): 12 x 12 per point
/// l(w)    = int_B f_j w^j sqrt(g) dx + int_faces phi_j w^j dS
/// nabla_i w^j = d_i w^j + Gamma^j_im w^m          (all three directions and components)
/// ```
/// with the twelve inputs `u = [v^1, v^2, v^3, d_1 v^1, ..., d_3 v^3]` of
/// [`crate::continuum::SOLID`]. The full metric is used: `g_12 != 0` (a chart that is not
/// orthogonally parametrised, such as an elliptical cone) needs no special case. Boundary
/// fluxes on a face `x_a = const` (outward sign `s`):
/// ```text
/// traction t_j:   phi_j = sqrt(g) sqrt(g^aa) t_j      (dS = sqrt(g) sqrt(g^aa) dx_b dx_c)
/// stress T^a_j:   phi_j = s sqrt(g) T^a_j
/// ```
/// Quadrature: `(k + 1)^3` Gauss points per element (`k` the degree) (exact for the constant-coefficient
/// integrand of degree `2k` per direction). With [`VolumetricIntegration::Reduced`] the
/// volumetric part `lambda (div v)(div w) sqrt(g)` is integrated at `k^3` points (selective
/// reduced integration), the shear part with the full rule. Dirichlet conditions are imposed
/// symmetrically ([`ElementAssembly`]), so the matrix is symmetric positive definite once the
/// rigid motions are held, and [`capstan_solvers::SparseCholesky`] applies.
///
/// Dofs are numbered `3 node + c` (`c = 0, 1, 2` for `v^1, v^2, v^3`), nodes as
/// [`BoxGrid::node_index`].
///
/// # Errors
/// See [`SolidNavier::new`].
pub struct SolidNavier<G> {
    pub(crate) setup: SolidSetup<G>,
    /// Set when assembled for one process's rows ([`SolidNavier::distribution`]).
    distribution: Option<std::sync::Arc<dyn capstan_solvers::row_distribution::RowDistribution>>,
    system: LinearSystem,
}

impl<G> core::fmt::Debug for SolidNavier<G> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("SolidNavier")
            .field("element", &self.setup.lines.element())
            .field("grid", &self.setup.grid)
            .field("material", &self.setup.material)
            .finish_non_exhaustive()
    }
}

/// Adds `scale B^T K B` to the element matrix `out` (`l x l`, `l = 3 nen`) for the shape
/// values `phi` at one point: `B` maps the local dofs to the twelve inputs
/// (`v^c -> N_a`, `d_p v^c -> d_p N_a`). Only the upper triangle is accumulated.
#[allow(clippy::needless_range_loop)] // mirrors B^T K B
pub(super) fn add_point(out: &mut [f64], k: &[[f64; 12]; 12], phi: &[[f64; 4]]) {
    let nen = phi.len();
    let l = COMPONENTS * nen;
    // kb[i][3 b + d] = (K B)_(i, (b, d))
    let mut kb = vec![[0.0f64; 12]; l];
    for (b, f) in phi.iter().enumerate() {
        for d in 0..COMPONENTS {
            let col = &mut kb[COMPONENTS * b + d];
            for i in 0..12 {
                col[i] =
                    k[i][d] * f[0] + k[i][3 + d] * f[1] + k[i][6 + d] * f[2] + k[i][9 + d] * f[3];
            }
        }
    }
    for (a, f) in phi.iter().enumerate() {
        for c in 0..COMPONENTS {
            let r = COMPONENTS * a + c;
            let row = &mut out[r * l..(r + 1) * l];
            for (s, col) in kb.iter().enumerate().skip(r) {
                row[s] += f[0] * col[c] + f[1] * col[3 + c] + f[2] * col[6 + c] + f[3] * col[9 + c];
            }
        }
    }
}

impl<G: ShellGeometry + Sync> SolidNavier<G> {
    /// Builds and assembles the operator.
    ///
    /// # Errors
    /// [`ElasticityError::InvalidParameter`] naming `grid.n1`, `grid.n2` or `grid.n3` if a
    /// direction is not a whole number of elements (Q2: odd node counts, even `n2` when
    /// periodic; Qp: `n - 1`, periodic `n2`, multiples of `p`); [`ElasticityError::InconsistentBoundary`] if grid and conditions disagree on
    /// periodicity or a pinned node is outside the grid; [`ElasticityError::Geometry`] at the
    /// first point where the chart is degenerate (e.g. the focal surface inside the body:
    /// `sqrt(g) <= 0`); [`ElasticityError::NonFinite`] for non-finite boundary data or body
    /// force.
    pub fn new(
        chart: G,
        material: Material,
        grid: BoxGrid,
        boundary: &SolidBoundary,
        body_force: Option<&SolidForce>,
        element: impl Into<HexElement>,
        volumetric: VolumetricIntegration,
    ) -> Result<Self, ElasticityError> {
        let setup = SolidSetup::new(chart, material, grid, boundary, element.into(), volumetric)?;
        let element = setup.element();
        let np = element.nodes_per_direction();
        let mut connectivity = Vec::with_capacity(setup.element_count() * np.pow(3));
        for e in 0..setup.element_count() {
            connectivity.extend(setup.element_nodes(e));
        }
        // one process of a distributed solve assembles its own rows only
        let distribution = capstan_solvers::row_distribution::installed();
        let assembly = match &distribution {
            None => ElementAssembly::new(
                setup.grid.node_count(),
                COMPONENTS,
                np.pow(3),
                connectivity,
                &setup.dirichlet,
            )?,
            Some(d) => ElementAssembly::for_rows(
                setup.grid.node_count(),
                COMPONENTS,
                np.pow(3),
                &connectivity,
                &setup.dirichlet,
                d.owned(COMPONENTS * setup.grid.node_count(), COMPONENTS),
            )?,
        };
        // the load whole on every process (the elements' own share of it is cheap)
        let load = setup.load(boundary, body_force)?;
        let matrices = element_data(
            &setup,
            &|e| assembly.element_id(e),
            assembly.element_count(),
        )?;
        let l = COMPONENTS * np.pow(3);
        let mut system = assembly.assemble(
            |e, out| {
                out.copy_from_slice(&matrices[e * l * l..(e + 1) * l * l]);
            },
            &load,
            &setup.dirichlet,
        )?;
        if let Some(d) = &distribution {
            // the right-hand side whole on every rank (the Dirichlet lifting of the other
            // rows was a partial sum)
            d.gather(&mut system.rhs, COMPONENTS)?;
        }
        // the element slots are dropped here: only the assembled values are kept
        Ok(Self {
            setup,
            distribution,
            system,
        })
    }

    /// The process's share of a distributed solve this operator was assembled for (its
    /// rows only: [`ElementAssembly::for_rows`], the rows
    /// [`capstan_solvers::row_distribution::RowDistribution::owned`] of 3 unknowns a node;
    /// the right-hand side whole), `None` for the whole operator. Set when a distribution
    /// with more than one process is installed
    /// ([`capstan_solvers::row_distribution::install`]); the L2 errors and the linear
    /// [`SolidNavier::solve`] need the whole operator.
    pub fn distribution(
        &self,
    ) -> Option<&std::sync::Arc<dyn capstan_solvers::row_distribution::RowDistribution>> {
        self.distribution.as_ref()
    }

    /// The grid.
    pub fn grid(&self) -> &BoxGrid {
        &self.setup.grid
    }

    /// The element.
    pub fn element(&self) -> HexElement {
        self.setup.element()
    }

    /// Number of unknowns, `3 n1 n2 n3`.
    pub fn dof_count(&self) -> usize {
        self.setup.dof_count()
    }

    /// The dof of component `c` (0, 1, 2 for `v^1, v^2, v^3`) at node `(i1, i2, i3)`.
    pub fn dof(&self, node: [usize; 3], c: usize) -> usize {
        self.setup.dof(node, c)
    }

    /// The assembled system `A v = b` (symmetric).
    pub fn system(&self) -> &LinearSystem {
        &self.system
    }

    /// Solves the linear problem with `solver` (Cholesky: the matrix is SPD).
    ///
    /// # Errors
    /// Solver failures (a singular matrix when the rigid motions are not held).
    pub fn solve(&self, solver: &mut dyn LinearSolver<f64>) -> Result<Vec<f64>, ElasticityError> {
        self.system.solve(solver)
    }

    /// Error norms of the discrete displacement `v` against `exact` (contravariant
    /// `[v^1, v^2, v^3]` at `(x1, x2, x3)`), by a `(k + 2)^3`-point Gauss rule per element.
    ///
    /// # Math
    /// ```text
    /// |e|^2 = g_ij e^i e^j     (physical length)
    /// l2 = sqrt(int |v_h - v|^2 sqrt(g) dx),   l2_exact = sqrt(int |v|^2 sqrt(g) dx)
    /// ```
    ///
    /// # Errors
    /// [`ElasticityError::DimensionMismatch`] for a wrong length; geometry failures.
    pub fn l2_errors(
        &self,
        v: &[f64],
        exact: &(dyn Fn([f64; 3]) -> [f64; 3] + Sync),
    ) -> Result<(f64, f64), ElasticityError> {
        self.setup.l2_errors(v, exact)
    }
}

/// Every element matrix (row-major, `l x l` each, symmetric), in parallel.
///
/// `ids(e)` is the grid's number of the assembly's element `e` (`ne` of them: the whole grid,
/// or one process's elements, [`ElementAssembly::for_rows`]).
fn element_data<G: ShellGeometry + Sync>(
    setup: &SolidSetup<G>,
    ids: &(dyn Fn(usize) -> usize + Sync),
    ne: usize,
) -> Result<Vec<f64>, ElasticityError> {
    let element = setup.element();
    let len = setup.element_size();
    let full = ElementRule::new(element, element.gauss_1d(), len);
    let nen = full.nen;
    let l = COMPONENTS * nen;
    let reduced = (setup.volumetric == VolumetricIntegration::Reduced)
        .then(|| ElementRule::new(element, element.reduced_1d(), len));
    let mut data = vec![0.0; ne * l * l];
    let (lambda, mu) = (setup.material.lambda(), setup.material.mu());
    let full_lambda = if reduced.is_some() { 0.0 } else { lambda };
    data.par_chunks_mut(l * l).enumerate().try_for_each(
        |(e, out)| -> Result<(), ElasticityError> {
            let points = setup.element_points(ids(e), &full.points)?;
            for (q, (p, _)) in points.iter().enumerate() {
                let kq = energy_matrix(p, &SOLID, full_lambda, mu, full.weight(q));
                add_point(out, &kq, full.shape_at(q));
            }
            if let Some(rule) = &reduced {
                // lambda (div v)(div w) sqrt(g): a rank-one update per reduced point
                let points = setup.element_points(ids(e), &rule.points)?;
                let mut d = vec![0.0; l];
                for (r, (p, _)) in points.iter().enumerate() {
                    let c = lambda * p.sqrt_g * rule.weight(r);
                    let t = divergence_coefficients(p, &SOLID);
                    for (a, f) in rule.shape_at(r).iter().enumerate() {
                        for comp in 0..COMPONENTS {
                            d[COMPONENTS * a + comp] = t[comp] * f[0]
                                + t[3 + comp] * f[1]
                                + t[6 + comp] * f[2]
                                + t[9 + comp] * f[3];
                        }
                    }
                    for i in 0..l {
                        let ci = c * d[i];
                        for j in i..l {
                            out[i * l + j] += ci * d[j];
                        }
                    }
                }
            }
            // the lower triangle from the upper
            for i in 0..l {
                for j in 0..i {
                    out[i * l + j] = out[j * l + i];
                }
            }
            Ok(())
        },
    )?;
    Ok(data)
}
