//! Error per unknown of the 3-D corner-refined Qp hexahedra ([`SolidCornerNavier`]) against
//! the uniform tensor grid of `fem-qp` ([`SolidNavier`]) on the paper's linear stand-in in
//! 3-D: the section-3 circle (`a = b = 2`, `h = 1`, `E = 1e3`, `nu = 1/4`,
//! `x2 in [-pi/2, pi/2]`, `x1 in [-0.5, 0.5]`) with the contact face `x3 = 0` clamped, end
//! stresses `T^2_2 = 1` and `2`, free outer surface, and plane-strain or free `x1` faces.
//!
//! ```text
//! cargo run --release -p capstan-elasticity --example solid_corner_study -- plane-strain 3
//! cargo run --release -p capstan-elasticity --example solid_corner_study -- free 3
//! ```
//! Prints one line per run: method, cells `[x1, x2, x3]`, layers, free unknowns, the
//! compliance `C = b . v` (the energy norm squared of the solution: its error is the energy
//! error, which the corner singularities govern) and its relative error against the
//! reference (corner mesh of order `p + 2`, 8 layers).

use capstan_elasticity::finite_element::VolumetricIntegration;
use capstan_elasticity::finite_element::high_order::CornerSettings;
use capstan_elasticity::solid::{
    FaceCondition, HexElement, SideFaces, SolidBody, SolidCornerNavier, SolidNavier,
};
use capstan_geometry::{EllipticalPrism, ShellChart};
use capstan_solvers::SparseCholesky;

fn body(sides: SideFaces) -> SolidBody<EllipticalPrism<f64>> {
    let mut b = SolidBody::new(
        EllipticalPrism::new(2.0, 2.0).expect("a circle"),
        [-0.5, 0.5],
        [2, 2, 2],
    );
    b.sides = sides;
    b
}

fn boundary(b: &SolidBody<EllipticalPrism<f64>>) -> capstan_elasticity::solid::SolidBoundary {
    let mut boundary = b.boundary(1.0, 2.0);
    boundary.faces[4] = FaceCondition::clamped();
    boundary
}

/// `(free unknowns, compliance)`: the prescribed dofs are the decoupled identity columns
/// of the symmetric Dirichlet elimination.
fn compliance(system: &capstan_elasticity::LinearSystem, v: &[f64]) -> (usize, f64) {
    let c = system.rhs.iter().zip(v).map(|(b, x)| b * x).sum();
    let (ptr, rows) = (system.pattern.col_ptr(), system.pattern.row_idx());
    let free = (0..v.len())
        .filter(|&d| (ptr[d]..ptr[d + 1]).any(|k| rows[k] != d && system.values[k] != 0.0))
        .count();
    (free, c)
}

fn corner(
    b: &SolidBody<EllipticalPrism<f64>>,
    p: usize,
    ne1: usize,
    s: CornerSettings,
) -> (usize, f64) {
    let grid = capstan_elasticity::solid::BoxGrid::new(
        b.x1,
        b.theta,
        b.thickness,
        [p * ne1 + 1, 2, 2],
        false,
    )
    .expect("a grid");
    let op = SolidCornerNavier::new(
        ShellChart::new(b.surface),
        b.material,
        grid,
        &boundary(b),
        None,
        CornerSettings { order: p, ..s },
    )
    .expect("the corner operator");
    let v = op.solve(&mut SparseCholesky::default()).expect("a solve");
    compliance(op.system(), &v)
}

fn uniform(b: &SolidBody<EllipticalPrism<f64>>, p: usize, ne: [usize; 3]) -> (usize, f64) {
    let mut b = b.clone();
    b.nodes = ne.map(|e| p * e + 1);
    let op = SolidNavier::new(
        ShellChart::new(b.surface),
        b.material,
        b.grid().expect("a grid"),
        &boundary(&b),
        None,
        HexElement::Gll(p),
        VolumetricIntegration::Full,
    )
    .expect("the tensor operator");
    let v = op.solve(&mut SparseCholesky::default()).expect("a solve");
    compliance(op.system(), &v)
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let sides = match args.get(1).map(String::as_str) {
        Some("free") => SideFaces::Free,
        _ => SideFaces::PlaneStrain,
    };
    let p: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(3);
    let b = body(sides);
    let ne1 = 2;
    let settings = |layers: usize| CornerSettings {
        order: p,
        cells: [12, 2],
        layers,
        ratio: 0.3,
    };
    let reference = corner(
        &b,
        p + 2,
        ne1,
        CornerSettings {
            layers: 8,
            ..settings(0)
        },
    );
    println!(
        "reference p {}: unknowns {}, C {:.12e}",
        p + 2,
        reference.0,
        reference.1
    );
    let report = |name: &str, cells: [usize; 3], layers: usize, (n, c): (usize, f64)| {
        let e = ((c - reference.1) / reference.1).abs();
        println!(
            "{name} p {p} cells {cells:?} layers {layers}: unknowns {n}, C {c:.12e}, error {e:.3e}"
        );
    };
    for k in 1..=3 {
        let ne = [ne1, 12 * k, 2 * k];
        report("uniform", ne, 0, uniform(&b, p, ne));
    }
    for layers in [1, 2, 3, 4, 5, 6] {
        report(
            "corner",
            [ne1, 12, 2],
            layers,
            corner(&b, p, ne1, settings(layers)),
        );
    }
}
