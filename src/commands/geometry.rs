//! `capstan geometry`: a report of the obstacle's differential geometry on the contact interval.

use capstan_friction::membrane::development;
use capstan_geometry::{Obstacle, ShellChart, Surface};
use serde::Serialize;

use crate::error::CliError;
use crate::scene::Scene;

/// Sampled geometry of the scene's obstacle on `[membrane.theta0, membrane.theta_max]`.
#[derive(Debug, Clone, Serialize)]
pub struct GeometryReport {
    /// The obstacle description (`obstacle.*`).
    pub obstacle: crate::scene::ObstacleSpec,
    /// The generator coordinate at which the report is taken (1 for cones, 0 for prisms).
    pub x1: f64,
    /// Sample points `x2`.
    pub x2: Vec<f64>,
    /// Mean curvature `H = -1/2 b^a_a` (paper's sign).
    pub mean_curvature: Vec<f64>,
    /// Gaussian curvature `K`.
    pub gaussian_curvature: Vec<f64>,
    /// `a_22` (first fundamental form).
    pub a22: Vec<f64>,
    /// `b_22` (second fundamental form).
    pub b22: Vec<f64>,
    /// Surface Christoffel symbol `Gamma^2_22`.
    pub christoffel_222: Vec<f64>,
    /// `sqrt(g)` of the shell chart at `x3 = body.thickness`.
    pub sqrt_g_outer: Vec<f64>,
    /// `a_ab`, the whole first fundamental form (the metric of the surface).
    pub first_form: Vec<[[f64; 2]; 2]>,
    /// `b_ab`, the whole second fundamental form.
    pub second_form: Vec<[[f64; 2]; 2]>,
    /// On a cone: the development map onto the plane at `x1` (Theorem 2's coordinates).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub development: Option<DevelopmentReport>,
}

/// The development map `(x1, x2) -> (chi1, chi2)` of a cone at each sample point
/// ([`capstan_friction::membrane::DevelopmentPoint`]).
///
/// # Math
/// ```text
/// rbar = sqrt(1 + ubar^2 + vbar^2),  phi(x2) = int_0^{x2} |w' x w| / |w|^2 dt
/// chi1 = x1 rbar cos(phi),  chi2 = x1 rbar sin(phi),  J = d(chi1, chi2)/d(x1, x2)
/// ```
/// with `J^T J = a_ab` (an isometry).
#[derive(Debug, Clone, Serialize)]
pub struct DevelopmentReport {
    /// `phi(x2)`, the angle of the developed generator, measured from `x2 = 0`.
    pub phi: Vec<f64>,
    /// `phi'(x2)`.
    pub phi_rate: Vec<f64>,
    /// `rbar(x2)`.
    pub radius: Vec<f64>,
    /// `(chi1, chi2)`.
    pub chi: Vec<[f64; 2]>,
    /// `jacobian[i][j] = d chi_(i+1) / d x_(j+1)`.
    pub jacobian: Vec<[[f64; 2]; 2]>,
}

/// Evenly spaced samples on `[a, b]`, both ends included.
pub fn linspace(a: f64, b: f64, n: usize) -> Vec<f64> {
    match n {
        0 => vec![],
        1 => vec![a],
        _ => (0..n)
            .map(|i| a + (b - a) * i as f64 / (n - 1) as f64)
            .collect(),
    }
}

/// Builds the report.
///
/// # Errors
/// Invalid obstacle parameters, or a degenerate point in the interval (typed geometry error).
pub fn report(scene: &Scene) -> Result<GeometryReport, CliError> {
    let m = &scene.membrane;
    Ok(report_at(scene, &linspace(m.theta0, m.theta_max, m.samples.max(2)))?.report)
}

/// The geometry at chosen points `x2`: the keys of [`GeometryReport`] and the whole tensors
/// (what `capstan.geometry(scene, x2)` returns in Python).
#[derive(Debug, Clone, Serialize)]
pub struct GeometryDetail {
    /// The keys of `capstan geometry --json`, at these points.
    #[serde(flatten)]
    pub report: GeometryReport,
    /// `sigma(x1, x2)`.
    pub point: Vec<[f64; 3]>,
    /// Unit normal `N`.
    pub normal: Vec<[f64; 3]>,
    /// `a^ab`.
    pub first_form_inverse: Vec<[[f64; 2]; 2]>,
    /// `b^a_b`.
    pub mixed_second_form: Vec<[[f64; 2]; 2]>,
    /// `christoffel[c][a][b] = Gamma^c_ab` of the surface.
    pub christoffel: Vec<[[[f64; 2]; 2]; 2]>,
    /// `g_ij` of the shell chart on the obstacle (`x3 = 0`).
    pub shell_metric: Vec<[[f64; 3]; 3]>,
    /// `g_ij` of the shell chart at `x3 = body.thickness`.
    pub shell_metric_outer: Vec<[[f64; 3]; 3]>,
}

/// The geometry of the scene's obstacle at the points `x2` (`x1` as in [`report`]).
///
/// # Errors
/// As [`report`].
pub fn report_at(scene: &Scene, x2: &[f64]) -> Result<GeometryDetail, CliError> {
    let obstacle = scene.obstacle.build()?;
    let x1 = if obstacle.is_cone() { 1.0 } else { 0.0 };
    let chart = ShellChart::new(&obstacle);
    let x2 = x2.to_vec();
    let mut d = GeometryDetail {
        report: GeometryReport {
            obstacle: scene.obstacle.clone(),
            x1,
            x2: x2.clone(),
            mean_curvature: vec![],
            gaussian_curvature: vec![],
            a22: vec![],
            b22: vec![],
            christoffel_222: vec![],
            sqrt_g_outer: vec![],
            first_form: vec![],
            second_form: vec![],
            development: None,
        },
        point: vec![],
        normal: vec![],
        first_form_inverse: vec![],
        mixed_second_form: vec![],
        christoffel: vec![],
        shell_metric: vec![],
        shell_metric_outer: vec![],
    };
    for &t in &x2 {
        let g = Surface::<f64>::geometry(&obstacle, [x1, t])?;
        let r = &mut d.report;
        r.mean_curvature.push(g.mean_curvature);
        r.gaussian_curvature.push(g.gaussian_curvature);
        r.a22.push(g.first_form[1][1]);
        r.b22.push(g.second_form[1][1]);
        r.christoffel_222.push(g.christoffel[1][1][1]);
        let outer = chart.point([x1, t, scene.body.thickness])?;
        r.sqrt_g_outer.push(outer.sqrt_g);
        d.point.push(g.point);
        d.normal.push(g.normal);
        r.first_form.push(g.first_form);
        r.second_form.push(g.second_form);
        d.first_form_inverse.push(g.first_form_inverse);
        d.mixed_second_form.push(g.mixed_second_form);
        d.christoffel.push(g.christoffel);
        d.shell_metric.push(chart.point([x1, t, 0.0])?.metric);
        d.shell_metric_outer.push(outer.metric);
    }
    let budget = scene.membrane.max_subdivisions;
    let points = match &obstacle {
        Obstacle::CircularCone(c) => Some(development(c, x1, &x2, budget)?),
        Obstacle::Cone(c) => Some(development(c.profile_curve(), x1, &x2, budget)?),
        _ => None,
    };
    d.report.development = points.map(|p| DevelopmentReport {
        phi: p.iter().map(|q| q.phi).collect(),
        phi_rate: p.iter().map(|q| q.phi_rate).collect(),
        radius: p.iter().map(|q| q.radius).collect(),
        chi: p.iter().map(|q| q.chi).collect(),
        jacobian: p.iter().map(|q| q.jacobian).collect(),
    });
    Ok(d)
}

/// Human-readable table of the report.
pub fn table(r: &GeometryReport, obstacle: &Obstacle) -> String {
    let mut s = format!(
        "obstacle: {:?}\n{:>10} {:>12} {:>12} {:>12} {:>12} {:>12}\n",
        obstacle, "x2", "H", "K", "a22", "b22", "sqrt(g) top"
    );
    let step = (r.x2.len() / 12).max(1);
    for i in (0..r.x2.len()).step_by(step) {
        s.push_str(&format!(
            "{:>10.5} {:>12.6} {:>12.3e} {:>12.6} {:>12.6} {:>12.6}\n",
            r.x2[i],
            r.mean_curvature[i],
            r.gaussian_curvature[i],
            r.a22[i],
            r.b22[i],
            r.sqrt_g_outer[i]
        ));
    }
    if let Some(d) = &r.development {
        s.push_str(&format!(
            "\ndevelopment at x1 = {}: chi = x1 rbar (cos phi, sin phi)\n{:>10} {:>12} {:>12} {:>12} {:>12}\n",
            r.x1, "x2", "phi", "rbar", "chi1", "chi2"
        ));
        for i in (0..r.x2.len()).step_by(step) {
            s.push_str(&format!(
                "{:>10.5} {:>12.8} {:>12.8} {:>12.8} {:>12.8}\n",
                r.x2[i], d.phi[i], d.radius[i], d.chi[i][0], d.chi[i][1]
            ));
        }
    }
    s
}
