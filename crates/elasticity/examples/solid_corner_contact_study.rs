//! Error per unknown of the 3-D corner-refined body ([`SolidCornerNavier`]) against uniform
//! `fem-qp` hexahedra in the frictional contact solve: the finite-width ellipse (`a = 2`,
//! `b = 1.5`, `x1 in [-0.5, 0.5]`, free sides, `h = 1`, `E = 1e3`, `nu = 1/4`, Coulomb
//! `mu = 0.5`, `eps = 1e-5`) at the tension ratio 1.5, by the full-system Newton (sparse LU).
//!
//! ```text
//! cargo run --release -p capstan-elasticity --example solid_corner_contact_study -- 3
//! ```
//! Prints per run: mesh, unknowns, `max |v2|` and its relative error against the reference
//! (corner mesh of order `p + 2`, 8 layers).

use capstan_elasticity::contact::{ContactModel, EndLoads, FullSystemSettings, FullSystemSolver};
use capstan_elasticity::finite_element::high_order::CornerSettings;
use capstan_elasticity::friction::{RegularisedCoulomb, RegularisedCoulombParams};
use capstan_elasticity::solid::{HexElement, SolidBody, SolidCornerNavier};
use capstan_geometry::{EllipticalPrism, ShellChart};

const EPS: f64 = 1e-5;

fn body(p: usize, ne: [usize; 3]) -> SolidBody<EllipticalPrism<f64>> {
    SolidBody {
        order: HexElement::Gll(p),
        ..SolidBody::new(
            EllipticalPrism::new(2.0, 1.5).expect("an ellipse"),
            [-0.5, 0.5],
            ne.map(|e| p * e + 1),
        )
    }
}

fn params() -> RegularisedCoulombParams<f64> {
    RegularisedCoulombParams::new(0.5, EPS).expect("valid friction")
}

/// `(unknowns, max |v2|)`.
fn corner(p: usize, ne1: usize, s: CornerSettings) -> (usize, f64) {
    let b = body(p, [ne1, 1, 1]);
    let model = ContactModel::new(
        |tau0, tau_max| {
            SolidCornerNavier::new(
                ShellChart::new(b.surface),
                b.material,
                b.grid()?,
                &b.boundary(tau0, tau_max),
                None,
                CornerSettings { order: p, ..s },
            )
        },
        RegularisedCoulomb,
        params(),
        EPS,
    )
    .expect("a model");
    solve(&model)
}

fn uniform(p: usize, ne: [usize; 3]) -> (usize, f64) {
    let model = body(p, ne)
        .model(RegularisedCoulomb, params(), EPS)
        .expect("a model");
    solve(&model)
}

fn solve<D: capstan_elasticity::contact::ContactOperator>(
    model: &ContactModel<D, RegularisedCoulomb>,
) -> (usize, f64) {
    let s = FullSystemSolver::new(model, FullSystemSettings::default())
        .expect("a solver")
        .solve(EndLoads::ratio(1.5))
        .expect("a solution");
    (
        s.displacement.len(),
        s.max_azimuthal_displacement.value.abs(),
    )
}

fn main() {
    let p: usize = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(3);
    let ne1 = 2;
    let settings = |layers: usize| CornerSettings {
        order: p,
        cells: [12, 2],
        layers,
        ratio: 0.3,
    };
    let reference = corner(
        p + 2,
        ne1,
        CornerSettings {
            layers: 8,
            ..settings(0)
        },
    );
    println!(
        "reference p {}: unknowns {}, max |v2| {:.12e}",
        p + 2,
        reference.0,
        reference.1
    );
    let report = |name: &str, cells: [usize; 3], layers: usize, (n, v): (usize, f64)| {
        let e = ((v - reference.1) / reference.1).abs();
        println!(
            "{name} p {p} cells {cells:?} layers {layers}: unknowns {n}, max |v2| {v:.12e}, error {e:.3e}"
        );
    };
    for k in 1..=3 {
        let ne = [ne1, 12 * k, 2 * k];
        report("uniform", ne, 0, uniform(p, ne));
    }
    for layers in [1, 2, 3, 4, 6] {
        report(
            "corner",
            [ne1, 12, 2],
            layers,
            corner(p, ne1, settings(layers)),
        );
    }
}
