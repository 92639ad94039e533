//! Adding a new obstacle: write only `sigma`.
//!
//! Problem: an egg-shaped convex prism `sigma(x1, x2) = (x1, 2 sin x2, 1.5 cos x2 + 0.2 cos 2 x2)`,
//! which is not an ellipse. Implementing `Surface::sigma` once, generically over the scalar,
//! gives exact tangents, normal, fundamental forms, curvatures, Christoffel symbols and the
//! shell chart `sigma + x3 N` by forward-mode automatic differentiation.
//!
//! Run: `cargo run --example custom_obstacle`
//! Look at: `H > 0` everywhere (a convex obstacle with outward normal), `K = 0` (a prism), and
//! `sqrt(g) = |a_2| (1 + 2 H x3)` on the outer side (for a prism `2H` is the profile's curvature).

use capstan::geometry::{Scalar, ShellChart, Surface};

/// The egg-shaped prism; nothing but `sigma` is written.
struct Egg;

impl Surface<f64> for Egg {
    fn sigma<S: Scalar<f64>>(&self, [x1, x2]: [S; 2]) -> [S; 3] {
        [x1, x2.sin() * 2.0, x2.cos() * 1.5 + (x2 * 2.0).cos() * 0.2]
    }
}

/// Mean curvature, Gaussian curvature and `sqrt(g)` at `x3 = 0.5` along the profile.
fn profile_table(n: usize) -> Vec<[f64; 4]> {
    let chart = ShellChart::new(Egg);
    (0..n)
        .map(|i| {
            let t = -std::f64::consts::PI + 2.0 * std::f64::consts::PI * i as f64 / n as f64;
            let g = Egg.geometry([0.0, t]).expect("the egg is regular");
            let p = chart.point([0.0, t, 0.5]).expect("inside the shell");
            [t, g.mean_curvature, g.gaussian_curvature, p.sqrt_g]
        })
        .collect()
}

fn main() {
    println!("{:>9} {:>12} {:>12} {:>12}", "x2", "H", "K", "sqrt(g)");
    for [t, h, k, sg] in profile_table(16) {
        println!("{t:>9.4} {h:>12.6} {k:>12.2e} {sg:>12.6}");
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn egg_is_convex_developable_and_matches_its_curvature_formula() {
        for [t, h, k, _] in profile_table(64) {
            assert!(h > 0.0, "convex: H > 0 at {t}");
            assert!(k.abs() < 1e-13, "prism: K = 0 at {t}");
            // H = (v'u'' - u'v'') / (2 (u'^2 + v'^2)^(3/2)) for a prism
            let (u1, u2) = (2.0 * t.cos(), -2.0 * t.sin());
            let (v1, v2) = (
                -1.5 * t.sin() - 0.4 * (2.0 * t).sin(),
                -1.5 * t.cos() - 0.8 * (2.0 * t).cos(),
            );
            let expected = (v1 * u2 - u1 * v2) / (2.0 * (u1 * u1 + v1 * v1).powf(1.5));
            assert!((h - expected).abs() < 1e-13 * expected.abs());
        }
        // sqrt(g) = |a_2| (1 + 2 H x3) at x3 = 0.5; at x2 = -pi, |a_2| = 2 and H = 0.0875
        let first = profile_table(16)[0];
        assert!((first[3] - 2.0 * (1.0 + 2.0 * first[1] * 0.5)).abs() < 1e-13);
    }
}
