//! The scalar bound of the crate.

use core::fmt::{Debug, Display};

/// A real floating-point scalar the generic parts of the crate work with (`f64`, `f32`).
///
/// The pattern helpers, the iterative backends and the problem traits are generic over it; the
/// faer backends ([`crate::SparseLu`], [`crate::SparseCholesky`])
/// and the nonlinear solvers are implemented for `f64` only.
pub trait SolverScalar: num_traits::Float + Send + Sync + Debug + Display + 'static {
    /// The value as `f64`, for error reports (NaN when it does not convert).
    fn as_f64(self) -> f64 {
        self.to_f64().unwrap_or(f64::NAN)
    }
    /// `value` converted to `Self` (rounded for `f32`).
    fn from_f64(value: f64) -> Self {
        <Self as num_traits::NumCast>::from(value).unwrap_or_else(Self::nan)
    }
}

impl<T: num_traits::Float + Send + Sync + Debug + Display + 'static> SolverScalar for T {}

/// Euclidean norm `|x|_2`: a plain sum of squares, redone with scaling only when that
/// overflows or underflows.
pub(crate) fn norm2<F: SolverScalar>(x: &[F]) -> F {
    let plain = x.iter().fold(F::zero(), |s, v| s + *v * *v);
    if plain.is_finite() && plain > F::min_positive_value() / F::epsilon() {
        return plain.sqrt();
    }
    if plain.is_nan() {
        return plain;
    }
    let scale = x.iter().fold(F::zero(), |m, v| m.max(v.abs()));
    if scale == F::zero() || !scale.is_finite() {
        // zero vector, or an infinity that the caller reports
        return scale;
    }
    let inv = F::one() / scale;
    let sum = x.iter().fold(F::zero(), |s, v| s + (*v * inv) * (*v * inv));
    scale * sum.sqrt()
}

/// Maximum norm `max_i |x_i|` (0 for an empty slice).
pub fn max_abs(x: &[f64]) -> f64 {
    x.iter().fold(0.0_f64, |m, v| m.max(v.abs()))
}

/// `max_i |a_i - b_i|` over the common length of `a` and `b` (0 when either is empty).
pub fn max_abs_difference(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .fold(0.0_f64, |m, (x, y)| m.max((x - y).abs()))
}

/// [`SolverError::NonFinite`](crate::SolverError::NonFinite) naming `quantity` at the first
/// non-finite entry of `x`, outside any iteration.
///
/// # Errors
/// As said.
pub(crate) fn check_finite<F: SolverScalar>(
    quantity: &'static str,
    x: &[F],
) -> Result<(), crate::error::SolverError> {
    match first_non_finite(x) {
        Some(index) => Err(crate::error::SolverError::NonFinite {
            quantity,
            index,
            iteration: None,
        }),
        None => Ok(()),
    }
}

/// Index of the first non-finite entry, if any.
pub(crate) fn first_non_finite<F: SolverScalar>(x: &[F]) -> Option<usize> {
    x.iter().position(|v| !v.is_finite())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn norm2_matches_naive_sum_of_squares() {
        let x = [3.0_f64, -4.0, 12.0];
        assert_eq!(norm2(&x), 13.0); // 3-4-12-13: exact in binary
    }

    #[test]
    fn norm2_does_not_overflow_on_large_entries() {
        let x = [1e200_f64, 1e200];
        let expected = 1e200 * 2f64.sqrt();
        assert!((norm2(&x) - expected).abs() <= 1e-15 * expected); // round-off only
    }

    #[test]
    fn norm2_does_not_underflow_on_tiny_entries() {
        let x = [3e-200_f64, 4e-200];
        assert!((norm2(&x) - 5e-200).abs() <= 1e-15 * 5e-200); // round-off only
    }

    #[test]
    fn norm2_propagates_nan_and_zero() {
        assert!(norm2(&[1.0_f64, f64::NAN]).is_nan());
        assert_eq!(norm2::<f64>(&[]), 0.0);
        assert_eq!(norm2(&[0.0_f64, 0.0]), 0.0);
        assert!(norm2(&[1.0_f64, f64::INFINITY]).is_infinite());
    }

    #[test]
    fn conversions_round_trip() {
        assert_eq!(f32::from_f64(0.5).as_f64(), 0.5);
        assert_eq!(first_non_finite(&[1.0, f64::INFINITY]), Some(1));
        assert_eq!(first_non_finite(&[1.0_f32]), None);
    }
}
