//! The paper's figure PrismEqnPlot2: tension ratio against b/a on an elliptical prism.
//!
//! Problem: a membrane on the ellipse `(x1, a sin t, b cos t)`, `a = 1`, at limiting
//! equilibrium on `[-pi/4, pi/4]` with `mu = 1/2`; `b/a` runs over `[1/2, 3/2]`. Theorem 1
//! gives `T_max/T0 = exp(2 mu atan(b/a))` (eq. PrismEqnPlot): the ratio grows with the
//! curvature of the contact region.
//!
//! Run: `cargo run --example capstan_ratio_vs_ba [-- OUT.csv]` (default
//! `target/figures/capstan_ratio_vs_ba.csv`). Columns: `b_over_a, tension_ratio, paper`
//! (`paper` is the printed closed form). Look at: the ratio rising from 1.5899 at b/a = 1/2
//! to 2.6719 at b/a = 3/2, and the two columns agreeing to rounding.

use std::path::PathBuf;

use capstan_friction::samples::{RatioRow, RatioVersusAspect};

fn csv(rows: &[RatioRow]) -> String {
    let mut s = String::from("b_over_a,tension_ratio,paper\n");
    for r in rows {
        s.push_str(&format!(
            "{:.6},{:.15},{:.15}\n",
            r.b_over_a, r.ratio, r.paper
        ));
    }
    s
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = std::env::args()
        .nth(1)
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from("target/figures/capstan_ratio_vs_ba.csv"));
    let rows = RatioVersusAspect::default().run()?;
    if let Some(dir) = out.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir)?;
    }
    std::fs::write(&out, csv(&rows))?;
    let worst = rows
        .iter()
        .map(|r| ((r.ratio - r.paper) / r.paper).abs())
        .fold(0.0, f64::max);
    println!(
        "wrote {} rows to {} (b/a {} .. {}: ratio {:.6} .. {:.6}; largest relative difference to exp(2 mu atan(b/a)): {:.1e})",
        rows.len(),
        out.display(),
        rows[0].b_over_a,
        rows[rows.len() - 1].b_over_a,
        rows[0].ratio,
        rows[rows.len() - 1].ratio,
        worst
    );
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn small_figure_matches_exp_2_mu_atan_b_over_a() {
        let rows = RatioVersusAspect {
            points: 3,
            ..Default::default()
        }
        .run()
        .unwrap();
        // b/a = 1: exp(2 * 0.5 * pi/4) = exp(pi/4)
        assert!((rows[1].ratio - std::f64::consts::FRAC_PI_4.exp()).abs() < 1e-14);
        assert!(
            rows.iter()
                .all(|r| ((r.ratio - r.paper) / r.paper).abs() < 1e-14)
        );
        assert!(csv(&rows).lines().count() == 4);
    }
}
