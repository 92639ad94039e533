//! Frictional contact of the 3-D body: the plane-strain extrusion reproduces the 2-D contact
//! solution, the condensed solver agrees with the full-system Newton on a body of finite
//! width and on a cone, and orthotropic friction slips off the traction direction.

use capstan_elasticity::contact::{
    BoundarySolver, ContactSettings, EndLoads, FullSystemSettings, FullSystemSolver, ThickBody,
};
use capstan_elasticity::finite_element::DiscretisationMethod;
use capstan_elasticity::friction::{RegularisedCoulomb, RegularisedCoulombParams};
use capstan_elasticity::solid::{SideFaces, SolidBody};
use capstan_geometry::{EllipticalPrism, Obstacle};

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
        let scale = max_abs(&a.displacement);
        let d = max_diff(&a.displacement, &b.displacement);
        assert!(d < 1e-7 * scale, "ratio {ratio}: {:e}", d / scale);
        // symmetric in x1: the free sides bulge symmetrically, no net axial slide
        let v1 = &a.contact.solid.as_ref().unwrap().v1;
        let n2 = 17;
        for i2 in 0..n2 {
            let (left, right) = (v1[i2], v1[4 * n2 + i2]);
            assert!((left + right).abs() < 1e-8 * scale, "{left} {right}");
        }
    }
}
