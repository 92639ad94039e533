//! Type-erased surfaces and profile curves: a user obstacle behind a pointer, still exact.
//!
//! [`Surface::sigma`] and [`ProfileCurve::profile`] are generic over the scalar, so neither
//! trait is object-safe. [`DynSurface`] and [`DynProfile`] are their object-safe faces: the
//! value and every partial derivative up to fourth order at a real point. [`SharedSurface`]
//! and [`SharedProfile`] put them behind an `Arc` and implement the generic traits again,
//! evaluating `sigma` (or the profile) at any scalar by its Taylor polynomial about the real
//! part of the argument.
//!
//! # Math
//! A forward-mode dual number `x = x0 + h` (`x0` real, `h` the infinitesimal part) whose
//! type carries derivatives up to order `n` (num-dual's `NDERIV`) has `h^(n+1) = 0`, so
//! ```text
//! f(x0 + h) = sum_{|k| <= n} d^k f(x0) h^k / k!        exactly (no truncation error)
//! ```
//! The workspace evaluates charts at `f64` (`n = 0`), at `Jet3<f64>` (`n = 3`, every
//! [`Surface::jet`]) and at `Jet3<Dual1<f64>>` (`n = 4`, [`crate::ShellChart::point_over`]),
//! and the profile of a prism or cone at the same types. The polynomial here has order
//! [`TAYLOR_ORDER`] = 4: exact for every scalar with `NDERIV <= 4`. A scalar carrying fifth
//! or higher derivatives would get wrong high derivatives, so that is refused (a panic naming
//! the limit), never computed silently.

use std::fmt::Debug;
use std::sync::Arc;

use crate::ad::{self, SurfaceJet};
use crate::profile::ProfileCurve;
use crate::scalar::Scalar;
use crate::surface::Surface;

/// The highest derivative order a [`SharedSurface`] or [`SharedProfile`] evaluates exactly.
pub const TAYLOR_ORDER: usize = 4;

/// Fourth partial derivatives of a surface map: `d4[a][b][c][d] = d_a d_b d_c d_d sigma`.
pub type FourthDerivatives = [[[[[f64; 3]; 2]; 2]; 2]; 2];

/// The object-safe face of a [`ProfileCurve`] over `f64` (every one is a `DynProfile`).
pub trait DynProfile: Send + Sync + Debug {
    /// `(u(t), v(t))`.
    fn value(&self, t: f64) -> [f64; 2];
    /// [`ProfileCurve::profile_jet`]: `[[u, u', u'', u'''], [v, ...]]`.
    fn jet3(&self, t: f64) -> [[f64; 4]; 2];
    /// `[[u, u', u'', u''', u''''], [v, ...]]`, exactly (forward-mode AD).
    fn jet4(&self, t: f64) -> [[f64; 5]; 2];
}

impl<P: ProfileCurve<f64> + Send + Sync + Debug> DynProfile for P {
    fn value(&self, t: f64) -> [f64; 2] {
        self.profile(t)
    }
    fn jet3(&self, t: f64) -> [[f64; 4]; 2] {
        self.profile_jet(t)
    }
    fn jet4(&self, t: f64) -> [[f64; 5]; 2] {
        ad::curve_jet4(|s| self.profile(s), t)
    }
}

/// The object-safe face of a [`Surface`] over `f64` (every one is a `DynSurface`).
pub trait DynSurface: Send + Sync + Debug {
    /// `sigma(x)`.
    fn value(&self, x: [f64; 2]) -> [f64; 3];
    /// [`Surface::jet`]: `sigma` and its derivatives up to third order.
    fn jet3(&self, x: [f64; 2]) -> SurfaceJet<f64>;
    /// The fourth partial derivatives of `sigma`, exactly (forward-mode AD).
    fn fourth_derivatives(&self, x: [f64; 2]) -> FourthDerivatives;
}

impl<S: Surface<f64> + Send + Sync + Debug> DynSurface for S {
    fn value(&self, x: [f64; 2]) -> [f64; 3] {
        self.sigma(x)
    }
    fn jet3(&self, x: [f64; 2]) -> SurfaceJet<f64> {
        self.jet(x)
    }
    fn fourth_derivatives(&self, x: [f64; 2]) -> FourthDerivatives {
        ad::surface_fourth_derivatives(|y| self.sigma(y), x)
    }
}

/// How many derivatives the scalar `S` carries, refusing more than [`TAYLOR_ORDER`].
#[track_caller]
fn taylor_order<S: Scalar<f64>>() -> usize {
    assert!(
        S::NDERIV <= TAYLOR_ORDER,
        "a type-erased obstacle is exact to derivative order {TAYLOR_ORDER}; this scalar carries {}",
        S::NDERIV
    );
    S::NDERIV
}

/// `1/k!` for `k <= 4`.
const INVERSE_FACTORIAL: [f64; 5] = [1.0, 1.0, 0.5, 1.0 / 6.0, 1.0 / 24.0];

/// A user profile curve or surface behind a shared pointer (cloning shares it).
///
/// Two are equal when they share the same curve or surface.
#[derive(Debug)]
pub struct Shared<T: ?Sized>(Arc<T>);

impl<T: ?Sized> Shared<T> {
    /// The wrapped curve or surface.
    pub fn inner(&self) -> &T {
        &self.0
    }
}

impl<T: ?Sized> Clone for Shared<T> {
    fn clone(&self) -> Self {
        Self(Arc::clone(&self.0))
    }
}

impl<T: ?Sized> PartialEq for Shared<T> {
    fn eq(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.0, &other.0)
    }
}

/// A profile curve behind a shared pointer; a [`ProfileCurve`] again, exactly.
///
/// `profile_jet` is the wrapped curve's own (bit for bit); `profile` at a dual number is the
/// Taylor polynomial of the module docs.
///
/// # Panics
/// `profile` panics on a scalar carrying more than [`TAYLOR_ORDER`] derivatives.
pub type SharedProfile = Shared<dyn DynProfile>;

impl SharedProfile {
    /// Wraps `profile`.
    pub fn new<P: ProfileCurve<f64> + Send + Sync + Debug + 'static>(profile: P) -> Self {
        Self(Arc::new(profile))
    }
}

impl ProfileCurve<f64> for SharedProfile {
    #[track_caller]
    fn profile<S: Scalar<f64>>(&self, t: S) -> [S; 2] {
        let order = taylor_order::<S>();
        let t0 = t.re();
        if order == 0 {
            return self.0.value(t0).map(S::from);
        }
        let h = t - S::from(t0);
        let jet = if order <= 3 {
            self.0.jet3(t0).map(|c| [c[0], c[1], c[2], c[3], 0.0])
        } else {
            self.0.jet4(t0)
        };
        jet.map(|c| {
            // Horner: c0 + h (c1 + h/2 (c2 + h/3 (c3 + h/4 c4)))
            let mut sum = S::from(c[order] * INVERSE_FACTORIAL[order]);
            for k in (0..order).rev() {
                sum = sum * h + c[k] * INVERSE_FACTORIAL[k];
            }
            sum
        })
    }
    fn profile_jet(&self, t: f64) -> [[f64; 4]; 2] {
        self.0.jet3(t)
    }
}

/// A surface behind a shared pointer; a [`Surface`] again, exactly.
///
/// `jet` is the wrapped surface's own (bit for bit); `sigma` at a dual number is the Taylor
/// polynomial of the module docs.
///
/// # Panics
/// `sigma` panics on a scalar carrying more than [`TAYLOR_ORDER`] derivatives.
pub type SharedSurface = Shared<dyn DynSurface>;

impl SharedSurface {
    /// Wraps `surface`.
    pub fn new<S: Surface<f64> + Send + Sync + Debug + 'static>(surface: S) -> Self {
        Self(Arc::new(surface))
    }
}

impl Surface<f64> for SharedSurface {
    #[track_caller]
    #[allow(clippy::needless_range_loop)] // index loops mirror d_a d_b ... sigma h_a h_b ...
    fn sigma<S: Scalar<f64>>(&self, x: [S; 2]) -> [S; 3] {
        let order = taylor_order::<S>();
        let x0 = x.map(|s| s.re());
        if order == 0 {
            return self.0.value(x0).map(S::from);
        }
        let h = [x[0] - S::from(x0[0]), x[1] - S::from(x0[1])];
        let jet = self.0.jet3(x0);
        let d4 = (order == 4).then(|| self.0.fourth_derivatives(x0));
        core::array::from_fn(|c| {
            let mut sum = S::from(jet.point[c]);
            for a in 0..2 {
                sum += h[a] * jet.d1[a][c];
                if order < 2 {
                    continue;
                }
                for b in 0..2 {
                    let hab = h[a] * h[b];
                    sum += hab * (jet.d2[a][b][c] * INVERSE_FACTORIAL[2]);
                    if order < 3 {
                        continue;
                    }
                    for e in 0..2 {
                        let habe = hab * h[e];
                        sum += habe * (jet.d3[a][b][e][c] * INVERSE_FACTORIAL[3]);
                        if let Some(d4) = &d4 {
                            for f in 0..2 {
                                sum += habe * h[f] * (d4[a][b][e][f][c] * INVERSE_FACTORIAL[4]);
                            }
                        }
                    }
                }
            }
            sum
        })
    }
    fn jet(&self, x: [f64; 2]) -> SurfaceJet<f64> {
        self.0.jet3(x)
    }
}
