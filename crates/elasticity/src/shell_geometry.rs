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
}

impl<S: Surface<f64>> ShellGeometry for ShellChart<S> {
    fn shell_point(&self, x: [f64; 3]) -> Result<ShellPoint<f64>, GeometryError> {
        self.point(x)
    }
}

impl<T: ShellGeometry + ?Sized> ShellGeometry for &T {
    fn shell_point(&self, x: [f64; 3]) -> Result<ShellPoint<f64>, GeometryError> {
        (**self).shell_point(x)
    }
}
