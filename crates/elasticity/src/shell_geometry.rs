//! What the elasticity code needs from a geometry: the shell chart at a point.

use capstan_geometry::{GeometryError, ShellChart, ShellPoint, Surface};

/// A 3-D chart that yields the shell geometry (metric, inverse metric, `sqrt(g)`,
/// Christoffel symbols, bases) at a point `(x1, x2, x3)`.
///
/// Implemented for every [`ShellChart`] over a [`Surface`], so any obstacle written once as
/// `sigma(x1, x2)` works with the elasticity code unchanged.
pub trait ShellGeometry {
    /// The geometry at `x = (x1, x2, x3)`.
    ///
    /// # Errors
    /// The chart's [`GeometryError`].
    fn shell_point(&self, x: [f64; 3]) -> Result<ShellPoint<f64>, GeometryError>;

    /// The geometry at `(x[0], x[1], x3)` for every `x3` in `heights`, appended to `out` in
    /// order: a column of points above one surface point, as the quadrature points of a
    /// column of elements. The default calls [`ShellGeometry::shell_point`] per height;
    /// [`ShellChart`] overrides it with one surface jet per column ([`ShellChart::frame`]),
    /// equal bit for bit.
    ///
    /// # Errors
    /// The chart's [`GeometryError`] at the first height that fails (`out` may then hold the
    /// points before it).
    fn shell_column(
        &self,
        x: [f64; 2],
        heights: &[f64],
        out: &mut Vec<ShellPoint<f64>>,
    ) -> Result<(), GeometryError> {
        for &x3 in heights {
            out.push(self.shell_point([x[0], x[1], x3])?);
        }
        Ok(())
    }
}

impl<S: Surface<f64>> ShellGeometry for ShellChart<S> {
    fn shell_point(&self, x: [f64; 3]) -> Result<ShellPoint<f64>, GeometryError> {
        self.point(x)
    }

    fn shell_column(
        &self,
        x: [f64; 2],
        heights: &[f64],
        out: &mut Vec<ShellPoint<f64>>,
    ) -> Result<(), GeometryError> {
        if heights.is_empty() {
            return Ok(());
        }
        let frame = match self.frame(x) {
            Ok(frame) => frame,
            // the pointwise path reports the first height
            Err(_) => return self.shell_point([x[0], x[1], heights[0]]).map(|_| ()),
        };
        for &x3 in heights {
            out.push(frame.point(x3)?);
        }
        Ok(())
    }
}

impl<T: ShellGeometry + ?Sized> ShellGeometry for &T {
    fn shell_point(&self, x: [f64; 3]) -> Result<ShellPoint<f64>, GeometryError> {
        (**self).shell_point(x)
    }

    fn shell_column(
        &self,
        x: [f64; 2],
        heights: &[f64],
        out: &mut Vec<ShellPoint<f64>>,
    ) -> Result<(), GeometryError> {
        (**self).shell_column(x, heights, out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use capstan_geometry::{CircularCylinder, EllipticalPrism, ExpressionProfile, GeneralPrism};

    /// The default `shell_column`, written against `shell_point` only.
    struct Pointwise<'a, G>(&'a G);

    impl<G: ShellGeometry> ShellGeometry for Pointwise<'_, G> {
        fn shell_point(&self, x: [f64; 3]) -> Result<ShellPoint<f64>, GeometryError> {
            self.0.shell_point(x)
        }
    }

    fn column_override_equals_default<G: ShellGeometry>(chart: &G, heights: &[f64]) {
        for x2 in [-2.0, -0.4, 0.0, 0.3, 1.7] {
            let (mut fast, mut slow) = (vec![], vec![]);
            let a = chart.shell_column([0.0, x2], heights, &mut fast);
            let b = Pointwise(chart).shell_column([0.0, x2], heights, &mut slow);
            assert_eq!(a, b, "x2 {x2}");
            assert_eq!(fast, slow, "x2 {x2}"); // bit for bit
        }
    }

    #[test]
    fn chart_column_equals_pointwise_default() {
        let heights = [0.0, 0.05, 0.2, 0.5, 0.95];
        column_override_equals_default(
            &ShellChart::new(EllipticalPrism::new(1.0, 2.0).unwrap()),
            &heights,
        );
        let profile =
            ExpressionProfile::parse("3 * sin(t) - 0.2 * sin(3 * t)", "2 * cos(t) + 0.1 * t^2")
                .unwrap();
        column_override_equals_default(&ShellChart::new(GeneralPrism::new(profile)), &heights);
        // a column that crosses the focal surface of a unit cylinder fails at the same height
        let cylinder = ShellChart::new(CircularCylinder::new(1.0).unwrap());
        column_override_equals_default(&cylinder, &[0.5, -0.5, -1.0, -2.0]);
        let mut out = vec![];
        assert!(
            cylinder
                .shell_column([0.0, 0.1], &[0.5, -1.0], &mut out)
                .is_err()
        );
    }
}
