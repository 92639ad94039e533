//! Reference problems shared by tests, benches and examples.

use std::f64::consts::FRAC_PI_4;

use capstan_geometry::{EllipticalPrism, ExpressionProfile, GeneralPrism, Obstacle};

use crate::membrane::{MembraneLoads, MembraneProblem, closed_form::ellipse_quarter_ratio};

/// The paper's figure PrismEqnPlot2: tension ratio on `[-pi/4, pi/4]` of an ellipse against
/// `b/a`, with `mu = 1/2`, `a = 1`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RatioVersusAspect {
    /// Coefficient of friction.
    pub mu: f64,
    /// Smallest `b/a`.
    pub ratio_min: f64,
    /// Largest `b/a`.
    pub ratio_max: f64,
    /// Number of `b/a` values.
    pub points: usize,
}

impl Default for RatioVersusAspect {
    fn default() -> Self {
        Self {
            mu: 0.5,
            ratio_min: 0.5,
            ratio_max: 1.5,
            points: 101,
        }
    }
}

/// One row of [`RatioVersusAspect::run`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RatioRow {
    /// `b/a`.
    pub b_over_a: f64,
    /// `T(pi/4)/T(-pi/4)` computed by [`crate::membrane::tension_profile`].
    pub ratio: f64,
    /// `exp(2 mu atan(b/a))` (eq. PrismEqnPlot).
    pub paper: f64,
}

impl RatioVersusAspect {
    /// The rows of the figure.
    ///
    /// # Errors
    /// Forward-model errors (none for valid settings).
    pub fn run(&self) -> Result<Vec<RatioRow>, crate::error::FrictionError> {
        let n = self.points.max(2);
        (0..n)
            .map(|i| {
                let r =
                    self.ratio_min + (self.ratio_max - self.ratio_min) * i as f64 / (n - 1) as f64;
                let obstacle = Obstacle::Ellipse(EllipticalPrism::new(1.0, r)?);
                let problem = MembraneProblem {
                    mu: self.mu,
                    theta0: -FRAC_PI_4,
                    theta_max: FRAC_PI_4,
                    samples: 2,
                    ..Default::default()
                };
                let p = crate::membrane::tension_profile(&obstacle, &problem)?;
                Ok(RatioRow {
                    b_over_a: r,
                    ratio: p.tension_ratio(),
                    paper: ellipse_quarter_ratio(self.mu, r),
                })
            })
            .collect()
    }
}

/// An ellipse `(a sin t, b cos t)` given twice: as the closed-form obstacle and as expressions.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReferenceEllipse {
    /// Horizontal semi-axis.
    pub a: f64,
    /// Vertical semi-axis.
    pub b: f64,
}

impl Default for ReferenceEllipse {
    fn default() -> Self {
        Self { a: 2.0, b: 1.0 }
    }
}

impl ReferenceEllipse {
    /// The closed-form obstacle.
    ///
    /// # Panics
    /// If `a` or `b` is not positive (a programmer error in a reference problem).
    #[track_caller]
    pub fn closed_form(&self) -> Obstacle {
        Obstacle::Ellipse(EllipticalPrism::new(self.a, self.b).expect("positive semi-axes"))
    }
    /// The same ellipse as an expression-defined prism.
    ///
    /// # Panics
    /// Never for finite semi-axes (the expressions always parse).
    #[track_caller]
    pub fn expressions(&self) -> Obstacle {
        let p =
            ExpressionProfile::parse(&format!("{}*sin(t)", self.a), &format!("{}*cos(t)", self.b))
                .expect("the ellipse expressions parse");
        Obstacle::Prism(GeneralPrism::new(p))
    }
}

/// A non-elliptical convex prism `(2 sin t + 0.1 sin 2t, 1.5 cos t)` (convex for all `t`).
///
/// # Panics
/// Never (the expressions parse).
#[track_caller]
pub fn wobbly_prism() -> Obstacle {
    let p = ExpressionProfile::parse("2*sin(t) + 0.1*sin(2*t)", "1.5*cos(t)").expect("parses");
    Obstacle::Prism(GeneralPrism::new(p))
}

/// A belt with weight and steady speed: `rho = 0.8`, `l = 0.5`, `h = 0.1`, `g = 9.81`,
/// `V = 2` (`rho_l = 0.04`, `w = 0.3924`, `rho_l V^2 = 0.16`).
pub fn heavy_fast_belt() -> MembraneLoads {
    MembraneLoads {
        gravity: 9.81,
        density: 0.8,
        width: 0.5,
        thickness: 0.1,
        speed: 2.0,
    }
}

/// A belt of density `density` and unit width and thickness (so `density` is also its mass
/// per length) under standard gravity `g = 9.81`, at rest.
pub fn weighted_belt(density: f64) -> MembraneLoads {
    MembraneLoads {
        gravity: 9.81,
        density,
        ..Default::default()
    }
}
