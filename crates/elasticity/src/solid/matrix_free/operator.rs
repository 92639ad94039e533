//! The matrix-free operator: construction (chart at the quadrature points, diagonal,
//! right-hand side) and its action.

use capstan_solvers::LinearOperator;
use rayon::prelude::*;

use super::kernel::{self, GEOMETRY, Scratch, Tables};
use crate::continuum::{SOLID, energy_matrix};
use crate::error::ElasticityError;
use crate::finite_element::VolumetricIntegration;
use crate::material::Material;
use crate::shell_geometry::ShellGeometry;
use crate::solid::boundary::SolidBoundary;
use crate::solid::element::{ElementRule, HexElement};
use crate::solid::grid::BoxGrid;
use crate::solid::setup::{COMPONENTS, SolidForce, SolidSetup};

/// The curvilinear Navier operator of a 3-D body by Q1, Q2 or Qp hexahedra, matrix-free:
/// the same operator as [`crate::solid::SolidNavier`] (same weak form, quadrature and Dirichlet
/// elimination), applied by sum factorisation.
///
/// # Math
/// ```text
/// y = A x = sum_e R_e^T sum_q B_q^T K_q B_q R_e x        (K_q: the 12 x 12 energy matrix)
/// B_q R_e x at the (p + 1)^3 Gauss points: values and d_1, d_2, d_3 of each component by
///   contractions with the 1-D tables B[q][a] = l_a(xi_q), D[q][a] = l_a'(xi_q) one direction
///   at a time: O(p^4) per element instead of O(p^6)
/// K_q applied pointwise (kernel: N = nabla v, E, M = g^-1 E, T = lambda tr M + 2 mu M) from
///   31 numbers per point: s = sqrt(g) w, g_ij, g^ij, Gamma^n_im (stored once)
/// Dirichlet dof d (symmetric elimination, as assembled):  y_d = A_dd x_d, and x_d does not
///   enter the free rows
/// ```
/// The diagonal `A_dd` is computed without assembly (per element `sum_q phi^T K_q phi` over
/// the four entries of each local dof). Elements are applied in two passes of alternating
/// `x1` slabs (no two slabs of a pass share a node), slabs in parallel.
///
/// Memory: `31 (p + 1)^3` numbers per element (Q1: about 80 per unknown; Q2: 35; Qp4: 21)
/// plus the diagonal and the Dirichlet mask, against about 100 to 400 per unknown for the
/// assembled matrix.
///
/// # Errors
/// See [`SolidMatrixFree::new`].
pub struct SolidMatrixFree<G> {
    pub(crate) setup: SolidSetup<G>,
    tables: Tables,
    geometry: Vec<f64>,
    lambda: f64,
    two_mu: f64,
    constrained: Vec<bool>,
    diagonal: Vec<f64>,
    rhs: Vec<f64>,
}

impl<G> core::fmt::Debug for SolidMatrixFree<G> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("SolidMatrixFree")
            .field("element", &self.setup.lines.element())
            .field("grid", &self.setup.grid)
            .finish_non_exhaustive()
    }
}

impl<G: ShellGeometry + Sync> SolidMatrixFree<G> {
    /// Builds the operator: the chart at every quadrature point, the diagonal and the
    /// right-hand side (loads with the Dirichlet lifting), as [`crate::solid::SolidNavier::new`]
    /// with the same arguments.
    ///
    /// # Errors
    /// The errors of [`crate::solid::SolidNavier::new`]; [`ElasticityError::InvalidParameter`]
    /// naming `discretisation.volumetric` for [`VolumetricIntegration::Reduced`] (not
    /// implemented matrix-free).
    pub fn new(
        chart: G,
        material: Material,
        grid: BoxGrid,
        boundary: &SolidBoundary,
        body_force: Option<&SolidForce>,
        element: impl Into<HexElement>,
        volumetric: VolumetricIntegration,
    ) -> Result<Self, ElasticityError> {
        if volumetric != VolumetricIntegration::Full {
            return Err(ElasticityError::InvalidParameter {
                field: "discretisation.volumetric",
                value: f64::NAN,
                allowed: "full with the matrix-free operator",
            });
        }
        let setup = SolidSetup::new(chart, material, grid, boundary, element.into(), volumetric)?;
        let element = setup.element();
        let len = setup.element_size();
        let gauss = element.gauss_1d();
        let tables = Tables::new(
            element.nodes_per_direction(),
            &gauss.0,
            |xi| element.shape_1d(xi),
            len,
        );
        let rule = ElementRule::new(element, gauss, len);
        let (lambda, mu) = (material.lambda(), material.mu());
        let nq3 = tables.nq.pow(3);
        let nen = element.nodes_per_element();
        // the chart at the points and the element diagonals, in parallel
        let per_element: Vec<(Vec<f64>, Vec<f64>)> = (0..setup.element_count())
            .into_par_iter()
            .map(|e| -> Result<(Vec<f64>, Vec<f64>), ElasticityError> {
                let points = setup.element_points(e, &rule.points)?;
                let mut geo = vec![0.0; nq3 * GEOMETRY];
                let mut diag = vec![0.0; COMPONENTS * nen];
                for (q, (p, _)) in points.iter().enumerate() {
                    let w = rule.weight(q);
                    kernel::pack(p, w, &mut geo[q * GEOMETRY..(q + 1) * GEOMETRY]);
                    let k = energy_matrix(p, &SOLID, lambda, mu, w);
                    for (a, phi) in rule.shape_at(q).iter().enumerate() {
                        for c in 0..COMPONENTS {
                            let idx = [c, 3 + c, 6 + c, 9 + c];
                            let mut s = 0.0;
                            for (r, &ir) in idx.iter().enumerate() {
                                for (t, &it) in idx.iter().enumerate() {
                                    s += phi[r] * phi[t] * k[ir][it];
                                }
                            }
                            diag[COMPONENTS * a + c] += s;
                        }
                    }
                }
                Ok((geo, diag))
            })
            .collect::<Result<_, _>>()?;
        let mut diagonal = vec![0.0; setup.dof_count()];
        let mut geometry = Vec::with_capacity(setup.element_count() * nq3 * GEOMETRY);
        for (e, (geo, diag)) in per_element.into_iter().enumerate() {
            geometry.extend_from_slice(&geo);
            for (a, node) in setup.element_nodes(e).into_iter().enumerate() {
                for c in 0..COMPONENTS {
                    diagonal[COMPONENTS * node + c] += diag[COMPONENTS * a + c];
                }
            }
        }
        let constrained: Vec<bool> = setup.dirichlet.iter().map(Option::is_some).collect();
        let load = setup.load(boundary, body_force)?;
        let mut op = Self {
            setup,
            tables,
            geometry,
            lambda,
            two_mu: 2.0 * mu,
            constrained,
            diagonal,
            rhs: Vec::new(),
        };
        op.rhs = op.lifted(load)?;
        Ok(op)
    }

    /// The right-hand side of the same operator for other loads: `boundary` (with the same
    /// Dirichlet conditions as the operator's, only its tractions and stresses read) and
    /// `body_force`, with the operator's Dirichlet lifting.
    ///
    /// # Errors
    /// Boundary-data errors as [`SolidMatrixFree::new`]; [`ElasticityError::NonFinite`].
    pub fn rhs_for(
        &self,
        boundary: &SolidBoundary,
        body_force: Option<&SolidForce>,
    ) -> Result<Vec<f64>, ElasticityError> {
        let load = self.setup.load(boundary, body_force)?;
        self.lifted(load)
    }

    /// `load` with the Dirichlet lifting:
    /// ```text
    /// b_f = l_f - A_fd g_d,   b_d = A_dd g_d
    /// ```
    fn lifted(&self, load: Vec<f64>) -> Result<Vec<f64>, ElasticityError> {
        let lift: Vec<f64> = self
            .setup
            .dirichlet
            .iter()
            .map(|g| g.unwrap_or(0.0))
            .collect();
        let mut a_lift = vec![0.0; lift.len()];
        self.apply_elements(&lift, &mut a_lift, false);
        let rhs: Vec<f64> = load
            .iter()
            .zip(&a_lift)
            .enumerate()
            .map(|(d, (l, a))| match self.setup.dirichlet[d] {
                Some(g) => self.diagonal[d] * g,
                None => l - a,
            })
            .collect();
        if let Some(d) = rhs.iter().position(|v| !v.is_finite()) {
            let x = self
                .setup
                .grid
                .coordinates(self.setup.grid.node(d / COMPONENTS));
            return Err(ElasticityError::NonFinite {
                what: "matrix-free right-hand side",
                at: [x[1], x[2]],
            });
        }
        Ok(rhs)
    }

    /// The L2 error norms of `v` against `exact` (see [`crate::solid::SolidNavier::l2_errors`]).
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

impl<G: Sync> SolidMatrixFree<G> {
    /// The grid.
    pub fn grid(&self) -> &BoxGrid {
        &self.setup.grid
    }

    /// The element.
    pub fn element(&self) -> HexElement {
        self.setup.lines.element()
    }

    /// Number of unknowns, `3 n1 n2 n3`.
    pub fn dof_count(&self) -> usize {
        self.constrained.len()
    }

    /// The right-hand side `b` of `A v = b` (equal to the assembled one to round-off).
    pub fn rhs(&self) -> &[f64] {
        &self.rhs
    }

    /// `true` for the dofs with a prescribed value (numbering `3 node + c`).
    pub fn constrained(&self) -> &[bool] {
        &self.constrained
    }

    /// The material.
    pub fn material(&self) -> Material {
        self.setup.material
    }

    /// Bytes held by the operator (quadrature data, diagonal, mask, right-hand side).
    pub fn bytes(&self) -> usize {
        8 * (self.geometry.len() + self.diagonal.len() + self.rhs.len()) + self.constrained.len()
    }

    /// `y = sum_e R_e^T A_e R_e x` over every element, the input's constrained entries
    /// zeroed when `mask` (the rows of constrained dofs are left as the elements give them).
    fn apply_elements(&self, x: &[f64], y: &mut [f64], mask: bool) {
        let [_, n2, n3] = self.setup.grid.counts();
        let [ne1, ne2, ne3] = self.setup.elements;
        let k = self.element().degree();
        let (np, nq) = (self.tables.np, self.tables.nq);
        let nn = np * np * np;
        let per_element = nq.pow(3) * GEOMETRY;
        let plane = COMPONENTS * n2 * n3;
        y.fill(0.0);
        // slab e1 touches the node planes k e1 ..= k e1 + k: alternate slabs share none
        for parity in 0..2 {
            let start = parity * k * plane;
            if start >= y.len() {
                continue;
            }
            y[start..]
                .par_chunks_mut(2 * k * plane)
                .enumerate()
                .for_each_init(
                    || (self.tables.scratch(), vec![0.0; 3 * nn], vec![0.0; 3 * nn]),
                    |(scratch, u, out): &mut (Scratch, Vec<f64>, Vec<f64>), (j, chunk)| {
                        let e1 = 2 * j + parity;
                        if e1 >= ne1 {
                            return;
                        }
                        let base = e1 * k * plane;
                        for e2 in 0..ne2 {
                            for e3 in 0..ne3 {
                                let e = (e1 * ne2 + e2) * ne3 + e3;
                                let dof = |a1: usize, a2: usize, a3: usize| {
                                    let node = ((k * e1 + a1) * n2 + (k * e2 + a2) % n2) * n3
                                        + k * e3
                                        + a3;
                                    COMPONENTS * node
                                };
                                let mut a = 0;
                                for a1 in 0..np {
                                    for a2 in 0..np {
                                        for a3 in 0..np {
                                            let d = dof(a1, a2, a3);
                                            for c in 0..COMPONENTS {
                                                u[c * nn + a] = if mask && self.constrained[d + c] {
                                                    0.0
                                                } else {
                                                    x[d + c]
                                                };
                                            }
                                            a += 1;
                                        }
                                    }
                                }
                                self.tables.element(
                                    &self.geometry[e * per_element..(e + 1) * per_element],
                                    self.lambda,
                                    self.two_mu,
                                    u,
                                    out,
                                    scratch,
                                );
                                let mut a = 0;
                                for a1 in 0..np {
                                    for a2 in 0..np {
                                        for a3 in 0..np {
                                            let d = dof(a1, a2, a3) - base;
                                            for c in 0..COMPONENTS {
                                                chunk[d + c] += out[c * nn + a];
                                            }
                                            a += 1;
                                        }
                                    }
                                }
                            }
                        }
                    },
                );
        }
    }
}

impl<G: Sync> LinearOperator for SolidMatrixFree<G> {
    fn dimension(&self) -> usize {
        self.constrained.len()
    }

    fn apply(&self, x: &[f64], y: &mut [f64]) {
        assert!(
            x.len() == self.dimension() && y.len() == self.dimension(),
            "lengths of A x"
        );
        self.apply_elements(x, y, true);
        y.par_iter_mut()
            .zip(&self.constrained)
            .zip(&self.diagonal)
            .zip(x)
            .for_each(|(((yi, &c), &d), &xi)| {
                if c {
                    *yi = d * xi;
                }
            });
    }

    fn diagonal(&self) -> Vec<f64> {
        self.diagonal.clone()
    }
}
