//! Converging quantities of the contact solution under refinement: the slip measure (the
//! length of the interpolated slipping set) converges at a measured rate while the node
//! fraction moves in steps of one node.

use capstan_elasticity::contact::{
    BoundarySolver, ContactQuantities, ContactSettings, EndLoads, ThickBody, default_probes,
};
use capstan_elasticity::finite_element::DiscretisationMethod;
use capstan_elasticity::friction::{RegularisedCoulomb, RegularisedCoulombParams};

const EPS: f64 = 1e-5;

fn quantities(
    method: DiscretisationMethod,
    n2: usize,
    n3: usize,
) -> (f64, std::collections::BTreeMap<String, f64>) {
    let body = ThickBody {
        method,
        ..ThickBody::paper(n2, n3).unwrap()
    };
    let params = RegularisedCoulombParams::new(0.5, EPS).unwrap();
    let model = body.model(RegularisedCoulomb, params, EPS).unwrap();
    let solver = BoundarySolver::new(&model, ContactSettings::default()).unwrap();
    let sol = solver.solve(EndLoads::ratio(2.0)).unwrap();
    let q = ContactQuantities::new(&model, &sol, &default_probes(body.theta)).unwrap();
    (sol.slip_fraction, q.scalars(&sol))
}

#[test]
fn explore() {
    for method in [DiscretisationMethod::Fd, DiscretisationMethod::FemQ2] {
        for (n2, n3) in [(61, 11), (121, 21), (241, 41), (481, 81)] {
            let (f, q) = quantities(method, n2, n3);
            println!("{method:?} {n2} {n3} frac {f:.6} {q:?}");
        }
    }
}
