//! Frictional contact of the 3-D body: the plane-strain extrusion reproduces the 2-D contact
//! solution, the condensed solver agrees with the full-system Newton on a body of finite
//! width and on a cone, and orthotropic friction slips off the traction direction.

use capstan_elasticity::contact::{
    BoundarySolver, ContactSettings, ContactSolution, EndLoads, FullSystemSettings,
    FullSystemSolver, ThickBody,
};
use capstan_elasticity::finite_element::DiscretisationMethod;
use capstan_elasticity::friction::{
    OrthotropicCoulomb, OrthotropicCoulombParams, RegularisedCoulomb, RegularisedCoulombParams,
};
use capstan_elasticity::solid::{SideFaces, SolidBody};
use capstan_geometry::{EllipticalPrism, ExpressionProfile, GeneralCone, Obstacle};

const EPS: f64 = 1e-5;

fn coulomb(mu: f64) -> RegularisedCoulombParams<f64> {
    RegularisedCoulombParams::new(mu, EPS).unwrap()
}

fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
}

fn max_abs(v: &[f64]) -> f64 {
    v.iter().fold(0.0f64, |m, x| m.max(x.abs()))
}

/// The two solutions' displacements agree to `1e-7` of the largest (the solvers' tolerances);
/// returns that scale.
#[track_caller]
fn assert_agree(a: &ContactSolution, b: &ContactSolution, what: &str) -> f64 {
    let scale = max_abs(&a.displacement);
    let d = max_diff(&a.displacement, &b.displacement);
    assert!(d < 1e-7 * scale, "{what}: {:e}", d / scale);
    scale
}

#[test]
fn plane_strain_extrusion_reproduces_the_two_dimensional_contact_solution() {
    // the circle (a rigid rotation held by friction) and an ellipse (none)
    for (a, b) in [(2.0, 2.0), (2.0, 1.5)] {
        let obstacle = Obstacle::Ellipse(EllipticalPrism::new(a, b).unwrap());
        let (n2, n3) = (21, 6);
        let plane = ThickBody {
            obstacle: obstacle.clone(),
            method: DiscretisationMethod::FemQ1,
            ..ThickBody::paper(n2, n3).unwrap()
        };
        let solid = SolidBody {
            sides: SideFaces::PlaneStrain,
            ..SolidBody::new(obstacle, [-0.5, 0.5], [2, n2, n3])
        };
        let m2 = plane.model(RegularisedCoulomb, coulomb(0.5), EPS).unwrap();
        let m3 = solid.model(RegularisedCoulomb, coulomb(0.5), EPS).unwrap();
        let s2 = BoundarySolver::new(&m2, ContactSettings::default()).unwrap();
        let s3 = BoundarySolver::new(&m3, ContactSettings::default()).unwrap();
        assert_eq!(
            s2.sliding().is_some(),
            s3.sliding().is_some(),
            "a = {a}, b = {b}"
        );
        if let (Some(l2), Some(l3)) = (s2.sliding(), s3.sliding()) {
            assert!((l2.upper_ratio - l3.upper_ratio).abs() < 1e-9 * l2.upper_ratio);
            assert!((l2.lower_ratio - l3.lower_ratio).abs() < 1e-9 * l2.lower_ratio);
        }
        for ratio in [1.5, 2.5] {
            let loads = EndLoads::ratio(ratio);
            let p2 = s2.solve(loads).unwrap();
            let p3 = s3.solve(loads).unwrap();
            let c3 = &p3.contact;
            // both x1 rows of the extrusion carry the 2-D profile
            for row in 0..2 {
                let pick = |f: &[f64]| f[row * n2..(row + 1) * n2].to_vec();
                let scale = max_abs(&p2.contact.v2);
                let d = max_diff(&pick(&c3.v2), &p2.contact.v2);
                assert!(
                    d < 1e-9 * scale,
                    "a = {a}, b = {b}, ratio {ratio}: v2 {d:e}"
                );
                let s = max_abs(&p2.contact.normal_stress);
                let d = max_diff(&pick(&c3.normal_stress), &p2.contact.normal_stress);
                assert!(d < 1e-9 * s, "normal stress {d:e}");
                assert_eq!(pick(&c3.slip).len(), n2);
            }
            assert!((p2.slip_fraction - p3.slip_fraction).abs() < 1e-12);
            let v1 = &c3.solid.as_ref().unwrap().v1;
            assert!(max_abs(v1) == 0.0, "v^1 is held on plane-strain faces");
        }
    }
}

#[test]
fn finite_width_ellipse_condensed_solver_agrees_with_full_system_newton() {
    let obstacle = Obstacle::Ellipse(EllipticalPrism::new(2.0, 1.5).unwrap());
    let body = SolidBody::new(obstacle, [-0.5, 0.5], [5, 17, 5]);
    let model = body.model(RegularisedCoulomb, coulomb(0.5), EPS).unwrap();
    let condensed = BoundarySolver::new(&model, ContactSettings::default()).unwrap();
    let full = FullSystemSolver::new(&model, FullSystemSettings::default()).unwrap();
    for ratio in [1.5, 2.5] {
        let loads = EndLoads::ratio(ratio);
        let a = condensed.solve(loads).unwrap();
        let b = full.solve(loads).unwrap();
        let scale = assert_agree(&a, &b, &format!("ratio {ratio}"));
        // symmetric in x1: the free sides bulge symmetrically, no net axial slide
        let v1 = &a.contact.solid.as_ref().unwrap().v1;
        let n2 = 17;
        for i2 in 0..n2 {
            let (left, right) = (v1[i2], v1[4 * n2 + i2]);
            assert!((left + right).abs() < 1e-8 * scale, "{left} {right}");
        }
    }
}

/// A band `x1 in [1, 1.4]` of thickness 0.1 on the cone `x1 (1, ubar, vbar)` with the profile
/// `(a sin t, b cos t)` (a right circular cone for `a = b`).
fn cone_band(a: f64, b: f64, nodes: [usize; 3]) -> SolidBody<Obstacle> {
    let profile =
        ExpressionProfile::parse(&format!("{a} * sin(t)"), &format!("{b} * cos(t)")).unwrap();
    SolidBody {
        thickness: 0.1,
        ..SolidBody::new(Obstacle::Cone(GeneralCone::new(profile)), [1.0, 1.4], nodes)
    }
}

#[test]
fn cones_condensed_solver_agrees_with_full_system_newton() {
    // circular (half-aperture atan 0.25 < atan mu: the band does not slide to the apex): a
    // rigid rotation about the axis; elliptical: g_12 != 0, no rigid mode
    for (a, b) in [(0.25, 0.25), (0.3, 0.2)] {
        let body = cone_band(a, b, [3, 17, 3]);
        let model = body.model(RegularisedCoulomb, coulomb(0.5), EPS).unwrap();
        let condensed = BoundarySolver::new(&model, ContactSettings::default()).unwrap();
        let full = FullSystemSolver::new(&model, FullSystemSettings::default()).unwrap();
        let mode = condensed.sliding();
        assert_eq!(mode.is_some(), a == b, "a = {a}, b = {b}: {mode:?}");
        for ratio in [1.3, 1.8] {
            let loads = EndLoads::ratio(ratio);
            let x = condensed.solve(loads).unwrap();
            let y = full.solve(loads).unwrap();
            assert_agree(&x, &y, &format!("a = {a}, b = {b}, ratio {ratio}"));
            assert!(x.stats.residual < 1e-9);
            // compressive contact (the band is pressed on the cone)
            assert!(x.contact.normal_stress.iter().filter(|s| **s < 0.0).count() > 40);
        }
    }
}

#[test]
fn orthotropic_coulomb_slips_off_the_traction_direction_on_the_three_dimensional_body() {
    // orthotropy axes at 45 degrees to the slip frame: sliding along x2 meets a traction
    // with an x1 component, so slip and traction are not parallel
    let (mu, angle) = ([0.2, 0.8], core::f64::consts::FRAC_PI_4);
    let params = OrthotropicCoulombParams::new(mu, angle, EPS).unwrap();
    let obstacle = Obstacle::Ellipse(EllipticalPrism::new(2.0, 1.5).unwrap());
    let body = SolidBody::new(obstacle, [-0.5, 0.5], [5, 17, 5]);
    let model = body.model(OrthotropicCoulomb, params, EPS).unwrap();
    let solver = BoundarySolver::new(&model, ContactSettings::default()).unwrap();
    let sol = solver.solve(EndLoads::ratio(1.4)).unwrap();
    assert!(sol.stats.residual < 1e-9);
    let c = &sol.contact;
    let s = c.solid.as_ref().unwrap();
    let (cos, sin) = (angle.cos(), angle.sin());
    let mut slipping = 0;
    let mut off_axis = 0;
    for k in 0..c.x2.len() {
        let u = [s.slip_1[k], c.slip[k]];
        let t = [s.friction_traction_1[k], c.friction_traction[k]];
        let p = c.normal_stress[k];
        // orthotropy axes: u' = R(-phi) u, t' = R(-phi) t
        let up = [cos * u[0] + sin * u[1], -sin * u[0] + cos * u[1]];
        let tp = [cos * t[0] + sin * t[1], -sin * t[0] + cos * t[1]];
        let m = (mu[0] * mu[0] * up[0] * up[0] + mu[1] * mu[1] * up[1] * up[1]).sqrt();
        if m < 2.0 * mu[1] * EPS || p >= 0.0 {
            continue; // regularised zone or tension
        }
        slipping += 1;
        // limit surface (t'_1/mu_1)^2 + (t'_2/mu_2)^2 = p^2
        let f = (tp[0] / mu[0]).powi(2) + (tp[1] / mu[1]).powi(2);
        assert!(
            (f.sqrt() - p.abs()).abs() < 1e-10 * p.abs(),
            "site {k}: {f} vs {p}"
        );
        // slip rule: u' parallel to (t'_1/mu_1^2, t'_2/mu_2^2), opposed (compression)
        let r = [tp[0] / (mu[0] * mu[0]), tp[1] / (mu[1] * mu[1])];
        let cross = r[0] * up[1] - r[1] * up[0];
        let size = (r[0].hypot(r[1])) * up[0].hypot(up[1]);
        assert!(cross.abs() < 1e-9 * size, "site {k}: {cross:e}");
        assert!(
            r[0] * up[0] + r[1] * up[1] < 0.0,
            "friction opposes the slip"
        );
        // slip and traction not parallel
        let sine = (t[0] * u[1] - t[1] * u[0]) / (t[0].hypot(t[1]) * u[0].hypot(u[1]));
        if sine.abs() > 0.1 {
            off_axis += 1;
        }
    }
    assert!(slipping >= 10, "{slipping} slipping sites");
    // (a site that slides along an orthotropy axis meets a parallel traction)
    assert!(
        10 * off_axis >= 9 * slipping,
        "{off_axis} of {slipping} slipping sites slide off their traction"
    );
}

/// The recovered nodal stress of the interpolated manufactured field on the elliptical cone
/// (`g_12 != 0`) converges at second order to the exact `T^ij` (differences of the nodal
/// values, one-sided at the faces).
#[test]
#[allow(clippy::needless_range_loop)] // mirrors T^ij = T^i_l g^lj
fn recovered_nodal_stress_is_second_order_on_the_elliptical_cone() {
    use capstan_elasticity::finite_element::ElementOrder;
    use capstan_elasticity::studies::solid::{SolidField, SolidMms};
    let mms = SolidMms::elliptical_cone();
    let exact = mms.exact();
    let mut errors = Vec::new();
    for m in [4, 8, 16] {
        let op = mms.operator([m + 1; 3], ElementOrder::Q1).unwrap();
        let grid = op.grid();
        let v: Vec<f64> = (0..grid.node_count())
            .flat_map(|k| exact.field.displacement(grid.coordinates(grid.node(k))).0)
            .collect();
        let fields = op.fields(&v).unwrap();
        let (mut err, mut size) = (0.0f64, 0.0f64);
        for k in 0..grid.node_count() {
            let x = grid.coordinates(grid.node(k));
            let p = capstan_geometry::ShellChart::new(mms.obstacle.clone())
                .point(x)
                .unwrap();
            let mixed = exact.mixed_stress(x).unwrap();
            for i in 0..3 {
                for j in 0..3 {
                    let t: f64 = (0..3).map(|l| mixed[i][l] * p.inverse_metric[l][j]).sum();
                    err = err.max((fields.stress[k][i][j] - t).abs());
                    size = size.max(t.abs());
                }
            }
            assert_eq!(
                fields.displacement[k],
                [v[3 * k], v[3 * k + 1], v[3 * k + 2]]
            );
        }
        errors.push(err / size);
    }
    let orders: Vec<f64> = errors.windows(2).map(|e| (e[0] / e[1]).log2()).collect();
    assert!(
        orders.iter().all(|p| (p - 2.0).abs() < 0.3),
        "{errors:?} {orders:?}"
    );
    assert!(errors[2] < 1e-2, "{errors:?}");
}
