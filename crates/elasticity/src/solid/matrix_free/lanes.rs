//! A batch of [`LANES`] numbers with element-wise arithmetic: the matrix-free Q1 and Q2
//! kernels apply [`LANES`] elements at once (one per lane), which the compiler turns into
//! vector instructions. Every lane does exactly the operations of the scalar kernel, so a
//! batched application equals the element-by-element one bit for bit.

use core::ops::{Add, AddAssign, Mul, Sub};

/// Elements per batch of the Q1 and Q2 kernels.
pub(super) const LANES: usize = 4;

/// The arithmetic the pointwise and contraction kernels need: `f64` (one element) and
/// [`Lanes`] (one element per lane).
pub(super) trait Lane:
    Copy
    + Default
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Mul<f64, Output = Self>
    + AddAssign
{
}

impl Lane for f64 {}

/// [`LANES`] numbers, one per element of a batch.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(super) struct Lanes(pub(super) [f64; LANES]);

impl Lane for Lanes {}

impl Add for Lanes {
    type Output = Self;
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        Self(core::array::from_fn(|l| self.0[l] + o.0[l]))
    }
}

impl Sub for Lanes {
    type Output = Self;
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        Self(core::array::from_fn(|l| self.0[l] - o.0[l]))
    }
}

impl Mul for Lanes {
    type Output = Self;
    #[inline(always)]
    fn mul(self, o: Self) -> Self {
        Self(core::array::from_fn(|l| self.0[l] * o.0[l]))
    }
}

impl Mul<f64> for Lanes {
    type Output = Self;
    #[inline(always)]
    fn mul(self, o: f64) -> Self {
        Self(core::array::from_fn(|l| self.0[l] * o))
    }
}

impl AddAssign for Lanes {
    #[inline(always)]
    fn add_assign(&mut self, o: Self) {
        for (a, b) in self.0.iter_mut().zip(o.0) {
            *a += b;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lanes_do_the_scalar_operations_lane_by_lane() {
        let a = Lanes([1.0, -2.0, 0.5, 3.0]);
        let b = Lanes([0.25, 4.0, -1.0, 1e-3]);
        let mut c = a;
        c += b;
        for l in 0..LANES {
            assert_eq!((a + b).0[l], a.0[l] + b.0[l]);
            assert_eq!((a - b).0[l], a.0[l] - b.0[l]);
            assert_eq!((a * b).0[l], a.0[l] * b.0[l]);
            assert_eq!((a * 3.5).0[l], a.0[l] * 3.5);
            assert_eq!(c.0[l], a.0[l] + b.0[l]);
        }
    }
}
