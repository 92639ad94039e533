//! Capability traits of a nonlinear problem `r(u) = 0`: a residual, and a sparse Jacobian on a
//! fixed pattern.

use crate::scalar::SolverScalar;
use crate::sparsity_pattern::SparsityPattern;

/// A residual `r(u)`; the nonlinear solvers look for `r(u) = 0`.
///
/// # Errors
/// The problem's own [`Residual::Error`] (e.g. a constitutive law evaluated outside its
/// domain); the solvers wrap it in [`crate::SolverError::Problem`].
///
/// # Example
/// ```
/// use capstan_solvers::Residual;
/// struct Square; // r(u) = u^2 - 2
/// impl Residual<f64> for Square {
///     type Error = std::convert::Infallible;
///     fn residual(&self, u: &[f64], r: &mut [f64]) -> Result<(), Self::Error> {
///         r[0] = u[0] * u[0] - 2.0;
///         Ok(())
///     }
/// }
/// let mut r = [0.0];
/// Square.residual(&[2.0], &mut r).unwrap();
/// assert_eq!(r, [2.0]);
/// ```
pub trait Residual<F: SolverScalar> {
    /// The problem's error type.
    type Error: std::error::Error + Send + Sync + 'static;
    /// Writes `r(u)` into `r` (same length as `u`).
    ///
    /// # Errors
    /// Whatever the problem cannot evaluate.
    fn residual(&self, u: &[F], r: &mut [F]) -> Result<(), Self::Error>;
}

/// The Jacobian `J(u) = dr/du` of a [`Residual`], on a sparsity pattern fixed for the
/// problem's life.
///
/// # Math
/// ```text
/// J_ij(u) = d r_i / d u_j,   stored as values[s] for the slot s of (i, j) in pattern()
/// ```
pub trait Jacobian<F: SolverScalar>: Residual<F> {
    /// The (square) pattern of `J`; the same object for every call.
    fn pattern(&self) -> &SparsityPattern;
    /// Writes the values of `J(u)` in `pattern()` slot order. The solvers hand in `values`
    /// zeroed, so assembly may accumulate with `+=`.
    ///
    /// # Errors
    /// Whatever the problem cannot evaluate.
    fn jacobian(&self, u: &[F], values: &mut [F]) -> Result<(), Self::Error>;
}
