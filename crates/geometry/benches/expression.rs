//! Expression evaluation against the same function compiled as Rust, per scalar type.
//!
//! Groups are `geometry/expression/eval/<expression>/<scalar>`, each with a `closure` and an
//! `expression` run; the ratio `expression / closure` is the interpreter's overhead.
//! `geometry/expression/parse` times parsing and compiling.
//!
//! Run with `cargo bench -p capstan-geometry --bench expression` (the bench target needs
//! `harness = false`).

use std::hint::black_box;

use capstan_geometry::Scalar;
use capstan_geometry::expression::Expression;
use criterion::{Criterion, criterion_group, criterion_main};
use num_dual::{Dual2_64, Dual3_64, Dual64};

/// The scene-file example profile.
const PROFILE: &str = "2*sin(t) + 0.2*sin(2*t)";

fn profile<S: Scalar<f64>>(t: S) -> S {
    t.sin() * 2.0 + (t * 2.0).sin() * 0.2
}

/// A longer expression using powers, a variable denominator and more functions.
const BUMP: &str = "sqrt(1 + t^2) * exp(-t^2/2) + atan(t)^3 / (2 + cos(t))";

fn bump<S: Scalar<f64>>(t: S) -> S {
    let t2 = t.powi(2);
    (t2 + 1.0).sqrt() * (-(t2 / 2.0)).exp() + t.atan().powi(3) / (t.cos() + 2.0)
}

/// Benchmarks `expression` and `closure` on the scalar made from `t` by `seed`.
fn compare<S: Scalar<f64>>(
    c: &mut Criterion,
    name: &str,
    expression: &Expression,
    closure: fn(S) -> S,
    scalar: &str,
    seed: fn(f64) -> S,
) {
    let mut group = c.benchmark_group(format!("geometry/expression/eval/{name}/{scalar}"));
    let t = seed(0.3);
    group.bench_function("closure", |b| b.iter(|| closure(black_box(t))));
    group.bench_function("expression", |b| b.iter(|| expression.eval(black_box(t))));
    group.finish();
}

fn eval(c: &mut Criterion) {
    for (name, src, closure) in [
        ("profile", PROFILE, profile::<f64> as fn(f64) -> f64),
        ("bump", BUMP, bump::<f64>),
    ] {
        let e = Expression::parse(src).unwrap();
        compare(c, name, &e, closure, "f64", |t| t);
    }
    for (name, src, closure) in [
        (
            "profile",
            PROFILE,
            profile::<Dual64> as fn(Dual64) -> Dual64,
        ),
        ("bump", BUMP, bump),
    ] {
        let e = Expression::parse(src).unwrap();
        compare(c, name, &e, closure, "dual64", |t| {
            Dual64::from(t).derivative()
        });
    }
    let e = Expression::parse(PROFILE).unwrap();
    compare(c, "profile", &e, profile, "dual2_64", |t| {
        Dual2_64::from(t).derivative()
    });
    compare(c, "profile", &e, profile, "dual3_64", |t| {
        Dual3_64::from(t).derivative()
    });
}

fn parse(c: &mut Criterion) {
    let mut group = c.benchmark_group("geometry/expression/parse");
    group.bench_function("profile", |b| {
        b.iter(|| Expression::parse(black_box(PROFILE)))
    });
    group.bench_function("bump", |b| b.iter(|| Expression::parse(black_box(BUMP))));
    group.finish();
}

criterion_group!(benches, eval, parse);
criterion_main!(benches);
