//! Brent's bracketing root finder.

use crate::error::FrictionError;

/// Settings of [`Brent::solve`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Brent {
    /// Absolute tolerance on the root.
    pub x_tol: f64,
    /// Largest number of iterations.
    pub max_iterations: usize,
}

impl Default for Brent {
    fn default() -> Self {
        Self {
            x_tol: 1e-15,
            max_iterations: 200,
        }
    }
}

impl Brent {
    /// A root of `f` in `[a, b]`, given `f(a)` and `f(b)` of opposite signs (or one zero).
    ///
    /// # Math
    /// Brent (1973): inverse quadratic interpolation or secant steps, falling back to
    /// bisection whenever they would not shrink the bracket fast enough; the bracket always
    /// contains a sign change.
    ///
    /// # Errors
    /// Whatever `f` returns; [`FrictionError::RootNotConverged`] after `max_iterations`.
    ///
    /// # Panics
    /// If `fa` and `fb` have the same strict sign (a programmer error: no bracket).
    ///
    /// # Example
    /// ```
    /// use capstan_friction::root::Brent;
    /// let f = |x: f64| Ok(x * x - 2.0);
    /// let r = Brent::default().solve(f, 0.0, -2.0, 2.0, 2.0).unwrap();
    /// assert!((r - 2f64.sqrt()).abs() < 1e-15);
    /// ```
    #[track_caller]
    pub fn solve<G>(&self, mut f: G, a: f64, fa: f64, b: f64, fb: f64) -> Result<f64, FrictionError>
    where
        G: FnMut(f64) -> Result<f64, FrictionError>,
    {
        assert!(
            fa * fb <= 0.0,
            "Brent::solve needs a bracket: f(a) = {fa}, f(b) = {fb}"
        );
        let (mut a, mut fa, mut b, mut fb) = (a, fa, b, fb);
        if fa == 0.0 {
            return Ok(a);
        }
        if fb == 0.0 {
            return Ok(b);
        }
        let (mut c, mut fc) = (a, fa);
        let mut d = b - a;
        let mut e = d;
        for _ in 0..self.max_iterations {
            if fb * fc > 0.0 {
                c = a;
                fc = fa;
                d = b - a;
                e = d;
            }
            if fc.abs() < fb.abs() {
                a = b;
                b = c;
                c = a;
                fa = fb;
                fb = fc;
                fc = fa;
            }
            let tol = 2.0 * f64::EPSILON * b.abs() + 0.5 * self.x_tol;
            let m = 0.5 * (c - b);
            if m.abs() <= tol || fb == 0.0 {
                return Ok(b);
            }
            if e.abs() >= tol && fa.abs() > fb.abs() {
                let s = fb / fa;
                let (mut p, mut q);
                if a == c {
                    p = 2.0 * m * s;
                    q = 1.0 - s;
                } else {
                    let qq = fa / fc;
                    let r = fb / fc;
                    p = s * (2.0 * m * qq * (qq - r) - (b - a) * (r - 1.0));
                    q = (qq - 1.0) * (r - 1.0) * (s - 1.0);
                }
                if p > 0.0 {
                    q = -q;
                } else {
                    p = -p;
                }
                if 2.0 * p < (3.0 * m * q - (tol * q).abs()).min((e * q).abs()) {
                    e = d;
                    d = p / q;
                } else {
                    d = m;
                    e = m;
                }
            } else {
                d = m;
                e = m;
            }
            a = b;
            fa = fb;
            b += if d.abs() > tol { d } else { tol.copysign(m) };
            fb = f(b)?;
        }
        Err(FrictionError::RootNotConverged {
            iterations: self.max_iterations,
            width: (c - b).abs(),
        })
    }
}
