//! The frictional contact face `x3 = 0` of a 3-D body: two tangential entries per contact
//! node, the recovered `T^3_j` rows, and the body as a [`ContactOperator`].

use capstan_solvers::{ColumnOrdering, GridShape};

use crate::contact::operator::{ContactOperator, Extremum, extremum};
use crate::continuum::{SOLID, mixed_strains};
use crate::discretisation::{ContactNode, LinearSystem, SparseRow};
use crate::error::ElasticityError;
use crate::shell_geometry::ShellGeometry;
use crate::solid::SolidNavier;
use crate::solid::setup::SolidSetup;

impl<G: ShellGeometry + Sync> SolidSetup<G> {
    /// The contact entries of every node of the face `x3 = 0` ([`SolidSetup::contact_pair`]).
    pub(crate) fn contact_entries(&self) -> Result<Vec<ContactNode>, ElasticityError> {
        let [n1, n2, _] = self.grid.counts();
        let mut out = Vec::with_capacity(2 * n1 * n2);
        for i1 in 0..n1 {
            for i2 in 0..n2 {
                out.extend(self.contact_pair(i1, i2)?);
            }
        }
        Ok(out)
    }

    /// The largest `v^2`, `v^3` over the nodes and where they are.
    pub(crate) fn extremes(&self, v: &[f64]) -> [Extremum; 2] {
        let nodes = self.grid.node_count();
        [1, 2].map(|c| {
            extremum(
                nodes,
                |m| v[3 * m + c],
                |m| {
                    let x = self.grid.coordinates(self.grid.node(m));
                    (Some(x[0]), x[1], x[2])
                },
            )
        })
    }

    /// The contact entries of node `(i1, i2, 0)`: `v^1` and `v^2`.
    ///
    /// # Math
    /// At `x3 = 0` (`g_ab = a_ab`, `g^33 = 1`, unit normal `n = -g^3`):
    /// ```text
    /// T^3_j = sum_k u_k (lambda delta_3j tr M_k + 2 mu M_k[3][j])   (inputs u of the SOLID layout)
    /// w = sqrt(g) sqrt(g^33) W1(i1) W2(i2)          int N dx1 dx2 (boundary flux weight; Q1/Q2
    ///                                                 lumped, Qp the GLL weights: exact)
    /// frame_1 = [sqrt(a_11), 0],  frame_2 = [a_12 / sqrt(a_11), 1 / sqrt(a^22)]
    /// ```
    /// in the frame `e_1 = a_1/|a_1|`, `e_2 = a^2/|a^2|`: `|F v|^2 = a_ab v^a v^b`.
    pub(crate) fn contact_pair(
        &self,
        i1: usize,
        i2: usize,
    ) -> Result<[ContactNode; 2], ElasticityError> {
        let [n1, n2, _] = self.grid.counts();
        let [d1, d2, _] = self.grid.spacing();
        let node = [i1, i2, 0];
        let x = self.grid.coordinates(node);
        let p = self.chart.shell_point(x)?;
        let g = &p.metric;
        let gi = &p.inverse_metric;
        let strains = mixed_strains(&p, &SOLID);
        let (lambda, two_mu) = (self.material.lambda(), 2.0 * self.material.mu());
        let stencil = self.node_stencil(node);
        let row = |j: usize| -> SparseRow {
            let mut terms = Vec::with_capacity(3 * stencil.len());
            for (at, w) in &stencil {
                for c in 0..3 {
                    // inputs: v^c (index c), d_q v^c (index 3 + 3 q + c)
                    let mut a = 0.0;
                    for (q, wq) in w.iter().enumerate() {
                        if *wq == 0.0 {
                            continue;
                        }
                        let k = if q == 0 { c } else { 3 + 3 * (q - 1) + c };
                        let m = &strains[k];
                        let trace = m[0][0] + m[1][1] + m[2][2];
                        let t = if j == 2 { lambda * trace } else { 0.0 } + two_mu * m[2][j];
                        a += t * wq;
                    }
                    terms.push((self.dof(*at, c), a));
                }
            }
            SparseRow::from_terms(&mut terms)
        };
        let normal = row(2);
        let weight = p.sqrt_g
            * gi[2][2].sqrt()
            * self.lines.weight(i1, n1, d1, false)
            * self.lines.weight(i2, n2, d2, self.grid.is_periodic());
        let site = i1 * n2 + i2;
        let sqrt_a11 = g[0][0].sqrt();
        let frames = [[sqrt_a11, 0.0], [g[0][1] / sqrt_a11, 1.0 / gi[1][1].sqrt()]];
        let entry = |c: usize| -> ContactNode {
            let dof = self.dof(node, c);
            ContactNode {
                node: [i2, 0],
                i1,
                site,
                x1: x[0],
                x2: x[1],
                component: c + 1,
                frame: frames[c],
                tangential_row: self.dirichlet[dof].is_none().then_some(dof),
                tangential_dof: dof,
                normal_dof: self.dof(node, 2),
                traction_weight: weight,
                sqrt_g22: g[c][c].sqrt(),
                normal_stress: normal.clone(),
                shear_stress: row(c),
            }
        };
        Ok([entry(0), entry(1)])
    }
}

impl<G: ShellGeometry + Sync> ContactOperator for SolidNavier<G> {
    fn method(&self) -> &'static str {
        self.element().method_name()
    }

    fn dof_count(&self) -> usize {
        SolidNavier::dof_count(self)
    }

    /// Nested dissection of the `(x1, x2)` plane along element boundaries, each column of
    /// `3 n3` unknowns above a surface node one block (the numbering `3 ((i1 n2 + i2) n3 + i3)
    /// + c` makes a column consecutive): the separators cut through the whole thickness. AMD
    /// for a periodic `x2`.
    fn lu_ordering(&self) -> ColumnOrdering {
        let [n1, n2, n3] = self.setup.grid.counts();
        if self.setup.grid.is_periodic() {
            return ColumnOrdering::Auto;
        }
        ColumnOrdering::ElementNestedDissection {
            grid: GridShape {
                n2: n1,
                n3: n2,
                dofs_per_node: 3 * n3,
                periodic: false,
            },
            degree: self.element().degree(),
        }
    }

    /// The trilinear hierarchy of the box ([`crate::solid::box_hierarchy`]), Dirichlet dofs
    /// constrained; for Qp elements of degree 3 and more (GLL nodes, where the trilinear
    /// interpolation between uniform grids does not apply) first the p-multigrid transfer
    /// from the Q1 field on the element vertices, then the box hierarchy of the vertex grid.
    fn multigrid_prolongations(
        &self,
        coarsest_unknowns: usize,
    ) -> Option<std::sync::Arc<[capstan_solvers::CsrMatrix]>> {
        if self.element().degree() <= 2 {
            return Some(self.multigrid_hierarchy(coarsest_unknowns).prolongations);
        }
        let constrained: Vec<bool> = self.setup.dirichlet.iter().map(Option::is_some).collect();
        let grid = &self.setup.grid;
        let (first, counts, mask) =
            crate::solid::matrix_free::p_prolongation(grid, self.element(), &constrained);
        let vertices = crate::solid::BoxGrid::new(
            grid.x1_range(),
            grid.x2_range(),
            grid.thickness(),
            counts,
            grid.is_periodic(),
        )
        .ok()?;
        let rest = crate::solid::box_hierarchy(&vertices, &mask, coarsest_unknowns);
        Some(
            core::iter::once(first)
                .chain(rest.prolongations.iter().cloned())
                .collect(),
        )
    }

    /// The three rigid translations of space in the contravariant components
    /// `v^i = g^i . e_d` at every node, block size 3; `None` if the chart fails at a node.
    ///
    /// # Math
    /// ```text
    /// z_d[3 m + i] = g^i(x_m) . e_d           d = 0, 1, 2   (0 at prescribed dofs)
    /// ```
    /// `a(z, w) = 0` for every `w`: the strain of a rigid motion vanishes, so without
    /// boundary conditions `A z = 0`. The prescribed (Dirichlet) dofs are set to zero: their
    /// rows are decoupled identities. The three rotations `u = e_a x Theta` are rigid motions
    /// too, but with them PETSc's GAMG failed to set up (a zero pivot on a coarse level) on the
    /// ellipse of `docs/solid.md` at 111,843 unknowns on one rank and at 15,795 on two; with
    /// the translations alone it converges everywhere tried (`docs/scale-out.md`).
    fn near_null_space(&self) -> Option<capstan_solvers::NearNullSpace> {
        let [n1, n2, n3] = self.setup.grid.counts();
        let n = self.dof_count();
        let mut vectors = vec![vec![0.0; n]; 3];
        let heights: Vec<f64> = (0..n3)
            .map(|k| self.setup.grid.coordinates([0, 0, k])[2])
            .collect();
        let mut column = Vec::with_capacity(n3);
        for i1 in 0..n1 {
            for i2 in 0..n2 {
                let x = self.setup.grid.coordinates([i1, i2, 0]);
                column.clear();
                self.setup
                    .chart
                    .shell_column([x[0], x[1]], &heights, &mut column)
                    .ok()?;
                for (i3, p) in column.iter().enumerate() {
                    let m = self.setup.grid.node_index([i1, i2, i3]);
                    for (i, gi) in p.contravariant_basis.iter().enumerate() {
                        for (d, z) in vectors.iter_mut().enumerate() {
                            z[3 * m + i] = gi[d];
                        }
                    }
                }
            }
        }
        for (d, g) in self.setup.dirichlet.iter().enumerate() {
            if g.is_some() {
                vectors.iter_mut().for_each(|z| z[d] = 0.0);
            }
        }
        Some(capstan_solvers::NearNullSpace {
            block_size: 3,
            vectors,
        })
    }

    fn row_distribution(
        &self,
    ) -> Option<(
        std::sync::Arc<dyn capstan_solvers::row_distribution::RowDistribution>,
        usize,
    )> {
        self.distribution().map(|d| (std::sync::Arc::clone(d), 3))
    }

    fn contact_system(&self) -> Result<LinearSystem, ElasticityError> {
        Ok(self.system().clone())
    }

    fn contact_entries(&self) -> Result<Vec<ContactNode>, ElasticityError> {
        self.setup.contact_entries()
    }

    fn extremes(&self, v: &[f64]) -> [Extremum; 2] {
        self.setup.extremes(v)
    }

    fn solid(&self) -> Option<&dyn crate::solid::SolidOutput> {
        Some(self)
    }
}
