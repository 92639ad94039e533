//! The observed order of a convergence study, shared by the membrane tests.

/// Least-squares slope of `ln e` against `ln x` over the study's `(x, e)` points.
pub fn observed_order(study: &[(f64, f64)]) -> f64 {
    let n = study.len() as f64;
    let (xs, ys): (Vec<f64>, Vec<f64>) = study.iter().map(|(x, e)| (x.ln(), e.ln())).unzip();
    let (mx, my) = (xs.iter().sum::<f64>() / n, ys.iter().sum::<f64>() / n);
    let sxy: f64 = xs.iter().zip(&ys).map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = xs.iter().map(|x| (x - mx).powi(2)).sum();
    sxy / sxx
}

/// The study as lines `x e`, for the test's printed output.
pub fn table(study: &[(f64, f64)]) -> String {
    study
        .iter()
        .map(|(x, e)| format!("{x:.4e} {e:.4e}\n"))
        .collect()
}
