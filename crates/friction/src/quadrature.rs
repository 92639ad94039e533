//! Adaptive Gauss–Kronrod quadrature (G7–K15), generic over the scalar.

use capstan_geometry::{Real, real};

use crate::error::FrictionError;

/// Kronrod nodes in `(0, 1]`, largest first; odd indices (1, 3, 5) and the centre are the
/// Gauss nodes. QUADPACK `qk15` (Piessens et al. 1983).
#[allow(clippy::excessive_precision)] // published digits kept verbatim; they round to the nearest f64
const XGK: [f64; 8] = [
    0.991_455_371_120_812_639_206_854_697_526_329,
    0.949_107_912_342_758_524_526_189_684_047_851,
    0.864_864_423_359_769_072_789_712_788_640_926,
    0.741_531_185_599_394_439_863_864_773_280_788,
    0.586_087_235_467_691_130_294_144_845_693_013,
    0.405_845_151_377_397_166_906_606_412_076_961,
    0.207_784_955_007_898_467_600_689_403_773_245,
    0.0,
];
/// Kronrod weights for [`XGK`].
#[allow(clippy::excessive_precision)] // published digits kept verbatim; they round to the nearest f64
const WGK: [f64; 8] = [
    0.022_935_322_010_529_224_963_732_008_058_970,
    0.063_092_092_629_978_553_290_700_663_189_204,
    0.104_790_010_322_250_183_839_876_322_541_518,
    0.140_653_259_715_525_918_745_189_590_510_238,
    0.169_004_726_639_267_902_826_583_426_598_550,
    0.190_350_578_064_785_409_913_256_402_421_014,
    0.204_432_940_075_298_892_414_161_999_234_649,
    0.209_482_141_084_727_828_012_999_174_891_714,
];
/// Gauss weights for `XGK[1], XGK[3], XGK[5]` and the centre.
#[allow(clippy::excessive_precision)] // published digits kept verbatim; they round to the nearest f64
const WG: [f64; 4] = [
    0.129_484_966_168_869_693_270_611_432_679_082,
    0.279_705_391_489_276_667_901_467_771_423_780,
    0.381_830_050_505_118_944_950_369_775_488_975,
    0.417_959_183_673_469_387_755_102_040_816_327,
];

/// One panel of an adaptive quadrature: `integral ~ int_a^b f` with an error estimate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Panel<F> {
    /// Lower limit.
    pub a: F,
    /// Upper limit.
    pub b: F,
    /// The 15-point Kronrod estimate.
    pub integral: F,
    /// QUADPACK's error estimate from the embedded 7-point Gauss rule.
    pub error: F,
    /// `int_a^b |f|` (Kronrod), the scale for relative tolerances.
    pub abs_integral: F,
}

/// The result of [`GaussKronrod::integrate`].
#[derive(Debug, Clone, PartialEq)]
pub struct Quadrature<F> {
    /// `int_a^b f`.
    pub value: F,
    /// Sum of the panels' error estimates.
    pub error: F,
    /// The accepted panels, ordered from `a` to `b`.
    pub panels: Vec<Panel<F>>,
    /// Number of integrand evaluations.
    pub evaluations: usize,
}

/// The 15-point Gauss–Kronrod rule on `[a, b]` with QUADPACK's error estimate.
///
/// # Math
/// ```text
/// K = h sum_k wgk_k f(c + h x_k),  G = h sum_k wg_k f(c + h x_k) (Gauss nodes only),
/// c = (a+b)/2, h = (b-a)/2
/// error = I_asc min(1, (200 |K - G| / I_asc)^1.5),  I_asc = int |f - K/(b-a)|
/// ```
/// `K` is exact for polynomials of degree 22, `G` for degree 13.
///
/// # Errors
/// Whatever `f` returns; [`FrictionError::NonFinite`] if `f` is not finite at a node.
pub fn gauss_kronrod_15<F, G>(f: &mut G, a: F, b: F) -> Result<Panel<F>, FrictionError>
where
    F: Real,
    G: FnMut(F) -> Result<F, FrictionError>,
{
    let half = real::<F>(0.5);
    let c = half * (a + b);
    let h = half * (b - a);
    let mut eval = |x: F| -> Result<F, FrictionError> {
        let v = f(x)?;
        if v.is_finite() {
            Ok(v)
        } else {
            Err(FrictionError::NonFinite {
                what: "integrand",
                angle: x.to_f64().unwrap_or(f64::NAN),
            })
        }
    };
    let fc = eval(c)?;
    let mut fv = [(F::zero(), F::zero()); 7];
    let mut kronrod = real::<F>(WGK[7]) * fc;
    let mut gauss = real::<F>(WG[3]) * fc;
    let mut abs = real::<F>(WGK[7]) * fc.abs();
    for (k, slot) in fv.iter_mut().enumerate() {
        let dx = h * real::<F>(XGK[k]);
        let (f1, f2) = (eval(c - dx)?, eval(c + dx)?);
        *slot = (f1, f2);
        let w = real::<F>(WGK[k]);
        kronrod += w * (f1 + f2);
        abs += w * (f1.abs() + f2.abs());
        if k % 2 == 1 {
            gauss += real::<F>(WG[k / 2]) * (f1 + f2);
        }
    }
    let mean = kronrod * half;
    let mut asc = real::<F>(WGK[7]) * (fc - mean).abs();
    for (k, (f1, f2)) in fv.iter().enumerate() {
        asc += real::<F>(WGK[k]) * ((*f1 - mean).abs() + (*f2 - mean).abs());
    }
    let ah = h.abs();
    let (integral, abs_integral, asc) = (kronrod * h, abs * ah, asc * ah);
    let mut error = ((kronrod - gauss) * h).abs();
    if asc > F::zero() && error > F::zero() {
        error = asc * F::one().min((real::<F>(200.0) * error / asc).powf(real::<F>(1.5)));
    }
    let floor = real::<F>(50.0) * F::epsilon() * abs_integral;
    Ok(Panel {
        a,
        b,
        integral,
        error: error.max(floor),
        abs_integral,
    })
}

/// The default panel budget of adaptive quadrature (`membrane.max_subdivisions`): `2^16`,
/// 64 times what the needle cones of issue 18 need (alpha down to 1e-6, 20 wraps: 1024 pass)
/// and about a second of work where a profile is nearly singular (a fuzz finding took 2^20
/// panels, 10 s, to reach the typed error).
pub const DEFAULT_MAX_SUBDIVISIONS: usize = 1 << 16;

/// Settings of the globally adaptive Gauss–Kronrod integrator.
///
/// The panel with the largest error estimate is bisected until the summed estimate is below
/// `max(abs_tol, rel_tol int|f|)` and every panel's `|integral| <= max_panel_integral`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GaussKronrod<F> {
    /// Absolute tolerance.
    pub abs_tol: F,
    /// Relative tolerance (against `int |f|`).
    pub rel_tol: F,
    /// Largest number of panels before giving up (scene key `membrane.max_subdivisions`).
    pub max_panels: usize,
    /// Largest `|integral|` of one accepted panel (e.g. `pi/2` to keep each panel's turning
    /// angle on one branch of `atan2`); infinite by default.
    pub max_panel_integral: F,
}

impl<F: Real> Default for GaussKronrod<F> {
    fn default() -> Self {
        Self {
            abs_tol: real(1e-14),
            rel_tol: real(1e-13),
            max_panels: DEFAULT_MAX_SUBDIVISIONS,
            max_panel_integral: F::infinity(),
        }
    }
}

impl<F: Real> GaussKronrod<F> {
    /// `int_a^b f` (either order of limits).
    ///
    /// # Errors
    /// Whatever `f` returns; [`FrictionError::QuadratureNotConverged`] when the panel budget
    /// runs out or a panel cannot be split further before the tolerance is met.
    ///
    /// # Example
    /// ```
    /// use capstan_friction::quadrature::GaussKronrod;
    /// let q = GaussKronrod::default().integrate(|x: f64| Ok(x.cos().exp()), 0.0, 10.0).unwrap();
    /// // int_0^10 exp(cos x) dx = 12.156059217947777797... (mpmath, 30 digits)
    /// assert!((q.value - 12.156_059_217_947_778).abs() < 1e-13 * 12.2);
    /// ```
    pub fn integrate<G>(&self, mut f: G, a: F, b: F) -> Result<Quadrature<F>, FrictionError>
    where
        G: FnMut(F) -> Result<F, FrictionError>,
    {
        use std::collections::BinaryHeap;
        // Work per split is O(log panels): a heap orders the panels by error (the bits of a
        // non-negative f64 order as the value), a stack holds the panels too large in value,
        // and the sums are kept running (recomputed exactly before acceptance).
        let key = |p: &Panel<F>| p.error.to_f64().unwrap_or(f64::INFINITY).to_bits();
        let first = gauss_kronrod_15(&mut f, a, b)?;
        let mut panels = vec![first];
        let mut heap = BinaryHeap::from([(key(&first), 0usize)]);
        let mut too_big: Vec<usize> = Vec::new();
        if first.integral.abs() > self.max_panel_integral {
            too_big.push(0);
        }
        let (mut error, mut abs) = (first.error, first.abs_integral);
        let mut evaluations = 15;
        let exact_sums = |panels: &[Panel<F>]| {
            panels
                .iter()
                .fold((F::zero(), F::zero(), F::zero()), |(v, e, s), p| {
                    (v + p.integral, e + p.error, s + p.abs_integral)
                })
        };
        loop {
            let worst = if let Some(i) = too_big.pop() {
                i
            } else {
                let target = self.abs_tol.max(self.rel_tol * abs);
                if error <= target {
                    let (value, exact_error, exact_abs) = exact_sums(&panels);
                    error = exact_error;
                    abs = exact_abs;
                    if error <= self.abs_tol.max(self.rel_tol * abs) {
                        panels.sort_by(|p, q| {
                            let (pa, qa) = (p.a.to_f64(), q.a.to_f64());
                            if b >= a {
                                pa.partial_cmp(&qa)
                            } else {
                                qa.partial_cmp(&pa)
                            }
                            .unwrap_or(core::cmp::Ordering::Equal)
                        });
                        return Ok(Quadrature {
                            value,
                            error,
                            panels,
                            evaluations,
                        });
                    }
                }
                // Entries go stale when their panel is split; the index then holds a newer
                // panel whose key differs.
                loop {
                    match heap.pop() {
                        Some((k, i)) if k == key(&panels[i]) => break i,
                        Some(_) => {}
                        None => unreachable!("every panel has a heap entry"),
                    }
                }
            };
            let p = panels[worst];
            let mid = real::<F>(0.5) * (p.a + p.b);
            let tiny = real::<F>(100.0) * F::epsilon() * (p.a.abs().max(p.b.abs()) + F::one());
            if panels.len() >= self.max_panels || (p.b - p.a).abs() <= tiny {
                return Err(FrictionError::QuadratureNotConverged {
                    a: a.to_f64().unwrap_or(f64::NAN),
                    b: b.to_f64().unwrap_or(f64::NAN),
                    error: exact_sums(&panels).1.to_f64().unwrap_or(f64::NAN),
                    panels: panels.len(),
                    limit: self.max_panels,
                });
            }
            let left = gauss_kronrod_15(&mut f, p.a, mid)?;
            let right = gauss_kronrod_15(&mut f, mid, p.b)?;
            evaluations += 30;
            error = (error - p.error + left.error + right.error).max(F::zero());
            abs = (abs - p.abs_integral + left.abs_integral + right.abs_integral).max(F::zero());
            panels[worst] = left;
            panels.push(right);
            for (i, q) in [(worst, left), (panels.len() - 1, right)] {
                heap.push((key(&q), i));
                if q.integral.abs() > self.max_panel_integral {
                    too_big.push(i);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kronrod_is_exact_to_degree_22_and_gauss_to_degree_13() {
        for degree in 0..=22 {
            let mut f = |x: f64| Ok(x.powi(degree));
            let p = gauss_kronrod_15(&mut f, 0.0, 1.0).unwrap();
            let exact = 1.0 / f64::from(degree + 1);
            assert!(
                (p.integral - exact).abs() < 4e-16,
                "degree {degree}: {}",
                p.integral - exact
            );
        }
        // Gauss part exact to degree 13: the raw difference K - G vanishes there.
        for degree in 0..=13 {
            let xs = [XGK[1], XGK[3], XGK[5]];
            let mut g = WG[3] * if degree == 0 { 1.0 } else { 0.0 };
            for (k, x) in xs.iter().enumerate() {
                g += WG[k] * (x.powi(degree) + (-x).powi(degree));
            }
            let exact = if degree % 2 == 0 {
                2.0 / f64::from(degree + 1)
            } else {
                0.0
            };
            assert!((g - exact).abs() < 4e-16, "gauss degree {degree}");
        }
    }

    #[test]
    fn adaptive_error_follows_tolerance() {
        // int_0^1 sqrt(x) = 2/3: a singular derivative forces refinement near 0.
        for tol in [1e-6, 1e-9, 1e-12] {
            let gk = GaussKronrod {
                abs_tol: tol,
                rel_tol: 0.0,
                ..Default::default()
            };
            let q = gk.integrate(|x: f64| Ok(x.sqrt()), 0.0, 1.0).unwrap();
            let err = (q.value - 2.0 / 3.0).abs();
            assert!(err <= tol, "tol {tol}: error {err}");
            assert!(q.error <= tol);
        }
    }

    #[test]
    fn reversed_limits_change_sign_and_panels_stay_ordered() {
        let gk = GaussKronrod {
            max_panel_integral: 0.1,
            ..Default::default()
        };
        let q = gk.integrate(|x: f64| Ok(x.cos()), 2.0, 0.0).unwrap();
        assert!((q.value + 2f64.sin()).abs() < 1e-14);
        assert!(q.panels.iter().all(|p| p.integral.abs() <= 0.1));
        assert!(q.panels.windows(2).all(|w| w[0].b == w[1].a));
    }

    #[test]
    fn budget_exhaustion_is_a_typed_error() {
        let gk = GaussKronrod {
            max_panels: 3,
            abs_tol: 1e-15,
            rel_tol: 0.0,
            ..Default::default()
        };
        let e = gk
            .integrate(|x: f64| Ok(x.abs().sqrt()), -1.0, 1.0)
            .unwrap_err();
        assert!(matches!(e, FrictionError::QuadratureNotConverged { .. }));
    }
}
