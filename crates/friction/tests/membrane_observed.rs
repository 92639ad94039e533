//! The membrane's Newton iteration reports every step to its progress hook, and observing it
//! changes nothing.

use capstan_friction::membrane_displacement::{
    EndCondition, MembraneDisplacement, MembraneDisplacementProblem,
};
use capstan_friction::{RegularisedCoulomb, RegularisedCoulombParams};
use capstan_geometry::EllipticalPrism;

#[test]
fn membrane_newton_reports_each_step_and_the_residual_falls() {
    let ellipse = EllipticalPrism::new(2.0, 1.0).unwrap();
    let model = MembraneDisplacement::new(
        &ellipse,
        RegularisedCoulomb,
        RegularisedCoulombParams::new(0.5, 1e-5).unwrap(),
    );
    let problem = MembraneDisplacementProblem {
        theta0: -1.2,
        theta1: 1.2,
        nodes: 101,
        stiffness: 1e3,
        start: EndCondition::Tension(1.0),
        end: EndCondition::Displacement(0.05),
    };
    let mut seen = Vec::new();
    let observed = model
        .solve_observed(&problem, None, Default::default(), &mut |i, r, s| {
            seen.push((i, r, s))
        })
        .unwrap();
    let plain = model.solve(&problem, None, Default::default()).unwrap();
    assert_eq!(observed.displacement, plain.displacement); // observing changes nothing
    assert_eq!(seen.len(), observed.iterations + 1); // the start and every step
    assert_eq!(
        seen.iter().map(|p| p.0).collect::<Vec<_>>(),
        (0..=observed.iterations).collect::<Vec<_>>()
    );
    assert!(observed.iterations >= 1);
    assert_eq!(seen.last().unwrap().1, observed.residual);
    assert!(seen.last().unwrap().1 < 1e-6 * seen[0].1, "{seen:?}");
}
