//! Comparing the friction models: the coefficient of friction each model implies for the same
//! tension pair, against `b/a`, `h` and `nu` (the paper's section 3 and conclusions), and the
//! thick body's threshold ratio as `h -> 0` against the capstan value.
//!
//! Problem: an elastic body (thick: plane-strain Kikuchi–Oden contact, FD grid `n2 x n3`;
//! membrane: the 1-D displacement model of `capstan_friction::membrane_displacement`) on the
//! elliptical prism `(a sin t, b cos t)`, `a = 2`, contact `[-pi/2, pi/2]`, `tau0 = 1`,
//! `E = 1e3`, `nu = 1/4`, `h = 1`, `eps = 1e-5`, friction `nu_F = 1/2` (defaults of the paper).
//! For each configuration the thick body's threshold ratio `r_K` (Slip = 1) is found; the
//! Kikuchi–Oden model implies `nu_F = 1/2` for the pair `(1, r_K)` by construction, the capstan
//! equation implies `mu_F = ln(r_K) / Psi` (`Psi = pi` here) and the membrane model the `mu`
//! at which it fully slips at `r_K` (Brent on its discrete full-slip ratio).
//!
//! Run: `cargo run --release --example models_compare -- [--quick] [OUT_DIR]`
//! (default `out/models`). Writes `implied_mu.csv`, `thickness.csv` and plots
//! `implied_mu_vs_{b_over_a,thickness,poisson}.{svg,png}`.
//! Look at: `mu_capstan < nu_F = 0.5` in every row (the paper's finding `mu_F <= nu_F`), and
//! `r_K` rising towards `exp(nu_F pi) = 4.81` as `h -> 0` without reaching it.

use std::f64::consts::{FRAC_PI_2, PI};

use capstan::output::{LinePlot, OutputDir, Series, Table, write_plot};
use capstan_elasticity::Material;
use capstan_elasticity::contact::{
    BoundarySolver, ContactSettings, ThickBody, ThresholdSettings, threshold_ratio,
};
use capstan_friction::membrane_displacement::{
    EndCondition, MembraneDisplacement, MembraneDisplacementProblem,
};
use capstan_friction::root::Brent;
use capstan_friction::{RegularisedCoulomb, RegularisedCoulombParams};
use capstan_geometry::{EllipticalPrism, Obstacle};

const EPS: f64 = 1e-5;
const NU_F: f64 = 0.5;

/// One configuration of the thick body.
#[derive(Debug, Clone, Copy)]
struct Config {
    b_over_a: f64,
    thickness: f64,
    poisson: f64,
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

/// The thick body's threshold ratio (Slip = 1) at friction `mu` on an `n2 x n3` grid.
fn thick_threshold(
    c: Config,
    mu: f64,
    n2: usize,
    n3: usize,
) -> Result<f64, Box<dyn std::error::Error>> {
    let body = ThickBody {
        obstacle: Obstacle::Ellipse(EllipticalPrism::new(2.0, 2.0 * c.b_over_a)?),
        thickness: c.thickness,
        material: Material::new(1e3, c.poisson)?,
        ..ThickBody::paper(n2, n3)?
    };
    let model = body.model(
        RegularisedCoulomb,
        RegularisedCoulombParams::new(mu, EPS)?,
        EPS,
    )?;
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

/// The membrane model's full-slip ratio at friction `mu` (`n` nodes).
fn membrane_ratio(
    b_over_a: f64,
    mu: f64,
    n: usize,
) -> Result<f64, capstan_friction::FrictionError> {
    let e = EllipticalPrism::new(2.0, 2.0 * b_over_a)?;
    let problem = MembraneDisplacementProblem {
        theta0: -FRAC_PI_2,
        theta1: FRAC_PI_2,
        nodes: n,
        stiffness: 1e3,
        start: EndCondition::Tension(1.0),
        end: EndCondition::Displacement(1.0), // pulled far: every node slides
    };
    let law = RegularisedCoulombParams::new(mu, EPS)?;
    let s = MembraneDisplacement::new(&e, RegularisedCoulomb, law).solve(
        &problem,
        None,
        Default::default(),
    )?;
    Ok(s.tension_ratio())
}

/// The coefficient at which the membrane model fully slips at ratio `r`.
fn membrane_mu(b_over_a: f64, r: f64, n: usize) -> Result<f64, capstan_friction::FrictionError> {
    let f = |mu: f64| Ok(membrane_ratio(b_over_a, mu, n)? - r);
    let (lo, hi) = (0.0, 2.0);
    Brent {
        x_tol: 1e-10,
        ..Default::default()
    }
    .solve(f, lo, f(lo)?, hi, f(hi)?)
}

struct Row {
    config: Config,
    grid: (usize, usize),
    ratio: f64,
    mu_capstan: f64,
    mu_membrane: f64,
}

fn row(c: Config, grid: (usize, usize)) -> Result<Row, Box<dyn std::error::Error>> {
    let ratio = thick_threshold(c, NU_F, grid.0, grid.1).map_err(|e| {
        format!(
            "b/a {} h {} nu {} grid {grid:?}: {e}",
            c.b_over_a, c.thickness, c.poisson
        )
    })?;
    Ok(Row {
        config: c,
        grid,
        ratio,
        mu_capstan: ratio.ln() / PI, // Psi = pi on [-pi/2, pi/2] of every ellipse
        mu_membrane: membrane_mu(c.b_over_a, ratio, 801)?,
    })
}

/// Keeps a row, or reports why the configuration has none (and goes on).
fn keep(rows: &mut Vec<Row>, r: Result<Row, Box<dyn std::error::Error>>) {
    match r {
        Ok(r) => rows.push(r),
        Err(e) => eprintln!("skipped a configuration: {e}"),
    }
}

fn print(rows: &[Row]) {
    println!("  b/a      h     nu   grid       r_K      nu_F  mu_capstan  mu_membrane");
    for r in rows {
        println!(
            "{:5.2} {:6.4} {:6.3} {:>4}x{:<3} {:9.5} {:6.3} {:11.5} {:12.5}",
            r.config.b_over_a,
            r.config.thickness,
            r.config.poisson,
            r.grid.0,
            r.grid.1,
            r.ratio,
            NU_F,
            r.mu_capstan,
            r.mu_membrane
        );
    }
}

fn table(rows: &[Row]) -> Table {
    let col = |f: &dyn Fn(&Row) -> f64| rows.iter().map(f).collect::<Vec<f64>>();
    Table::new()
        .f64("b_over_a", col(&|r| r.config.b_over_a))
        .f64("thickness", col(&|r| r.config.thickness))
        .f64("poisson", col(&|r| r.config.poisson))
        .f64("n2", col(&|r| r.grid.0 as f64))
        .f64("n3", col(&|r| r.grid.1 as f64))
        .f64("threshold_ratio", col(&|r| r.ratio))
        .f64("nu_kikuchi_oden", col(&|_| NU_F))
        .f64("mu_capstan", col(&|r| r.mu_capstan))
        .f64("mu_membrane", col(&|r| r.mu_membrane))
}

fn plot(rows: &[Row], x: &dyn Fn(&Row) -> f64, name: &str) -> LinePlot {
    let xs: Vec<f64> = rows.iter().map(x).collect();
    LinePlot::new(format!("implied coefficient of friction against {name}"))
        .x_label(name)
        .y_label("implied mu")
        .series(
            Series::line("Kikuchi-Oden nu_F", xs.clone(), vec![NU_F; rows.len()]).with_markers(),
        )
        .series(
            Series::line(
                "capstan mu_F",
                xs.clone(),
                rows.iter().map(|r| r.mu_capstan).collect::<Vec<_>>(),
            )
            .with_markers(),
        )
        .series(
            Series::line(
                "membrane mu",
                xs,
                rows.iter().map(|r| r.mu_membrane).collect::<Vec<_>>(),
            )
            .with_markers(),
        )
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let quick = args.iter().any(|a| a == "--quick");
    let out = args
        .iter()
        .find(|a| !a.starts_with("--"))
        .cloned()
        .unwrap_or_else(|| "out/models".into());
    let out = OutputDir::create(std::path::Path::new(&out))?;
    let grid = if quick { (41, 9) } else { (81, 17) };
    let base = Config::default();

    println!(
        "# thick body as h -> 0 (capstan value exp(nu_F pi) = {:.5}); grid convergence",
        (NU_F * PI).exp()
    );
    let hs: &[f64] = if quick {
        &[1.0, 0.5, 0.25]
    } else {
        &[1.0, 0.5, 0.25, 0.125, 0.0625]
    };
    let grids: &[(usize, usize)] = if quick {
        &[(41, 9)]
    } else {
        &[(41, 9), (81, 17), (161, 33)]
    };
    let mut thickness_rows = Vec::new();
    for &h in hs {
        for &g in grids {
            thickness_rows.push(row(
                Config {
                    thickness: h,
                    ..base
                },
                g,
            )?);
        }
    }
    print(&thickness_rows);
    out.write_csv("thickness.csv", &table(&thickness_rows))?;

    let mut sweeps: Vec<(&str, Vec<Row>)> = Vec::new();
    let ba: &[f64] = if quick {
        &[0.5, 1.0, 1.5]
    } else {
        &[0.5, 0.75, 1.0, 1.25, 1.5, 2.0]
    };
    let mut rows = Vec::new();
    for &b in ba {
        keep(
            &mut rows,
            row(
                Config {
                    b_over_a: b,
                    ..base
                },
                grid,
            ),
        );
    }
    sweeps.push(("b_over_a", rows));
    let nus: &[f64] = if quick {
        &[0.0, 0.25, 0.45]
    } else {
        &[0.0, 0.1, 0.25, 0.35, 0.45]
    };
    let mut rows = Vec::new();
    for &nu in nus {
        keep(
            &mut rows,
            row(
                Config {
                    poisson: nu,
                    ..base
                },
                grid,
            ),
        );
    }
    sweeps.push(("poisson", rows));
    let mut all = Vec::new();
    for (name, rows) in sweeps {
        println!(
            "# implied coefficients against {name} (grid {}x{})",
            grid.0, grid.1
        );
        print(&rows);
        let x: &dyn Fn(&Row) -> f64 = match name {
            "b_over_a" => &|r| r.config.b_over_a,
            _ => &|r| r.config.poisson,
        };
        write_plot(
            &out.file(&format!("implied_mu_vs_{name}"))?,
            &plot(&rows, x, name),
        )?;
        all.extend(rows);
    }
    let finest: Vec<Row> = thickness_rows
        .into_iter()
        .filter(|r| r.grid == *grids.last().unwrap())
        .collect();
    write_plot(
        &out.file("implied_mu_vs_thickness")?,
        &plot(&finest, &|r| r.config.thickness, "thickness"),
    )?;
    out.write_csv("implied_mu.csv", &table(&all))?;
    println!("wrote {}", out.file("implied_mu.csv")?.display());
    Ok(())
}
