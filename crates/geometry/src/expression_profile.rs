//! Profile curves defined by math expressions in `t` (for scene files).

use crate::error::GeometryError;
use crate::expression::Expression;
use crate::profile::ProfileCurve;
use crate::scalar::{Real, Scalar};

/// A profile `(u(t), v(t))` given by two expressions in `t`, with exact derivatives.
///
/// # Example
/// ```
/// use capstan_geometry::{ExpressionProfile, GeneralPrism, Surface};
/// let p = ExpressionProfile::parse("2*sin(t)", "2*cos(t)").unwrap();
/// let prism = GeneralPrism::new(p);
/// let h: f64 = prism.mean_curvature([0.0, 0.4]).unwrap();
/// assert!((h - 0.25).abs() < 1e-14); // circle of radius 2: H = 1/(2r)
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct ExpressionProfile {
    u: Expression,
    v: Expression,
}

impl ExpressionProfile {
    /// Parses `u(t)` and `v(t)`.
    ///
    /// # Errors
    /// [`GeometryError::Expression`] naming `obstacle.u` or `obstacle.v` when one does not parse.
    pub fn parse(u: &str, v: &str) -> Result<Self, GeometryError> {
        Self::parse_named(u, v, ["obstacle.u", "obstacle.v"])
    }

    /// Parses `u(t)` and `v(t)`, naming them `fields` in errors (e.g. `obstacle.ubar`).
    ///
    /// # Errors
    /// [`GeometryError::Expression`] naming the field that does not parse.
    pub fn parse_named(u: &str, v: &str, fields: [&'static str; 2]) -> Result<Self, GeometryError> {
        let parse = |src: &str, field| {
            Expression::parse(src).map_err(|source| GeometryError::Expression { field, source })
        };
        Ok(Self {
            u: parse(u, fields[0])?,
            v: parse(v, fields[1])?,
        })
    }

    /// The expressions `(u, v)`.
    pub fn expressions(&self) -> (&Expression, &Expression) {
        (&self.u, &self.v)
    }
}

impl<F: Real> ProfileCurve<F> for ExpressionProfile {
    fn profile<S: Scalar<F>>(&self, t: S) -> [S; 2] {
        [self.u.eval::<F, S>(t), self.v.eval::<F, S>(t)]
    }
}
