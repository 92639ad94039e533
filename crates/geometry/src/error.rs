//! The geometry crate's error type.

/// What can go wrong when building or evaluating a surface or shell chart.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum GeometryError {
    /// A parameter is non-finite or outside its allowed range.
    #[error("`{field}` = {value} is outside {allowed}")]
    InvalidParameter {
        /// The parameter's name, as in scene files (e.g. `obstacle.radius`).
        field: &'static str,
        /// The offending value.
        value: f64,
        /// The allowed range in words (e.g. `(0, inf)`).
        allowed: &'static str,
    },
    /// The parametrisation or a derived quantity is not finite at a point.
    #[error("{what} is not finite at (x1, x2, x3) = ({:.6}, {:.6}, {:.6})", at[0], at[1], at[2])]
    NonFinite {
        /// Which quantity (e.g. `sigma`, `normal`).
        what: &'static str,
        /// The curvilinear point `(x1, x2, x3)`.
        at: [f64; 3],
    },
    /// The parametrisation is degenerate at a point (zero tangent, undefined normal,
    /// or a shell coordinate `x3` past the focal surface where `sqrt(g) <= 0`).
    #[error("degenerate parametrisation at (x1, x2, x3) = ({:.6}, {:.6}, {:.6}): {what}", at[0], at[1], at[2])]
    Degenerate {
        /// What degenerates.
        what: &'static str,
        /// The curvilinear point `(x1, x2, x3)`.
        at: [f64; 3],
    },
    /// An expression-defined profile failed to parse or to evaluate.
    #[error("expression `{field}`: {source}")]
    Expression {
        /// Which expression (e.g. `obstacle.u`).
        field: &'static str,
        /// The parse or evaluation error.
        source: crate::expression::ExpressionError,
    },
    /// [`crate::registry::register`] was given a name that is registered already.
    #[error("an obstacle named `{name}` is registered already")]
    DuplicateObstacle {
        /// The name (`obstacle.shape`).
        name: &'static str,
    },
    /// `obstacle.shape` names no registered obstacle.
    #[error("`obstacle.shape` = {name:?} is not a registered obstacle: expected one of {allowed}")]
    UnknownObstacle {
        /// The name given.
        name: String,
        /// The registered names, comma-separated.
        allowed: String,
    },
    /// A scene parameter of an obstacle has the wrong kind (a number for an expression, ...).
    #[error("`obstacle.{key}` must be {expected}")]
    ParameterKind {
        /// The key under `[obstacle]` (e.g. `depth`).
        key: &'static str,
        /// What it must be (e.g. `a number`).
        expected: &'static str,
    },
    /// A builder read a key its registration does not declare (a registration bug).
    #[error("`obstacle.{key}` is not among the parameters the obstacle registers")]
    UndeclaredParameter {
        /// The key under `[obstacle]`.
        key: String,
    },
}

/// `value` if it is finite and `ok(value)`, else [`GeometryError::InvalidParameter`] naming
/// `field` (the scene key, e.g. `obstacle.depth`) and the `allowed` range.
///
/// # Errors
/// As described.
pub fn check(
    field: &'static str,
    value: f64,
    allowed: &'static str,
    ok: impl Fn(f64) -> bool,
) -> Result<f64, GeometryError> {
    if value.is_finite() && ok(value) {
        Ok(value)
    } else {
        Err(GeometryError::InvalidParameter {
            field,
            value,
            allowed,
        })
    }
}

/// Checks that `value` is finite and strictly positive.
pub(crate) fn positive(field: &'static str, value: f64) -> Result<(), GeometryError> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(GeometryError::InvalidParameter {
            field,
            value,
            allowed: "(0, inf)",
        })
    }
}
