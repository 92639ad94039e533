//! The default contact case (paper body, regularised Coulomb `mu = 0.5`, `eps = 1e-5`,
//! `tau_max / tau0 = 2`) with the Qp elements (`fem-qp`) through the unchanged boundary-only
//! solver, against Q2 on a fine grid: Slip, the limiting ratio and `max |v^2|` agree to
//! discretisation accuracy.

mod common;

use std::time::Instant;

use capstan_elasticity::Discretisation;
use capstan_elasticity::contact::ThickBody;
use capstan_elasticity::finite_element::DiscretisationMethod;

/// `(slip fraction, limiting ratio, max |v^2| on the outer surface, seconds)` on an
/// `n2 x n3` grid.
fn solve(method: DiscretisationMethod, order: usize, n2: usize, n3: usize) -> [f64; 4] {
    let start = Instant::now();
    let body = ThickBody {
        method,
        order,
        ..ThickBody::paper(n2, n3).unwrap()
    };
    let (model, _, [slip, limit, outer]) = common::default_contact(&body);
    let seconds = start.elapsed().as_secs_f64();
    assert_eq!(model.discretisation().method(), method.name());
    [slip, limit, outer, seconds]
}

#[test]
fn qp_boundary_solve_agrees_with_fine_q2_on_the_default_contact_case() {
    let q2 = solve(DiscretisationMethod::FemQ2, 4, 129, 33);
    // p = 4 on 16 x 4 elements (65 x 17 nodes), p = 6 on 8 x 2 (49 x 13)
    for (p, n2, n3) in [(4, 65, 17), (6, 49, 13)] {
        let qp = solve(DiscretisationMethod::FemQp, p, n2, n3);
        println!("q2 129 x 33: {q2:?}\nqp{p} {n2} x {n3}: {qp:?}");
        // Slip: fraction of contact nodes slipping, resolved to about one node spacing
        assert!((qp[0] - q2[0]).abs() < 0.05, "p {p}: {qp:?} vs {q2:?}");
        assert!(
            (qp[1] / q2[1] - 1.0).abs() < 2e-3,
            "p {p}: {qp:?} vs {q2:?}"
        );
        assert!(
            (qp[2] / q2[2] - 1.0).abs() < 1e-2,
            "p {p}: {qp:?} vs {q2:?}"
        );
    }
}
