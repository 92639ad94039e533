//! Membrane capstan profiles of 1000 samples: the closed form (ellipse), quadrature
//! (expression prism, no loads) and the ODE (expression prism with gravity and speed); and
//! the default `capstan contact --json` run in process (FD 250 x 41, `auto` Newton: scene,
//! assembly, condensation, solve and JSON output; issue 29's "fast by default" number).
//!
//! Run: `cargo bench --bench capstan` (`cargo bench --bench capstan -- contact` for the
//! default contact run alone). Accuracy against the closed-form ellipse is printed
//! once before timing (the expression prism is the same ellipse given as expressions).

use std::hint::black_box;

use capstan_friction::membrane::closed_form::ellipse_turning_angle;
use capstan_friction::membrane::{MembraneProblem, Method, tension_profile};
use capstan_friction::quadrature::GaussKronrod;
use capstan_friction::samples::{ReferenceEllipse, heavy_fast_belt};
use criterion::{Criterion, criterion_group, criterion_main};

fn max_relative(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| ((x - y) / y).abs())
        .fold(0.0, f64::max)
}

fn profiles(c: &mut Criterion) {
    let r = ReferenceEllipse::default();
    let (closed, expr) = (r.closed_form(), r.expressions());
    let free = MembraneProblem {
        mu: 0.5,
        theta0: -1.0,
        theta_max: 4.0,
        samples: 1000,
        ..Default::default()
    };
    let loaded = MembraneProblem {
        t0: 5.0,
        loads: heavy_fast_belt(),
        ..free
    };
    for (name, p) in [("no loads", &free), ("gravity + speed", &loaded)] {
        let exact = tension_profile(&closed, p).unwrap();
        let other = tension_profile(&expr, p).unwrap();
        eprintln!(
            "capstan accuracy ({name}): ellipse {} vs expression prism {}: max relative difference {:.2e}",
            exact.method,
            other.method,
            max_relative(&other.tension, &exact.tension)
        );
    }
    // The ODE against Theorem 1 by quadrature (variation of constants, continuous Psi):
    // T - c = e^{mu dPsi} [T0 - c - int (g_r2 + mu sqrt(a22) g_r3) e^{-mu dPsi}],
    // g_r2 = -w v', sqrt(a22) g_r3 = -w u' for gravity on (a sin t, b cos t).
    let (a, b, mu) = (r.a, r.b, loaded.mu);
    let (w, c0) = (
        loaded.loads.weight_per_length(),
        loaded.loads.speed_tension(),
    );
    let psi = |t: f64| ellipse_turning_angle(a, b, t) - ellipse_turning_angle(a, b, loaded.theta0);
    let ode = tension_profile(&expr, &loaded).unwrap();
    let (mut integral, mut worst) = (0.0, 0.0f64);
    for i in 1..ode.theta.len() {
        integral += GaussKronrod::default()
            .integrate(
                |s: f64| Ok((w * b * s.sin() - mu * w * a * s.cos()) * (-mu * psi(s)).exp()),
                ode.theta[i - 1],
                ode.theta[i],
            )
            .unwrap()
            .value;
        let t = ode.theta[i];
        let reference = c0 + (mu * psi(t)).exp() * (loaded.t0 - c0 - integral);
        worst = worst.max(((ode.tension[i] - reference) / reference).abs());
    }
    eprintln!(
        "capstan accuracy (gravity + speed): ODE vs Theorem 1 by quadrature: max relative difference {worst:.2e}"
    );
    assert_eq!(
        tension_profile(&closed, &free).unwrap().method,
        Method::ClosedForm
    );
    let mut g = c.benchmark_group("capstan/profile_1000");
    g.bench_function("ellipse_closed_form", |b| {
        b.iter(|| tension_profile(black_box(&closed), black_box(&free)).unwrap())
    });
    g.bench_function("expression_prism_quadrature", |b| {
        b.iter(|| tension_profile(black_box(&expr), black_box(&free)).unwrap())
    });
    g.bench_function("expression_prism_gravity_speed_ode", |b| {
        b.iter(|| tension_profile(black_box(&expr), black_box(&loaded)).unwrap())
    });
    g.bench_function("ellipse_gravity_speed_ode", |b| {
        b.iter(|| tension_profile(black_box(&closed), black_box(&loaded)).unwrap())
    });
    g.finish();
}

/// The default `capstan contact --json` (no scene file, no flags) through [`capstan::cli::run`].
fn contact_default(c: &mut Criterion) {
    use clap::Parser;
    let run = || {
        let cli = capstan::cli::Cli::parse_from(["capstan", "contact", "--json"]);
        capstan::cli::run(cli).unwrap()
    };
    assert!(
        run().contains("\"converged\": true"),
        "the default run converges"
    );
    let mut g = c.benchmark_group("capstan/contact");
    g.sample_size(10);
    g.bench_function("default_json", |b| b.iter(|| black_box(run())));
    g.finish();
}

criterion_group!(benches, profiles, contact_default);
criterion_main!(benches);
