//! Small fixed-size vector kernels used by the geometry formulas.

use core::ops::{Add, Mul, Sub};

use crate::scalar::Real;

/// The arithmetic the vector kernels need: floats and every dual number over them.
pub(crate) trait Arithmetic:
    Copy + Add<Output = Self> + Sub<Output = Self> + Mul<Output = Self>
{
}
impl<T: Copy + Add<Output = T> + Sub<Output = T> + Mul<Output = T>> Arithmetic for T {}

pub(crate) type Vec3<F> = [F; 3];

#[inline]
pub(crate) fn dot<F: Arithmetic>(a: &Vec3<F>, b: &Vec3<F>) -> F {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

#[inline]
pub(crate) fn cross<F: Arithmetic>(a: &Vec3<F>, b: &Vec3<F>) -> Vec3<F> {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

#[inline]
pub(crate) fn add<F: Arithmetic>(a: &Vec3<F>, b: &Vec3<F>) -> Vec3<F> {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

#[inline]
pub(crate) fn scale<F: Arithmetic>(s: F, a: &Vec3<F>) -> Vec3<F> {
    [s * a[0], s * a[1], s * a[2]]
}

/// `a + s b`
#[inline]
pub(crate) fn axpy<F: Arithmetic>(a: &Vec3<F>, s: F, b: &Vec3<F>) -> Vec3<F> {
    [a[0] + s * b[0], a[1] + s * b[1], a[2] + s * b[2]]
}

#[inline]
pub(crate) fn norm<F: Real>(a: &Vec3<F>) -> F {
    dot(a, a).sqrt()
}

#[inline]
pub(crate) fn is_finite<F: Real>(a: &Vec3<F>) -> bool {
    a.iter().all(|v| v.is_finite())
}

/// Inverse of a symmetric positive 2x2 matrix; `None` when singular or not finite.
#[inline]
pub(crate) fn inverse2<F: Real>(m: &[[F; 2]; 2]) -> Option<[[F; 2]; 2]> {
    let det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
    if !(det.is_finite() && det != F::zero()) {
        return None;
    }
    let inv = F::one() / det;
    Some([
        [m[1][1] * inv, -m[0][1] * inv],
        [-m[1][0] * inv, m[0][0] * inv],
    ])
}
