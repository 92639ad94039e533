//! Reference obstacles shared by tests, benches and examples.

use crate::error::check;
use crate::obstacle::Obstacle;
use crate::profile::ProfileCurve;
use crate::registration::{ObstacleParameter, ParameterDefault, RegisteredObstacle};
use crate::scalar::Scalar;

/// A trough: the circle of radius 2 with its top pressed in by `sag`.
///
/// # Math
/// ```text
/// (u, v) = (2 sin t, 2 cos t - sag sin^2 t)
/// psi'(t) = (v' u'' - u' v'') / (u'^2 + v'^2) = 4 (1 + sag cos^3 t) / (u'^2 + v'^2)
/// ```
/// The turning rate `psi'` is positive for `sag < 1`: convex, with the outward normal.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Trough {
    /// The sag `c` of the top, in `[0, 1)`.
    pub sag: f64,
}

impl ProfileCurve<f64> for Trough {
    fn profile<S: Scalar<f64>>(&self, t: S) -> [S; 2] {
        let s = t.sin();
        [s * 2.0, t.cos() * 2.0 - s * s * self.sag]
    }
}

/// The trough as a registration a test registers at run time (`obstacle.shape = "trough"`,
/// `obstacle.sag` in `[0, 1)`, default 0.3): a prism over [`Trough`]. Not built in.
pub const TROUGH: RegisteredObstacle = RegisteredObstacle {
    name: "trough",
    summary: "a circle of radius 2 whose top sags by obstacle.sag",
    parameters: &[ObstacleParameter {
        key: "sag",
        default: ParameterDefault::Number(0.3),
        allowed: "[0, 1)",
    }],
    build: |s| {
        let sag = check("obstacle.sag", s.number("sag")?, "[0, 1)", |c| {
            (0.0..1.0).contains(&c)
        })?;
        Ok(Obstacle::prism_over(Trough { sag }))
    },
};
