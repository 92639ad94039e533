//! The default contact case (paper body, regularised Coulomb `mu = 0.5`, `eps = 1e-5`,
//! `tau_max / tau0 = 2`) solved by the contact engineer's boundary solver on FD, Q1 and Q2:
//! the finite elements implement the `Discretisation` contract (contact rows, lumped weights)
//! faithfully enough that all three converge to the same answer.

use capstan_elasticity::Component;
use capstan_elasticity::Discretisation;
use capstan_elasticity::contact::{BoundarySolver, ContactSettings, EndLoads, ThickBody};
use capstan_elasticity::finite_element::{DiscretisationMethod, ElementOrder};
use capstan_elasticity::friction::{RegularisedCoulomb, RegularisedCoulombParams};

const EPS: f64 = 1e-5;

/// `(max |v^2| on the outer surface, slip fraction)` of the default case on `(4m+1) x (m+1)`.
fn solve(m: usize, order: Option<ElementOrder>) -> (f64, f64) {
    let method = match order {
        None => DiscretisationMethod::Fd,
        Some(ElementOrder::Q1) => DiscretisationMethod::FemQ1,
        Some(ElementOrder::Q2) => DiscretisationMethod::FemQ2,
    };
    let body = ThickBody {
        method,
        ..ThickBody::paper(4 * m + 1, m + 1).unwrap()
    };
    let params = RegularisedCoulombParams::new(0.5, EPS).unwrap();
    let model = body.model(RegularisedCoulomb, params, EPS).unwrap();
    let s = BoundarySolver::new(&model, ContactSettings::default()).unwrap();
    let sol = s.solve(EndLoads::ratio(2.0)).unwrap();
    let op = model.discretisation();
    assert_eq!(op.method(), method.name());
    let outer = (0..op.grid().n2())
        .map(|i| sol.displacement[op.dof([i, m], Component::X2)].abs())
        .fold(0.0f64, f64::max);
    (outer, sol.slip_fraction)
}

#[test]
fn fd_q1_q2_agree_on_the_default_contact_case() {
    let mut rows = vec![];
    for m in [8, 16] {
        let row: Vec<(f64, f64)> = [None, Some(ElementOrder::Q1), Some(ElementOrder::Q2)]
            .into_iter()
            .map(|o| solve(m, o))
            .collect();
        println!("m = {m}: {row:?}");
        rows.push(row);
    }
    let spread = |r: &[(f64, f64)]| {
        let v: Vec<f64> = r.iter().map(|x| x.0).collect();
        let (lo, hi) = v
            .iter()
            .fold((f64::MAX, f64::MIN), |(a, b), x| (a.min(*x), b.max(*x)));
        (hi - lo) / hi
    };
    assert!(spread(&rows[1]) < spread(&rows[0]), "{rows:?}");
    assert!(spread(&rows[1]) < 0.05, "{rows:?}");
}
