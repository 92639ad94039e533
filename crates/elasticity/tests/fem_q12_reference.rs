//! Contact results of `fem-q1` and `fem-q2` (full and reduced volumetric integration) on the
//! paper's body, against numbers recorded from main before the discretisation registry
//! (`FiniteElementNavier`, commit 0ba7dfd): whatever implements these names later (the Qp
//! family at `p = 1, 2`) must reproduce them to `1e-12` relative.

use capstan_elasticity::contact::{BoundarySolver, ContactSettings, EndLoads, ThickBody};
use capstan_elasticity::finite_element::{DiscretisationMethod, VolumetricIntegration};
use capstan_friction::{RegularisedCoulomb, RegularisedCoulombParams};

/// `[slip_fraction, max v^2, max v^3, sigma_n(first), sigma_n(middle), sigma_n(last),
/// v^2(middle contact node), sum of slip]` on a 41 x 9 grid, ratio 1.5, `mu = 0.5`,
/// `eps = 1e-5`.
fn numbers(method: DiscretisationMethod, volumetric: VolumetricIntegration) -> [f64; 8] {
    let body = ThickBody {
        method,
        volumetric,
        ..ThickBody::paper(41, 9).unwrap()
    };
    let params = RegularisedCoulombParams::new(0.5, 1e-5).unwrap();
    let model = body.model(RegularisedCoulomb, params, 1e-5).unwrap();
    let solver = BoundarySolver::new(&model, ContactSettings::default()).unwrap();
    let s = solver.solve(EndLoads::new(1.0, 1.5)).unwrap();
    let c = &s.contact;
    let mid = c.x2.len() / 2;
    [
        s.slip_fraction,
        s.max_azimuthal_displacement.value,
        s.max_radial_displacement.value,
        c.normal_stress[0],
        c.normal_stress[mid],
        c.normal_stress[c.normal_stress.len() - 1],
        c.v2[mid],
        c.slip.iter().sum(),
    ]
}

fn check(method: DiscretisationMethod, volumetric: VolumetricIntegration, recorded: [f64; 8]) {
    let got = numbers(method, volumetric);
    println!("{method} {volumetric:?}: {got:?}");
    for (k, (a, b)) in got.iter().zip(&recorded).enumerate() {
        // the same arithmetic up to summation order: round-off only
        assert!(
            (a - b).abs() <= 1e-12 * b.abs().max(1e-300),
            "{method} {volumetric:?} quantity {k}: {a:e} against recorded {b:e}"
        );
    }
}

#[test]
fn fem_q1_contact_matches_the_recorded_numbers() {
    check(
        DiscretisationMethod::FemQ1,
        VolumetricIntegration::Full,
        Q1_FULL,
    );
    check(
        DiscretisationMethod::FemQ1,
        VolumetricIntegration::Reduced,
        Q1_REDUCED,
    );
}

#[test]
fn fem_q2_contact_matches_the_recorded_numbers() {
    check(
        DiscretisationMethod::FemQ2,
        VolumetricIntegration::Full,
        Q2_FULL,
    );
    check(
        DiscretisationMethod::FemQ2,
        VolumetricIntegration::Reduced,
        Q2_REDUCED,
    );
}

const Q1_FULL: [f64; 8] = [
    0.34146341463414637,
    0.0024422917766326927,
    -0.0009319054193982086,
    -1.7622255249624201,
    -0.36226410906307893,
    -2.66209587270699,
    0.0003679613267642595,
    0.04141322642821943,
];
const Q1_REDUCED: [f64; 8] = [
    0.34146341463414637,
    0.002443637960299203,
    -0.0009351649671884118,
    -1.6260328518734597,
    -0.3627924066395277,
    -2.4557935803447792,
    0.00036724438484027247,
    0.04137264207421365,
];
const Q2_FULL: [f64; 8] = [
    0.34146341463414637,
    0.002446417175429214,
    -0.000939181733950425,
    -1.8025842170044424,
    -0.36251234610603467,
    -2.724250126064284,
    0.000369225452927782,
    0.04151565293572741,
];
const Q2_REDUCED: [f64; 8] = [
    0.34146341463414637,
    0.002450315381306965,
    -0.0009379106091008225,
    -1.6074727989500877,
    -0.36368424621763973,
    -2.4292338024752187,
    0.00036930599891467185,
    0.041571782993887293,
];
