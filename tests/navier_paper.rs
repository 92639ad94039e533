//! The derived operator against the paper's printed reduced equations (section 3, ellipse).
//!
//! Printed: `(lambda + mu) d_2(nabla_i v^i) + mu psi^2 Delta v^2 = 0` and
//! `(lambda + mu) d_3(nabla_i v^i) + mu Delta v^3 = 0`, `psi^2 = g_22`, with `Delta` the vector
//! Laplacian. They agree with `nabla_i T^i_j` when `Delta v^k` is read as the contravariant
//! component `(Delta v)^k = g^k . Delta U` of the vector Laplacian of the Cartesian displacement
//! `U = v^i g_i`, not as the scalar Laplacian of the function `v^k`.

use capstan_elasticity::samples::{ExactSolution, ManufacturedField, TrigonometricField};
use capstan_elasticity::{
    BoundaryConditions, ElasticityError, FiniteDifferenceNavier, Grid, Material, PlaneProblem,
};
use capstan_geometry::{EllipticalPrism, Obstacle, RightCircularCone, ShellChart, ShellPoint};

fn chart() -> ShellChart<Obstacle> {
    ShellChart::new(Obstacle::Ellipse(EllipticalPrism::new(1.0, 0.5).unwrap()))
}

fn point(x: [f64; 2]) -> ShellPoint<f64> {
    chart().point([0.0, x[0], x[1]]).unwrap()
}

/// Richardson-extrapolated central difference of `f` along `axis`.
fn derivative<const N: usize>(
    f: &dyn Fn([f64; 2]) -> [f64; N],
    x: [f64; 2],
    axis: usize,
) -> [f64; N] {
    let diff = |h: f64| {
        let (mut p, mut m) = (x, x);
        p[axis] += h;
        m[axis] -= h;
        let (a, b) = (f(p), f(m));
        core::array::from_fn::<f64, N, _>(|k| (a[k] - b[k]) / (2.0 * h))
    };
    let (d1, d2) = (diff(2e-3), diff(1e-3));
    core::array::from_fn(|k| (4.0 * d2[k] - d1[k]) / 3.0)
}

/// `nabla_i v^i = d_a v^a + Gamma^i_ia v^a`.
fn divergence(x: [f64; 2]) -> [f64; 1] {
    let (p, u) = (point(x), TrigonometricField.displacement(x));
    let mut d = u.gradient[0][0] + u.gradient[1][1];
    for a in 0..2 {
        d += (0..3).map(|i| p.christoffel[i][i][a + 1]).sum::<f64>() * u.value[a];
    }
    [d]
}

/// `sqrt(g) g^ab d_b U` (Cartesian, 3 components) for the outer derivative along `a`;
/// `d_b U = d_b v^c g_c + v^c Gamma^k_bc g_k`.
#[allow(clippy::needless_range_loop)] // index loops mirror v^c Gamma^k_bc g_k
fn laplacian_flux(x: [f64; 2], a: usize) -> [f64; 3] {
    let (p, u) = (point(x), TrigonometricField.displacement(x));
    let v = [0.0, u.value[0], u.value[1]];
    let du = |b: usize| -> [f64; 3] {
        core::array::from_fn(|e| {
            let mut s = 0.0;
            for c in 1..3 {
                s += u.gradient[b - 1][c - 1] * p.covariant_basis[c][e];
                for k in 0..3 {
                    s += v[c] * p.christoffel[k][b][c] * p.covariant_basis[k][e];
                }
            }
            s
        })
    };
    let (d2, d3) = (du(1), du(2));
    core::array::from_fn(|e| {
        p.sqrt_g * (p.inverse_metric[a][1] * d2[e] + p.inverse_metric[a][2] * d3[e])
    })
}

/// The trigonometric field on the chart, `E = 10`, `nu = 0.3`, with its Lamé constants
/// `(lambda, mu)`.
fn trigonometric_solution() -> (
    ExactSolution<ShellChart<Obstacle>, TrigonometricField>,
    f64,
    f64,
) {
    let material = Material::new(10.0, 0.3).unwrap();
    let (l, m) = (material.lambda(), material.mu());
    let exact = ExactSolution {
        chart: chart(),
        material,
        field: TrigonometricField,
    };
    (exact, l, m)
}

#[test]
fn printed_navier_equations_match_with_the_vector_laplacian() {
    let (exact, l, m) = trigonometric_solution();
    for x in [[0.3, 0.2], [-0.9, 0.1], [0.8, 0.45]] {
        let p = point(x);
        let ours = exact.forcing(x).unwrap().map(|f| -f); // nabla_i T^i_j
        let grad_div = [
            derivative(&divergence, x, 0)[0],
            derivative(&divergence, x, 1)[0],
        ];
        let f2 = derivative(&|y| laplacian_flux(y, 1), x, 0);
        let f3 = derivative(&|y| laplacian_flux(y, 2), x, 1);
        let lap_u: [f64; 3] = core::array::from_fn(|e| (f2[e] + f3[e]) / p.sqrt_g);
        let dot = |a: &[f64; 3], b: &[f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        // (Delta v)^k = g^k . Delta U; printed: (lambda+mu) d_j div + mu g_jj (Delta v)^j
        let vec_lap = [1, 2].map(|k| dot(&p.contravariant_basis[k], &lap_u));
        let printed = [
            (l + m) * grad_div[0] + m * p.metric[1][1] * vec_lap[0],
            (l + m) * grad_div[1] + m * vec_lap[1],
        ];
        for j in 0..2 {
            // nested Richardson differences: ~1e-9 absolute
            assert!(
                (ours[j] - printed[j]).abs() < 1e-7 * (1.0 + ours[j].abs()),
                "j={} {ours:?} {printed:?}",
                j + 2
            );
        }
        // Read as the scalar Laplacian of the function v^2, the printed equation is wrong:
        let scalar_flux = |y: [f64; 2], a: usize| -> [f64; 1] {
            let (q, u) = (point(y), TrigonometricField.displacement(y));
            [q.sqrt_g
                * (q.inverse_metric[a][1] * u.gradient[0][0]
                    + q.inverse_metric[a][2] * u.gradient[1][0])]
        };
        let s2 = derivative(&|y| scalar_flux(y, 1), x, 0)[0]
            + derivative(&|y| scalar_flux(y, 2), x, 1)[0];
        let scalar_reading = (l + m) * grad_div[0] + m * p.metric[1][1] * s2 / p.sqrt_g;
        assert!(
            (scalar_reading - ours[0]).abs() > 1e-3 * ours[0].abs().max(1.0),
            "{scalar_reading} {}",
            ours[0]
        );
    }
}

#[test]
fn printed_end_and_contact_stresses_match() {
    // T^2_2 = (lambda+2mu)(d_2 v^2 + Gamma^2_22 v^2 + Gamma^2_23 v^3) + lambda d_3 v^3,
    // T^3_3 = lambda (...) + (lambda+2mu) d_3 v^3,  T^3_2 = mu (psi^2 d_3 v^2 + d_2 v^3).
    let (exact, l, m) = trigonometric_solution();
    for x in [[0.3, 0.0], [-1.1, 0.2], [0.9, 0.5]] {
        let (p, u) = (point(x), TrigonometricField.displacement(x));
        let t = exact.mixed_stress(x).unwrap();
        let e22 = u.gradient[0][0]
            + p.christoffel[1][1][1] * u.value[0]
            + p.christoffel[1][1][2] * u.value[1];
        let d3v3 = u.gradient[1][1];
        assert!((t[1][1] - ((l + 2.0 * m) * e22 + l * d3v3)).abs() < 1e-12);
        assert!((t[2][2] - (l * e22 + (l + 2.0 * m) * d3v3)).abs() < 1e-12);
        assert!(
            (t[2][1] - m * (p.metric[1][1] * u.gradient[1][0] + u.gradient[0][1])).abs() < 1e-12
        );
    }
}

#[test]
fn plane_strain_rejects_a_cone() {
    let chart = ShellChart::new(Obstacle::CircularCone(RightCircularCone::new(0.4).unwrap()));
    let grid = Grid::new([-0.5, 0.5], 0.2, 5, 3, false).unwrap();
    let bc = BoundaryConditions::paper_clamped(1.0, 1.0);
    let material = Material::new(1.0, 0.3).unwrap();
    let problem = PlaneProblem {
        chart,
        material,
        grid,
        boundary: bc,
        body_force: None,
    };
    let err = FiniteDifferenceNavier::new(problem).unwrap_err();
    assert!(
        matches!(
            err,
            ElasticityError::NotPlaneStrain { .. } | ElasticityError::Geometry(_)
        ),
        "{err}"
    );
}
