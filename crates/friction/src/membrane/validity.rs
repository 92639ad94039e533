//! Locating the first angle where a validity condition fails.

use crate::error::FrictionError;

/// The first angle in `points` (ascending) where `good` is false, refined by bisection between
/// the last good point and the first bad one; `None` if every point is good.
///
/// The bisection assumes one good-to-bad transition between neighbouring points, so `points`
/// should resolve the condition (every accepted ODE step, quadrature node or sample).
pub(crate) fn first_failure<G>(points: &[f64], mut good: G) -> Result<Option<f64>, FrictionError>
where
    G: FnMut(f64) -> Result<bool, FrictionError>,
{
    for (i, &p) in points.iter().enumerate() {
        if good(p)? {
            continue;
        }
        if i == 0 {
            return Ok(Some(p));
        }
        let (mut lo, mut hi) = (points[i - 1], p);
        for _ in 0..80 {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            if good(mid)? {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        return Ok(Some(hi));
    }
    Ok(None)
}

/// `n + 1` evenly spaced points on `[a, b]`, ends exact.
pub(crate) fn grid(a: f64, b: f64, n: usize) -> Vec<f64> {
    let n = n.max(1);
    (0..=n)
        .map(|i| {
            if i == n {
                b
            } else {
                a + (b - a) * i as f64 / n as f64
            }
        })
        .collect()
}

/// Merges sorted point sets (ascending, duplicates removed).
pub(crate) fn merged(mut points: Vec<f64>, more: &[f64]) -> Vec<f64> {
    points.extend_from_slice(more);
    points.sort_by(f64::total_cmp);
    points.dedup();
    points
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bisection_finds_the_transition() {
        let pts = grid(0.0, 1.0, 10);
        let at = first_failure(&pts, |x| Ok(x < 0.3337)).unwrap().unwrap();
        assert!((at - 0.3337).abs() < 1e-15);
        assert_eq!(first_failure(&pts, |_| Ok(true)).unwrap(), None);
        assert_eq!(first_failure(&pts, |_| Ok(false)).unwrap(), Some(0.0));
    }
}
