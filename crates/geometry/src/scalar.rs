//! The scalar types geometry is written against.
//!
//! A chart is written once, generic over `S: Scalar<F>`, so that it can be evaluated
//! on plain floats (`S = F`) and on every forward-mode dual number over `F`; exact
//! derivatives then come from evaluating the same code on dual numbers (see [`crate::ad`]).
//! Outside [`crate::ad`], these aliases are the only place the dual-number crate is named.

use num_dual::{DualNum, DualNumFloat};

/// A primitive floating-point type: `f64` or `f32`.
///
/// num-dual's `DualNumFloat` brings num-traits' `Float + FloatConst`.
pub trait Real: DualNumFloat + DualNum<Primitive = Self> + Send + Sync {}
impl<T: DualNumFloat + DualNum<Primitive = T> + Send + Sync> Real for T {}

/// What a chart is written against: `F` itself and every dual number over it.
///
/// Provides the arithmetic `S op S`, `S op F`, `S::from(F)`, and the elementary
/// functions of num-dual's `DualNum` (`sin`, `cos`, `sqrt`, `exp`, `ln`, `atan`, `powi`, ...).
pub trait Scalar<F: Real>: DualNum<Primitive = F> + Copy {}
impl<F: Real, D: DualNum<Primitive = F> + Copy> Scalar<F> for D {}

/// Converts an `f64` constant into the primitive type `F`.
///
/// # Panics
/// Never for `f64` and `f32` targets (every `f64` has a nearest `f32`).
#[inline]
#[track_caller]
pub fn real<F: Real>(value: f64) -> F {
    <F as num_traits::NumCast>::from(value)
        .expect("f64 constant representable in the primitive float type")
}
