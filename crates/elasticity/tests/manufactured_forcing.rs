//! The manufactured forcing `f_j = -nabla_i T^i_j` by forward-mode AD: against closed forms
//! (zero on the Lamé field, the Navier equations on the plane chart), against the
//! Richardson-extrapolated central difference it replaced, and the 3-D forcing against the
//! 2-D one on a field in plane strain.

use capstan_elasticity::Material;
use capstan_elasticity::ShellGeometry;
use capstan_elasticity::samples::{
    ExactSolution, LameCylinder, ManufacturedField, MmsBoundaries, PrismMms, TrigonometricField,
};
use capstan_elasticity::studies::solid::{SolidExact, SolidField, SolidMms};
use capstan_geometry::{CircularCylinder, Obstacle, Plane, Scalar, ShellChart};

/// `sum_a d_a P_a(x)` over `(coordinate axis, flux index a)` by the Richardson-extrapolated
/// central difference `(4 D(h/2) - D(h))/3`, `h = 2e-3` (truncation `O(h^4) ~ 1e-12`
/// relative, round-off `~1e-13`): the forcing's former method.
fn richardson_divergence<const D: usize, const N: usize>(
    x: [f64; D],
    axes: &[(usize, usize)],
    flux: impl Fn([f64; D], usize) -> [f64; N],
) -> [f64; N] {
    let h = 2e-3;
    let mut div = [0.0; N];
    for &(axis, a) in axes {
        let diff = |step: f64| -> [f64; N] {
            let (mut yp, mut ym) = (x, x);
            yp[axis] += step;
            ym[axis] -= step;
            let (fp, fm) = (flux(yp, a), flux(ym, a));
            core::array::from_fn(|e| (fp[e] - fm[e]) / (2.0 * step))
        };
        let (d1, d2) = (diff(h), diff(0.5 * h));
        for e in 0..N {
            div[e] += (4.0 * d2[e] - d1[e]) / 3.0;
        }
    }
    div
}

/// The 2-D forcing by the Richardson difference of `sqrt(g) T^a_j`.
fn richardson_forcing<M: ManufacturedField>(
    exact: &ExactSolution<ShellChart<Obstacle>, M>,
    x: [f64; 2],
) -> [f64; 2] {
    let sqrt_g = |y: [f64; 2]| exact.chart.shell_point([0.0, y[0], y[1]]).unwrap().sqrt_g;
    let flux = |y: [f64; 2], a: usize| {
        let t = exact.mixed_stress(y).unwrap();
        [sqrt_g(y) * t[a][1], sqrt_g(y) * t[a][2]]
    };
    let div = richardson_divergence(x, &[(0, 1), (1, 2)], flux);
    let p = exact.chart.shell_point([0.0, x[0], x[1]]).unwrap();
    let t = exact.mixed_stress(x).unwrap();
    let gamma_t = |j: usize| -> f64 {
        (0..3)
            .flat_map(|i| (0..3).map(move |k| (i, k)))
            .map(|(i, k)| p.christoffel[k][i][j] * t[i][k])
            .sum()
    };
    [0, 1].map(|e| -(div[e] / p.sqrt_g - gamma_t(e + 1)))
}

#[test]
fn forcing_agrees_with_the_richardson_difference_on_the_study_charts() {
    for mms in [
        PrismMms::ellipse(0.5, MmsBoundaries::TractionContact),
        PrismMms::expression_prism(MmsBoundaries::TractionContact),
    ] {
        let exact = ExactSolution {
            chart: ShellChart::new(mms.obstacle.clone()),
            material: mms.material,
            field: TrigonometricField,
        };
        let mut worst = 0.0f64;
        for x2 in [mms.theta[0], -0.4, 0.1, 0.7, mms.theta[1]] {
            for x3 in [0.0, 0.13, 0.5 * mms.thickness, mms.thickness] {
                let (ad, fd) = (
                    exact.forcing([x2, x3]).unwrap(),
                    richardson_forcing(&exact, [x2, x3]),
                );
                for e in 0..2 {
                    // the difference's truncation (~1e-12 of the fifth derivatives) and
                    // round-off (~1e-13 / h): far below 1e-10
                    let diff = (ad[e] - fd[e]).abs() / (1.0 + fd[e].abs());
                    worst = worst.max(diff);
                    assert!(diff < 1e-10, "{} {x2} {x3}: {ad:?} {fd:?}", mms.geometry);
                }
            }
        }
        println!(
            "{}: max |AD - Richardson| / (1 + |f|) = {worst:.2e}",
            mms.geometry
        );
    }
}

#[test]
fn lame_field_has_zero_forcing_on_the_circular_cylinder() {
    let lame = LameCylinder::default();
    let exact = ExactSolution {
        chart: ShellChart::new(Obstacle::Cylinder(
            CircularCylinder::new(lame.radius).unwrap(),
        )),
        material: lame.material,
        field: lame.field(),
    };
    let mut worst = 0.0f64;
    for x2 in [0.0, 0.7, 2.5, 5.9] {
        for x3 in [0.0, 0.3, 0.77, 1.0] {
            let f = exact.forcing([x2, x3]).unwrap();
            // stresses are O(p = 1): round-off of the exact derivatives only
            assert!(f.iter().all(|v| v.abs() < 1e-12), "{x2} {x3}: {f:?}");
            worst = f.iter().fold(worst, |m, v| m.max(v.abs()));
        }
    }
    println!("Lamé: max |f| = {worst:.2e}");
}

#[test]
fn forcing_on_the_plane_chart_is_the_navier_closed_form() {
    // Cartesian chart (x1, x2, x3): f = -((lambda + mu) grad div v + mu Lap v), with
    // v^2 = 0.05 sin(1.3 y + 0.2) q(z),  q = 1 + z/2 + z^2/4
    // v^3 = 0.1 sin(1.2 z) w(y),         w = 1 + cos(0.8 y)/2
    // div v = 0.065 cos(1.3 y + 0.2) q + 0.12 cos(1.2 z) w
    // d_y div = -0.0845 sin(1.3 y + 0.2) q + 0.12 cos(1.2 z) w',   w' = -0.4 sin(0.8 y)
    // d_z div = 0.065 cos(1.3 y + 0.2) q' - 0.144 sin(1.2 z) w,    q' = (1 + z)/2
    // Lap v^2 = 0.05 sin(1.3 y + 0.2) (q'' - 1.69 q),              q'' = 1/2
    // Lap v^3 = 0.1 sin(1.2 z) (w'' - 1.44 w),                     w'' = -0.32 cos(0.8 y)
    let material = Material::new(10.0, 0.3).unwrap();
    let (l, m) = (material.lambda(), material.mu());
    let exact = ExactSolution {
        chart: ShellChart::new(Obstacle::Plane(Plane)),
        material,
        field: TrigonometricField,
    };
    let mut worst = 0.0f64;
    for y in [-1.0f64, -0.2, 0.4, 1.3] {
        for z in [0.0f64, 0.25, 0.6] {
            let (s13, c13) = (1.3 * y + 0.2).sin_cos();
            let (s12, c12) = (1.2 * z).sin_cos();
            let (s8, c8) = (0.8 * y).sin_cos();
            let (q, dq) = (1.0 + 0.5 * z + 0.25 * z * z, 0.5 * (1.0 + z));
            let (w, dw, ddw) = (1.0 + 0.5 * c8, -0.4 * s8, -0.32 * c8);
            let div_y = -0.0845 * s13 * q + 0.12 * c12 * dw;
            let div_z = 0.065 * c13 * dq - 0.144 * s12 * w;
            let lap2 = 0.05 * s13 * (0.5 - 1.69 * q);
            let lap3 = 0.1 * s12 * (ddw - 1.44 * w);
            let closed = [-((l + m) * div_y + m * lap2), -((l + m) * div_z + m * lap3)];
            let f = exact.forcing([y, z]).unwrap();
            for e in 0..2 {
                // closed form: round-off only
                let diff = (f[e] - closed[e]).abs() / (1.0 + closed[e].abs());
                assert!(diff < 1e-12, "{y} {z}: {f:?} against {closed:?}");
                worst = worst.max(diff);
            }
        }
    }
    println!("plane: max |f - closed form| / (1 + |f|) = {worst:.2e}");
}

/// The 2-D field as a 3-D one: `v^1 = 0`, no `x1` dependence (plane strain).
struct PlaneStrainField;

impl SolidField for PlaneStrainField {
    fn value<S: Scalar<f64>>(&self, [_, x2, x3]: [S; 3]) -> [S; 3] {
        let [v2, v3] = TrigonometricField.value([x2, x3]);
        [S::zero(), v2, v3]
    }
}

#[test]
fn solid_forcing_of_a_plane_strain_field_is_the_2d_forcing() {
    let mms = PrismMms::ellipse(0.5, MmsBoundaries::TractionContact);
    let chart = || ShellChart::new(mms.obstacle.clone());
    let solid = SolidExact {
        chart: chart(),
        material: mms.material,
        field: PlaneStrainField,
    };
    let plane = ExactSolution {
        chart: chart(),
        material: mms.material,
        field: TrigonometricField,
    };
    let mut worst = 0.0f64;
    for x in [[0.3, -0.9, 0.1], [0.0, 0.2, 0.45], [1.0, 0.8, 0.0]] {
        let (f3, f2) = (
            solid.forcing(x).unwrap(),
            plane.forcing([x[1], x[2]]).unwrap(),
        );
        // the same exact derivatives through two input layouts: round-off only
        assert!(f3[0].abs() < 1e-13, "{x:?}: {f3:?}");
        for e in 0..2 {
            let diff = (f3[e + 1] - f2[e]).abs() / (1.0 + f2[e].abs());
            assert!(diff < 1e-12, "{x:?}");
            worst = worst.max(diff);
        }
    }
    println!("3-D against 2-D: max difference / (1 + |f|) = {worst:.2e}");
}

#[test]
fn solid_forcing_agrees_with_the_richardson_difference_on_the_cone() {
    let mms = SolidMms::elliptical_cone();
    let exact = mms.exact();
    let mut worst = 0.0f64;
    for x in [[1.1, -0.5, 0.0], [1.25, 0.1, 0.07], [1.45, 0.55, 0.15]] {
        let flux = |y: [f64; 3], a: usize| {
            let p = exact.chart.shell_point(y).unwrap();
            let t = exact.mixed_stress(y).unwrap();
            [0, 1, 2].map(|j| p.sqrt_g * t[a][j])
        };
        let div = richardson_divergence(x, &[(0, 0), (1, 1), (2, 2)], flux);
        let p = exact.chart.shell_point(x).unwrap();
        let t = exact.mixed_stress(x).unwrap();
        let ad = exact.forcing(x).unwrap();
        for j in 0..3 {
            let gamma_t: f64 = (0..3)
                .flat_map(|i| (0..3).map(move |k| (i, k)))
                .map(|(i, k)| p.christoffel[k][i][j] * t[i][k])
                .sum();
            let fd = -(div[j] / p.sqrt_g - gamma_t);
            let diff = (ad[j] - fd).abs() / (1.0 + fd.abs());
            worst = worst.max(diff);
            assert!(diff < 1e-10, "{x:?} j {j}: {} against {fd}", ad[j]);
        }
    }
    println!("cone: max |AD - Richardson| / (1 + |f|) = {worst:.2e}");
}

#[test]
fn field_gradients_by_ad_match_their_closed_forms() {
    // Lamé: d_3 v^3 = A - B / r^2; trigonometric: d_2 v^2 = 0.065 cos(1.3 x2 + 0.2) q(x3),
    // d_2 v^3 = -0.04 sin(1.2 x3) sin(0.8 x2)
    let field = LameCylinder::default().field();
    for x3 in [0.0, 0.4, 1.0] {
        let u = field.displacement([0.3, x3]);
        let r = field.radius + x3;
        let closed = field.a - field.b / (r * r);
        assert!((u.gradient[1][1] - closed).abs() < 1e-14 * closed.abs()); // round-off only
        assert_eq!(
            [
                u.value[0],
                u.gradient[0][0],
                u.gradient[0][1],
                u.gradient[1][0]
            ],
            [0.0; 4]
        );
    }
    for [x2, x3] in [[-0.7f64, 0.1f64], [0.4, 0.45]] {
        let u = TrigonometricField.displacement([x2, x3]);
        let q = 1.0 + 0.5 * x3 + 0.25 * x3 * x3;
        let d22 = 0.065 * (1.3 * x2 + 0.2).cos() * q;
        let d23 = -0.04 * (1.2 * x3).sin() * (0.8 * x2).sin();
        assert!((u.gradient[0][0] - d22).abs() < 1e-15);
        assert!((u.gradient[0][1] - d23).abs() < 1e-15);
    }
}

/// The forcing with a column cache ([`ExactSolution::cached_forcing`]) equals the uncached
/// one bit for bit, whatever the order of the points (column by column, alternating columns,
/// two caches interleaved on one thread, two threads at once).
#[test]
fn cached_forcing_is_the_forcing_in_any_order() {
    use capstan_elasticity::studies::ColumnCache;
    let level = capstan_elasticity::verification::GridLevel { n2: 5, n3: 3 };
    let exact = PrismMms::ellipse(2.0, MmsBoundaries::TractionContact)
        .parts(level)
        .unwrap()
        .1;
    let other = PrismMms::expression_prism(MmsBoundaries::TractionContact)
        .parts(level)
        .unwrap()
        .1;
    let points: Vec<[f64; 2]> = [-1.2, -0.4, 0.35, 1.0]
        .iter()
        .flat_map(|&x2| [0.0, 0.1, 0.27, 0.5].map(|x3| [x2, x3]))
        .collect();
    let alternating: Vec<[f64; 2]> = (0..points.len())
        .map(|i| points[(i % 4) * 4 + i / 4])
        .collect();
    let (cache, other_cache) = (ColumnCache::default(), ColumnCache::default());
    for order in [&points, &alternating] {
        for x in order.iter() {
            assert_eq!(
                exact.cached_forcing(&cache, *x).unwrap(),
                exact.forcing(*x).unwrap()
            );
            assert_eq!(
                other.cached_forcing(&other_cache, *x).unwrap(),
                other.forcing(*x).unwrap()
            );
        }
    }
    std::thread::scope(|s| {
        for order in [&points, &alternating] {
            let (exact, cache) = (&*exact, &cache);
            s.spawn(move || {
                for x in order.iter() {
                    assert_eq!(
                        exact.cached_forcing(cache, *x).unwrap(),
                        exact.forcing(*x).unwrap()
                    );
                }
            });
        }
    });
}
