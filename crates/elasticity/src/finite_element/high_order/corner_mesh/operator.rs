//! [`CornerRefinedNavier`]: the Qp elements on the corner-refined mesh (`Layout`),
//! its geometry at the quadrature points, loads, Dirichlet data, statically condensed solve
//! and error norms.

use capstan_solvers::LinearSolver;
use faer::MatMut;
use rayon::prelude::*;

use super::super::gll::{gauss_legendre, gll_rule, lagrange_basis};
use super::super::kernel::{ElementTables, add_element_matrix, symmetrise};
use super::super::tensor_kernel::{X3Factors, condense_elements};
use super::layout::{CornerSettings, Layout, TransitionGrading, bilinear, local_edges, sides_of};
use crate::boundary::{Component, ComponentCondition, Side};
use crate::continuum::{PLANE_STRAIN, check_plane_strain, energy_matrix};
use crate::discretisation::LinearSystem;
use crate::error::ElasticityError;
use crate::finite_element::DisplacementErrors;
use crate::finite_element::ElementAssembly;
use crate::finite_element::boundary_terms::add_side_point_load;
use crate::finite_element::norms::{ElementMap, LagrangeElements, displacement_errors};
use crate::plane_problem::{PlaneProblem, body_force_load};
use crate::shell_geometry::ShellGeometry;
use capstan_solvers::CondensedBlock;

/// The plane-strain curvilinear Navier operator by Qp elements (GLL nodes) on a mesh refined
/// geometrically toward the four corners of the parameter rectangle only
/// ([`CornerSettings`]): coarse cells in the middle, two trapezoids per layer at each corner,
/// conforming throughout.
///
/// # Math
/// The weak form of [`super::super::HighOrderNavier`]. Element `e` is the bilinear image
/// `x(xi, eta) = sum_i N_i(xi, eta) x_i` of `[-1, 1]^2` through its four vertices; with
/// `J = dx / d(xi, eta)` the physical derivatives are `(d_2, d_3) = J^-T (d_xi, d_eta)`, so
/// the energy matrix of the plane-strain inputs `z = (v, d_2 v, d_3 v)` pulls back to the
/// reference inputs `zeta = (v, d_xi v, d_eta v)` as
/// ```text
/// k_ref = T^T k(x) T |det J| w_q,   z = T zeta,   T = diag(I_2, J^-T (x) I_2)
/// ```
/// and the sum-factorised kernel of the tensor elements (`X3Factors`) runs unchanged on the
/// reference tables (Gauss rule of `p + 1` points per direction). The element interiors are
/// condensed as for the tensor elements ([`CondensedBlock`]); the skeleton (vertices and
/// the `p - 1` nodes of every edge) carries the global system.
///
/// Scope: the whole rectangle (no periodic `x2`), Dirichlet data from the sides (no pinned
/// dofs), full integration. The grid's `n2 x n3` only gives the rectangle.
pub struct CornerRefinedNavier<G> {
    pub(super) problem: PlaneProblem<G>,
    pub(super) settings: CornerSettings,
    pub(super) layout: Layout,
    pub(super) gll: Vec<f64>,
    pub(super) tables: ElementTables,
    pub(super) factors: X3Factors,
    /// Position of every node.
    pub(super) positions: Vec<[f64; 2]>,
    /// Reference energy matrices, index `e nq^2 + q2 nq + q3`.
    pub(super) kq: Vec<[[f64; 6]; 6]>,
    pub(super) load: Vec<f64>,
    pub(super) dirichlet: Vec<Option<f64>>,
    /// Local nodes on the element edges, and inside.
    pub(super) boundary_local: Vec<usize>,
    pub(super) interior_local: Vec<usize>,
}

impl<G> core::fmt::Debug for CornerRefinedNavier<G> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        self.problem
            .debug_fields(f, "CornerRefinedNavier", Some(("settings", &self.settings)))
    }
}

/// Per quadrature point: the reference energy matrix and the body force times the weight.
type PointData = ([[f64; 6]; 6], [f64; 2]);

/// The rectangle's sides with their bit in `sides_of`, in the order Dirichlet data is looked
/// up ([`crate::BoundaryConditions::dirichlet_value_at`]: `x3` sides first).
const SIDES: [(Side, u8); 4] = [
    (Side::X3Min, 4),
    (Side::X3Max, 8),
    (Side::X2Min, 1),
    (Side::X2Max, 2),
];

impl<G: ShellGeometry + Sync> CornerRefinedNavier<G> {
    /// Builds the operator: mesh, nodes, geometry at the quadrature points, loads and
    /// Dirichlet data.
    ///
    /// # Errors
    /// [`ElasticityError::InvalidParameter`] for settings outside their ranges
    /// ([`CornerSettings::check`]), a periodic grid (`grid.periodic`) or pinned dofs
    /// (`boundary.pinned`); geometry failures, [`ElasticityError::NotPlaneStrain`],
    /// [`ElasticityError::NonFinite`] for non-finite loads.
    pub fn new(
        problem: PlaneProblem<G>,
        settings: CornerSettings,
    ) -> Result<Self, ElasticityError> {
        Self::with_transitions(problem, settings, &TransitionGrading::NONE)
    }

    /// [`Self::new`] with the `x2` lines also graded toward interior points of the face
    /// ([`TransitionGrading`]: the stick/slip transitions of a first solve);
    /// [`TransitionGrading::NONE`] is [`Self::new`].
    ///
    /// # Errors
    /// As [`Self::new`], and [`TransitionGrading::check`]'s.
    pub fn with_transitions(
        mut problem: PlaneProblem<G>,
        settings: CornerSettings,
        transitions: &TransitionGrading,
    ) -> Result<Self, ElasticityError> {
        settings.check()?;
        transitions.check()?;
        if problem.grid.is_periodic() {
            return Err(ElasticityError::InvalidParameter {
                field: "grid.periodic",
                value: 1.0,
                allowed: "a non-periodic x2 (corner refinement needs the four corners)",
            });
        }
        if !problem.boundary.pinned.is_empty() {
            return Err(ElasticityError::InvalidParameter {
                field: "boundary.pinned",
                value: problem.boundary.pinned.len() as f64,
                allowed: "no pinned dofs (Dirichlet data from the sides only)",
            });
        }
        let p = settings.order;
        let np = p + 1;
        let rect = [problem.grid.theta(), [0.0, problem.grid.thickness()]];
        let layout = if *transitions == TransitionGrading::NONE {
            Layout::new(rect, &settings)
        } else {
            Layout::graded(rect, &settings, transitions)
        };
        let (gll, _) = gll_rule(p);
        let (gq, gw) = gauss_legendre(p + 1);
        let tables = ElementTables::new(&gll, &gq, [2.0, 2.0]);
        let factors = X3Factors::new(&tables);
        let mut positions = vec![[0.0; 2]; layout.node_count];
        for (e, q) in layout.quads.iter().enumerate() {
            let v = q.map(|i| layout.vertices[i]);
            for a2 in 0..np {
                for a3 in 0..np {
                    let m = layout.element_nodes[e * np * np + a2 * np + a3];
                    positions[m] = bilinear(&v, [gll[a2], gll[a3]]).0;
                }
            }
        }
        let (boundary_local, interior_local): (Vec<usize>, Vec<usize>) =
            (0..np * np).partition(|&a| {
                let (a2, a3) = (a / np, a % np);
                a2 == 0 || a2 == p || a3 == 0 || a3 == p
            });
        let body_force = problem.body_force.take();
        let (lambda, mu) = (problem.material.lambda(), problem.material.mu());
        let nq = gq.len();
        // geometry and body force at the quadrature points, element by element
        let points = layout
            .quads
            .par_iter()
            .map(|q| -> Result<Vec<PointData>, ElasticityError> {
                let v = q.map(|i| layout.vertices[i]);
                let mut out = Vec::with_capacity(nq * nq);
                for (q2, &xi) in gq.iter().enumerate() {
                    for (q3, &eta) in gq.iter().enumerate() {
                        let (x, j) = bilinear(&v, [xi, eta]);
                        let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
                        let at = [0.0, x[0], x[1]];
                        let pt = problem.chart.shell_point(at)?;
                        check_plane_strain(&pt, at)?;
                        let w = gw[q2] * gw[q3] * det;
                        let k = pull_back(energy_matrix(&pt, &PLANE_STRAIN, lambda, mu, w), &j);
                        let f = body_force_load(body_force.as_ref(), x, pt.sqrt_g, w)?;
                        out.push((k, f));
                    }
                }
                Ok(out)
            })
            .collect::<Result<Vec<_>, _>>()?;
        let mut load = vec![0.0; 2 * layout.node_count];
        if body_force.is_some() {
            for (e, pts) in points.iter().enumerate() {
                let nodes = &layout.element_nodes[e * np * np..][..np * np];
                for (q, (_, f)) in pts.iter().enumerate() {
                    let (q2, q3) = (q / nq, q % nq);
                    for (a, &m) in nodes.iter().enumerate() {
                        let n = tables.value[(a / np) * nq + q2] * tables.value[(a % np) * nq + q3];
                        load[2 * m] += n * f[0];
                        load[2 * m + 1] += n * f[1];
                    }
                }
            }
        }
        let kq = points.into_iter().flatten().map(|(k, _)| k).collect();
        let mut op = Self {
            problem,
            settings,
            layout,
            gll,
            tables,
            factors,
            positions,
            kq,
            load,
            dirichlet: vec![],
            boundary_local,
            interior_local,
        };
        op.add_boundary_terms()?;
        Ok(op)
    }

    /// The settings.
    pub fn settings(&self) -> CornerSettings {
        self.settings
    }

    /// Number of elements.
    pub fn element_count(&self) -> usize {
        self.layout.quads.len()
    }

    /// Number of nodes (vertices, edge nodes, element interiors).
    pub fn node_count(&self) -> usize {
        self.layout.node_count
    }

    /// Unknowns, `2` per node (prescribed ones included, as for the other operators).
    pub fn dof_count(&self) -> usize {
        2 * self.layout.node_count
    }

    /// Unknowns of the condensed (skeleton) system.
    pub fn skeleton_dof_count(&self) -> usize {
        2 * self.layout.skeleton_count
    }

    /// `[x2, x3]` of node `m`.
    ///
    /// # Panics
    /// For `m` outside the nodes.
    #[track_caller]
    pub fn node_position(&self, m: usize) -> [f64; 2] {
        self.positions[m]
    }

    /// The four vertices of element `e`, `(xi, eta) = (-1,-1), (1,-1), (-1,1), (1,1)`.
    ///
    /// # Panics
    /// For `e` outside the elements.
    #[track_caller]
    pub fn element_vertices(&self, e: usize) -> [[f64; 2]; 4] {
        self.layout.quads[e].map(|i| self.layout.vertices[i])
    }

    /// The discrete displacement `[v^2, v^3]` of `v` in element `e` at the reference point
    /// `[xi, eta]` (the element polynomial).
    ///
    /// # Panics
    /// For `e` outside the elements or `v` shorter than [`Self::dof_count`].
    #[track_caller]
    pub fn element_value(&self, e: usize, v: &[f64], [xi, eta]: [f64; 2]) -> [f64; 2] {
        let np = self.np();
        let (b2, _) = lagrange_basis(&self.gll, xi);
        let (b3, _) = lagrange_basis(&self.gll, eta);
        let mut u = [0.0; 2];
        for (a, &m) in self.nodes(e).iter().enumerate() {
            let n = b2[a / np] * b3[a % np];
            u[0] += n * v[2 * m];
            u[1] += n * v[2 * m + 1];
        }
        u
    }

    pub(super) fn np(&self) -> usize {
        self.settings.order + 1
    }

    pub(super) fn nodes(&self, e: usize) -> &[usize] {
        let l = self.np() * self.np();
        &self.layout.element_nodes[e * l..(e + 1) * l]
    }

    /// Natural boundary terms along the element edges on the rectangle's sides (Gauss rule of
    /// `p + 1` points), and the Dirichlet value of every dof on a side with a prescribed
    /// displacement.
    fn add_boundary_terms(&mut self) -> Result<(), ElasticityError> {
        let p = self.settings.order;
        let np = p + 1;
        let rect = [
            self.problem.grid.theta(),
            [0.0, self.problem.grid.thickness()],
        ];
        let (gp, gw) = gauss_legendre(p + 1);
        let mut dirichlet = vec![None; self.dof_count()];
        let mut node_sides = vec![0u8; self.layout.node_count];
        for e in 0..self.element_count() {
            let q = self.layout.quads[e];
            let nodes = self.nodes(e).to_vec();
            // local nodes along each local edge, from its start vertex
            let along: [Vec<usize>; 4] = [
                (0..np).map(|b| nodes[b]).collect(),
                (0..np).map(|b| nodes[p * np + b]).collect(),
                (0..np).map(|a| nodes[a * np]).collect(),
                (0..np).map(|a| nodes[a * np + p]).collect(),
            ];
            for (edge, line) in local_edges(&q).iter().zip(&along) {
                let [xs, xe] = edge.map(|i| self.layout.vertices[i]);
                let mask = sides_of(xs, rect) & sides_of(xe, rect);
                for &(side, bit) in &SIDES {
                    if mask & bit == 0 {
                        continue;
                    }
                    line.iter().for_each(|&m| node_sides[m] |= bit);
                    let Some(cond) = self.problem.boundary.side(side).cloned() else {
                        continue;
                    };
                    let length = ((xe[0] - xs[0]).powi(2) + (xe[1] - xs[1]).powi(2)).sqrt();
                    for (&s, &w) in gp.iter().zip(&gw) {
                        let t = 0.5 * (s + 1.0);
                        let x = [xs[0] + t * (xe[0] - xs[0]), xs[1] + t * (xe[1] - xs[1])];
                        let at = [0.0, x[0], x[1]];
                        let pt = self.problem.chart.shell_point(at)?;
                        check_plane_strain(&pt, at)?;
                        let (shape, _) = lagrange_basis(&self.gll, s);
                        let terms = line.iter().copied().zip(shape);
                        let weight = [w, 0.5 * length];
                        add_side_point_load(&mut self.load, &cond, side, &pt, x, weight, terms)?;
                    }
                }
            }
        }
        for (m, &mask) in node_sides.iter().enumerate() {
            let x = self.positions[m];
            for c in Component::ALL {
                let prescribed = SIDES.iter().filter(|(_, bit)| mask & bit != 0).find_map(
                    |&(side, _)| match self.problem.boundary.side(side).map(|s| s.component(c)) {
                        Some(ComponentCondition::Displacement(f)) => {
                            Some(f.eval(if side.normal_index() == 2 { x[0] } else { x[1] }))
                        }
                        _ => None,
                    },
                );
                if let Some(value) = prescribed {
                    if !value.is_finite() {
                        return Err(ElasticityError::NonFinite {
                            what: "boundary displacement",
                            at: x,
                        });
                    }
                    dirichlet[2 * m + c.index()] = Some(value);
                }
            }
        }
        self.dirichlet = dirichlet;
        Ok(())
    }

    /// The stiffness matrix of element `e` in tensor form (`X3Factors::add_tensor_matrix`).
    fn tensor_matrix(&self, e: usize, tt: &mut Vec<f64>, m: &mut [f64]) {
        let f = &self.factors;
        m.fill(0.0);
        if tt.len() < f.scratch_len() {
            tt.resize(f.scratch_len(), 0.0);
        }
        let nq2 = self.tables.nq * self.tables.nq;
        let out = MatMut::from_column_major_slice_mut(m, f.rows(), f.cols());
        f.add_tensor_matrix(&self.kq[e * nq2..(e + 1) * nq2], tt, out);
    }

    /// The system on every node, not condensed (the reference of the condensed solve).
    ///
    /// # Errors
    /// [`ElasticityError::NonFinite`] for a non-finite element matrix; pattern errors.
    pub fn full_system(&self) -> Result<LinearSystem, ElasticityError> {
        let np2 = self.np() * self.np();
        let assembly = ElementAssembly::new(
            self.layout.node_count,
            2,
            np2,
            self.layout.element_nodes.clone(),
            &self.dirichlet,
        )?;
        let nq2 = self.tables.nq * self.tables.nq;
        assembly.assemble(
            |e, out| {
                add_element_matrix(&self.tables, &self.kq[e * nq2..(e + 1) * nq2], out);
                symmetrise(out, 2 * np2);
            },
            &self.load,
            &self.dirichlet,
        )
    }

    /// Condenses the element interiors onto the skeleton: the element Schur complements (in
    /// parallel) and the skeleton system they assemble into.
    ///
    /// # Errors
    /// [`ElasticityError::Solver`] if an interior block is not positive definite; pattern
    /// errors.
    pub fn condensed_system(&self) -> Result<CornerCondensed, ElasticityError> {
        let np = self.np();
        let local = |set: &[usize]| -> Vec<usize> {
            set.iter().flat_map(|&a| [2 * a, 2 * a + 1]).collect()
        };
        let (bd, id) = (local(&self.boundary_local), local(&self.interior_local));
        let f = &self.factors;
        let elements = condense_elements(
            self.element_count(),
            np,
            f.rows() * f.cols(),
            (&bd, &id),
            |e, tt, m| self.tensor_matrix(e, tt, m),
            (&self.load, |e| self.nodes(e)),
        )?;
        let ns = self.layout.skeleton_count;
        let connectivity: Vec<usize> = (0..self.element_count())
            .flat_map(|e| self.boundary_local.iter().map(move |&a| self.nodes(e)[a]))
            .collect();
        let dirichlet = &self.dirichlet[..2 * ns];
        let assembly =
            ElementAssembly::new(ns, 2, self.boundary_local.len(), connectivity, dirichlet)?;
        let mut load = self.load[..2 * ns].to_vec();
        for (e, c) in elements.iter().enumerate() {
            let nodes = assembly.nodes(e);
            for (r, g) in c.load.iter().enumerate() {
                load[2 * nodes[r / 2] + r % 2] += g;
            }
        }
        let system = assembly.assemble(
            |e, out| out.copy_from_slice(&elements[e].schur),
            &load,
            dirichlet,
        )?;
        Ok(CornerCondensed { system, elements })
    }

    /// The displacement on every node from the skeleton solution (skeleton nodes are the
    /// first ones), the interiors recovered element by element.
    ///
    /// # Errors
    /// [`ElasticityError::DimensionMismatch`] for a wrong length.
    pub fn recover(
        &self,
        condensed: &CornerCondensed,
        u_skeleton: &[f64],
    ) -> Result<Vec<f64>, ElasticityError> {
        let ns = self.layout.skeleton_count;
        ElasticityError::check_length("skeleton solution", 2 * ns, u_skeleton.len())?;
        let mut v = vec![0.0; self.dof_count()];
        v[..2 * ns].copy_from_slice(u_skeleton);
        let interiors: Vec<Vec<f64>> = (0..self.element_count())
            .into_par_iter()
            .map(|e| {
                let nodes = self.nodes(e);
                let ub: Vec<f64> = self
                    .boundary_local
                    .iter()
                    .flat_map(|&a| [u_skeleton[2 * nodes[a]], u_skeleton[2 * nodes[a] + 1]])
                    .collect();
                condensed.elements[e].recover(&ub)
            })
            .collect();
        for (e, ui) in interiors.iter().enumerate() {
            let nodes = self.nodes(e);
            for (r, &a) in self.interior_local.iter().enumerate() {
                v[2 * nodes[a]] = ui[2 * r];
                v[2 * nodes[a] + 1] = ui[2 * r + 1];
            }
        }
        Ok(v)
    }

    /// Solves by static condensation with `solver` (the skeleton system), interiors
    /// recovered.
    ///
    /// # Errors
    /// Assembly or solver errors.
    pub fn solve(&self, solver: &mut dyn LinearSolver<f64>) -> Result<Vec<f64>, ElasticityError> {
        let c = self.condensed_system()?;
        let u = c.system.solve(solver)?;
        self.recover(&c, &u)
    }

    /// The relative and absolute error norms of `v` against `exact` (as
    /// [`super::super::HighOrderNavier::displacement_errors`]): Gauss rule of `p + 2` points
    /// per direction on every element, weights `|det J|`; the max error over the nodes.
    ///
    /// # Errors
    /// [`ElasticityError::DimensionMismatch`] for a wrong length; geometry failures.
    pub fn displacement_errors(
        &self,
        v: &[f64],
        exact: &(dyn Fn([f64; 2]) -> [f64; 2] + Sync),
    ) -> Result<DisplacementErrors, ElasticityError> {
        let (gp, gw) = gauss_legendre(self.settings.order + 2);
        let basis: Vec<Vec<f64>> = gp.iter().map(|&x| lagrange_basis(&self.gll, x).0).collect();
        let element = |e: usize| -> (Vec<usize>, ElementMap<'_>) {
            let vx = self.element_vertices(e);
            let map = move |xi: [f64; 2]| {
                let (x, jac) = bilinear(&vx, xi);
                (x, jac[0][0] * jac[1][1] - jac[0][1] * jac[1][0])
            };
            (self.nodes(e).to_vec(), Box::new(map))
        };
        let elements = LagrangeElements {
            count: self.element_count(),
            rule: (&gp, &gw),
            basis: &basis,
            element: &element,
        };
        let position = |m: usize| self.positions[m];
        displacement_errors(
            &self.problem,
            &elements,
            self.layout.node_count,
            &position,
            v,
            exact,
        )
    }
}

/// The condensed system of a [`CornerRefinedNavier`] and the element data to recover the
/// interiors.
#[derive(Debug, Clone)]
pub struct CornerCondensed {
    /// The skeleton system.
    pub system: LinearSystem,
    /// Per element: Schur complement, condensed load, interior factor and coupling.
    pub elements: Vec<CondensedBlock>,
}

/// `T^T k T` for the plane-strain inputs (`[v^2, v^3, d_2 v^2, d_2 v^3, d_3 v^2, d_3 v^3]`)
/// with `(d_2, d_3) = J^-T (d_xi, d_eta)`: the energy matrix on the reference inputs.
fn pull_back(k: [[f64; 6]; 6], j: &[[f64; 2]; 2]) -> [[f64; 6]; 6] {
    let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
    // G = J^-T
    let g = [
        [j[1][1] / det, -j[1][0] / det],
        [-j[0][1] / det, j[0][0] / det],
    ];
    let mut t = [[0.0; 6]; 6];
    for c in 0..2 {
        t[c][c] = 1.0;
        for (r, row) in g.iter().enumerate() {
            t[2 + 2 * r + c][2 + c] = row[0];
            t[2 + 2 * r + c][4 + c] = row[1];
        }
    }
    // (T^T k T)[a][b] = sum_(r, s) T[r][a] k[r][s] T[s][b]
    let mut kt = [[0.0; 6]; 6];
    for r in 0..6 {
        for b in 0..6 {
            kt[r][b] = (0..6).map(|s| k[r][s] * t[s][b]).sum();
        }
    }
    core::array::from_fn(|a| core::array::from_fn(|b| (0..6).map(|r| t[r][a] * kt[r][b]).sum()))
}
