//! `capstan compare`: the coefficient of friction each model implies for the same tension
//! pair, against `b/a`, `h` and `nu` (the paper's section 3 and conclusions), and the thick
//! body's threshold ratio as `h -> 0` against the capstan value.
//!
//! # Math
//! An elastic body on the elliptical prism `(a sin t, b cos t)`, `a = 2`, contact
//! `[-pi/2, pi/2]`, `tau0 = 1`, `E = 1e3`, `nu = 1/4`, `h = 1`, `eps = 1e-5`, friction
//! `nu_F = 1/2` (the paper's defaults). For each configuration the thick body's threshold
//! ratio `r_K` (Slip = 1) is found; for the pair `(1, r_K)`:
//! ```text
//! Kikuchi–Oden   nu_F = 1/2                          by construction
//! capstan        mu_F = ln(r_K) / Psi                Psi = pi on [-pi/2, pi/2] of every ellipse
//! membrane       mu: membrane_ratio(mu) = r_K        full slip, Brent (801 nodes, k = 1e3)
//! ```
//! `docs/models.md` records the measured numbers.

use std::f64::consts::{FRAC_PI_2, PI};
use std::path::Path;

use capstan_elasticity::Material;
use capstan_elasticity::contact::{
    BoundarySolver, ContactSettings, ThickBody, ThresholdSettings, threshold_ratio,
};
use capstan_geometry::{EllipticalPrism, Obstacle};
use serde::Serialize;

use crate::commands::infer_mu::{MembraneSetup, coulomb_model, membrane_mu};
use crate::error::CliError;
use crate::output::{LinePlot, OutputDir, Series, Table, write_plot};

/// Regularisation width (slip length) of every model here.
pub const EPS: f64 = 1e-5;
/// The thick body's coefficient `nu_F`.
pub const NU_F: f64 = 0.5;

/// One configuration of the thick body.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Config {
    /// `b / a` of the ellipse (`a = 2`).
    pub b_over_a: f64,
    /// Thickness `h`.
    pub thickness: f64,
    /// Poisson's ratio `nu`.
    pub poisson: f64,
}

impl Default for Config {
    fn default() -> Self {
        Self {
            b_over_a: 1.0,
            thickness: 1.0,
            poisson: 0.25,
        }
    }
}

/// One row of the comparison.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct CompareRow {
    /// The configuration.
    #[serde(flatten)]
    pub config: Config,
    /// `[n2, n3]` of the thick body.
    pub grid: [usize; 2],
    /// The thick body's threshold ratio `r_K` at `nu_F`.
    pub threshold_ratio: f64,
    /// The Kikuchi–Oden coefficient (`nu_F`, by construction).
    pub nu_kikuchi_oden: f64,
    /// The capstan coefficient `ln(r_K) / pi`.
    pub mu_capstan: f64,
    /// The membrane displacement model's coefficient.
    pub mu_membrane: f64,
}

/// `capstan compare --json`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CompareReport {
    /// `nu_F`.
    pub nu_f: f64,
    /// The capstan ratio `exp(nu_F pi)` the thick body approaches as `h -> 0`.
    pub capstan_ratio: f64,
    /// The grid of the `b/a` and `nu` studies.
    pub grid: [usize; 2],
    /// `h` decreasing, every grid of the convergence study.
    pub thickness: Vec<CompareRow>,
    /// `b/a` study.
    pub b_over_a: Vec<CompareRow>,
    /// `nu` study.
    pub poisson: Vec<CompareRow>,
    /// Configurations without a result, and why.
    pub skipped: Vec<String>,
}

/// The thick body's threshold ratio (Slip = 1) at friction `mu` on an `n2 x n3` grid
/// (bisection to `1e-5` relative).
///
/// # Errors
/// Invalid configuration; contact solver failures.
pub fn thick_threshold(c: Config, mu: f64, grid: [usize; 2]) -> Result<f64, CliError> {
    let body = ThickBody {
        obstacle: Obstacle::Ellipse(EllipticalPrism::new(2.0, 2.0 * c.b_over_a)?),
        thickness: c.thickness,
        material: Material::new(1e3, c.poisson)?,
        ..ThickBody::paper(grid[0], grid[1])?
    };
    let model = coulomb_model(&body, mu, EPS)?;
    let solver = BoundarySolver::new(&model, ContactSettings::default())?;
    let t = threshold_ratio(
        &solver,
        ThresholdSettings {
            tolerance: 1e-5,
            ..Default::default()
        },
    )?;
    Ok(t.ratio)
}

/// One row: the threshold ratio and the coefficients it implies.
///
/// # Errors
/// See [`thick_threshold`] and [`membrane_mu`].
pub fn row(c: Config, grid: [usize; 2]) -> Result<CompareRow, CliError> {
    let ratio = thick_threshold(c, NU_F, grid)?;
    let e = EllipticalPrism::new(2.0, 2.0 * c.b_over_a)?;
    let setup = MembraneSetup {
        theta: [-FRAC_PI_2, FRAC_PI_2],
        stiffness: 1e3,
        eps: EPS,
        nodes: crate::commands::infer_mu::MEMBRANE_NODES,
        max_newton_iterations: 100,
        max_root_iterations: 200,
    };
    Ok(CompareRow {
        config: c,
        grid,
        threshold_ratio: ratio,
        nu_kikuchi_oden: NU_F,
        mu_capstan: ratio.ln() / PI, // Psi = pi on [-pi/2, pi/2] of every ellipse
        mu_membrane: membrane_mu(&e, setup, ratio)?.mu,
    })
}

/// Runs the studies (`quick`: grid 41 x 9, three values per axis).
///
/// # Errors
/// A failed row of the thickness study; rows of the `b/a` and `nu` studies that fail are
/// listed in [`CompareReport::skipped`] instead.
pub fn report(quick: bool) -> Result<CompareReport, CliError> {
    let grid = if quick { [41, 9] } else { [81, 17] };
    let base = Config::default();
    let hs: &[f64] = if quick {
        &[1.0, 0.5, 0.25]
    } else {
        &[1.0, 0.5, 0.25, 0.125, 0.0625]
    };
    let grids: &[[usize; 2]] = if quick {
        &[[41, 9]]
    } else {
        &[[41, 9], [81, 17], [161, 33]]
    };
    let mut thickness = Vec::new();
    for &h in hs {
        for &g in grids {
            let c = Config {
                thickness: h,
                ..base
            };
            thickness.push(row(c, g)?);
        }
    }
    let mut skipped = Vec::new();
    // the base configuration with one axis (`set`) at each of `values`
    let mut sweep = |values: &[f64], set: fn(&mut Config, f64)| {
        let mut rows = Vec::new();
        for &value in values {
            let mut c = base;
            set(&mut c, value);
            match row(c, grid) {
                Ok(r) => rows.push(r),
                Err(e) => skipped.push(format!(
                    "b/a {} h {} nu {} grid {grid:?}: {e}",
                    c.b_over_a, c.thickness, c.poisson
                )),
            }
        }
        rows
    };
    let ba: &[f64] = if quick {
        &[0.5, 1.0, 1.5]
    } else {
        &[0.5, 0.75, 1.0, 1.25, 1.5, 2.0]
    };
    let b_over_a = sweep(ba, |c, b| c.b_over_a = b);
    let nus: &[f64] = if quick {
        &[0.0, 0.25, 0.45]
    } else {
        &[0.0, 0.1, 0.25, 0.35, 0.45]
    };
    let poisson = sweep(nus, |c, nu| c.poisson = nu);
    Ok(CompareReport {
        nu_f: NU_F,
        capstan_ratio: (NU_F * PI).exp(),
        grid,
        thickness,
        b_over_a,
        poisson,
        skipped,
    })
}

fn rows_text(rows: &[CompareRow]) -> String {
    let mut s =
        String::from("  b/a      h     nu   grid       r_K      nu_F  mu_capstan  mu_membrane\n");
    for r in rows {
        s += &format!(
            "{:5.2} {:6.4} {:6.3} {:>4}x{:<3} {:9.5} {:6.3} {:11.5} {:12.5}\n",
            r.config.b_over_a,
            r.config.thickness,
            r.config.poisson,
            r.grid[0],
            r.grid[1],
            r.threshold_ratio,
            r.nu_kikuchi_oden,
            r.mu_capstan,
            r.mu_membrane
        );
    }
    s
}

/// Plain text: the three studies.
pub fn table(r: &CompareReport) -> String {
    let mut s = format!(
        "# thick body as h -> 0 (capstan value exp(nu_F pi) = {:.5}); grid convergence\n{}",
        r.capstan_ratio,
        rows_text(&r.thickness)
    );
    for (name, rows) in [("b_over_a", &r.b_over_a), ("poisson", &r.poisson)] {
        s += &format!(
            "# implied coefficients against {name} (grid {}x{})\n{}",
            r.grid[0],
            r.grid[1],
            rows_text(rows)
        );
    }
    for k in &r.skipped {
        s += &format!("skipped: {k}\n");
    }
    s
}

/// The CSV columns of rows.
pub fn csv_table(rows: &[CompareRow]) -> Table {
    let col = |f: &dyn Fn(&CompareRow) -> f64| rows.iter().map(f).collect::<Vec<f64>>();
    Table::new()
        .f64("b_over_a", col(&|r| r.config.b_over_a))
        .f64("thickness", col(&|r| r.config.thickness))
        .f64("poisson", col(&|r| r.config.poisson))
        .f64("n2", col(&|r| r.grid[0] as f64))
        .f64("n3", col(&|r| r.grid[1] as f64))
        .f64("threshold_ratio", col(&|r| r.threshold_ratio))
        .f64("nu_kikuchi_oden", col(&|r| r.nu_kikuchi_oden))
        .f64("mu_capstan", col(&|r| r.mu_capstan))
        .f64("mu_membrane", col(&|r| r.mu_membrane))
}

/// The three implied coefficients against `x` (one series per model).
pub fn plot(rows: &[CompareRow], x: &dyn Fn(&CompareRow) -> f64, name: &str) -> LinePlot {
    let xs: Vec<f64> = rows.iter().map(x).collect();
    let ys = |f: &dyn Fn(&CompareRow) -> f64| rows.iter().map(f).collect::<Vec<f64>>();
    LinePlot::new(format!("implied coefficient of friction against {name}"))
        .x_label(name)
        .y_label("implied mu")
        .series(
            Series::line("Kikuchi-Oden nu_F", xs.clone(), ys(&|r| r.nu_kikuchi_oden))
                .with_markers(),
        )
        .series(Series::line("capstan mu_F", xs.clone(), ys(&|r| r.mu_capstan)).with_markers())
        .series(Series::line("membrane mu", xs, ys(&|r| r.mu_membrane)).with_markers())
}

/// Writes `compare.json`, `implied_mu.csv` (the `b/a` and `nu` rows), `thickness.csv` and
/// the plots `implied_mu_vs_{b_over_a,poisson,thickness}.{svg,png}` (thickness: finest grid).
///
/// # Errors
/// I/O and plotting errors.
pub fn write_out(dir: &Path, r: &CompareReport) -> Result<(), CliError> {
    let out = OutputDir::create(dir)?;
    out.write_json("compare.json", r)?;
    out.write_csv("thickness.csv", &csv_table(&r.thickness))?;
    let all: Vec<CompareRow> = r.b_over_a.iter().chain(&r.poisson).copied().collect();
    out.write_csv("implied_mu.csv", &csv_table(&all))?;
    write_plot(
        &out.file("implied_mu_vs_b_over_a")?,
        &plot(&r.b_over_a, &|r| r.config.b_over_a, "b_over_a"),
    )?;
    write_plot(
        &out.file("implied_mu_vs_poisson")?,
        &plot(&r.poisson, &|r| r.config.poisson, "poisson"),
    )?;
    let finest = r.thickness.iter().map(|r| r.grid[0]).max().unwrap_or(0);
    let thin: Vec<CompareRow> = r
        .thickness
        .iter()
        .filter(|r| r.grid[0] == finest)
        .copied()
        .collect();
    write_plot(
        &out.file("implied_mu_vs_thickness")?,
        &plot(&thin, &|r| r.config.thickness, "thickness"),
    )?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn membrane_implies_the_capstan_mu_at_the_threshold() {
        let r = row(Config::default(), [41, 9]).unwrap();
        // full slip: the membrane is the capstan equation up to its grid error (801 nodes)
        assert!((r.mu_membrane / r.mu_capstan - 1.0).abs() < 1e-5, "{r:?}");
        assert!(r.mu_capstan < NU_F, "{r:?}");
    }
}
