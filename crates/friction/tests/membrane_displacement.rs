//! The membrane displacement model converges to the capstan profile of the same obstacle:
//! observed orders on a circle, an ellipse and an expression prism.

use std::f64::consts::FRAC_PI_2;

use capstan_friction::membrane::{PrismMembrane, ProfilePoint};
use capstan_friction::membrane_displacement::{
    EndCondition, MembraneDisplacement, MembraneDisplacementProblem, MembraneDisplacementSolution,
};
use capstan_friction::{FrictionLaw, RegularisedCoulomb, RegularisedCoulombParams, SmoothCoulomb};
use capstan_geometry::{CircularCylinder, EllipticalPrism, ExpressionProfile, ProfileCurve};

mod orders;
use orders::{observed_order, table};

const MU: f64 = 0.5;
const STIFFNESS: f64 = 1e3; // E h l with the paper's E = 1e3, h = l = 1

/// Runs `$f` on the three obstacles: circle r = 2, ellipse a = 2, b = 1, and a
/// non-elliptical expression prism.
macro_rules! for_obstacles {
    ($f:ident) => {{
        $f("circle", &CircularCylinder::new(2.0).unwrap());
        $f("ellipse", &EllipticalPrism::new(2.0, 1.0).unwrap());
        let wobbly = ExpressionProfile::parse("2*sin(t) + 0.1*sin(2*t)", "1.5*cos(t)").unwrap();
        $f("expression", &wobbly);
    }};
}

/// `Psi(theta) - Psi(theta0)` at the nodes.
fn psi<C: ProfileCurve<f64>>(profile: &C, theta: &[f64]) -> Vec<f64> {
    PrismMembrane::new(profile)
        .turning_angles(theta[0], theta)
        .unwrap()
}

/// Prints the `what` study of obstacle `name` and asserts its observed order is `expected`
/// within 0.1.
#[track_caller]
fn assert_order(name: &str, what: &str, study: &[(f64, f64)], expected: f64) {
    let p = observed_order(study);
    println!("{name}: {what} order {p:.3}\n{}", table(study));
    assert!(
        (p - expected).abs() < 0.1,
        "{name}: order {p}\n{}",
        table(study)
    );
}

fn solve<C: ProfileCurve<f64>, L: FrictionLaw<f64>>(
    profile: &C,
    law: L,
    params: L::Params,
    nodes: usize,
    start: EndCondition,
    end: EndCondition,
) -> MembraneDisplacementSolution {
    let problem = MembraneDisplacementProblem {
        theta0: -FRAC_PI_2,
        theta1: FRAC_PI_2,
        nodes,
        stiffness: STIFFNESS,
        start,
        end,
    };
    MembraneDisplacement::new(profile, law, params)
        .solve(&problem, None, Default::default())
        .unwrap()
}

/// Max relative deviation from the capstan profile `T(theta_a) exp(mu (Psi - Psi(theta_a)))`
/// anchored at the tension end `anchor` (0 or last).
fn capstan_error<C: ProfileCurve<f64>>(
    profile: &C,
    s: &MembraneDisplacementSolution,
    anchor_last: bool,
) -> f64 {
    let psi = psi(profile, &s.theta);
    let (ia, n) = if anchor_last {
        (s.theta.len() - 1, s.theta.len())
    } else {
        (0, s.theta.len())
    };
    let ta = s.tension[ia];
    (0..n)
        .map(|i| (s.tension[i] / (ta * (MU * (psi[i] - psi[ia])).exp()) - 1.0).abs())
        .fold(0.0, f64::max)
}

/// The `eps` study of a Coulomb-type `law` with `mu = MU`: `(eps, capstan_error)` for each
/// width, on `nodes` nodes between the end conditions `[start, end]`; the capstan profile is
/// anchored at the end held by a tension.
fn eps_study<C, L>(
    profile: &C,
    law: L,
    widths: [f64; 4],
    nodes: usize,
    [start, end]: [EndCondition; 2],
) -> Vec<(f64, f64)>
where
    C: ProfileCurve<f64>,
    L: FrictionLaw<f64, Params = RegularisedCoulombParams<f64>> + Copy,
{
    let anchor_last = matches!(end, EndCondition::Tension(_));
    widths
        .iter()
        .map(|&eps| {
            let params = RegularisedCoulombParams::new(MU, eps).unwrap();
            let s = solve(profile, law, params, nodes, start, end);
            (eps, capstan_error(profile, &s, anchor_last))
        })
        .collect()
}

/// Regularised Coulomb pulled far (displacement at `theta_max`, so `w >= eps` everywhere):
/// the capstan profile for every `eps`; the error is the grid's, second order.
#[test]
fn full_slip_coulomb_membrane_is_the_capstan_profile_to_second_order_in_the_grid() {
    fn run<C: ProfileCurve<f64>>(name: &str, profile: &C) {
        let params = RegularisedCoulombParams::new(MU, 1e-5).unwrap();
        let study: Vec<(f64, f64)> = [101, 201, 401, 801]
            .iter()
            .map(|&n| {
                let s = solve(
                    profile,
                    RegularisedCoulomb,
                    params,
                    n,
                    EndCondition::Tension(1.0),
                    EndCondition::Displacement(1.0),
                );
                assert_eq!(s.slip_fraction(1e-5), 1.0, "{name}: not fully slipping");
                (
                    std::f64::consts::PI / (n - 1) as f64,
                    capstan_error(profile, &s, false),
                )
            })
            .collect();
        assert_order(name, "grid", &study, 2.0);
        assert!(study[3].1 < 2e-5, "{name}: {}", table(&study));
    }
    for_obstacles!(run);
}

/// The smooth law `mu p w / sqrt(w^2 + eps^2)` in the same full-slip state: second order in `eps`.
#[test]
fn full_slip_smooth_membrane_converges_to_capstan_at_second_order_in_eps() {
    fn run<C: ProfileCurve<f64>>(name: &str, profile: &C) {
        let study = eps_study(
            profile,
            SmoothCoulomb,
            [0.04, 0.02, 0.01, 0.005],
            2001,
            [EndCondition::Tension(1.0), EndCondition::Displacement(1.0)],
        );
        assert_order(name, "smooth eps", &study, 2.0);
    }
    for_obstacles!(run);
}

/// Low-tension end anchored (`w(theta0) = 0`), `T_max` pulled: a stick layer of length
/// `eps k / T(theta0)` at the anchor; first order in `eps`.
#[test]
fn anchored_coulomb_membrane_converges_to_capstan_at_first_order_in_eps() {
    fn run<C: ProfileCurve<f64>>(name: &str, profile: &C) {
        let study = eps_study(
            profile,
            RegularisedCoulomb,
            [4e-5, 2e-5, 1e-5, 5e-6],
            20001,
            [EndCondition::Displacement(0.0), EndCondition::Tension(3.0)],
        );
        assert_order(name, "anchored eps", &study, 1.0);
        // the leading term mu kappa(theta0) delta / 2, delta = eps k / T(theta0)
        let kappa0 = {
            let pt = ProfilePoint::from_jet(profile.profile_jet(-FRAC_PI_2));
            pt.turning_rate / pt.a22.sqrt()
        };
        let t_theta0 = 3.0 * (-MU * psi(profile, &[-FRAC_PI_2, FRAC_PI_2])[1]).exp();
        let predicted = MU * kappa0 * 5e-6 * STIFFNESS / (2.0 * t_theta0);
        assert!(
            (study[3].1 / predicted - 1.0).abs() < 0.01,
            "{name}: {} vs {predicted}",
            study[3].1
        );
    }
    for_obstacles!(run);
}
