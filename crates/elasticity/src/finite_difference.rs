//! Second-order finite differences (vertex-centred finite volumes) for the plane-strain
//! curvilinear Navier operator.

use capstan_geometry::ShellPoint;
use rayon::prelude::*;

use crate::boundary::{Component, ComponentCondition, Side};
use crate::continuum::check_plane_strain;
use crate::continuum::kinematics::{
    LocalDisplacement, christoffel_contraction, contravariant_stress, mixed_stress_coefficients,
};
use crate::discretisation::{ContactNode, Discretisation, LinearSystem, RowBlock, SparseRow};
use crate::error::ElasticityError;
use crate::fields::NodalFields;
use crate::plane_problem::PlaneProblem;
use crate::plane_strain_operator::{plane_strain_numbering, setup_accessors};
use crate::shell_geometry::ShellGeometry;

/// Coefficients of two scalar linear functionals (one per equation `j = 2, 3`) of the six
/// local inputs `[v^2, v^3, d_2 v^2, d_2 v^3, d_3 v^2, d_3 v^3]`.
type Coefficients = [[f64; 6]; 2];

/// Stencil weights `[value, d_2, d_3]` of one node in a local reconstruction.
type Stencil = Vec<([usize; 2], [f64; 3])>;

/// Rows per parallel block of [`FiniteDifferenceNavier`]'s assembly.
const ROW_BLOCK: usize = 2048;

/// Rows remembered by [`SortOrders`]: one per row shape of a grid's stencils (interior,
/// edges, corners, both equations) fits.
const SORT_ORDER_CACHE: usize = 16;

/// The order in which `terms.sort_unstable_by_key(|t| t.0)` puts a row's terms, remembered
/// per row shape: rows whose columns are the same offsets from the row (the interior rows of
/// a grid) are put in the same order without sorting again.
///
/// # Math
/// An unstable sort's permutation is a function of its comparisons' outcomes alone, and
/// those depend on the keys' order alone, which a common shift `c -> c + d` keeps. Sorting
/// `(column, position as f64)` pairs (the same element type, the same key) therefore moves
/// the positions exactly as the sort moves the terms, including the order of equal columns:
/// the merged row, sums included, is the same bit for bit as after sorting the terms.
#[derive(Default)]
struct SortOrders {
    /// `(column - row offsets, positions in sorted order)` per remembered shape, the most
    /// recently used first.
    shapes: Vec<(Vec<isize>, Vec<u32>)>,
    /// Scratch for a new shape.
    pairs: Vec<(usize, f64)>,
}

impl SortOrders {
    /// The positions of `terms` (row `d`) in the order of their sort by column.
    fn order(&mut self, d: usize, terms: &[(usize, f64)]) -> &[u32] {
        let offset = |c: usize| c as isize - d as isize;
        let same = |shape: &[isize]| {
            shape.len() == terms.len() && shape.iter().zip(terms).all(|(&o, t)| o == offset(t.0))
        };
        if let Some(at) = self.shapes.iter().position(|(shape, _)| same(shape)) {
            self.shapes[..=at].rotate_right(1);
        } else {
            self.pairs.clear();
            self.pairs
                .extend(terms.iter().enumerate().map(|(k, t)| (t.0, k as f64)));
            self.pairs.sort_unstable_by_key(|t| t.0);
            let shape = terms.iter().map(|t| offset(t.0)).collect();
            let order = self.pairs.iter().map(|t| t.1 as u32).collect();
            if self.shapes.len() == SORT_ORDER_CACHE {
                self.shapes.pop();
            }
            self.shapes.insert(0, (shape, order));
        }
        &self.shapes[0].1
    }
}

/// The geometry cached at the grid column `x2_i` (see the fields of [`FiniteDifferenceNavier`]).
struct CachedColumn {
    source: Vec<Coefficients>,
    node_scale: Vec<[f64; 3]>,
    contact: Option<(Coefficients, f64)>,
    east: Vec<Coefficients>,
    north: Vec<Coefficients>,
}

/// The plane-strain curvilinear Navier operator by second-order finite differences on an
/// `n2 x n3` grid, with the geometry cached once.
///
/// # Math
/// The equilibrium equations `nabla_i T^i_j + f_j = 0` (`j = 2, 3`) in conservative form,
/// ```text
/// d_a (sqrt(g) T^a_j) - sqrt(g) Gamma^k_ij T^i_k + sqrt(g) f_j = 0      (a = 2, 3; d_1 = 0)
/// T^i_j = lambda E^m_m delta^i_j + 2 mu g^ik E_kj,   E_kl = (nabla_k v_l + nabla_l v_k)/2
/// nabla_k v_l = g_ln (d_k v^n + Gamma^n_km v^m)                          (v^1 = 0)
/// ```
/// are integrated over the control volume of each node, `[x2 -+ dx2/2] x [x3 -+ dx3/2]`
/// clipped to the rectangle (half and quarter cells on the boundary). Row `(i2, i3, j)` is
/// ```text
/// -(1/|V|) sum_faces (outward flux sqrt(g) T^a_j) |face| + sqrt(g) Gamma^k_ij T^i_k = sqrt(g) f_j
/// ```
/// Fluxes are evaluated at face midpoints with the geometry there: on an `x2` face
/// `v = (v_i + v_{i+1})/2`, `d_2 v = (v_{i+1} - v_i)/dx2` and `d_3 v` the mean of the nodal
/// central differences (second-order one-sided on boundaries); likewise on `x3` faces. The
/// Christoffel term uses nodal differences. On a boundary face the outward flux is the data:
/// `sqrt(g) sqrt(g^aa) t_j` for a traction, `s sqrt(g) T^a_j` for a stress condition. Dirichlet
/// rows are `s v^c = s f` with `s = (lambda + 2 mu)/dx3^2` (a scale like the balance rows').
///
/// Only the chart's metric, inverse metric, `sqrt(g)` and Christoffel symbols are used: a new
/// obstacle needs no new code here. The chart must be `x1`-invariant (a prism); this is
/// checked at every cached point.
///
/// # Errors
/// See [`FiniteDifferenceNavier::new`].
///
/// # Example
/// ```
/// use capstan_elasticity::{BoundaryConditions, Discretisation, FiniteDifferenceNavier, Grid};
/// use capstan_elasticity::{Material, PlaneProblem};
/// use capstan_geometry::{EllipticalPrism, ShellChart};
/// use capstan_solvers::SparseLu;
/// let chart = ShellChart::new(EllipticalPrism::new(2.0, 2.0).unwrap());
/// let grid = Grid::new([-1.5707963, 1.5707963], 1.0, 25, 5, false).unwrap();
/// let bc = BoundaryConditions::paper_clamped(1.0, 1.0);
/// let material = Material::new(1e3, 0.25).unwrap();
/// let problem = PlaneProblem { chart, material, grid, boundary: bc, body_force: None };
/// let op = FiniteDifferenceNavier::new(problem).unwrap();
/// let v = op.solve(&mut SparseLu::default()).unwrap();
/// // equal end tensions: the tangential displacement is odd in x2
/// let (left, right) = (v[op.dof([0, 4], capstan_elasticity::Component::X2)], v[op.dof([24, 4], capstan_elasticity::Component::X2)]);
/// assert!(left < 0.0 && (left + right).abs() < 1e-10);
/// ```
pub struct FiniteDifferenceNavier<G> {
    /// The problem (its body force is evaluated row by row).
    problem: PlaneProblem<G>,
    /// `sqrt(g) Gamma^k_ij T^i_k` coefficients at the nodes.
    source: Vec<Coefficients>,
    /// `[sqrt(g), sqrt(g^22), sqrt(g^33)]` at the nodes.
    node_scale: Vec<[f64; 3]>,
    /// `sqrt(g) T^2_j` at `(x2_i + dx2/2, x3_j)`, index `i n3 + j`.
    east: Vec<Coefficients>,
    /// `sqrt(g) T^3_j` at `(x2_i, x3_j + dx3/2)`, index `i (n3 - 1) + j`.
    north: Vec<Coefficients>,
    /// `[T^3_2, T^3_3]` coefficients and `sqrt(g_22)` on `x3 = 0`.
    contact: Vec<(Coefficients, f64)>,
    /// Prescribed value of each dof, `None` for a balance row.
    dirichlet: Vec<Option<f64>>,
    dirichlet_scale: f64,
}

impl<G> core::fmt::Debug for FiniteDifferenceNavier<G> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        self.problem.debug_fields(f, "FiniteDifferenceNavier", None)
    }
}

impl<G: ShellGeometry + Sync> FiniteDifferenceNavier<G> {
    /// Builds the operator and caches the geometry at the nodes and face midpoints.
    ///
    /// # Errors
    /// [`ElasticityError::InconsistentBoundary`] if periodicity of grid and conditions differ or
    /// a pinned node is outside the grid; [`ElasticityError::Geometry`] where the chart cannot
    /// be evaluated (e.g. past the focal surface); [`ElasticityError::NotPlaneStrain`] for a
    /// chart that is not `x1`-invariant; [`ElasticityError::NonFinite`] for non-finite
    /// Dirichlet data.
    pub fn new(problem: PlaneProblem<G>) -> Result<Self, ElasticityError> {
        problem.boundary.check_grid(&problem.grid)?;
        let (chart, material, grid) = (&problem.chart, problem.material, problem.grid);
        let (n2, n3) = (grid.n2(), grid.n3());
        let (dx2, dx3) = (grid.dx2(), grid.dx3());
        // One column of points above each `x2` (the chart's frame once per column), the
        // columns in parallel: the same points bit for bit as `shell_point` one by one.
        let nodes: Vec<f64> = (0..n3).map(|j| grid.x3(j)).collect();
        let mids: Vec<f64> = (0..n3 - 1).map(|j| grid.x3(j) + 0.5 * dx3).collect();
        let column = |x2: f64,
                      heights: &[f64],
                      out: &mut Vec<ShellPoint<f64>>|
         -> Result<(), ElasticityError> {
            out.clear();
            chart.shell_column([0.0, x2], heights, out)?;
            for (p, &x3) in out.iter().zip(heights) {
                check_plane_strain(p, [0.0, x2, x3])?;
            }
            Ok(())
        };
        let flux = |p: &ShellPoint<f64>, a: usize| -> Coefficients {
            let c = mixed_stress_coefficients(p, &material);
            core::array::from_fn(|e| core::array::from_fn(|k| p.sqrt_g * c[k][a][e + 1]))
        };
        let n_east = if grid.is_periodic() { n2 } else { n2 - 1 };
        let columns = (0..n2)
            .into_par_iter()
            .map_init(
                Vec::new,
                |pts, i| -> Result<CachedColumn, ElasticityError> {
                    column(grid.x2(i), &nodes, pts)?;
                    let mut cached = CachedColumn {
                        source: Vec::with_capacity(n3),
                        node_scale: Vec::with_capacity(n3),
                        contact: None,
                        east: Vec::with_capacity(n3),
                        north: Vec::with_capacity(n3 - 1),
                    };
                    for (j, p) in pts.iter().enumerate() {
                        let c = mixed_stress_coefficients(p, &material);
                        cached.source.push(core::array::from_fn(|e| {
                            core::array::from_fn(|k| {
                                p.sqrt_g * christoffel_contraction(p, &c[k], e + 1)
                            })
                        }));
                        cached.node_scale.push([
                            p.sqrt_g,
                            p.inverse_metric[1][1].sqrt(),
                            p.inverse_metric[2][2].sqrt(),
                        ]);
                        if j == 0 {
                            let t3: Coefficients =
                                core::array::from_fn(|e| core::array::from_fn(|k| c[k][2][e + 1]));
                            cached.contact = Some((t3, p.metric[1][1].sqrt()));
                        }
                    }
                    if i < n_east {
                        column(grid.x2(i) + 0.5 * dx2, &nodes, pts)?;
                        cached.east.extend(pts.iter().map(|p| flux(p, 1)));
                    }
                    column(grid.x2(i), &mids, pts)?;
                    cached.north.extend(pts.iter().map(|p| flux(p, 2)));
                    Ok(cached)
                },
            )
            .collect::<Result<Vec<_>, _>>()?;
        let mut source = Vec::with_capacity(grid.node_count());
        let mut node_scale = Vec::with_capacity(grid.node_count());
        let mut contact = Vec::with_capacity(n2);
        let mut east = Vec::with_capacity(n_east * n3);
        let mut north = Vec::with_capacity(n2 * (n3 - 1));
        for c in columns {
            source.extend(c.source);
            node_scale.extend(c.node_scale);
            contact.extend(c.contact);
            east.extend(c.east);
            north.extend(c.north);
        }
        let mut op = Self {
            dirichlet_scale: (material.lambda() + 2.0 * material.mu()) / (dx3 * dx3),
            problem,
            source,
            node_scale,
            east,
            north,
            contact,
            dirichlet: vec![],
        };
        op.dirichlet = op.problem.dirichlet_values(|node| grid.coordinates(node))?;
        Ok(op)
    }

    setup_accessors!();

    /// Face `(i + 1/2, j)` between nodes `i` and `ip`.
    fn east_stencil(&self, i: usize, ip: usize, j: usize, out: &mut Stencil) {
        out.clear();
        let w = 1.0 / self.problem.grid.dx2();
        out.push(([i, j], [0.5, -w, 0.0]));
        out.push(([ip, j], [0.5, w, 0.0]));
        for (jj, w3) in self.problem.grid.d3_stencil(j) {
            out.push(([i, jj], [0.0, 0.0, 0.5 * w3]));
            out.push(([ip, jj], [0.0, 0.0, 0.5 * w3]));
        }
    }

    /// Face `(i, j + 1/2)`.
    fn north_stencil(&self, i: usize, j: usize, out: &mut Stencil) {
        out.clear();
        let w = 1.0 / self.problem.grid.dx3();
        out.push(([i, j], [0.5, 0.0, -w]));
        out.push(([i, j + 1], [0.5, 0.0, w]));
        for (ii, w2) in self.problem.grid.d2_stencil(i) {
            out.push(([ii, j], [0.0, 0.5 * w2, 0.0]));
            out.push(([ii, j + 1], [0.0, 0.5 * w2, 0.0]));
        }
    }

    fn add_terms(
        &self,
        terms: &mut Vec<(usize, f64)>,
        scale: f64,
        coef: &Coefficients,
        e: usize,
        stencil: &Stencil,
    ) {
        for (node, w) in stencil {
            for c in 0..2 {
                let a = coef[e][c] * w[0] + coef[e][2 + c] * w[1] + coef[e][4 + c] * w[2];
                terms.push((self.dof(*node, Component::ALL[c]), scale * a));
            }
        }
    }

    /// Outward parameter-space flux `s sqrt(g) T^a_e` through `side` at `node`, from the data.
    fn boundary_flux(
        &self,
        side: Side,
        e: usize,
        node: [usize; 2],
    ) -> Result<f64, ElasticityError> {
        let k = self.problem.grid.node_index(node);
        let [sqrt_g, s22, s33] = self.node_scale[k];
        let x = self.problem.grid.coordinates(node);
        let s = if side.normal_index() == 1 { x[1] } else { x[0] };
        let cond = self
            .problem
            .boundary
            .side(side)
            .ok_or(ElasticityError::InconsistentBoundary {
                what: "no condition on a bounded side",
            })?
            .component(Component::ALL[e]);
        let value = match cond {
            ComponentCondition::Traction(f) => {
                let normal = if side.normal_index() == 1 { s22 } else { s33 };
                sqrt_g * normal * f.eval(s)
            }
            ComponentCondition::Stress(f) => side.sign() * sqrt_g * f.eval(s),
            ComponentCondition::Displacement(_) => {
                return Err(ElasticityError::InconsistentBoundary {
                    what: "a balance row on a side with a prescribed displacement",
                });
            }
        };
        if !value.is_finite() {
            return Err(ElasticityError::NonFinite {
                what: "boundary traction",
                at: x,
            });
        }
        Ok(value)
    }

    /// The terms and right-hand side of the row of dof `d`.
    fn row(
        &self,
        d: usize,
        terms: &mut Vec<(usize, f64)>,
        st: &mut Stencil,
    ) -> Result<f64, ElasticityError> {
        terms.clear();
        if let Some(value) = self.dirichlet[d] {
            terms.push((d, self.dirichlet_scale));
            return Ok(self.dirichlet_scale * value);
        }
        let node @ [i, j] = self.problem.grid.node(d / 2);
        let e = d % 2;
        let (n2, n3, periodic) = (
            self.problem.grid.n2(),
            self.problem.grid.n3(),
            self.problem.grid.is_periodic(),
        );
        let (dx2, dx3) = (self.problem.grid.dx2(), self.problem.grid.dx3());
        let h2 = if !periodic && (i == 0 || i == n2 - 1) {
            0.5 * dx2
        } else {
            dx2
        };
        let h3 = if j == 0 || j == n3 - 1 {
            0.5 * dx3
        } else {
            dx3
        };
        let area = h2 * h3;
        let mut rhs = 0.0;
        if periodic || i < n2 - 1 {
            let ip = (i + 1) % n2;
            self.east_stencil(i, ip, j, st);
            self.add_terms(terms, -h3 / area, &self.east[i * n3 + j], e, st);
        } else {
            rhs += h3 / area * self.boundary_flux(Side::X2Max, e, node)?;
        }
        if periodic || i > 0 {
            let im = (i + n2 - 1) % n2;
            self.east_stencil(im, i, j, st);
            self.add_terms(terms, h3 / area, &self.east[im * n3 + j], e, st);
        } else {
            rhs += h3 / area * self.boundary_flux(Side::X2Min, e, node)?;
        }
        if j < n3 - 1 {
            self.north_stencil(i, j, st);
            self.add_terms(terms, -h2 / area, &self.north[i * (n3 - 1) + j], e, st);
        } else {
            rhs += h2 / area * self.boundary_flux(Side::X3Max, e, node)?;
        }
        if j > 0 {
            self.north_stencil(i, j - 1, st);
            self.add_terms(terms, h2 / area, &self.north[i * (n3 - 1) + j - 1], e, st);
        } else {
            rhs += h2 / area * self.boundary_flux(Side::X3Min, e, node)?;
        }
        self.problem.grid.node_stencil(node, st);
        let k = self.problem.grid.node_index(node);
        self.add_terms(terms, 1.0, &self.source[k], e, st);
        if let Some(f) = &self.problem.body_force {
            let x = self.problem.grid.coordinates(node);
            let fe = f(x)[e];
            if !fe.is_finite() {
                return Err(ElasticityError::NonFinite {
                    what: "body force",
                    at: x,
                });
            }
            rhs += self.node_scale[k][0] * fe;
        }
        // No structural zeros are needed for a friction Jacobian: the Christoffel term above
        // already couples this row to every column of the nodal stencil, which holds the
        // columns of `T^3_j` at the node (see `contact_nodes`).
        Ok(rhs)
    }

    /// Visits every row in dof order with its merged, column-sorted terms.
    fn visit(&self, f: impl FnMut(usize, &[(usize, f64)], f64)) -> Result<(), ElasticityError> {
        self.visit_rows(0..self.dof_count(), f)
    }

    /// Visits the rows `rows` in dof order with their merged, column-sorted terms.
    fn visit_rows(
        &self,
        rows: core::ops::Range<usize>,
        mut f: impl FnMut(usize, &[(usize, f64)], f64),
    ) -> Result<(), ElasticityError> {
        let mut terms = Vec::with_capacity(64);
        let mut st = Vec::with_capacity(16);
        let mut merged: Vec<(usize, f64)> = Vec::with_capacity(64);
        let mut orders = SortOrders::default();
        for d in rows {
            let rhs = self.row(d, &mut terms, &mut st)?;
            let order = orders.order(d, &terms);
            merged.clear();
            for &k in order {
                let (c, v) = terms[k as usize];
                match merged.last_mut() {
                    Some(last) if last.0 == c => last.1 += v,
                    _ => merged.push((c, v)),
                }
            }
            f(d, &merged, rhs);
        }
        Ok(())
    }

    /// The local displacement at a node from nodal values `v`.
    fn local(&self, node: [usize; 2], v: &[f64]) -> LocalDisplacement {
        let mut st = Vec::with_capacity(8);
        self.problem.grid.node_stencil(node, &mut st);
        LocalDisplacement::from_stencil(&st, |n, c| v[self.dof(n, Component::ALL[c])])
    }
}

impl<G: ShellGeometry + Sync> Discretisation for FiniteDifferenceNavier<G> {
    fn method(&self) -> &'static str {
        "fd"
    }

    /// Nested dissection with one-node-line separators (the 9-point stencil's reach).
    /// `bench_navier 2000 321 --ordering nd` against `--ordering auto` (AMD): 2.67e8 stored
    /// factor values against 3.48e8, factor 9.7 s against 17.2 s, VmHWM 3378 against 4237 MiB
    /// (1000 x 161: 5.74e7 against 6.41e7, 2.22 s against 2.44 s).
    fn lu_ordering(&self) -> capstan_solvers::ColumnOrdering {
        capstan_solvers::ColumnOrdering::NestedDissection {
            grid: self.problem.grid.shape(),
            separator_width: 1,
        }
    }

    plane_strain_numbering!();

    fn entries(&self) -> Result<Vec<(usize, usize)>, ElasticityError> {
        let mut entries = Vec::with_capacity(self.dof_count() * 20);
        self.visit(|d, terms, _| entries.extend(terms.iter().map(|t| (d, t.0))))?;
        Ok(entries)
    }

    /// One pass over the rows for the pattern, the values and the right-hand side (the
    /// default visits them twice: [`Discretisation::entries`], then
    /// [`Discretisation::refill`]), blocks of `ROW_BLOCK` (2048) rows in parallel, placed into
    /// compressed columns in row order ([`LinearSystem::from_row_blocks`]); the same system,
    /// bit for bit, as one sequential pass through [`LinearSystem::from_entries`].
    fn system(&self) -> Result<LinearSystem, ElasticityError> {
        let n = self.dof_count();
        let blocks = (0..n.div_ceil(ROW_BLOCK))
            .into_par_iter()
            .map(|b| {
                let rows = b * ROW_BLOCK..n.min((b + 1) * ROW_BLOCK);
                let mut block = RowBlock {
                    cols: Vec::with_capacity(rows.len() * 20),
                    values: Vec::with_capacity(rows.len() * 20),
                    ends: Vec::with_capacity(rows.len()),
                };
                let mut rhs = Vec::with_capacity(rows.len());
                self.visit_rows(rows, |_, terms, b| {
                    block.cols.extend(terms.iter().map(|t| t.0));
                    block.values.extend(terms.iter().map(|t| t.1));
                    block.ends.push(block.cols.len());
                    rhs.push(b);
                })?;
                Ok((block, rhs))
            })
            .collect::<Result<Vec<_>, ElasticityError>>()?;
        let (blocks, rhs): (Vec<RowBlock>, Vec<Vec<f64>>) = blocks.into_iter().unzip();
        LinearSystem::from_row_blocks(&blocks, rhs.concat())
    }

    fn fill_values(
        &self,
        add: &mut dyn FnMut(usize, f64),
        rhs: &mut [f64],
    ) -> Result<(), ElasticityError> {
        let mut k = 0;
        self.visit(|d, terms, b| {
            for t in terms {
                add(k, t.1);
                k += 1;
            }
            rhs[d] = b;
        })
    }

    fn contact_nodes(&self) -> Result<Vec<ContactNode>, ElasticityError> {
        let mut st = Vec::with_capacity(8);
        let h3 = 0.5 * self.problem.grid.dx3();
        (0..self.problem.grid.n2())
            .map(|i| {
                let node = [i, 0];
                let k = self.problem.grid.node_index(node);
                let (coef, sqrt_g22) = &self.contact[i];
                let [sqrt_g, _, s33] = self.node_scale[k];
                self.problem.grid.node_stencil(node, &mut st);
                let rows = [0, 1].map(|e| {
                    let mut terms = Vec::with_capacity(16);
                    self.add_terms(&mut terms, 1.0, coef, e, &st);
                    SparseRow::from_terms(&mut terms)
                });
                Ok(ContactNode::at(
                    self,
                    i,
                    &self.dirichlet,
                    sqrt_g * s33 / h3,
                    *sqrt_g22,
                    rows,
                ))
            })
            .collect()
    }

    fn fields(&self, v: &[f64]) -> Result<NodalFields, ElasticityError> {
        ElasticityError::check_length("displacement", self.dof_count(), v.len())?;
        NodalFields::from_nodes(self.problem.grid, &self.problem.chart, |node, p| {
            let u = self.local(node, v);
            Ok((u, contravariant_stress(p, &self.problem.material, &u)))
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{BoundaryConditions, Grid, Material};
    use capstan_geometry::{EllipticalPrism, ShellChart};

    /// The system by the plain per-row sort and the general pattern builder: what
    /// [`FiniteDifferenceNavier::system`] replaced.
    fn sorted_reference<G: ShellGeometry + Sync>(fd: &FiniteDifferenceNavier<G>) -> LinearSystem {
        let n = fd.dof_count();
        let (mut terms, mut st) = (Vec::new(), Vec::new());
        let (mut entries, mut values, mut rhs) = (Vec::new(), Vec::new(), Vec::new());
        for d in 0..n {
            rhs.push(fd.row(d, &mut terms, &mut st).unwrap());
            terms.sort_unstable_by_key(|t| t.0);
            let mut merged: Vec<(usize, f64)> = Vec::new();
            for &(c, v) in &terms {
                match merged.last_mut() {
                    Some(last) if last.0 == c => last.1 += v,
                    _ => merged.push((c, v)),
                }
            }
            entries.extend(merged.iter().map(|t| (d, t.0)));
            values.extend(merged.iter().map(|t| t.1));
        }
        let mut system = LinearSystem::from_entries(n, &entries).unwrap();
        for (k, v) in values.into_iter().enumerate() {
            system.add_entry(k, v);
        }
        system.rhs = rhs;
        system
    }

    #[test]
    fn system_matches_the_sorted_rows_bit_for_bit() {
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        // more rows than one parallel block, and a grid with edge and corner rows of every kind
        for (a, b, n2, n3) in [(2.0, 1.2, 25, 5), (2.0, 2.0, 301, 9)] {
            let problem = PlaneProblem {
                chart: ShellChart::new(EllipticalPrism::new(a, b).unwrap()),
                material: Material::new(1e3, 0.25).unwrap(),
                grid: Grid::new([-1.2, 1.4], 1.0, n2, n3, false).unwrap(),
                boundary: BoundaryConditions::paper_clamped(1.0, 2.0),
                body_force: None,
            };
            let fd = FiniteDifferenceNavier::new(problem).unwrap();
            let system = fd.system().unwrap();
            let reference = sorted_reference(&fd);
            assert_eq!(system.pattern, reference.pattern);
            assert_eq!(bits(&system.values), bits(&reference.values));
            assert_eq!(bits(&system.rhs), bits(&reference.rhs));
            // the refill path (entries, then values by entry number) agrees as well
            let entries = fd.entries().unwrap();
            let mut refilled = LinearSystem::from_entries(fd.dof_count(), &entries).unwrap();
            let mut rhs = vec![0.0; fd.dof_count()];
            let mut add = |k: usize, v: f64| refilled.add_entry(k, v);
            fd.fill_values(&mut add, &mut rhs).unwrap();
            assert_eq!(bits(&refilled.values), bits(&reference.values));
            assert_eq!(bits(&rhs), bits(&reference.rhs));
        }
    }

    #[test]
    fn sort_orders_repeat_the_sort_of_every_shape() {
        // rows of shifted shapes with repeated columns (the sort is unstable among them) and
        // values whose sums depend on the order of addition
        let mut orders = SortOrders::default();
        let shapes: [&[isize]; 3] = [
            &[
                4, -2, 0, 4, 2, -2, 0, 6, 4, -4, 2, 0, 4, 8, -2, 6, 0, 2, 4, -2, 0, 4, 2, 6,
            ],
            &[
                1, 0, 1, 3, 0, 1, 5, 3, 1, 0, 1, 5, 3, 0, 1, 3, 1, 0, 5, 3, 1, 0,
            ],
            &[0, 0, 0],
        ];
        for d in 10..60 {
            let shape = shapes[d % 3];
            let terms: Vec<(usize, f64)> = shape
                .iter()
                .enumerate()
                .map(|(k, &o)| ((d as isize + o) as usize, 0.1 + 1e-3 * (k * k) as f64 / 3.0))
                .collect();
            let mut sorted = terms.clone();
            sorted.sort_unstable_by_key(|t| t.0);
            let again: Vec<(usize, f64)> = orders
                .order(d, &terms)
                .iter()
                .map(|&k| terms[k as usize])
                .collect();
            let bits =
                |v: &[(usize, f64)]| v.iter().map(|t| (t.0, t.1.to_bits())).collect::<Vec<_>>();
            assert_eq!(bits(&again), bits(&sorted), "row {d}");
        }
        assert_eq!(orders.shapes.len(), 3);
    }
}
