//! Adding a discretisation: linear triangles (P1), written outside capstan, registered once,
//! then named from scenes like a built-in method.
//!
//! Problem: the plane-strain curvilinear Navier operator of the thick body (paper section 3)
//! on the parameter rectangle `[theta0, theta1] x [0, h]`, by the Galerkin method with linear
//! triangles: every cell of the `n2 x n3` grid is cut along its diagonal into two triangles
//! (same nodes and unknowns `v^2, v^3` as the built-in methods):
//! ```text
//! a(v, w) = int_Omega u(v)^T K_q u(w) dx2 dx3          u = [v^2, v^3, d_2 v^2, d_2 v^3, d_3 v^2, d_3 v^3]
//! K_q     = sqrt(g) (lambda tr M_k tr M_l + 2 mu tr(M_k M_l))   capstan_elasticity::continuum::energy_matrix
//! l(w)    = int_Omega f_j w^j sqrt(g) dx2 dx3 + int_sides phi_j w^j ds    phi_j: continuum::face_flux
//! ```
//! integrated with the three-point edge-midpoint rule on each triangle (exact for quadratics)
//! and two Gauss points on each boundary edge; Dirichlet rows eliminated symmetrically by
//! `finite_element::ElementAssembly`. The contact rows (`T^3_2`, `T^3_3` at the nodes of
//! `x3 = 0`) and the nodal fields are recovered with the grid's second-order difference
//! stencil, as the built-in methods do. P1 is second order in the displacement (L2), first
//! in its gradient.
//!
//! The method is registered as `p1-triangles` (`discretisation.method = "p1-triangles"`); the
//! contact solvers, sweeps, outputs and grid sequencing then use it with no capstan edit.
//!
//! Run: `cargo run --release --example extend_discretisation`
//! Look at: the observed order on a manufactured solution (about 2), and the contact solve
//! of the paper's body with P1 beside Q1 on the same grid (the same slip zone, displacements
//! within the discretisation error of each other).

use std::sync::Arc;

use capstan::elasticity::continuum::kinematics::{contravariant_stress, mixed_stress_coefficients};
use capstan::elasticity::continuum::{
    FaceData, PLANE_STRAIN, check_plane_strain, energy_matrix, face_flux,
};
use capstan::elasticity::finite_element::ElementAssembly;
use capstan::elasticity::kinematics::LocalDisplacement;
use capstan::elasticity::registry::{
    self, DiscretisationScheme, PlaneOperator, RegisteredDiscretisation,
};
use capstan::elasticity::{
    Component, ComponentCondition, ContactNode, Discretisation, ElasticityError, Grid,
    LinearSystem, NodalFields, PlaneProblem, SharedChart, ShellGeometry, Side, SparseRow,
};
use capstan::geometry::ShellPoint;
use capstan::solvers::SparsityPattern;

/// Linear triangles on the grid of a [`PlaneProblem`]: element matrices and load computed
/// once, assembled on a pattern built once.
struct P1Triangles {
    problem: PlaneProblem<SharedChart>,
    assembly: ElementAssembly,
    /// Per triangle, the 6 x 6 element matrix (local dof `2 a + c`), row-major.
    matrices: Vec<[f64; 36]>,
    /// Body force and natural boundary terms.
    load: Vec<f64>,
    /// The prescribed value of every dof (`None`: a balance row).
    dirichlet: Vec<Option<f64>>,
}

/// The two triangles of cell `(i, j)`: its diagonal runs from `(i, j)` to `(i + 1, j + 1)`.
fn cell_triangles(i: usize, j: usize) -> [[[usize; 2]; 3]; 2] {
    [
        [[i, j], [i + 1, j], [i + 1, j + 1]],
        [[i, j], [i + 1, j + 1], [i, j + 1]],
    ]
}

impl P1Triangles {
    /// Builds the operator of `problem`.
    ///
    /// # Errors
    /// A periodic grid (a full wrap: not supported here) as
    /// [`ElasticityError::InconsistentBoundary`]; the chart's and the boundary data's errors.
    fn new(problem: PlaneProblem<SharedChart>) -> Result<Self, ElasticityError> {
        let grid = problem.grid;
        problem.boundary.check_grid(&grid)?;
        if grid.is_periodic() {
            return Err(ElasticityError::InconsistentBoundary {
                what: "p1-triangles: a periodic grid (full wrap) is not supported",
            });
        }
        let dirichlet = (0..2 * grid.node_count())
            .map(|d| {
                let c = [Component::X2, Component::X3][d % 2];
                problem.boundary.dirichlet_value(&grid, grid.node(d / 2), c)
            })
            .collect::<Result<Vec<_>, _>>()?;
        let mut connectivity = Vec::new();
        for i in 0..grid.n2() - 1 {
            for j in 0..grid.n3() - 1 {
                for t in cell_triangles(i, j) {
                    connectivity.extend(t.map(|n| grid.node_index(n)));
                }
            }
        }
        let assembly =
            ElementAssembly::new(grid.node_count(), 2, 3, connectivity.clone(), &dirichlet)?;
        let (lambda, mu) = (problem.material.lambda(), problem.material.mu());
        let mut matrices = Vec::with_capacity(connectivity.len() / 3);
        let mut load = vec![0.0; 2 * grid.node_count()];
        for nodes in connectivity.chunks(3) {
            let x = [0, 1, 2].map(|a| grid.coordinates(grid.node(nodes[a])));
            // linear shape functions: constant gradients from the vertices
            let area2 = (x[1][0] - x[0][0]) * (x[2][1] - x[0][1])
                - (x[2][0] - x[0][0]) * (x[1][1] - x[0][1]);
            let gradient = [0, 1, 2].map(|a| {
                let (b, c) = ((a + 1) % 3, (a + 2) % 3);
                [(x[b][1] - x[c][1]) / area2, (x[c][0] - x[b][0]) / area2]
            });
            let mut m = [0.0; 36];
            // edge midpoints, weight area / 3 each: N = 1/2 at the edge's two vertices
            for q in 0..3 {
                let (a, b) = (q, (q + 1) % 3);
                let at = [0.5 * (x[a][0] + x[b][0]), 0.5 * (x[a][1] + x[b][1])];
                let p = point(&problem, at)?;
                let weight = area2.abs() / 6.0;
                let k = energy_matrix(&p, &PLANE_STRAIN, lambda, mu, weight);
                let shape = |n: usize| if n == a || n == b { 0.5 } else { 0.0 };
                // inputs of local dof (n, c): v^c -> N_n, d_2 v^c -> d_2 N_n, d_3 v^c -> d_3 N_n
                let inputs = |n: usize, c: usize| {
                    [
                        (c, shape(n)),
                        (2 + c, gradient[n][0]),
                        (4 + c, gradient[n][1]),
                    ]
                };
                for r in 0..6 {
                    for s in 0..6 {
                        for (i, bi) in inputs(r / 2, r % 2) {
                            for (j, bj) in inputs(s / 2, s % 2) {
                                m[6 * r + s] += bi * k[i][j] * bj;
                            }
                        }
                    }
                }
                if let Some(force) = &problem.body_force {
                    let f = force(at);
                    for n in [a, b] {
                        for c in 0..2 {
                            load[2 * nodes[n] + c] += weight * p.sqrt_g * 0.5 * f[c];
                        }
                    }
                }
            }
            matrices.push(m);
        }
        add_boundary_loads(&problem, &mut load)?;
        Ok(Self {
            problem,
            assembly,
            matrices,
            load,
            dirichlet,
        })
    }

    fn assemble(&self) -> Result<LinearSystem, ElasticityError> {
        self.assembly.assemble(
            |e, out| out.copy_from_slice(&self.matrices[e]),
            &self.load,
            &self.dirichlet,
        )
    }

    /// `[T^3_2, T^3_3]` at contact node `i` as rows over the dofs: the pointwise stress of the
    /// displacement recovered by the grid's difference stencil.
    fn contact_rows(&self, i: usize) -> Result<[SparseRow; 2], ElasticityError> {
        let grid = &self.problem.grid;
        let p = point(&self.problem, grid.coordinates([i, 0]))?;
        let coefficients = mixed_stress_coefficients(&p, &self.problem.material);
        let mut stencil = Vec::new();
        grid.node_stencil([i, 0], &mut stencil);
        Ok([1, 2].map(|j| {
            let mut terms = Vec::new();
            for (node, w) in &stencil {
                for c in 0..2 {
                    let x: f64 = (0..3).map(|k| w[k] * coefficients[2 * k + c][2][j]).sum();
                    terms.push((2 * grid.node_index(*node) + c, x));
                }
            }
            SparseRow::from_terms(&mut terms)
        }))
    }
}

/// The chart point at `(x2, x3)`, checked for the plane-strain reduction.
fn point(
    problem: &PlaneProblem<SharedChart>,
    [x2, x3]: [f64; 2],
) -> Result<ShellPoint<f64>, ElasticityError> {
    let p = problem.chart.shell_point([0.0, x2, x3])?;
    check_plane_strain(&p, [0.0, x2, x3])?;
    Ok(p)
}

/// Adds `int phi_j w^j ds` of every natural side condition to `load` (two Gauss points per
/// boundary edge; the edge's shape functions are linear, as in every P1 element).
fn add_boundary_loads(
    problem: &PlaneProblem<SharedChart>,
    load: &mut [f64],
) -> Result<(), ElasticityError> {
    let grid = problem.grid;
    let gauss = [0.5 - 0.5 / 3f64.sqrt(), 0.5 + 0.5 / 3f64.sqrt()];
    for side in Side::ALL {
        let Some(condition) = problem.boundary.side(side) else {
            continue;
        };
        let nodes: Vec<[usize; 2]> = match side {
            Side::X3Min => (0..grid.n2()).map(|i| [i, 0]).collect(),
            Side::X3Max => (0..grid.n2()).map(|i| [i, grid.n3() - 1]).collect(),
            Side::X2Min => (0..grid.n3()).map(|j| [0, j]).collect(),
            Side::X2Max => (0..grid.n3()).map(|j| [grid.n2() - 1, j]).collect(),
        };
        // the coordinate along the side
        let along = |node: [usize; 2]| {
            let x = grid.coordinates(node);
            if side.normal_index() == 2 { x[0] } else { x[1] }
        };
        for c in [Component::X2, Component::X3] {
            let data = |s: f64| match condition.component(c) {
                ComponentCondition::Displacement(_) => None,
                ComponentCondition::Traction(f) => Some(FaceData::Traction(f.eval(s))),
                ComponentCondition::Stress(f) => Some(FaceData::Stress(f.eval(s))),
            };
            for edge in nodes.windows(2) {
                let (s0, s1) = (along(edge[0]), along(edge[1]));
                for t in gauss {
                    let s = s0 + t * (s1 - s0);
                    let Some(value) = data(s) else { continue };
                    let at = side.point(&grid, s);
                    let p = point(problem, at)?;
                    let flux = face_flux(&p, side.normal_index(), side.sign(), value, at)?;
                    let w = 0.5 * (s1 - s0);
                    load[2 * grid.node_index(edge[0]) + c.index()] += w * (1.0 - t) * flux;
                    load[2 * grid.node_index(edge[1]) + c.index()] += w * t * flux;
                }
            }
        }
    }
    Ok(())
}

impl Discretisation for P1Triangles {
    fn method(&self) -> &'static str {
        "p1-triangles"
    }

    fn grid(&self) -> &Grid {
        &self.problem.grid
    }

    fn dof_count(&self) -> usize {
        2 * self.problem.grid.node_count()
    }

    fn dof(&self, node: [usize; 2], component: Component) -> usize {
        2 * self.problem.grid.node_index(node) + component.index()
    }

    fn entries(&self) -> Result<Vec<(usize, usize)>, ElasticityError> {
        Ok(SparsityPattern::entries(self.assembly.pattern()).collect())
    }

    fn fill_values(
        &self,
        add: &mut dyn FnMut(usize, f64),
        rhs: &mut [f64],
    ) -> Result<(), ElasticityError> {
        let system = self.assemble()?;
        for (k, x) in system.values.iter().enumerate() {
            add(k, *x);
        }
        rhs.copy_from_slice(&system.rhs);
        Ok(())
    }

    fn system(&self) -> Result<LinearSystem, ElasticityError> {
        self.assemble()
    }

    fn contact_nodes(&self) -> Result<Vec<ContactNode>, ElasticityError> {
        let grid = &self.problem.grid;
        (0..grid.n2())
            .map(|i| {
                let p = point(&self.problem, grid.coordinates([i, 0]))?;
                // int N_i dx2 on x3 = 0: the trapezoid rule's weight
                let end = i == 0 || i == grid.n2() - 1;
                let length = if end { 0.5 } else { 1.0 } * grid.dx2();
                let weight = p.sqrt_g * p.inverse_metric[2][2].sqrt() * length;
                let rows = self.contact_rows(i)?;
                Ok(ContactNode::at(
                    self,
                    i,
                    &self.dirichlet,
                    weight,
                    p.metric[1][1].sqrt(),
                    rows,
                ))
            })
            .collect()
    }

    fn fields(&self, v: &[f64]) -> Result<NodalFields, ElasticityError> {
        ElasticityError::check_length("displacement", self.dof_count(), v.len())?;
        let grid = self.problem.grid;
        let mut stencil = Vec::new();
        NodalFields::from_nodes(grid, &self.problem.chart, |node, p| {
            grid.node_stencil(node, &mut stencil);
            let u = LocalDisplacement::from_stencil(&stencil, |n, c| v[2 * grid.node_index(n) + c]);
            Ok((u, contravariant_stress(p, &self.problem.material, &u)))
        })
    }
}

/// The registry's variant: P1 triangles have no data of their own.
#[derive(Debug)]
struct P1Scheme;

impl DiscretisationScheme for P1Scheme {
    fn name(&self) -> &'static str {
        "p1-triangles"
    }

    fn build(&self, problem: PlaneProblem<SharedChart>) -> Result<PlaneOperator, ElasticityError> {
        Ok(Box::new(P1Triangles::new(problem)?))
    }
}

/// Registers `p1-triangles` once per process (the registry refuses a second registration of
/// a name; tests run in parallel threads).
fn register() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        registry::register(RegisteredDiscretisation {
            name: "p1-triangles",
            summary: "linear triangles (two per grid cell), plane strain only",
            parameters: &[],
            build: |s| {
                s.require_full_uniform("full with p1-triangles", "1 (uniform) with p1-triangles")?;
                Ok(Arc::new(P1Scheme))
            },
        })
        .expect("p1-triangles is registered once");
    });
}

/// `(h, L2 error)` of P1 on the manufactured solution of an elliptical prism (exact forcing;
/// `traction`: displacement on the ends, tractions on `x3 = 0, h`; else a stress condition
/// `T^2_j` on one end and bilateral contact on `x3 = 0`) on grids `(2 m + 1) x (m + 1)`.
fn mms_errors(levels: &[usize], traction: bool) -> Result<Vec<(f64, f64)>, ElasticityError> {
    use capstan::elasticity::samples::{MmsBoundaries, PrismMms, displacement_error};
    use capstan::elasticity::verification::GridLevel;
    register();
    let boundaries = if traction {
        MmsBoundaries::TractionContact
    } else {
        MmsBoundaries::BilateralContact
    };
    let mms = PrismMms::ellipse(0.5, boundaries);
    levels
        .iter()
        .map(|&m| {
            let (parts, exact) = mms.parts(GridLevel {
                n2: 2 * m + 1,
                n3: m + 1,
            })?;
            let scheme = registry::build("p1-triangles", &Default::default())?;
            let op = scheme.build(parts.share_chart())?;
            let v = op.solve(&mut capstan::solvers::SparseLu::default())?;
            let [_, l2] = displacement_error(&op, &v, &exact.field)?;
            Ok((op.grid().dx3(), l2))
        })
        .collect()
}

/// Slip fraction and largest azimuthal displacement of the paper's contact problem on a
/// `61 x 11` grid with `discretisation.method = method`, named in the scene only.
fn contact(method: &str) -> Result<(f64, f64), capstan::CliError> {
    register();
    let scene = capstan::Scene::default()
        .with_raw("discretisation.method", &format!("{method:?}"), "example")?
        .with_raw("grid.n2", "61", "example")?
        .with_raw("grid.n3", "11", "example")?;
    let (report, _) =
        capstan::api::contact_observed(&scene, &mut capstan::solvers::SilentObserver)?;
    Ok((
        report.slip_fraction,
        report.max_azimuthal_displacement.value,
    ))
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let study = mms_errors(&[8, 16, 32], true)?;
    for (h, e) in &study {
        println!("h = {h:.5}   L2 error = {e:.3e}");
    }
    let order = capstan::elasticity::verification::observed_order(&study);
    println!("observed order {order:.2} (expected 2)");
    for method in ["p1-triangles", "fem-q1"] {
        let (slip, v2) = contact(method)?;
        println!("{method:>13}: slip fraction {slip:.4}, max |v^2| {v2:.6e}");
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn p1_is_second_order_on_a_manufactured_solution() {
        // measured: 6.43e-5, 1.60e-5, 3.99e-6 (traction sides), order 2.01
        for (traction, finest) in [(true, 6e-6), (false, 6e-6)] {
            let study = mms_errors(&[8, 16, 32], traction).unwrap();
            let order = capstan::elasticity::verification::observed_order(&study);
            assert!((order - 2.0).abs() < 0.15, "order {order}: {study:?}");
            assert!(study[2].1 < finest, "{study:?}");
        }
    }

    #[test]
    fn p1_contact_agrees_with_q1_on_the_same_grid() {
        let (p1_slip, p1_v2) = contact("p1-triangles").unwrap();
        let (q1_slip, q1_v2) = contact("fem-q1").unwrap();
        assert!(p1_slip > 0.0 && p1_slip < 1.0);
        // measured: 0.5902 vs 0.5574 (two of 61 nodes), max |v^2| 3.609e-3 vs 3.587e-3
        assert!((p1_slip - q1_slip).abs() < 0.05, "{p1_slip} vs {q1_slip}");
        assert!(
            (p1_v2 - q1_v2).abs() < 0.02 * q1_v2.abs(),
            "{p1_v2} vs {q1_v2}"
        );
    }

    #[test]
    fn an_unknown_volumetric_rule_is_refused_naming_the_key() {
        register();
        let scene = capstan::Scene::default()
            .with_raw("discretisation.method", "\"p1-triangles\"", "test")
            .and_then(|s| s.with_raw("discretisation.volumetric", "\"reduced\"", "test"));
        let message = match scene {
            Err(e) => e.to_string(),
            Ok(s) => capstan::api::contact_observed(&s, &mut capstan::solvers::SilentObserver)
                .unwrap_err()
                .to_string(),
        };
        assert!(message.contains("discretisation.volumetric"), "{message}");
    }
}
