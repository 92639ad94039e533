//! The matrix-free operator: construction (chart at the quadrature points, diagonal,
//! right-hand side) and its action.

use capstan_solvers::LinearOperator;
use rayon::prelude::*;

use super::kernel::{self, GEOMETRY, Tables};
use super::lanes::{LANES, Lanes};
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
/// `x1` slabs (no two slabs of a pass share a node), slabs in parallel. Q1 and Q2 run a
/// kernel compiled for their sizes on batches of 4 elements consecutive in `x3`, one per
/// vector lane (AVX2 when the CPU has it), with the next batch's chart prefetched; every lane
/// does the scalar kernel's operations in its order, so the result is the same bit for bit.
///
/// Memory: `31 (p + 1)^3` numbers per element (Q1: about 80 per unknown; Q2: 35; Qp4: 21)
/// plus the diagonal and the Dirichlet mask, against about 100 to 400 per unknown for the
/// assembled matrix. A chart invariant in `x1` (every slab's numbers equal the first's, as
/// on the prisms) is stored for one slab only: `1 / (elements in x1)` of that.
///
/// # Errors
/// See [`SolidMatrixFree::new`].
pub struct SolidMatrixFree<G> {
    pub(crate) setup: SolidSetup<G>,
    tables: Tables,
    geometry: Geometry,
    /// Slabs `x1 = const` of elements whose chart is stored: 1 when every slab's equals the
    /// first's (a chart invariant in `x1`, as the prisms'), else all of them.
    slabs: usize,
    lambda: f64,
    two_mu: f64,
    constrained: Vec<bool>,
    diagonal: Vec<f64>,
    rhs: Vec<f64>,
}

/// The chart at the quadrature points, `GEOMETRY` numbers a point.
enum Geometry {
    /// Element by element (element outer, then point): the general kernel.
    Elements(Vec<f64>),
    /// Batches of `LANES` elements consecutive in `x3` (column `(e1, e2)` outer, then batch,
    /// point, number; element `e3 = LANES j + l` in lane `l` of batch `j`, lanes past the
    /// column's end zero): the Q1 and Q2 kernels.
    Batches(Vec<Lanes>),
}

impl Geometry {
    /// Bytes held.
    fn bytes(&self) -> usize {
        match self {
            Self::Elements(v) => 8 * v.len(),
            Self::Batches(v) => 8 * LANES * v.len(),
        }
    }
}

/// `true` when the element has a kernel compiled for its size ([`Tables::element_batch`]):
/// Q1 and Q2 with their Gauss rules.
fn batch_kernel(np: usize, nq: usize) -> bool {
    matches!((np, nq), (2, 2) | (3, 3))
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
        // the chart at the points and the diagonal of element e
        let element_data = |e: usize| -> Result<(Vec<f64>, Vec<f64>), ElasticityError> {
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
        };
        // slab by slab (elements in parallel): the charts of slab 0 are kept, and those of
        // every slab only once one differs from slab 0's (a chart that is not invariant in x1)
        let [ne1, ne2, ne3] = setup.elements;
        let slab = ne2 * ne3;
        let mut diagonal = vec![0.0; setup.dof_count()];
        let mut first: Vec<Vec<f64>> = Vec::new();
        let mut every: Option<Vec<Vec<f64>>> = None;
        for e1 in 0..ne1 {
            let data: Vec<(Vec<f64>, Vec<f64>)> = (e1 * slab..(e1 + 1) * slab)
                .into_par_iter()
                .map(element_data)
                .collect::<Result<_, _>>()?;
            let mut charts = Vec::with_capacity(slab);
            for (i, (geo, diag)) in data.into_iter().enumerate() {
                for (a, node) in setup.element_nodes(e1 * slab + i).into_iter().enumerate() {
                    for c in 0..COMPONENTS {
                        diagonal[COMPONENTS * node + c] += diag[COMPONENTS * a + c];
                    }
                }
                charts.push(geo);
            }
            if e1 == 0 {
                first = charts;
            } else if let Some(all) = &mut every {
                all.extend(charts);
            } else if charts != first {
                let mut all = Vec::with_capacity(ne1 * slab);
                for _ in 0..e1 {
                    all.extend(first.iter().cloned());
                }
                all.extend(charts);
                every = Some(all);
            }
        }
        let (slabs, charts) = match every {
            Some(all) => (ne1, all),
            None => (1, first),
        };
        let batches = ne3.div_ceil(LANES);
        let mut geometry = if batch_kernel(tables.np, tables.nq) {
            let columns = slabs * ne2;
            Geometry::Batches(vec![Lanes::default(); columns * batches * nq3 * GEOMETRY])
        } else {
            Geometry::Elements(Vec::with_capacity(slabs * slab * nq3 * GEOMETRY))
        };
        for (e, geo) in charts.into_iter().enumerate() {
            match &mut geometry {
                Geometry::Elements(all) => all.extend_from_slice(&geo),
                Geometry::Batches(all) => {
                    // element e = column ne3 + e3: batch column batches + e3 / LANES, lane e3 % LANES
                    let (column, e3) = (e / ne3, e % ne3);
                    let start = (column * batches + e3 / LANES) * nq3 * GEOMETRY;
                    for (to, &from) in all[start..start + nq3 * GEOMETRY].iter_mut().zip(&geo) {
                        to.0[e3 % LANES] = from;
                    }
                }
            }
        }
        let constrained: Vec<bool> = setup.dirichlet.iter().map(Option::is_some).collect();
        let load = setup.load(boundary, body_force)?;
        let mut op = Self {
            setup,
            tables,
            geometry,
            slabs,
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

    /// Slabs `x1 = const` of elements whose chart is stored: 1 when the chart is invariant in
    /// `x1` (every slab's quadrature numbers equal the first's, as on the prisms), else the
    /// number of elements in `x1`.
    pub fn stored_slabs(&self) -> usize {
        self.slabs
    }

    /// Bytes held by the operator (quadrature data, diagonal, mask, right-hand side).
    pub fn bytes(&self) -> usize {
        self.geometry.bytes() + 8 * (self.diagonal.len() + self.rhs.len()) + self.constrained.len()
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
                    || {
                        let work = (vec![0.0; 3 * nn], vec![0.0; 3 * nn], vec![0; np * np]);
                        (self.tables.scratch(), work)
                    },
                    |(scratch, (u, out, rows)), (j, chunk)| {
                        let e1 = 2 * j + parity;
                        if e1 >= ne1 {
                            return;
                        }
                        let base = e1 * k * plane;
                        for e2 in 0..ne2 {
                            // first dof of the node line (a1, a2, x3 = 0) of the column (e1, e2)
                            for a1 in 0..np {
                                for a2 in 0..np {
                                    rows[a1 * np + a2] =
                                        COMPONENTS * ((k * e1 + a1) * n2 + (k * e2 + a2) % n2) * n3;
                                }
                            }
                            let column = (e1 % self.slabs) * ne2 + e2;
                            match &self.geometry {
                                Geometry::Elements(geometry) => {
                                    for e3 in 0..ne3 {
                                        let first = COMPONENTS * k * e3;
                                        gather(
                                            x,
                                            mask,
                                            &self.constrained,
                                            rows,
                                            first,
                                            np,
                                            |i, v| {
                                                u[i] = v;
                                            },
                                        );
                                        let e = column * ne3 + e3;
                                        self.tables.element(
                                            &geometry[e * per_element..(e + 1) * per_element],
                                            self.lambda,
                                            self.two_mu,
                                            u,
                                            out,
                                            scratch,
                                        );
                                        scatter(chunk, rows, first, base, np, |i| out[i]);
                                    }
                                }
                                Geometry::Batches(geometry) => {
                                    let batches = ne3.div_ceil(LANES);
                                    let mut ub = [Lanes::default(); 3 * 27];
                                    let mut yb = [Lanes::default(); 3 * 27];
                                    for jb in 0..batches {
                                        let lanes = LANES.min(ne3 - LANES * jb);
                                        for l in 0..lanes {
                                            let first = COMPONENTS * k * (LANES * jb + l);
                                            gather(
                                                x,
                                                mask,
                                                &self.constrained,
                                                rows,
                                                first,
                                                np,
                                                |i, v| {
                                                    ub[i].0[l] = v;
                                                },
                                            );
                                        }
                                        let at = (column * batches + jb) * per_element;
                                        let geo = &geometry[at..at + per_element];
                                        // the next batch's chart, stored right after this one
                                        prefetch(
                                            geometry.get(at + per_element..at + 2 * per_element),
                                        );
                                        let (lambda, two_mu) = (self.lambda, self.two_mu);
                                        if np == 2 {
                                            self.tables.element_batch::<2, 2, 8, 8>(
                                                geo, lambda, two_mu, &ub, &mut yb,
                                            );
                                        } else {
                                            self.tables.element_batch::<3, 3, 27, 27>(
                                                geo, lambda, two_mu, &ub, &mut yb,
                                            );
                                        }
                                        for l in 0..lanes {
                                            let first = COMPONENTS * k * (LANES * jb + l);
                                            scatter(chunk, rows, first, base, np, |i| yb[i].0[l]);
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

/// Asks the CPU to bring `data` into its caches (a hint, no effect on results): the chart of
/// the next batch is loaded while this one is computed.
#[inline(always)]
fn prefetch(data: Option<&[Lanes]>) {
    #[cfg(target_arch = "x86_64")]
    if let Some(data) = data {
        use core::arch::x86_64::{_MM_HINT_T0, _mm_prefetch};
        // two Lanes (64 bytes) a cache line
        for line in data.chunks(2) {
            // SAFETY: a prefetch is a hint: it never faults, reads nothing observable and
            // needs only SSE, which every x86_64 CPU has.
            unsafe { _mm_prefetch::<_MM_HINT_T0>(line.as_ptr().cast()) };
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = data;
}

/// Gathers the local values of one element (component outer, then node `(a1, a2, a3)`):
/// `put(c np^3 + a, x_d)` for its dofs `d`, the constrained ones as zero when `mask`. `rows`
/// holds the first dof of each of its `np^2` node lines `(a1, a2)`, `first` the offset of its
/// first node along them.
#[inline(always)]
fn gather(
    x: &[f64],
    mask: bool,
    constrained: &[bool],
    rows: &[usize],
    first: usize,
    np: usize,
    mut put: impl FnMut(usize, f64),
) {
    let nn = np * np * np;
    for (line, &row) in rows.iter().enumerate() {
        let at = row + first;
        let xs = &x[at..at + COMPONENTS * np];
        let cs = &constrained[at..at + COMPONENTS * np];
        for a3 in 0..np {
            for c in 0..COMPONENTS {
                let i = COMPONENTS * a3 + c;
                put(
                    c * nn + line * np + a3,
                    if mask && cs[i] { 0.0 } else { xs[i] },
                );
            }
        }
    }
}

/// Adds one element's local result `get(c np^3 + a)` into `chunk`, the dofs from `base` on
/// (offsets as in [`gather`]).
#[inline(always)]
fn scatter(
    chunk: &mut [f64],
    rows: &[usize],
    first: usize,
    base: usize,
    np: usize,
    get: impl Fn(usize) -> f64,
) {
    let nn = np * np * np;
    for (line, &row) in rows.iter().enumerate() {
        let at = row + first - base;
        let ys = &mut chunk[at..at + COMPONENTS * np];
        for a3 in 0..np {
            for c in 0..COMPONENTS {
                ys[COMPONENTS * a3 + c] += get(c * nn + line * np + a3);
            }
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
