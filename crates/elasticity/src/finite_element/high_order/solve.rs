//! Assembly of the Qp operator (full and statically condensed), its [`Discretisation`]
//! implementation (contact entries, output fields) and error norms.

use rayon::prelude::*;

use super::gll::{gauss_legendre, lagrange_basis};
use super::kernel::{
    DIRECT_KERNEL_ORDERS, add_element_matrix, add_element_matrix_direct, symmetrise,
};
use super::mesh::locate;
use super::operator::HighOrderNavier;
use super::skeleton::Skeleton;
use super::tensor_kernel::{X3Factors, condense_elements};
use crate::continuum::kinematics::contravariant_stress;
use crate::continuum::{PLANE_STRAIN, divergence_coefficients};
use crate::discretisation::{ContactNode, Discretisation, LinearSystem};
use crate::error::ElasticityError;
use crate::fields::NodalFields;
use crate::finite_element::DisplacementErrors;
use crate::finite_element::ElementAssembly;
use crate::finite_element::norms::{ElementMap, LagrangeElements, displacement_errors};
use crate::finite_element::volumetric::VolumetricIntegration;
use crate::plane_strain_operator::plane_strain_numbering;
use crate::shell_geometry::ShellGeometry;
use capstan_solvers::CondensedBlock;
use capstan_solvers::LinearSolver;

/// The statically condensed system of a [`HighOrderNavier`]: the skeleton system and what
/// each element needs to recover its interior values.
#[derive(Debug, Clone)]
pub struct CondensedSystem {
    /// `S u_B = f_B + g` on the skeleton dofs (`2 s + c`, skeleton node `s`).
    pub system: LinearSystem,
    elements: Vec<CondensedBlock>,
}

impl<G: ShellGeometry + Sync> HighOrderNavier<G> {
    /// Element dofs `l = 2 (p + 1)^2`.
    fn local_dofs(&self) -> usize {
        2 * self.np() * self.np()
    }

    /// Adds the (symmetric) stiffness matrix of element `e` to `out` (`l x l`, local dof
    /// `2 a + c`).
    /// The kernel is the direct quadrature loop for `p <= 2`
    /// ([`super::add_element_matrix_direct`], symmetric as computed) and the sum
    /// factorisation above.
    pub(super) fn element_matrix(&self, e: usize, out: &mut [f64]) {
        let nq2 = self.tables.nq * self.tables.nq;
        let direct = self.degree <= DIRECT_KERNEL_ORDERS;
        let kernel = if direct {
            add_element_matrix_direct
        } else {
            add_element_matrix
        };
        kernel(&self.tables, &self.kq[e * nq2..(e + 1) * nq2], out);
        if let Some(rt) = &self.reduced_tables {
            let nr2 = rt.nq * rt.nq;
            kernel(rt, &self.kv[e * nr2..(e + 1) * nr2], out);
        }
        if !direct {
            symmetrise(out, self.local_dofs());
        }
    }

    /// The `x3` factors of the full rule and of the reduced rule (SRI), for
    /// [`Self::tensor_matrix`].
    fn x3_factors(&self) -> (X3Factors, Option<X3Factors>) {
        (
            X3Factors::new(&self.tables),
            self.reduced_tables.as_ref().map(X3Factors::new),
        )
    }

    /// The stiffness matrix of element `e` in tensor form
    /// ([`X3Factors::add_tensor_matrix`]) into `m` (overwritten), `tt` scratch.
    fn tensor_matrix(
        &self,
        e: usize,
        (full, reduced): &(X3Factors, Option<X3Factors>),
        tt: &mut Vec<f64>,
        m: &mut [f64],
    ) {
        m.fill(0.0);
        let mut add = |f: &X3Factors, kq: &[[[f64; 6]; 6]]| {
            let len = f.scratch_len();
            if tt.len() < len {
                tt.resize(len, 0.0);
            }
            let out = faer::MatMut::from_column_major_slice_mut(&mut *m, f.rows(), f.cols());
            f.add_tensor_matrix(kq, &mut tt[..len], out);
        };
        let nq2 = self.tables.nq * self.tables.nq;
        add(full, &self.kq[e * nq2..(e + 1) * nq2]);
        if let (Some(r), Some(rt)) = (reduced, &self.reduced_tables) {
            let nr2 = rt.nq * rt.nq;
            add(r, &self.kv[e * nr2..(e + 1) * nr2]);
        }
    }

    fn element_count(&self) -> usize {
        self.elements[0] * self.elements[1]
    }

    /// The pattern of the whole system (every GLL node), built on first use.
    fn full_assembly(&self) -> Result<&ElementAssembly, ElasticityError> {
        if let Some(a) = self.full.get() {
            return Ok(a);
        }
        let connectivity = (0..self.element_count())
            .flat_map(|e| self.element_nodes(e))
            .collect();
        let a = ElementAssembly::new(
            self.problem.grid.node_count(),
            2,
            self.np() * self.np(),
            connectivity,
            &self.dirichlet,
        )?;
        let _ = self.full.set(a);
        Ok(self.full.get().expect("just set"))
    }

    /// The skeleton numbering and pattern, built on first use.
    fn skeleton(&self) -> Result<&Skeleton, ElasticityError> {
        if let Some(s) = self.skeleton.get() {
            return Ok(s);
        }
        let s = Skeleton::new(
            self.degree,
            [self.problem.grid.n2(), self.problem.grid.n3()],
            self.element_count(),
            |e| self.element_nodes(e),
            &self.dirichlet,
        )?;
        let _ = self.skeleton.set(s);
        Ok(self.skeleton.get().expect("just set"))
    }

    /// The system on every node, not condensed (what [`Discretisation::system`] returns).
    ///
    /// # Errors
    /// [`ElasticityError::NonFinite`] for a non-finite element matrix; pattern errors.
    pub fn full_system(&self) -> Result<LinearSystem, ElasticityError> {
        self.full_assembly()?.assemble(
            |e, out| self.element_matrix(e, out),
            &self.load,
            &self.dirichlet,
        )
    }

    /// Condenses the element interiors: the element Schur complements (in parallel) and the
    /// skeleton system they assemble into ([`CondensedBlock`]).
    ///
    /// # Errors
    /// [`ElasticityError::InconsistentBoundary`] for a prescribed dof inside an element;
    /// [`ElasticityError::Solver`] if an interior block is not positive definite.
    pub fn condensed_system(&self) -> Result<CondensedSystem, ElasticityError> {
        let sk = self.skeleton()?;
        let local = |set: &[usize]| -> Vec<usize> {
            set.iter().flat_map(|&a| [2 * a, 2 * a + 1]).collect()
        };
        let (bd, id) = (local(&sk.boundary_local), local(&sk.interior_local));
        let np = self.np();
        let factors = self.x3_factors();
        let elements = condense_elements(
            self.element_count(),
            np,
            factors.0.rows() * factors.0.cols(),
            (&bd, &id),
            |e, tt, m| self.tensor_matrix(e, &factors, tt, m),
            (&self.load, |e| self.element_nodes(e)),
        )?;
        let mut load: Vec<f64> = sk
            .nodes
            .iter()
            .flat_map(|&m| [self.load[2 * m], self.load[2 * m + 1]])
            .collect();
        for (e, c) in elements.iter().enumerate() {
            let nodes = sk.assembly.nodes(e);
            for (r, g) in c.load.iter().enumerate() {
                load[2 * nodes[r / 2] + r % 2] += g;
            }
        }
        let system = sk.assembly.assemble(
            |e, out| out.copy_from_slice(&elements[e].schur),
            &load,
            &sk.dirichlet,
        )?;
        Ok(CondensedSystem { system, elements })
    }

    /// The displacement on every node from the skeleton solution `u_skeleton` of
    /// `condensed.system`: skeleton values scattered, interiors `u_I = y - X u_B`.
    ///
    /// # Errors
    /// [`ElasticityError::DimensionMismatch`] for a wrong length.
    pub fn recover(
        &self,
        condensed: &CondensedSystem,
        u_skeleton: &[f64],
    ) -> Result<Vec<f64>, ElasticityError> {
        let sk = self.skeleton()?;
        ElasticityError::check_length("skeleton solution", 2 * sk.nodes.len(), u_skeleton.len())?;
        let mut v = vec![0.0; self.dof_count()];
        for (s, &m) in sk.nodes.iter().enumerate() {
            v[2 * m] = u_skeleton[2 * s];
            v[2 * m + 1] = u_skeleton[2 * s + 1];
        }
        let interiors: Vec<Vec<f64>> = (0..self.element_count())
            .into_par_iter()
            .map(|e| {
                let ub: Vec<f64> = sk
                    .assembly
                    .nodes(e)
                    .iter()
                    .flat_map(|&s| [u_skeleton[2 * s], u_skeleton[2 * s + 1]])
                    .collect();
                condensed.elements[e].recover(&ub)
            })
            .collect();
        for (e, ui) in interiors.iter().enumerate() {
            let nodes = self.element_nodes(e);
            for (r, &a) in sk.interior_local.iter().enumerate() {
                v[2 * nodes[a]] = ui[2 * r];
                v[2 * nodes[a] + 1] = ui[2 * r + 1];
            }
        }
        Ok(v)
    }

    /// Solves by static condensation: condense, factorise and solve the skeleton system with
    /// `solver`, recover the interiors. Falls back to the full system when a prescribed dof
    /// lies inside an element.
    ///
    /// # Errors
    /// Assembly or solver errors.
    pub fn solve_condensed(
        &self,
        solver: &mut dyn LinearSolver<f64>,
    ) -> Result<Vec<f64>, ElasticityError> {
        match self.condensed_system() {
            Ok(c) => {
                let u = c.system.solve(solver)?;
                self.recover(&c, &u)
            }
            Err(ElasticityError::InconsistentBoundary { .. }) => self.full_system()?.solve(solver),
            Err(e) => Err(e),
        }
    }

    /// The element containing `x` (clamped to the rectangle) and the reference coordinates
    /// there.
    fn locate(&self, [x2, x3]: [f64; 2]) -> (usize, [f64; 2]) {
        let (e2, xi) = locate(&self.breaks[0], x2);
        let (e3, eta) = locate(&self.breaks[1], x3);
        (e2 * self.elements[1] + e3, [xi, eta])
    }

    /// The discrete displacement `[v^2, v^3]` at `x` (the element polynomial; clamped to the
    /// rectangle).
    pub fn displacement_at(&self, v: &[f64], x: [f64; 2]) -> [f64; 2] {
        let (e, [xi, eta]) = self.locate(x);
        let nodes = self.element_nodes(e);
        let np = self.np();
        let (b2, _) = lagrange_basis(&self.gll, xi);
        let (b3, _) = lagrange_basis(&self.gll, eta);
        let mut u = [0.0; 2];
        for a2 in 0..np {
            for a3 in 0..np {
                let (n, m) = (b2[a2] * b3[a3], nodes[a2 * np + a3]);
                u[0] += n * v[2 * m];
                u[1] += n * v[2 * m + 1];
            }
        }
        u
    }

    /// Interpolates the discrete and the exact displacement over every element with a
    /// `(p + 2)`-point Gauss rule per direction and returns the error norms
    /// ([`crate::finite_element::DisplacementErrors`]; the max error is over the GLL nodes at
    /// their own coordinates).
    ///
    /// # Errors
    /// [`ElasticityError::DimensionMismatch`] for a wrong length; geometry failures.
    pub fn displacement_errors(
        &self,
        v: &[f64],
        exact: &(dyn Fn([f64; 2]) -> [f64; 2] + Sync),
    ) -> Result<DisplacementErrors, ElasticityError> {
        let (gp, gw) = gauss_legendre(self.degree + 2);
        let basis: Vec<Vec<f64>> = gp.iter().map(|&x| lagrange_basis(&self.gll, x).0).collect();
        let element = |e: usize| -> (Vec<usize>, ElementMap<'_>) {
            let ([x0, y0], [l2, l3]) = self.element_box(e);
            let map = move |[xi, eta]: [f64; 2]| {
                let x = [x0 + 0.5 * (xi + 1.0) * l2, y0 + 0.5 * (eta + 1.0) * l3];
                (x, 0.25 * l2 * l3)
            };
            (self.element_nodes(e), Box::new(map))
        };
        let elements = LagrangeElements {
            count: self.element_count(),
            rule: (&gp, &gw),
            basis: &basis,
            element: &element,
        };
        let grid = &self.problem.grid;
        let position = |k: usize| self.node_coordinates(grid.node(k));
        displacement_errors(
            &self.problem,
            &elements,
            grid.node_count(),
            &position,
            v,
            exact,
        )
    }
}

impl<G: ShellGeometry + Sync> Discretisation for HighOrderNavier<G> {
    /// `fem-qp`, or `fem-q1` / `fem-q2` for orders 1, 2 with the nodal-difference recovery
    /// ([`super::QpSettings::method_name`]).
    fn method(&self) -> &'static str {
        self.settings().method_name()
    }

    /// Nested dissection along element boundaries of degree `p`: it eliminates the element
    /// interiors first, the sparse-factorisation counterpart of static condensation.
    fn lu_ordering(&self) -> capstan_solvers::ColumnOrdering {
        capstan_solvers::ColumnOrdering::ElementNestedDissection {
            grid: self.problem.grid.shape(),
            degree: self.degree,
        }
    }

    plane_strain_numbering!();

    /// The Gauss–Lobatto–Legendre positions ([`HighOrderNavier::node_coordinates`]).
    fn node_position(&self, node: [usize; 2]) -> [f64; 2] {
        self.node_coordinates(node)
    }

    fn entries(&self) -> Result<Vec<(usize, usize)>, ElasticityError> {
        Ok(self.full_assembly()?.pattern().entries().collect())
    }

    fn fill_values(
        &self,
        add: &mut dyn FnMut(usize, f64),
        rhs: &mut [f64],
    ) -> Result<(), ElasticityError> {
        let system = self.full_system()?;
        for (k, x) in system.values.into_iter().enumerate() {
            add(k, x);
        }
        rhs.copy_from_slice(&system.rhs);
        Ok(())
    }

    /// The whole system (every node), assembled straight into its pattern; equal to the
    /// default `entries()` + `fill()` path.
    fn system(&self) -> Result<LinearSystem, ElasticityError> {
        self.full_system()
    }

    /// Static condensation ([`HighOrderNavier::solve_condensed`]).
    fn solve(&self, solver: &mut dyn LinearSolver<f64>) -> Result<Vec<f64>, ElasticityError> {
        self.solve_condensed(solver)
    }

    /// # Math
    /// Traction weight `sqrt(g) sqrt(g^33) int N_i dx2` with `int N_i dx2 = w_a L2 / 2` per
    /// element sharing the node (`w_a` the GLL weight: exact, the GLL rule integrates degree
    /// `2p - 1`; for `p = 1, 2` the trapezoid and Simpson's `1/3, 4/3` pattern); `T^3_3`,
    /// `T^3_2` from the node's value and derivatives by the operator's [`super::NodalRecovery`]
    /// (`Element`: the pointwise stress also under SRI; `Differences` with SRI: `T^3_3` with
    /// the reduced-point divergence). The entry's `x2` is the node's GLL position.
    fn contact_nodes(&self) -> Result<Vec<ContactNode>, ElasticityError> {
        (0..self.problem.grid.n2())
            .map(|i| {
                let x2 = self.x2[i];
                let at = [0.0, x2, 0.0];
                let p = self.problem.chart.shell_point(at)?;
                crate::continuum::check_plane_strain(&p, at)?;
                let length: f64 = self
                    .elements_along(i, self.elements[0], self.problem.grid.is_periodic())
                    .iter()
                    .map(|&(e, a)| self.gll_weights[a] * 0.5 * self.span(0, e).1)
                    .sum();
                let weight = p.sqrt_g * p.inverse_metric[2][2].sqrt() * length;
                let mut node = ContactNode::at(
                    self,
                    i,
                    &self.dirichlet,
                    weight,
                    p.metric[1][1].sqrt(),
                    self.contact_rows(i, &p),
                );
                node.x2 = x2;
                Ok(node)
            })
            .collect()
    }

    /// Fields at the GLL nodes (at their own coordinates; `NodalFields::grid` is the uniform
    /// grid of the same node counts): value and gradient by the operator's
    /// [`super::NodalRecovery`]; with `Differences` and SRI the stress
    /// `T^ij = lambda g^ij div_h v + 2 mu E^ij` with the reduced-point divergence (so its
    /// `T^33 g_33` on `x3 = 0` is the contact row's `T^3_3`).
    fn fields(&self, v: &[f64]) -> Result<NodalFields, ElasticityError> {
        ElasticityError::check_length("displacement", self.dof_count(), v.len())?;
        let split = self.recovery == super::NodalRecovery::Differences
            && self.volumetric == VolumetricIntegration::Reduced;
        NodalFields::from_nodes_at(
            self.problem.grid,
            |node| self.node_coordinates(node),
            &self.problem.chart,
            |node, p| {
                let u = self.local(node, v);
                let mut stress = contravariant_stress(p, &self.problem.material, &u);
                if split {
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
            },
        )
    }
}
