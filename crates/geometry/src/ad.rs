//! Forward-mode automatic differentiation of charts (the only module naming num-dual types).
//!
//! A surface `sigma(x1, x2)` written generically over [`crate::Scalar`] is evaluated on
//! hyper-hyper-dual numbers, which carry exact first, second and third partial derivatives
//! along three chosen directions. Four evaluations give every distinct derivative of a map
//! of two variables up to third order:
//!
//! ```text
//! directions (1,1,1): d_1, d_11, d_111
//! directions (1,1,2): d_2, d_12, d_112
//! directions (1,2,2): d_22, d_122
//! directions (2,2,2): d_222
//! ```

use num_dual::{Dual, Dual3, HyperHyperDual};

use crate::scalar::{Real, Scalar};

/// A scalar type carrying third-order mixed derivatives, used to differentiate charts.
///
/// `Jet3<D>` over a dual number `D` (e.g. [`Dual1`]) nests: its parts then carry one more
/// derivative (fourth derivatives of `sigma`, first derivatives of the shell geometry).
pub type Jet3<D> = HyperHyperDual<D>;

/// A first-order dual number `x + eps dx` over the scalar `D` (a float or a dual number):
/// evaluating a generic map on it gives the map and its directional derivative exactly.
pub type Dual1<D> = Dual<D>;

/// The dual number `x + eps dx`.
pub fn seed<F: Real, D: Scalar<F>>(x: D, dx: D) -> Dual1<D> {
    Dual::new(x, dx)
}

/// The value `x` of `x + eps dx`.
pub fn value_part<F: Real, D: Scalar<F>>(d: Dual1<D>) -> D {
    d.re
}

/// The derivative part `dx` of `x + eps dx`.
pub fn derivative_part<F: Real, D: Scalar<F>>(d: Dual1<D>) -> D {
    d.eps
}

/// The primitive real part of any scalar (`x` itself for a float, the innermost value of a
/// nested dual number).
pub fn real_part<F: Real, D: Scalar<F>>(d: D) -> F {
    d.re()
}

/// Value and exact gradient of a map `R^M -> R^N` written generically, at a point whose
/// coordinates are any scalar `D` (floats, or dual numbers for derivatives of the gradient).
///
/// # Math
/// `f(x)`, then `M` evaluations on `x + eps e_k` (`k = 1 ... M`): `f(x + eps e_k) = f(x) + eps d_k f(x)`.
/// Returns `(f(x), gradient)` with `gradient[k][n] = d_k f_n(x)`.
///
/// # Example
/// ```
/// use capstan_geometry::{ad::value_and_gradient, Scalar};
/// fn f<S: Scalar<f64>>([x, y]: [S; 2]) -> [S; 1] {
///     [x * y * y]
/// }
/// let (v, g) = value_and_gradient(f, [3.0_f64, 2.0]);
/// assert_eq!((v[0], g[0][0], g[1][0]), (12.0, 4.0, 12.0));
/// ```
pub fn value_and_gradient<F: Real, D: Scalar<F>, const M: usize, const N: usize, G>(
    f: G,
    x: [D; M],
) -> ([D; N], [[D; N]; M])
where
    G: Fn([Dual1<D>; M]) -> [Dual1<D>; N],
{
    let value = f(x.map(Dual::from_re)).map(|o| o.re);
    let gradient = core::array::from_fn(|k| {
        let y =
            core::array::from_fn(|i| Dual::new(x[i], if i == k { D::one() } else { D::zero() }));
        f(y).map(|o| o.eps)
    });
    (value, gradient)
}

/// Position and exact partial derivatives of a surface map up to third order at one point.
///
/// Indices are 0-based (paper index 1 is array index 0); every array is symmetric in its
/// derivative indices, e.g. `d2[a][b] = d2[b][a] = d_a d_b sigma`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceJet<F> {
    /// `sigma(x)`.
    pub point: [F; 3],
    /// `d1[a] = d_a sigma` (the tangent vectors `a_a`).
    pub d1: [[F; 3]; 2],
    /// `d2[a][b] = d_a d_b sigma`.
    pub d2: [[[F; 3]; 2]; 2],
    /// `d3[a][b][c] = d_a d_b d_c sigma`.
    pub d3: [[[[F; 3]; 2]; 2]; 2],
}

impl<F: Real> SurfaceJet<F> {
    /// Whether every entry is finite.
    pub fn is_finite(&self) -> bool {
        let finite = |v: &[F; 3]| v.iter().all(|c| c.is_finite());
        finite(&self.point)
            && self.d1.iter().all(finite)
            && self.d2.iter().flatten().all(finite)
            && self.d3.iter().flatten().flatten().all(finite)
    }
}

/// Seeds `x` for the derivative directions `dirs` (each 0 or 1) and evaluates `f`.
fn eval_along<F: Real, D: Scalar<F>, G>(f: &G, x: [D; 2], dirs: [usize; 3]) -> [Jet3<D>; 3]
where
    G: Fn([Jet3<D>; 2]) -> [Jet3<D>; 3],
{
    let seed = |k: usize| {
        let mut v = Jet3::from_re(x[k]);
        if dirs[0] == k {
            v = v.derivative1();
        }
        if dirs[1] == k {
            v = v.derivative2();
        }
        if dirs[2] == k {
            v = v.derivative3();
        }
        v
    };
    f([seed(0), seed(1)])
}

/// Exact derivatives up to third order of a map `R^2 -> R^3` written generically.
///
/// # Math
/// With hyper-hyper-dual inputs `x_k + eps1 [p=k] + eps2 [q=k] + eps3 [r=k]`, the output's
/// `eps1 eps2 eps3` part is `d_p d_q d_r f` exactly (no truncation error).
///
/// # Example
/// ```
/// use capstan_geometry::{ad::surface_jet, Scalar};
/// // f(x, y) = (x y^2, sin x, 0), written once for every scalar type
/// fn f<S: Scalar<f64>>([x, y]: [S; 2]) -> [S; 3] {
///     [x * y * y, x.sin(), x * 0.0]
/// }
/// let jet = surface_jet(f, [0.5_f64, 2.0]);
/// assert!((jet.d3[0][1][1][0] - 2.0).abs() < 1e-15); // d_x d_y d_y (x y^2) = 2
/// assert!((jet.d2[0][0][1] + 0.5_f64.sin()).abs() < 1e-15);
/// ```
pub fn surface_jet<F: Real, G>(f: G, x: [F; 2]) -> SurfaceJet<F>
where
    G: Fn([Jet3<F>; 2]) -> [Jet3<F>; 3],
{
    surface_jet_over::<F, F, G>(f, x)
}

/// [`surface_jet`] at a point whose coordinates are any scalar `D`: with `D` a dual number
/// ([`Dual1`]), every entry of the jet carries its derivative along the seeded direction
/// (so `sigma`'s fourth derivatives, exactly).
///
/// # Example
/// ```
/// use capstan_geometry::{ad, Scalar};
/// fn f<S: Scalar<f64>>([x, y]: [S; 2]) -> [S; 3] {
///     [x * x * x * x * y, y, x]
/// }
/// // d/dx of the jet at (1, 2): d_x (d_x d_x d_x (x^4 y)) = 24 y = 48
/// let x = [ad::seed(1.0_f64, 1.0), ad::seed(2.0, 0.0)];
/// let jet = ad::surface_jet_over(f, x);
/// assert_eq!(ad::derivative_part(jet.d3[0][0][0][0]), 48.0);
/// ```
pub fn surface_jet_over<F: Real, D: Scalar<F>, G>(f: G, x: [D; 2]) -> SurfaceJet<D>
where
    G: Fn([Jet3<D>; 2]) -> [Jet3<D>; 3],
{
    let z = D::zero();
    let mut jet = SurfaceJet {
        point: [z; 3],
        d1: [[z; 3]; 2],
        d2: [[[z; 3]; 2]; 2],
        d3: [[[[z; 3]; 2]; 2]; 2],
    };
    let e000 = eval_along(&f, x, [0, 0, 0]);
    let e001 = eval_along(&f, x, [0, 0, 1]);
    let e011 = eval_along(&f, x, [0, 1, 1]);
    let e111 = eval_along(&f, x, [1, 1, 1]);
    for c in 0..3 {
        jet.point[c] = e000[c].re;
        jet.d1[0][c] = e000[c].eps1;
        jet.d1[1][c] = e001[c].eps3;
        jet.d2[0][0][c] = e000[c].eps1eps2;
        let d01 = e001[c].eps1eps3;
        jet.d2[0][1][c] = d01;
        jet.d2[1][0][c] = d01;
        jet.d2[1][1][c] = e011[c].eps2eps3;
        jet.d3[0][0][0][c] = e000[c].eps1eps2eps3;
        let d001 = e001[c].eps1eps2eps3;
        jet.d3[0][0][1][c] = d001;
        jet.d3[0][1][0][c] = d001;
        jet.d3[1][0][0][c] = d001;
        let d011 = e011[c].eps1eps2eps3;
        jet.d3[0][1][1][c] = d011;
        jet.d3[1][0][1][c] = d011;
        jet.d3[1][1][0][c] = d011;
        jet.d3[1][1][1][c] = e111[c].eps1eps2eps3;
    }
    jet
}

/// Value and first three derivatives of a map `R -> R^N` written generically.
///
/// Returns `out[k] = [f_k, f_k', f_k'', f_k''']`.
///
/// # Example
/// ```
/// use capstan_geometry::{ad::curve_jet, Scalar};
/// fn f<S: Scalar<f64>>(t: S) -> [S; 1] {
///     [t.sin()]
/// }
/// let [s] = curve_jet(f, 0.3_f64);
/// assert!((s[3] + 0.3_f64.cos()).abs() < 1e-15);
/// ```
pub fn curve_jet<F: Real, const N: usize, G>(f: G, t: F) -> [[F; 4]; N]
where
    G: Fn(Dual3<F>) -> [Dual3<F>; N],
{
    let out = f(Dual3::from_re(t).derivative());
    out.map(|d| [d.re, d.v1, d.v2, d.v3])
}

/// Value and first four derivatives of a map `R -> R^N` written generically.
///
/// Returns `out[k] = [f_k, f_k', f_k'', f_k''', f_k'''']`: the curve is evaluated once on a
/// third-order dual number over a first-order one, whose `v3` part carries `f'''` and its
/// derivative.
///
/// # Example
/// ```
/// use capstan_geometry::{ad::curve_jet4, Scalar};
/// fn f<S: Scalar<f64>>(t: S) -> [S; 1] {
///     [t.sin()]
/// }
/// let [s] = curve_jet4(f, 0.3_f64);
/// assert!((s[4] - 0.3_f64.sin()).abs() < 1e-15);
/// ```
pub fn curve_jet4<F: Real, const N: usize, G>(f: G, t: F) -> [[F; 5]; N]
where
    G: Fn(Dual3<Dual1<F>>) -> [Dual3<Dual1<F>>; N],
{
    let one = Dual::new(F::one(), F::zero());
    let z = Dual::from_re(F::zero());
    let out = f(Dual3::new(Dual::new(t, F::one()), one, z, z));
    out.map(|d| [d.re.re, d.v1.re, d.v2.re, d.v3.re, d.v3.eps])
}

/// The fourth partial derivatives `d4[a][b][c][d] = d_a d_b d_c d_d f` of a map `R^2 -> R^3`
/// written generically: [`surface_jet_over`] on dual coordinates seeded along each axis.
///
/// # Example
/// ```
/// use capstan_geometry::{ad, Scalar};
/// fn f<S: Scalar<f64>>([x, y]: [S; 2]) -> [S; 3] {
///     [x * x * y * y, y, x]
/// }
/// let d4 = ad::surface_fourth_derivatives(f, [1.0_f64, 2.0]);
/// assert_eq!(d4[0][0][1][1][0], 4.0); // d_x d_x d_y d_y (x^2 y^2) = 4
/// assert_eq!(d4[1][0][1][0][0], 4.0);
/// assert_eq!(d4[0][0][0][1][0], 0.0);
/// ```
pub fn surface_fourth_derivatives<F: Real, G>(f: G, x: [F; 2]) -> [[[[[F; 3]; 2]; 2]; 2]; 2]
where
    G: Fn([Jet3<Dual1<F>>; 2]) -> [Jet3<Dual1<F>>; 3],
{
    core::array::from_fn(|a| {
        let seeded =
            core::array::from_fn(|k| Dual::new(x[k], if k == a { F::one() } else { F::zero() }));
        let jet = surface_jet_over::<F, Dual1<F>, _>(&f, seeded);
        jet.d3.map(|m| m.map(|r| r.map(|v| v.map(|d| d.eps))))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn surface_jet_of_polynomial_is_exact() {
        // f = (x^3 y, x y^3, x^2 y^2)
        let (x, y) = (0.7_f64, -1.3_f64);
        let jet = surface_jet(
            |[x, y]| [x * x * x * y, x * y * y * y, x * x * y * y],
            [x, y],
        );
        assert_eq!(jet.point[0], x * x * x * y);
        assert!((jet.d1[0][0] - 3.0 * x * x * y).abs() < 1e-14);
        assert!((jet.d1[1][1] - 3.0 * x * y * y).abs() < 1e-14);
        assert!((jet.d2[0][1][2] - 4.0 * x * y).abs() < 1e-14);
        assert!((jet.d2[1][1][0]).abs() < 1e-14);
        assert!((jet.d3[0][0][0][0] - 6.0 * y).abs() < 1e-14);
        assert!((jet.d3[0][0][1][0] - 6.0 * x).abs() < 1e-14);
        assert!((jet.d3[0][1][1][2] - 4.0 * x).abs() < 1e-14);
        assert!((jet.d3[1][1][1][1] - 6.0 * x).abs() < 1e-14);
        assert!((jet.d3[1][0][1][2] - 4.0 * x).abs() < 1e-14);
    }
}
