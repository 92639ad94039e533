//! Volumetric locking of the finite elements as Poisson's ratio approaches 1/2, and its remedy,
//! selective reduced integration (`discretisation.volumetric = "reduced"`), on exact solutions.
//!
//! The Lamé cylinder (inner radius 1, wall 1, internal pressure 1, `E = 10`) stays
//! well-defined as `nu -> 1/2`: `v^3 = a r + b / r` with `b = p / (2 mu (1/r1^2 - 1/r2^2))`
//! independent of `lambda` and `a = mu b / ((lambda + mu) r2^2) -> 0`, so the limit is the
//! divergence-free `b / r` with a finite pressure `lambda div v = 2 a lambda -> 2 mu b / r2^2`.
//! Errors are relative physical L2 (`||U_h - U|| / ||U||`, `dA = sqrt(g) dx2 dx3`).
//!
//! Quick variants (three grids) run in CI; the four-grid table is `#[ignore]`d
//! (`cargo test --release --test fem_locking -- --ignored --nocapture`).

use capstan_elasticity::Material;
use capstan_elasticity::finite_element::{
    ElementOrder, FemProblem, FemStudy, VolumetricIntegration,
};
use capstan_elasticity::samples::{LameCylinder, MmsBoundaries, PrismMms};
use capstan_elasticity::verification::{GridLevel, Study, observed_order};

use ElementOrder::{Q1, Q2};
use VolumetricIntegration::{Full, Reduced};

const POISSON: [f64; 4] = [0.3, 0.49, 0.4999, 0.4999999];

fn lame(nu: f64) -> FemProblem {
    FemProblem::Lame(LameCylinder {
        material: Material::new(10.0, nu).unwrap(),
        ..LameCylinder::default()
    })
}

/// `(h, relative L2 error)` on the `count` coarsest grids of the study (`n3 = 9, 17, 33, 65`
/// for the Lamé cylinder).
fn relative_l2(
    problem: FemProblem,
    order: ElementOrder,
    volumetric: VolumetricIntegration,
    count: usize,
) -> Vec<(f64, f64)> {
    let study = FemStudy::new(problem, order).with_volumetric(volumetric);
    let mut levels = study.levels();
    levels.truncate(count);
    levels
        .into_iter()
        .map(|l: GridLevel| {
            let (h, e) = study
                .errors(l)
                .unwrap_or_else(|err| panic!("{order:?} {volumetric:?} {l:?}: {err}"));
            (h, e.l2 / e.l2_exact)
        })
        .collect()
}

fn row(label: &str, nu: f64, errors: &[(f64, f64)]) -> String {
    let cells: Vec<String> = errors.iter().map(|(_, e)| format!("{e:.3e}")).collect();
    format!(
        "| {label} | {nu} | {} | {:.2} |",
        cells.join(" | "),
        observed_order(errors)
    )
}

#[test]
fn q1_full_locks_and_its_error_grows_like_one_over_one_minus_two_nu() {
    // coarsest-grid errors of Q1 with the full rule: the locking constant lambda / mu
    let e: Vec<f64> = POISSON
        .iter()
        .map(|&nu| relative_l2(lame(nu), Q1, Full, 1)[0].1)
        .collect();
    println!("Q1 full, n3 = 9: {e:?}");
    // observed 1.29e-3, 3.77e-2, 0.80, 0.9998: from nu = 0.3 to 0.49, 1 / (1 - 2 nu) grows
    // 20x and the error 29x; beyond, it saturates at O(1) (the locked displacement is a
    // vanishing fraction of the exact one) instead of converging
    assert!(e[1] > 15.0 * e[0], "{e:?}");
    assert!(e[2] > 0.5 && e[3] > 0.99, "locked: {e:?}");
    // while Q1-SRI on the same grid stays within 30% of its nu = 0.3 error (observed 7.2e-4,
    // 8.9e-4)
    let sri = [0.3, 0.4999999].map(|nu| relative_l2(lame(nu), Q1, Reduced, 1)[0].1);
    assert!(sri[1] < 1.3 * sri[0] && sri[1] < 1e-3, "{sri:?}");
}

#[test]
fn lame_q1_sri_is_second_order_uniformly_in_nu_quick() {
    let mut table = vec![];
    let mut finest = vec![];
    for nu in POISSON {
        let errors = relative_l2(lame(nu), Q1, Reduced, 3);
        table.push(row("Q1-SRI", nu, &errors));
        let p = observed_order(&errors);
        assert!((p - 2.0).abs() < 0.15, "nu {nu}: {}", table.join("\n"));
        finest.push(errors[2].1);
    }
    println!("{}", table.join("\n"));
    // uniform in nu: the finest error moves by less than 2x from nu = 0.3 to 0.4999999
    let (lo, hi) = finest
        .iter()
        .fold((f64::MAX, 0.0f64), |(a, b), &x| (a.min(x), b.max(x)));
    assert!(hi < 2.0 * lo, "{finest:?}");
}

#[test]
fn lame_q2_sri_is_third_order_uniformly_in_nu_quick() {
    let mut table = vec![];
    let mut finest = vec![];
    for nu in POISSON {
        let errors = relative_l2(lame(nu), Q2, Reduced, 3);
        table.push(row("Q2-SRI", nu, &errors));
        let p = observed_order(&errors);
        assert!((p - 3.0).abs() < 0.15, "nu {nu}: {}", table.join("\n"));
        finest.push(errors[2].1);
    }
    println!("{}", table.join("\n"));
    let (lo, hi) = finest
        .iter()
        .fold((f64::MAX, 0.0f64), |(a, b), &x| (a.min(x), b.max(x)));
    assert!(hi < 2.0 * lo, "{finest:?}");
}

#[test]
fn ellipse_mms_keeps_full_order_with_sri_at_nu_0_3() {
    // Q2-SRI's coarsest grid (n3 = 13) is pre-asymptotic (slope 3.4 to the next, 3.14 after):
    // the orders are taken over the three finest of the four grids
    let problem = FemProblem::Mms(PrismMms::ellipse(0.5, MmsBoundaries::TractionContact));
    for (order, expected) in [(Q1, 2.0), (Q2, 3.0)] {
        let full = relative_l2(problem.clone(), order, Full, 4);
        let reduced = relative_l2(problem.clone(), order, Reduced, 4);
        let table = [row("full", 0.3, &full), row("SRI", 0.3, &reduced)].join("\n");
        println!("{order:?}\n{table}");
        assert!(
            (observed_order(&reduced[1..]) - expected).abs() < 0.15,
            "{table}"
        );
        // the reduced rule changes the constant, not the order: within 2x of the full rule
        assert!(reduced[3].1 < 2.0 * full[3].1, "{table}");
    }
}

/// The whole table of the docs: every `nu`, Q1/Q2, full/SRI, four grids.
#[test]
#[ignore = "four grids, 16 studies: run with --release -- --ignored --nocapture"]
fn lame_locking_table_four_grids() {
    let mut table = vec![
        "| method | nu | n3 = 9 | 17 | 33 | 65 | order |".to_string(),
        "|---|---|---|---|---|---|---|".to_string(),
    ];
    for nu in POISSON {
        for (label, order, v) in [
            ("Q1-full", Q1, Full),
            ("Q1-SRI", Q1, Reduced),
            ("Q2-full", Q2, Full),
            ("Q2-SRI", Q2, Reduced),
        ] {
            let errors = relative_l2(lame(nu), order, v, 4);
            table.push(row(label, nu, &errors));
            // At nu = 0.4999999 the finest Q2 error (observed 1.8e-6 against 4.1e-6 on the
            // grid before) is at the round-off floor `eps cond(A)`, `cond(A) ~ lambda / mu h^-2`
            // (lambda / mu = 5e6): the order is taken over the three coarsest grids there.
            let used = if nu > 0.4999 { 3 } else { 4 };
            if v == Reduced {
                let expected = order.degree() as f64 + 1.0;
                assert!(
                    (observed_order(&errors[..used]) - expected).abs() < 0.15,
                    "{}",
                    table.join("\n")
                );
            }
        }
    }
    println!("{}", table.join("\n"));
}

/// Why the contact answers with SRI do not settle: the contact rows recover the normal stress
/// `T^3_3` at the contact nodes from nodal displacement differences with the full `lambda`, so
/// `lambda div v` at the nodes carries the checkerboard of the reduced (element-wise) pressure,
/// amplified by `lambda / mu`. Prints the node-to-node oscillation of the normal stress on the
/// paper's contact case (60 x 11 / 61 x 11, `nu = 0.45` and `0.4999`).
#[test]
#[ignore = "diagnostic: run with --release -- --ignored --nocapture"]
fn contact_normal_stress_oscillation_with_sri() {
    use capstan_elasticity::Grid;
    use capstan_elasticity::contact::{
        BoundarySolver, ContactModel, ContactSettings, EndLoads, ThickBody,
    };
    use capstan_elasticity::finite_element::FiniteElementNavier;
    use capstan_elasticity::friction::{RegularisedCoulomb, RegularisedCoulombParams};
    use capstan_geometry::ShellChart;
    for nu in [0.45, 0.4999] {
        for (order, n2, v) in [
            (Q1, 60, Full),
            (Q1, 60, Reduced),
            (Q2, 61, Full),
            (Q2, 61, Reduced),
        ] {
            let body = ThickBody {
                material: Material::new(1e3, nu).unwrap(),
                ..ThickBody::paper(n2, 11).unwrap()
            };
            let build = |t0: f64, tm: f64| {
                let grid = Grid::new(body.theta, body.thickness, body.n2, body.n3, false)?;
                FiniteElementNavier::with_volumetric(
                    ShellChart::new(body.obstacle.clone()),
                    body.material,
                    grid,
                    ThickBody::boundary(t0, tm),
                    None,
                    order,
                    v,
                )
            };
            let params = RegularisedCoulombParams::new(0.5, 1e-5).unwrap();
            let model = ContactModel::new(build, RegularisedCoulomb, params, 1e-5).unwrap();
            let s = BoundarySolver::new(&model, ContactSettings::default()).unwrap();
            match s.solve(EndLoads::ratio(2.0)) {
                Ok(sol) => {
                    let p = &sol.contact.normal_stress;
                    let mean = p.iter().map(|x| x.abs()).sum::<f64>() / p.len() as f64;
                    let osc = (1..p.len() - 1)
                        .map(|i| (p[i] - 0.5 * (p[i - 1] + p[i + 1])).abs())
                        .fold(0.0f64, f64::max);
                    let mid = p.len() / 2;
                    println!(
                        "nu {nu} {order:?} {v:?}: mean |T33| {mean:.3e}, max |second difference|/2 {osc:.3e} ({:.2} of mean), T33 at mid-4..mid+4 {:.3?}",
                        osc / mean,
                        &p[mid - 4..mid + 4]
                    );
                }
                Err(e) => println!("nu {nu} {order:?} {v:?}: {e}"),
            }
        }
    }
}
