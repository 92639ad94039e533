//! Extending capstan with a new obstacle, without editing capstan: a trough.
//!
//! Problem: a prism whose cross-section is a circle of radius 2 with its top pressed in by a
//! sag `c`, `sigma(x1, x2) = (x1, 2 sin x2, 2 cos x2 - c sin^2 x2)`. The profile is written
//! once, generically over the scalar; the obstacle is registered at run time under the name
//! `trough` with one scene key, `obstacle.sag`; from then on a scene names it
//! (`obstacle.shape = "trough"`) and every model takes it:
//! - the membrane (capstan) model, through the general prism method (Theorem 1: quadrature of
//!   the turning angle), checked here against a Simpson quadrature of the exact curvature
//!   `psi' = (v' u'' - u' v'') / (u'^2 + v'^2) = 4 (1 + c cos^3 t) / (u'^2 + v'^2)`, so
//!   `T_max / T0 = exp(mu (psi(theta_max) - psi(theta0)))`;
//! - the 2-D plane-strain body and the 3-D body in frictional contact (the Navier operator
//!   comes from the shell chart `sigma + x3 N` alone).
//!
//! Run: `cargo run --release --example extend_obstacle`
//! Look at: the membrane ratio equal to the quadrature (to ~1e-12), and both contact solves
//! converged with part of the contact sliding (`0 < slip fraction < 1`).

use capstan::geometry::registry::{self, ObstacleParameter, ParameterDefault, RegisteredObstacle};
use capstan::geometry::{Obstacle, ProfileCurve, Scalar};
use capstan::solvers::SilentObserver;
use capstan::{CliError, Scene, api};

/// The trough's cross-section `(2 sin t, 2 cos t - sag sin^2 t)`: convex for `sag < 1`.
#[derive(Debug, Clone, Copy)]
struct Trough {
    sag: f64,
}

impl ProfileCurve<f64> for Trough {
    fn profile<S: Scalar<f64>>(&self, t: S) -> [S; 2] {
        let s = t.sin();
        [s * 2.0, t.cos() * 2.0 - s * s * self.sag]
    }
}

/// The registration: name, scene parameters (key, default, range) and a validating builder.
const TROUGH: RegisteredObstacle = RegisteredObstacle {
    name: "trough",
    summary: "a circle of radius 2 whose top sags by obstacle.sag",
    parameters: &[ObstacleParameter {
        key: "sag",
        default: ParameterDefault::Number(0.3),
        allowed: "[0, 1)",
    }],
    build: |s| {
        let sag = registry::check("obstacle.sag", s.number("sag")?, "[0, 1)", |c| {
            (0.0..1.0).contains(&c)
        })?;
        Ok(Obstacle::prism_over(Trough { sag }))
    },
};

/// Registers the trough once per process (a second registration would be refused).
fn register_trough() {
    // `Once`, not find-then-register: the tests run on several threads and both would
    // see the name missing before either registered it.
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        registry::register(TROUGH).expect("first registration of `trough`");
    });
}

/// A scene on the trough with `sag`, wrapped over `[-0.6, 1.0]`, then the given `KEY=VALUE`
/// settings.
fn trough_scene(sag: f64, sets: &[(&str, &str)]) -> Result<Scene, CliError> {
    register_trough();
    let mut scene = Scene::default()
        .with_raw("obstacle.shape", "\"trough\"", "example")?
        .with_raw("obstacle.sag", &sag.to_string(), "example")?
        .with_raw("membrane.theta0", "-0.6", "example")?
        .with_raw("membrane.theta_max", "1.0", "example")?;
    for (key, value) in sets {
        scene = scene.with_raw(key, value, "example")?;
    }
    Ok(scene)
}

/// `T_max / T0` of the membrane on the trough by capstan, and by Simpson's rule here.
fn membrane_ratio(sag: f64) -> Result<(f64, f64), CliError> {
    let scene = trough_scene(sag, &[])?;
    let capstan = api::tension(&scene)?.tension_ratio;
    let (t0, t1, mu) = (
        scene.membrane.theta0,
        scene.membrane.theta_max,
        scene.friction.mu,
    );
    let turning_rate = |t: f64| {
        let (du, dv) = (2.0 * t.cos(), -2.0 * t.sin() - sag * (2.0 * t).sin());
        4.0 * (1.0 + sag * t.cos().powi(3)) / (du * du + dv * dv)
    };
    let n = 4000; // even; Simpson's error ~ (h^4) psi'''' : below 1e-13 here
    let h = (t1 - t0) / n as f64;
    let inner: f64 = (1..n)
        .map(|i| (if i % 2 == 1 { 4.0 } else { 2.0 }) * turning_rate(t0 + i as f64 * h))
        .sum();
    let psi = h / 3.0 * (turning_rate(t0) + inner + turning_rate(t1));
    Ok((capstan, (mu * psi).exp()))
}

/// Newton iterations and slip fraction of the 2-D (plane strain) contact on the trough.
fn contact_2d(sag: f64) -> Result<(bool, f64), CliError> {
    let scene = trough_scene(
        sag,
        &[
            ("grid.n2", "61"),
            ("grid.n3", "9"),
            ("body.thickness", "0.5"),
            ("loads.tau_max", "1.3"),
        ],
    )?;
    let (report, _) = api::contact_observed(&scene, &mut SilentObserver)?;
    Ok((report.converged, report.slip_fraction))
}

/// The same for a 3-D band of width 0.4 (Q1 hexahedra, free side faces).
fn contact_3d(sag: f64) -> Result<(bool, f64), CliError> {
    let scene = trough_scene(
        sag,
        &[
            ("discretisation.method", "\"fem-q1\""), // before the dimension: FD is 2-D only
            ("body.dimension", "3"),
            ("body.width", "0.4"),
            ("body.thickness", "0.1"),
            ("body.sides", "\"free\""),
            ("grid.n1", "3"),
            ("grid.n2", "33"),
            ("grid.n3", "3"),
            ("loads.tau_max", "1.3"),
        ],
    )?;
    let (report, _) = api::contact_observed(&scene, &mut SilentObserver)?;
    Ok((report.converged, report.slip_fraction))
}

fn main() -> Result<(), CliError> {
    for sag in [0.0, 0.3, 0.6] {
        let (capstan, quadrature) = membrane_ratio(sag)?;
        println!("sag {sag}: T_max/T0 = {capstan:.15} (Simpson {quadrature:.15})");
    }
    let (converged, slip) = contact_2d(0.3)?;
    println!("2-D contact on the trough: converged {converged}, slip fraction {slip:.4}");
    let (converged, slip) = contact_3d(0.3)?;
    println!("3-D contact on the trough: converged {converged}, slip fraction {slip:.4}");
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn membrane_on_the_trough_matches_the_quadrature() {
        for sag in [0.0, 0.3, 0.6] {
            let (capstan, quadrature) = membrane_ratio(sag).unwrap();
            // capstan's adaptive quadrature against Simpson with 4000 intervals (error ~1e-15)
            assert!(
                (capstan - quadrature).abs() < 1e-12 * quadrature,
                "{sag}: {capstan} {quadrature}"
            );
        }
        // sag 0 is the circle: exp(mu (theta_max - theta0)) = exp(0.5 * 1.6)
        let (circle, _) = membrane_ratio(0.0).unwrap();
        assert!((circle - 0.8_f64.exp()).abs() < 1e-12 * circle);
        // the sag changes the turning of the wrap [-0.6, 1.0], so the ratio
        assert!(membrane_ratio(0.6).unwrap().0 > 1.0005 * membrane_ratio(0.3).unwrap().0);
    }

    #[test]
    fn a_bad_sag_is_refused_naming_its_key() {
        let err = trough_scene(1.5, &[]).unwrap_err().to_string();
        assert!(
            err.contains("obstacle.sag") && err.contains("[0, 1)"),
            "{err}"
        );
    }

    #[test]
    fn contact_on_the_trough_converges_in_2d_and_3d() {
        for (what, (converged, slip)) in [
            ("2-D", contact_2d(0.3).unwrap()),
            ("3-D", contact_3d(0.3).unwrap()),
        ] {
            assert!(converged, "{what}");
            assert!(slip > 0.0 && slip < 1.0, "{what}: slip fraction {slip}");
        }
    }
}
