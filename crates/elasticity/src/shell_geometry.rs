//! What the elasticity code needs from a geometry: the shell chart at a point.

use capstan_geometry::{GeometryError, ShellChart, ShellFrame, ShellPoint, Surface};

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

    /// The frame of the surface point `x = (x1, x2)`, for a chart that has one: everything
    /// [`ShellGeometry::shell_point`] needs that does not depend on `x3`, its
    /// [`ShellFrame::point`] equal to `shell_point` bit for bit. The default, `None`, has
    /// [`ShellGeometry::shell_column`] evaluate point by point; [`ShellChart`] gives
    /// [`ShellChart::frame`] (one surface jet per column).
    fn shell_frame(&self, _x: [f64; 2]) -> Option<Result<ShellFrame<f64>, GeometryError>> {
        None
    }

    /// The geometry at `(x[0], x[1], x3)` for every `x3` in `heights`, appended to `out` in
    /// order: a column of points above one surface point, as the quadrature points of a
    /// column of elements. From the [`ShellGeometry::shell_frame`] when the chart has one,
    /// else by [`ShellGeometry::shell_point`] per height; equal bit for bit.
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
        if heights.is_empty() {
            return Ok(());
        }
        match self.shell_frame(x) {
            Some(Ok(frame)) => {
                for &x3 in heights {
                    out.push(frame.point(x3)?);
                }
            }
            // the pointwise path reports the first height
            Some(Err(_)) => return self.shell_point([x[0], x[1], heights[0]]).map(|_| ()),
            None => {
                for &x3 in heights {
                    out.push(self.shell_point([x[0], x[1], x3])?);
                }
            }
        }
        Ok(())
    }
}

impl<S: Surface<f64>> ShellGeometry for ShellChart<S> {
    fn shell_point(&self, x: [f64; 3]) -> Result<ShellPoint<f64>, GeometryError> {
        self.point(x)
    }

    fn shell_frame(&self, x: [f64; 2]) -> Option<Result<ShellFrame<f64>, GeometryError>> {
        Some(self.frame(x))
    }
}

impl<T: ShellGeometry + ?Sized> ShellGeometry for &T {
    fn shell_point(&self, x: [f64; 3]) -> Result<ShellPoint<f64>, GeometryError> {
        (**self).shell_point(x)
    }

    fn shell_frame(&self, x: [f64; 2]) -> Option<Result<ShellFrame<f64>, GeometryError>> {
        (**self).shell_frame(x)
    }
}

/// A chart shared by the operators of every registered discretisation, whatever the surface:
/// the registry builds plane-strain operators over it, so a user surface reaches every
/// discretisation without a type of its own.
pub type SharedChart = std::sync::Arc<dyn ShellGeometry + Send + Sync>;

impl<T: ShellGeometry + ?Sized> ShellGeometry for std::sync::Arc<T> {
    fn shell_point(&self, x: [f64; 3]) -> Result<ShellPoint<f64>, GeometryError> {
        (**self).shell_point(x)
    }

    fn shell_frame(&self, x: [f64; 2]) -> Option<Result<ShellFrame<f64>, GeometryError>> {
        (**self).shell_frame(x)
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

    /// A chart without a frame: `shell_column` point by point, against `shell_point` only.
    struct Pointwise<'a, G>(&'a G);

    impl<G: ShellGeometry> ShellGeometry for Pointwise<'_, G> {
        fn shell_point(&self, x: [f64; 3]) -> Result<ShellPoint<f64>, GeometryError> {
            self.0.shell_point(x)
        }
    }

    fn column_by_frame_equals_pointwise<G: ShellGeometry>(chart: &G, heights: &[f64]) {
        assert!(<&G as ShellGeometry>::shell_frame(&chart, [0.0, 0.3]).is_some()); // forwarded
        assert!(Pointwise(chart).shell_frame([0.0, 0.3]).is_none());
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
        column_by_frame_equals_pointwise(
            &ShellChart::new(EllipticalPrism::new(1.0, 2.0).unwrap()),
            &heights,
        );
        let profile =
            ExpressionProfile::parse("3 * sin(t) - 0.2 * sin(3 * t)", "2 * cos(t) + 0.1 * t^2")
                .unwrap();
        column_by_frame_equals_pointwise(&ShellChart::new(GeneralPrism::new(profile)), &heights);
        // a column that crosses the focal surface of a unit cylinder fails at the same height
        let cylinder = ShellChart::new(CircularCylinder::new(1.0).unwrap());
        column_by_frame_equals_pointwise(&cylinder, &[0.5, -0.5, -1.0, -2.0]);
        let mut out = vec![];
        assert!(
            cylinder
                .shell_column([0.0, 0.1], &[0.5, -1.0], &mut out)
                .is_err()
        );
    }
}
