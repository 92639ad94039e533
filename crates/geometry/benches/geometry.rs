//! Criterion bench: the full shell-chart set (metric, inverse, sqrt(g), all Gamma^k_ij) at one point.
//!
//! Groups: `geometry/shell_point/{ellipse_analytic, ellipse_automatic, expression_prism}`.
//! The ellipse's closed-form jet against the same ellipse differentiated automatically, and a
//! prism whose profile is an interpreted expression.

use std::hint::black_box;

use capstan_geometry::{
    EllipticalPrism, ExpressionProfile, GeneralPrism, Scalar, ShellChart, Surface,
};
use criterion::{Criterion, criterion_group, criterion_main};

/// The ellipse with only `sigma`: every derivative by the default automatic differentiation.
struct AutomaticEllipse(EllipticalPrism<f64>);

impl Surface<f64> for AutomaticEllipse {
    fn sigma<S: Scalar<f64>>(&self, x: [S; 2]) -> [S; 3] {
        self.0.sigma(x)
    }
}

fn shell_point(c: &mut Criterion) {
    let ellipse = EllipticalPrism::new(2.0, 1.5).unwrap();
    let analytic = ShellChart::new(ellipse);
    let automatic = ShellChart::new(AutomaticEllipse(ellipse));
    let prism = ShellChart::new(GeneralPrism::new(
        ExpressionProfile::parse("2*sin(t) + 0.2*sin(2*t)", "1.5*cos(t)").unwrap(),
    ));
    let x = [0.0, 0.7, 0.3];
    let mut group = c.benchmark_group("geometry/shell_point");
    group.bench_function("ellipse_analytic", |b| {
        b.iter(|| analytic.point(black_box(x)).unwrap())
    });
    group.bench_function("ellipse_automatic", |b| {
        b.iter(|| automatic.point(black_box(x)).unwrap())
    });
    group.bench_function("expression_prism", |b| {
        b.iter(|| prism.point(black_box(x)).unwrap())
    });
    group.finish();
}

criterion_group!(benches, shell_point);
criterion_main!(benches);
