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
//! at which it fully slips at `r_K` (Brent on its discrete full-slip ratio). The study itself
//! is `capstan::api::compare` (also `capstan compare`).
//!
//! Run: `cargo run --release --example models_compare -- [--quick] [OUT_DIR]`
//! (default `out/models`). Writes `compare.json`, `implied_mu.csv`, `thickness.csv` and plots
//! `implied_mu_vs_{b_over_a,thickness,poisson}.{svg,png}`.
//! Look at: `mu_capstan < nu_F = 0.5` in every row (the paper's finding `mu_F <= nu_F`), and
//! `r_K` rising towards `exp(nu_F pi) = 4.81` as `h -> 0` without reaching it.

use capstan::api;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let quick = args.iter().any(|a| a == "--quick");
    let out = args
        .iter()
        .find(|a| !a.starts_with("--"))
        .cloned()
        .unwrap_or_else(|| "out/models".into());
    let report = api::compare(quick)?;
    print!("{}", api::compare_table(&report));
    let dir = std::path::Path::new(&out);
    api::write_compare(dir, &report)?;
    println!("wrote {}", dir.join("implied_mu.csv").display());
    Ok(())
}
