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
//! Theorem 2 for comparison (a thick belt free to rotate about the axis slides earlier).

use capstan_elasticity::contact::{
    BoundarySolver, ContactSettings, EndLoads, FullSystemSettings, FullSystemSolver,
};
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

fn main() {
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
}
