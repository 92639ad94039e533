//! Loads as a list: a contact model over end tractions plus a body load, its right-hand side
//! by superposition of the unit loads, and the end-load case unchanged.

use std::sync::Arc;

use capstan_elasticity::contact::{
    BoundarySolver, ContactModel, ContactSettings, END_LOADS, EndLoads, ThickBody,
};
use capstan_elasticity::{Discretisation, ElasticityError, PlaneOperator};
use capstan_friction::{RegularisedCoulomb, RegularisedCoulombParams};

/// The paper's body (21 x 5, finite differences) with end tractions `m[0]`, `m[1]` and a
/// uniform covariant body force `f = (0, -m[2])` (toward the obstacle).
fn build(body: &ThickBody, m: &[f64]) -> Result<PlaneOperator, ElasticityError> {
    let mut problem = body.problem(m[0], m[1])?;
    let g = m[2];
    problem.body_force = Some(Arc::new(move |_| [0.0, -g]));
    body.scheme()?.build(problem)
}

#[test]
fn a_body_load_superposes_with_the_end_tractions() {
    let body = ThickBody::paper(21, 5).unwrap();
    let params = RegularisedCoulombParams::new(0.5, 1e-5).unwrap();
    let loads = [END_LOADS[0], END_LOADS[1], "loads.gravity"];
    let model = ContactModel::with_loads(
        |m: &[f64]| build(&body, m),
        &loads,
        RegularisedCoulomb,
        params,
        1e-5,
    )
    .unwrap();
    assert_eq!(model.loads(), &loads[..]);
    let m = [1.0, 1.7, 0.3];
    let direct = build(&body, &m).unwrap().system().unwrap().rhs;
    let superposed = model.rhs_of(&m);
    let scale = direct.iter().fold(0.0f64, |a, x| a.max(x.abs()));
    for (a, b) in direct.iter().zip(&superposed) {
        assert!((a - b).abs() <= 1e-12 * scale, "{a} {b}"); // linear in the loads: round-off
    }
    // the body load changes the right-hand side (it is not dropped)
    let ends_only = model.rhs(EndLoads::new(1.0, 1.7));
    assert!(
        ends_only
            .iter()
            .zip(&superposed)
            .any(|(a, b)| (a - b).abs() > 1e-3 * scale)
    );
}

#[test]
fn end_loads_model_is_the_two_load_list_bit_for_bit() {
    let body = ThickBody::paper(21, 5).unwrap();
    let params = RegularisedCoulombParams::new(0.5, 1e-5).unwrap();
    let two = body.model(RegularisedCoulomb, params, 1e-5).unwrap();
    let listed = ContactModel::with_loads(
        |m: &[f64]| body.discretisation(m[0], m[1]),
        &END_LOADS,
        RegularisedCoulomb,
        params,
        1e-5,
    )
    .unwrap();
    assert_eq!(two.loads(), &END_LOADS[..]);
    let loads = EndLoads::new(1.0, 1.5);
    assert_eq!(two.rhs(loads), listed.rhs(loads));
    let a = BoundarySolver::new(&two, ContactSettings::default())
        .unwrap()
        .solve(loads)
        .unwrap();
    let b = BoundarySolver::new(&listed, ContactSettings::default())
        .unwrap()
        .solve(loads)
        .unwrap();
    assert_eq!(a.displacement, b.displacement); // the same arithmetic
    // tau0 b_0 + tau_max b_1, entry by entry as before the list
    let by_hand: Vec<f64> = two
        .rhs_basis(0)
        .iter()
        .zip(two.rhs_basis(1))
        .map(|(x, y)| loads.tau0 * x + loads.tau_max * y)
        .collect();
    assert_eq!(two.rhs(loads), by_hand);
}

#[test]
fn fewer_than_two_loads_is_a_typed_error() {
    let body = ThickBody::paper(21, 5).unwrap();
    let params = RegularisedCoulombParams::new(0.5, 1e-5).unwrap();
    let err = ContactModel::with_loads(
        |m: &[f64]| body.discretisation(m[0], 0.0),
        &["loads.tau0"],
        RegularisedCoulomb,
        params,
        1e-5,
    )
    .unwrap_err();
    assert!(err.to_string().contains("`loads`"), "{err}");
}
