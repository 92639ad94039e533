//! The element boundaries of the Qp elements along one direction: uniform, or geometrically
//! graded toward both ends (hp meshes for corner singularities), and the search of the
//! element containing a point.

use super::nodal_recovery::NodalRecovery;
use crate::error::ElasticityError;
use crate::finite_element::element::ElementOrder;
use crate::finite_element::volumetric::VolumetricIntegration;

/// How the element boundaries of [`super::HighOrderNavier`] are spaced along each
/// non-periodic direction (scene key `discretisation.grading`).
///
/// # Math
/// `Uniform` (ratio `1`): `e` equal elements. Geometric with ratio `sigma < 1` and `n` layers:
/// the uniform partition of `[a, b]` (length `L`) into `m + 2` elements of size
/// `H = L / (m + 2)`, `m = e - 2n`, whose two end elements are each split into `n` layers
/// shrinking by `sigma` toward the end,
/// ```text
/// x_j = a + H sigma^(n - j),  j = 1 ... n   (x_0 = a),   mirrored at b
/// ```
/// so the smallest element is `H sigma^(n - 1)`: the geometric meshes of hp-FEM, which resolve
/// the `r^lambda` singularities at the corners of the parameter rectangle (clamped side against
/// loaded end) with exponential convergence when `p` grows with `n`; the `m` middle elements
/// keep the smooth part resolved. A periodic direction stays uniform. [`Grading::refined`] splits every element of the partition of `e / s`
/// elements into `s` equal ones (the same graded mesh refined in `h`).
///
/// # References
/// Schwab, *p- and hp-Finite Element Methods* (1998), §4.4: geometric meshes, `sigma ~ 0.15`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Grading {
    ratio: f64,
    layers: usize,
    split: usize,
}

impl Default for Grading {
    fn default() -> Self {
        Self::UNIFORM
    }
}

impl Grading {
    /// Equal elements.
    pub const UNIFORM: Self = Self {
        ratio: 1.0,
        layers: 0,
        split: 1,
    };

    /// The allowed ratios, as error messages and the scene key table state them.
    pub const ALLOWED: &'static str = "0.05 <= discretisation.grading <= 1 (1: uniform)";

    /// The allowed numbers of layers.
    pub const LAYERS: core::ops::RangeInclusive<usize> = 1..=12;

    /// Geometric grading with `ratio = sigma` (`1` is uniform) and `layers` layers at each end.
    ///
    /// # Errors
    /// [`ElasticityError::InvalidParameter`] naming `discretisation.grading` for a ratio
    /// outside `[0.05, 1]` (or not finite: below `0.05` the smallest elements fall under
    /// `1e-10` of the body within ten layers and the element matrices lose digits), or
    /// `discretisation.layers` outside [`Grading::LAYERS`].
    pub fn geometric(ratio: f64, layers: usize) -> Result<Self, ElasticityError> {
        if !(0.05..=1.0).contains(&ratio) {
            return Err(ElasticityError::InvalidParameter {
                field: "discretisation.grading",
                value: ratio,
                allowed: Self::ALLOWED,
            });
        }
        if !Self::LAYERS.contains(&layers) {
            return Err(ElasticityError::InvalidParameter {
                field: "discretisation.layers",
                value: layers as f64,
                allowed: "1 <= discretisation.layers <= 12",
            });
        }
        Ok(Self {
            ratio,
            layers,
            split: 1,
        })
    }

    /// Geometric layers at each end.
    pub fn layers(self) -> usize {
        self.layers
    }

    /// The same grading with every element split into `split` equal ones: a direction of `e`
    /// elements is graded as one of `e / split`, then each element divided (`e` must be a
    /// multiple of `split`).
    ///
    /// # Errors
    /// [`ElasticityError::InvalidParameter`] naming `grading.split` for `split = 0`.
    pub fn refined(self, split: usize) -> Result<Self, ElasticityError> {
        if split == 0 {
            return Err(ElasticityError::InvalidParameter {
                field: "grading.split",
                value: 0.0,
                allowed: "1, 2, ...",
            });
        }
        Ok(Self { split, ..self })
    }

    /// The ratio `sigma` (`1`: uniform).
    pub fn ratio(self) -> f64 {
        self.ratio
    }

    /// Equal parts per graded element ([`Grading::refined`]).
    pub fn split(self) -> usize {
        self.split
    }

    /// Whether the elements are equal.
    pub fn is_uniform(self) -> bool {
        self.ratio == 1.0
    }

    /// The `count + 1` element boundaries on `[a, b]`, graded toward both ends unless the
    /// direction is `periodic` or the grading uniform; `uniform(j)` is the `j`-th boundary of
    /// the uniform partition (the callers pass the grid's own lines, so uniform element ends
    /// are bitwise those of the grid).
    ///
    /// # Errors
    /// [`ElasticityError::InvalidParameter`] naming `field` when `count` is not a multiple of
    /// the split, or below two layers per end.
    pub(super) fn breaks(
        self,
        field: &'static str,
        [a, b]: [f64; 2],
        count: usize,
        periodic: bool,
        uniform: impl Fn(usize) -> f64,
    ) -> Result<Vec<f64>, ElasticityError> {
        if self.is_uniform() || periodic {
            return Ok((0..=count).map(uniform).collect());
        }
        if !count.is_multiple_of(self.split) || count / self.split < 2 * self.layers {
            return Err(ElasticityError::InvalidParameter {
                field,
                value: count as f64,
                allowed: "elements: a multiple of the grading's split, at least 2 layers (per split)",
            });
        }
        let coarse = self.geometric_breaks([a, b], count / self.split);
        let s = self.split as f64;
        let mut out: Vec<f64> = coarse
            .windows(2)
            .flat_map(|w| (0..self.split).map(move |k| w[0] + (w[1] - w[0]) * k as f64 / s))
            .collect();
        out.push(b);
        Ok(out)
    }

    /// The geometric partition of `[a, b]` into `count` elements (see the type).
    fn geometric_breaks(self, [a, b]: [f64; 2], count: usize) -> Vec<f64> {
        let (n, sigma) = (self.layers, self.ratio);
        let middle = count - 2 * n;
        let h = (b - a) / (middle + 2) as f64;
        let layer = |k: usize| h * sigma.powi(k as i32); // distance of a boundary to its end
        let mut out = Vec::with_capacity(count + 1);
        out.push(a);
        out.extend((0..n).rev().map(|k| a + layer(k)));
        out.extend((2..=middle).map(|j| a + h * j as f64));
        let first = usize::from(middle == 0); // no middle: the two halves meet at a + h
        out.extend((first..n).map(|k| b - layer(k)));
        out.push(b);
        debug_assert_eq!(out.len(), count + 1);
        out
    }
}

/// What the Qp operator is built with besides the problem: the order `p`, the integration of
/// the volumetric part, the grading of the element boundaries and the nodal recovery.
///
/// `fem-qp` is [`QpSettings::order`] with the scene's volumetric rule and grading; `fem-q1`
/// and `fem-q2` are [`QpSettings::element`]: orders 1 and 2 on uniform elements with the
/// nodal-difference recovery.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct QpSettings {
    /// The order `p` (`discretisation.order`, [`super::ORDERS`]).
    pub order: usize,
    /// How the volumetric part is integrated (`discretisation.volumetric`).
    pub volumetric: VolumetricIntegration,
    /// The element boundaries (`discretisation.grading`).
    pub grading: Grading,
    /// How nodal values and gradients are recovered for the contact rows and output fields.
    pub recovery: NodalRecovery,
}

impl QpSettings {
    /// Order `p`, full integration, uniform elements, the element recovery (`fem-qp`).
    pub fn order(p: usize) -> Self {
        Self {
            order: p,
            volumetric: VolumetricIntegration::Full,
            grading: Grading::UNIFORM,
            recovery: NodalRecovery::Element,
        }
    }

    /// The Q1 or Q2 element (`fem-q1`, `fem-q2`): order `k` of `order`, full integration,
    /// uniform elements, the nodal-difference recovery ([`NodalRecovery::Differences`]).
    ///
    /// # Example
    /// ```
    /// use capstan_elasticity::finite_element::{ElementOrder, NodalRecovery, QpSettings};
    /// let q2 = QpSettings::element(ElementOrder::Q2);
    /// assert_eq!((q2.order, q2.recovery), (2, NodalRecovery::Differences));
    /// assert_eq!(q2.method_name(), "fem-q2");
    /// assert_eq!(QpSettings::order(2).method_name(), "fem-qp");
    /// ```
    pub fn element(order: ElementOrder) -> Self {
        Self {
            recovery: NodalRecovery::Differences,
            ..Self::order(order.degree())
        }
    }

    /// The registered name of the discretisation these settings build: `fem-q1` or `fem-q2`
    /// with the nodal-difference recovery at order 1 or 2, `fem-qp` otherwise.
    pub fn method_name(&self) -> &'static str {
        match (self.recovery, self.order) {
            (NodalRecovery::Differences, 1) => ElementOrder::Q1.method_name(),
            (NodalRecovery::Differences, 2) => ElementOrder::Q2.method_name(),
            _ => "fem-qp",
        }
    }
}

/// The element `e` of the boundaries `breaks` containing `x` (clamped to the ends) and the
/// reference coordinate `xi = 2 (x - x_e) / (x_(e+1) - x_e) - 1` there.
pub(super) fn locate(breaks: &[f64], x: f64) -> (usize, f64) {
    let count = breaks.len() - 1;
    let e = breaks.partition_point(|&b| b <= x).clamp(1, count) - 1;
    let (x0, x1) = (breaks[e], breaks[e + 1]);
    (e, 2.0 * (x - x0) / (x1 - x0) - 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn geometric_breaks_shrink_by_the_ratio_toward_both_ends() {
        let (sigma, n) = (0.2, 3);
        let g = Grading::geometric(sigma, n).unwrap();
        for count in [6, 7, 10] {
            let x = g
                .breaks("n", [-1.0, 3.0], count, false, |_| f64::NAN)
                .unwrap();
            assert_eq!(x.len(), count + 1);
            assert!(x.windows(2).all(|w| w[1] > w[0]), "{x:?}");
            assert_eq!((x[0], x[count]), (-1.0, 3.0));
            let h: Vec<f64> = x.windows(2).map(|w| w[1] - w[0]).collect();
            let base = 4.0 / (count - 2 * n + 2) as f64;
            // layers: H sigma^(n-1), H sigma^(n-2) (1 - sigma), ..., H (1 - sigma)
            assert!(
                (h[0] - base * sigma.powi(n as i32 - 1)).abs() < 1e-14,
                "{h:?}"
            );
            assert!((h[count - 1] - h[0]).abs() < 1e-14, "{h:?}");
            for k in 0..n - 1 {
                let expected = if k == 0 {
                    (1.0 - sigma) / sigma
                } else {
                    1.0 / sigma
                };
                assert!((h[k + 1] / h[k] - expected).abs() < 1e-12, "{count}: {h:?}");
                assert!((h[count - 2 - k] / h[count - 1 - k] - expected).abs() < 1e-12);
            }
            // the middle elements are the base size
            for hm in &h[n..count - n] {
                assert!((hm - base).abs() < 1e-12, "{h:?}");
            }
        }
        match g.breaks("grid.n2", [0.0, 1.0], 5, false, |_| f64::NAN) {
            Err(ElasticityError::InvalidParameter { field, .. }) => assert_eq!(field, "grid.n2"),
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn uniform_and_periodic_breaks_are_the_callers_lines() {
        let line = |j: usize| 0.25 * j as f64;
        let g = Grading::geometric(0.15, 2).unwrap();
        let quarters = [0.0, 0.25, 0.5, 0.75, 1.0];
        assert_eq!(g.breaks("n", [0.0, 1.0], 4, true, line).unwrap(), quarters);
        let uniform = Grading::UNIFORM.breaks("n", [0.0, 1.0], 4, false, line);
        assert_eq!(uniform.unwrap(), quarters);
    }

    #[test]
    fn refined_grading_halves_every_graded_element() {
        let g = Grading::geometric(0.3, 2).unwrap();
        let coarse = g.breaks("n", [0.0, 2.0], 5, false, |_| f64::NAN).unwrap();
        let fine = g.refined(2).unwrap();
        let x = fine
            .breaks("n", [0.0, 2.0], 10, false, |_| f64::NAN)
            .unwrap();
        for (j, c) in coarse.iter().enumerate() {
            assert_eq!(x[2 * j], *c);
        }
        for j in 0..5 {
            assert!((x[2 * j + 1] - 0.5 * (coarse[j] + coarse[j + 1])).abs() < 1e-15);
        }
        match fine.breaks("grid.n3", [0.0, 2.0], 9, false, |_| f64::NAN) {
            Err(ElasticityError::InvalidParameter { field, .. }) => assert_eq!(field, "grid.n3"),
            other => panic!("{other:?}"),
        }
        assert!(g.refined(0).is_err());
    }

    #[test]
    fn grading_outside_its_range_is_a_typed_error() {
        for bad in [0.0, 0.04, 1.5, f64::NAN, -0.2] {
            match Grading::geometric(bad, 2) {
                Err(ElasticityError::InvalidParameter { field, .. }) => {
                    assert_eq!(field, "discretisation.grading");
                }
                other => panic!("{bad}: {other:?}"),
            }
        }
        for bad in [0, 13] {
            match Grading::geometric(0.15, bad) {
                Err(ElasticityError::InvalidParameter { field, .. }) => {
                    assert_eq!(field, "discretisation.layers");
                }
                other => panic!("{bad}: {other:?}"),
            }
        }
        assert!(Grading::geometric(1.0, 3).unwrap().is_uniform());
    }

    #[test]
    fn locate_finds_the_element_and_the_reference_coordinate() {
        let x = [0.0, 0.1, 0.5, 2.0];
        assert_eq!(locate(&x, 0.0), (0, -1.0));
        assert_eq!(locate(&x, 0.5), (2, -1.0));
        assert_eq!(locate(&x, 2.0), (2, 1.0));
        assert_eq!(locate(&x, 5.0).0, 2); // clamped
        assert_eq!(locate(&x, -1.0).0, 0);
        let (e, xi) = locate(&x, 0.3);
        assert!(e == 1 && xi.abs() < 1e-15);
    }
}
