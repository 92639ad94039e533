//! A user-written obstacle for the 3-D body: a belt along a geodesic of a right circular cone.
//!
//! Problem: the cone of half-aperture `alpha` (`tan alpha = 1/4`), written in the coordinates
//! of its development: a point `(X, Y) = (d + x1, x2)` of the developed plane (polar `rho`,
//! `psi`) lies on the cone at slant distance `rho` and azimuth `theta = psi / sin(alpha)`,
//! ```text
//! sigma(x1, x2) = (rho cos(alpha), rho sin(alpha) sin(theta), rho sin(alpha) cos(theta))
//! rho = sqrt((d + x1)^2 + x2^2),  psi = atan2(x2, d + x1)
//! ```
//! The chart is an isometry of the plane (`a_ab = delta_ab`: the cone is developable), and
//! the lines `x1 = const` are its geodesics: a body on `x1 in [-w/2, w/2]`,
//! `x2 in [-L, L]` is a belt wound along the geodesic at distance `d` from the apex, the
//! setting of the paper's Theorem 2 (membrane ratio `exp(2 mu cot(alpha) sin(psi_max))`,
//! `psi_max = atan(L/d)`). Only `sigma` is written; everything else follows by automatic
//! differentiation, and the 3-D contact solvers run on it unchanged.
//!
//! Run: `cargo run --release --example solid_belt_on_cone`
//! Look at: the metric (identity), the slip fraction growing with the tension ratio, the
//! boundary-only solver agreeing with the full-system Newton, and the membrane ratio of
//! Theorem 2 for comparison (a thick belt slides earlier).
//!
//! The thin limit: `cargo run --release --example solid_belt_on_cone -- thin-limit` (about ten
//! minutes) finds the full-slip threshold of the belt (`mu = 1/2`, `E = 1e3`, width 0.4, free
//! sides, `tau0 = 1`, `tau_max = r`) for thicknesses `h = 0.2 ... 0.0125`, Poisson ratios 0
//! (the membrane of Theorem 2 has none) and 1/4, on three grids, and writes the table to
//! stdout and `out/solid_cone_thin_limit.csv`. The threshold `r_K` is the smallest ratio at
//! which every contact node slides (`|u| >= eps`), by bisection (relative bracket `1e-4`). In
//! 3-D a node can slide with a small negative `e_2` component (sideways, at the belt's edges),
//! so the 2-D criterion "every node slides forward" (Slip = 1) may never be met: the table
//! counts those nodes at `r_K` (`backward`). A ratio at which the solver finds no solution
//! counts as past the threshold (the 3-D body has no sliding-mode limit to test it against,
//! see docs/solid.md) and is counted (`failed`). The normal curvature of the geodesic at
//! `x2 = 0` is `cot(alpha)/d = 4`, so `h = 0.2` is a body 0.8 times as thick as its radius of
//! curvature `R = 0.25`: compare `h / R` with the plane-strain study in docs/models.md.

use std::io::Write;

use capstan_elasticity::Material;
use capstan_elasticity::contact::{
    BoundarySolver, ContactError, ContactSettings, EndLoads, FullSystemSettings, FullSystemSolver,
};
use capstan_elasticity::finite_element::ElementOrder;
use capstan_elasticity::friction::{RegularisedCoulomb, RegularisedCoulombParams};
use capstan_elasticity::solid::SolidBody;
use capstan_geometry::{Scalar, Surface};

/// The right circular cone in developed coordinates (see the module docs).
#[derive(Debug, Clone, Copy)]
struct DevelopedCone {
    /// `tan(alpha)`.
    tan_alpha: f64,
    /// Distance of the geodesic `x1 = 0` from the apex in the development.
    d: f64,
}

impl Surface<f64> for DevelopedCone {
    fn sigma<S: Scalar<f64>>(&self, [x1, x2]: [S; 2]) -> [S; 3] {
        let alpha = self.tan_alpha.atan();
        let (sa, ca) = (alpha.sin(), alpha.cos());
        let x = x1 + self.d;
        let rho = (x * x + x2 * x2).sqrt();
        let theta = x2.atan2(x) * (1.0 / sa);
        [rho * ca, rho * sa * theta.sin(), rho * sa * theta.cos()]
    }
}

const CONE: DevelopedCone = DevelopedCone {
    tan_alpha: 0.25,
    d: 1.0,
};
const HALF_LENGTH: f64 = 0.5;
const WIDTH: f64 = 0.4;
const MU: f64 = 0.5;
const EPS: f64 = 1e-5;

/// The belt of thickness `h` and width `w` on an `n1 x n2 x n3` grid.
fn belt(h: f64, w: f64, nodes: [usize; 3]) -> SolidBody<DevelopedCone> {
    SolidBody {
        theta: [-HALF_LENGTH, HALF_LENGTH],
        thickness: h,
        ..SolidBody::new(CONE, [-w / 2.0, w / 2.0], nodes)
    }
}

/// Theorem 2 for the right circular cone: `exp(2 mu cot(alpha) sin(atan(L/d)))`.
fn membrane_ratio() -> f64 {
    (2.0 * MU / CONE.tan_alpha * (HALF_LENGTH / CONE.d).atan().sin()).exp()
}

/// `(ratio, slip fraction, max |v^2|, largest difference to the full-system Newton relative
/// to the largest displacement)` for each ratio.
fn solve(body: &SolidBody<DevelopedCone>, ratios: &[f64]) -> Vec<[f64; 4]> {
    let params = RegularisedCoulombParams::new(MU, EPS).expect("valid");
    let model = body
        .model(RegularisedCoulomb, params, EPS)
        .expect("a model");
    let condensed = BoundarySolver::new(&model, ContactSettings::default()).expect("set-up");
    let full = FullSystemSolver::new(&model, FullSystemSettings::default()).expect("set-up");
    ratios
        .iter()
        .map(|&r| {
            let a = condensed.solve(EndLoads::ratio(r)).expect("a solution");
            let b = full.solve(EndLoads::ratio(r)).expect("a solution");
            let scale = a.displacement.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            let diff = a
                .displacement
                .iter()
                .zip(&b.displacement)
                .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
            [
                r,
                a.slip_fraction,
                a.max_azimuthal_displacement.value.abs(),
                diff / scale,
            ]
        })
        .collect()
}

/// One threshold search.
#[derive(Debug, Clone, Copy)]
struct Threshold {
    /// Largest ratio with a stick node.
    below: f64,
    /// Smallest ratio fully slipping or without a solution.
    above: f64,
    /// Slip at `below`.
    slip_below: f64,
    /// Ratios tried at which the solver found no solution.
    failures: usize,
    /// Contact solves.
    solves: usize,
    /// At `above`: the nodes sliding with a negative `e_2` component (`usize::MAX`: `above`
    /// had no solution).
    backward: usize,
}

/// The belt of thickness `h`, Poisson ratio `nu` on `[n1, n2, n3]` Q2 nodes: its threshold.
fn threshold(h: f64, nu: f64, nodes: [usize; 3]) -> Result<Threshold, ContactError> {
    let body = SolidBody {
        material: Material::new(1e3, nu).expect("a valid material"),
        order: ElementOrder::Q2.into(),
        ..belt(h, WIDTH, nodes)
    };
    let params = RegularisedCoulombParams::new(MU, EPS).expect("valid");
    let model = body.model(RegularisedCoulomb, params, EPS)?;
    let solver = BoundarySolver::new(&model, ContactSettings::default())?;
    let (mut failures, mut solves, mut backward) = (0, 0, 0);
    let mut warm: Option<Vec<f64>> = None;
    // Some(slip) below the threshold, None at or past it
    let mut probe = |r: f64, warm: &mut Option<Vec<f64>>| -> Result<Option<f64>, ContactError> {
        solves += 1;
        match solver.solve_from(EndLoads::ratio(r), warm.as_deref()) {
            // every node slides (in 3-D a node may slide with a negative e_2 component)
            Ok(sol) if sol.every_node_slipping() => {
                backward = sol.contact.state.iter().filter(|&&s| s < 0).count();
                Ok(None)
            }
            Ok(sol) => {
                *warm = Some(sol.unknowns.clone());
                Ok(Some(sol.slip_fraction))
            }
            Err(ContactError::NotConverged { .. } | ContactError::NoEquilibrium { .. }) => {
                failures += 1;
                backward = usize::MAX;
                Ok(None)
            }
            Err(e) => Err(e),
        }
    };
    let (mut below, mut slip_below) = (1.0, probe(1.0, &mut warm)?.unwrap_or(1.0));
    // bracket: step up by 10 % until the belt slides
    let mut above = below;
    for _ in 0..60 {
        above *= 1.1;
        match probe(above, &mut warm)? {
            Some(s) => (below, slip_below) = (above, s),
            None => break,
        }
    }
    while above - below > 1e-4 * above {
        let mid = 0.5 * (below + above);
        match probe(mid, &mut warm)? {
            Some(s) => (below, slip_below) = (mid, s),
            None => above = mid,
        }
    }
    Ok(Threshold {
        below,
        above,
        slip_below,
        failures,
        solves,
        backward,
    })
}

/// The backward count for the table, `no solution` where the threshold is a failed solve.
fn backward(n: usize) -> String {
    if n == usize::MAX {
        "no solution".into()
    } else {
        n.to_string()
    }
}

/// The thin-limit table (see the module docs).
fn thin_limit() -> Result<(), Box<dyn std::error::Error>> {
    let membrane = membrane_ratio();
    println!("Theorem 2 (membrane): {membrane:.5}");
    std::fs::create_dir_all("out")?;
    let mut csv = std::fs::File::create("out/solid_cone_thin_limit.csv")?;
    writeln!(
        csv,
        "h,h_over_R,nu,n1,n2,n3,threshold,below,slip_below,failures,solves,backward,gap"
    )?;
    println!(
        "{:>6} {:>5} {:>5} {:>12} {:>10} {:>9} {:>8} {:>8} {:>9}",
        "h", "h/R", "nu", "grid", "r_K", "gap", "failed", "solves", "backward"
    );
    for nu in [0.0, 0.25] {
        for h in [0.2, 0.1, 0.05, 0.025, 0.0125] {
            for n2 in [41, 81, 161] {
                let nodes = [5, n2, 3];
                let t = threshold(h, nu, nodes)?;
                let gap = membrane - t.above;
                let h_over_r = h * CONE.d.recip() / CONE.tan_alpha;
                println!(
                    "{h:>6} {h_over_r:>5.2} {nu:>5} {:>12} {:>10.5} {gap:>9.5} {:>8} {:>8} {:>9}",
                    format!("{}x{}x{}", nodes[0], nodes[1], nodes[2]),
                    t.above,
                    t.failures,
                    t.solves,
                    backward(t.backward)
                );
                writeln!(
                    csv,
                    "{h},{h_over_r},{nu},{},{},{},{},{},{},{},{},{},{gap}",
                    nodes[0],
                    nodes[1],
                    nodes[2],
                    t.above,
                    t.below,
                    t.slip_below,
                    t.failures,
                    t.solves,
                    backward(t.backward)
                )?;
            }
        }
    }
    Ok(())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    if std::env::args().nth(1).as_deref() == Some("thin-limit") {
        return thin_limit();
    }
    let g = CONE.geometry([0.1, 0.3]).expect("a regular point");
    println!("metric a_ab at (0.1, 0.3): {:?}", g.first_form);
    println!("Theorem 2 (membrane) ratio: {:.6}", membrane_ratio());
    println!(
        "{:>8} {:>10} {:>12} {:>14}",
        "ratio", "Slip", "max |v2|", "condensed-full"
    );
    for [r, slip, v2, diff] in solve(&belt(0.2, 0.4, [5, 41, 5]), &[1.5, 2.0, 2.5, 3.0]) {
        println!("{r:>8.3} {slip:>10.6} {v2:>12.6e} {diff:>14.2e}");
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn developed_cone_is_an_isometry_of_the_plane() {
        for x in [[0.0, 0.0], [0.2, -0.4], [-0.3, 0.45]] {
            let g = CONE.geometry(x).expect("regular");
            for a in 0..2 {
                for b in 0..2 {
                    let delta = if a == b { 1.0 } else { 0.0 };
                    // AD through sqrt, atan2, sin, cos: round-off only
                    assert!(
                        (g.first_form[a][b] - delta).abs() < 1e-13,
                        "{x:?}: {:?}",
                        g.first_form
                    );
                }
            }
            assert!(g.gaussian_curvature.abs() < 1e-12, "developable");
            assert!(g.mean_curvature > 0.0, "convex with the outward normal");
        }
    }

    #[test]
    fn belt_slip_grows_with_the_ratio_and_both_solvers_agree() {
        let rows = solve(&belt(0.2, 0.4, [3, 21, 3]), &[1.5, 2.5]);
        for [_, slip, _, diff] in &rows {
            assert!(*diff < 1e-7, "{rows:?}");
            assert!(*slip > 0.0 && *slip < 1.0, "{rows:?}");
        }
        assert!(rows[1][1] > rows[0][1], "{rows:?}");
        assert!(membrane_ratio() > 5.9 && membrane_ratio() < 6.0);
    }

    #[test]
    fn thinner_belts_slide_closer_to_theorem_2() {
        // coarse grid: the trend of the thin-limit table, not its numbers
        let thick = threshold(0.2, 0.0, [3, 21, 3]).expect("a threshold");
        let thin = threshold(0.05, 0.0, [3, 21, 3]).expect("a threshold");
        for t in [thick, thin] {
            assert!(t.below < t.above && t.above < membrane_ratio(), "{t:?}");
            assert!(t.above - t.below <= 1e-4 * t.above, "{t:?}");
        }
        assert!(
            membrane_ratio() - thin.above < 0.7 * (membrane_ratio() - thick.above),
            "{thick:?} {thin:?}"
        );
    }
}
