//! The 3-D threshold of a finite-width body whose full slip is not rigid: the default cone
//! band (`obstacle.shape = "cone"`, `ubar = 0.5 sin t`, `vbar = 0.5 cos t`, `x1 in [0.5, 1.5]`,
//! `h = 1`, `mu = 0.5`, free sides) slides round the axis *and* towards the apex. Its
//! full-slip balance along the rigid rotation has friction pushing along the slip on the
//! tensile (bilateral) edge nodes, so it is no bound in the 2-D sense; the solutions run off
//! along the rotation as the ratio approaches it (`max |v| ~ c / (r_L - r)`), and the solver
//! reports no equilibrium past it.

use capstan_elasticity::contact::{
    BoundarySolver, ContactError, ContactSettings, EndLoads, ThresholdSettings, threshold_ratio,
};
use capstan_elasticity::friction::{RegularisedCoulomb, RegularisedCoulombParams};
use capstan_elasticity::solid::SolidBody;
use capstan_geometry::{ExpressionProfile, GeneralCone, Obstacle};

const EPS: f64 = 1e-5;

/// The scene's default 3-D body on the scene's default cone, Q1, `nodes`.
fn default_cone(nodes: [usize; 3]) -> SolidBody<Obstacle> {
    let profile = ExpressionProfile::parse("0.5*sin(t)", "0.5*cos(t)").unwrap();
    SolidBody::new(Obstacle::Cone(GeneralCone::new(profile)), [0.5, 1.5], nodes)
}

fn max_abs(v: &[f64]) -> f64 {
    v.iter().fold(0.0f64, |m, x| m.max(x.abs()))
}

#[test]
fn default_cone_runs_off_along_the_rotation_at_its_runaway_ratio() {
    let body = default_cone([3, 20, 3]);
    let law = RegularisedCoulombParams::new(0.5, EPS).unwrap();
    let model = body.model(RegularisedCoulomb, law, EPS).unwrap();
    let solver = BoundarySolver::new(&model, ContactSettings::default()).unwrap();
    let mode = solver.sliding().expect("the rotation about the axis");
    // no bound in the 2-D sense either way ...
    assert!(mode.upper_ratio.is_infinite() && mode.lower_ratio.is_infinite());
    // ... but a run-off balance each way; the cone is symmetric under x2 -> -x2, which maps
    // the loads (1, r) to (r, 1) and a homogeneous law's ratio r to 1 / r
    let [lower, upper] = mode.runaway_ratios.expect("run-off ratios");
    assert!((lower * upper - 1.0).abs() < 1e-9, "{lower} {upper}");
    assert!(upper > 1.0, "{upper}");
    // the continuation toward r_L runs off: (r_L - r) max |v| tends to a constant, at first
    // order in the distance d = r_L - r (its differences shrink tenfold per tenfold d)
    let mut warm: Option<Vec<f64>> = None;
    let mut products = vec![];
    let mut sizes = vec![];
    for r in [1.5, 2.5, 3.0, 3.5, 3.7] {
        let sol = solver
            .solve_from(EndLoads::ratio(r), warm.as_deref())
            .unwrap();
        sizes.push(max_abs(&sol.displacement));
        warm = Some(sol.unknowns);
    }
    for d in [1e-1, 1e-2, 1e-3] {
        let sol = solver
            .solve_from(EndLoads::ratio(upper - d), warm.as_deref())
            .unwrap();
        let size = max_abs(&sol.displacement);
        // the full residual grows with the displacement's size near the run-off (2.6e-9 at
        // max |v| = 2.4e3)
        let residual = sol.stats.residual;
        assert!(residual < 1e-11 * size.max(1.0), "d = {d}: {residual:e}");
        assert_eq!(sol.slip_fraction, 1.0);
        products.push(d * size);
        sizes.push(size);
        warm = Some(sol.unknowns);
    }
    assert!(sizes.windows(2).all(|w| w[1] > w[0]), "{sizes:?}");
    assert!(sizes[sizes.len() - 1] > 1e3 * sizes[0], "{sizes:?}");
    let (d1, d2) = (products[1] - products[0], products[2] - products[1]);
    let rate = (d1 / d2).log10();
    assert!((rate - 1.0).abs() < 0.15, "{products:?}: rate {rate}");
    eprintln!(
        "runaway {upper:.12}, (r_L - r) max|v| at d = 1e-1, 1e-2, 1e-3: {products:?}, rate {rate:.3}"
    );
    // past the balance: no equilibrium, reported with the run-off range (not a failure)
    for r in [upper * (1.0 + 1e-3), 2.0 * upper, lower * (1.0 - 1e-3)] {
        match solver.solve(EndLoads::ratio(r)) {
            Err(ContactError::NoEquilibrium {
                ratio,
                lower: l,
                upper: u,
            }) => {
                assert_eq!((ratio, l, u), (r, lower, upper));
            }
            other => panic!("ratio {r}: {other:?}"),
        }
    }
}

#[test]
fn threshold_of_the_default_cone_stops_at_slip_one_below_the_runaway_ratio() {
    let body = default_cone([3, 20, 3]);
    let law = RegularisedCoulombParams::new(0.5, EPS).unwrap();
    let model = body.model(RegularisedCoulomb, law, EPS).unwrap();
    let solver = BoundarySolver::new(&model, ContactSettings::default()).unwrap();
    let [_, upper] = solver.sliding().unwrap().runaway_ratios.unwrap();
    let t = threshold_ratio(&solver, ThresholdSettings::default()).unwrap();
    assert_eq!(t.limiting_ratio, Some(upper));
    // every node slides forward well before the run-off (the band also slides to the apex)
    assert!(t.ratio < upper && t.ratio > 1.0, "{t:?}");
    assert!(!t.above_is_no_equilibrium);
    assert!(t.above - t.below <= 1e-6 * t.above);
    assert!(t.slip_fraction_below < 1.0);
    let at = solver.solve(EndLoads::ratio(t.above)).unwrap();
    assert_eq!(at.slip_fraction, 1.0);
}
