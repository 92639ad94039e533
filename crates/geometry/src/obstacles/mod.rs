//! The obstacles this crate registers, in the order of [`crate::registry::names`].
//!
//! A new obstacle is one file here (its surface or profile curve and a `REGISTRATION`) plus
//! its line below: nothing else in the workspace changes, and scenes can name it at once.

mod paper;

use crate::registration::RegisteredObstacle;

/// The built-in obstacles.
pub(crate) fn builtin() -> Vec<&'static RegisteredObstacle> {
    vec![
        &paper::CYLINDER,
        &paper::ELLIPSE,
        &paper::PRISM,
        &paper::CIRCULAR_CONE,
        &paper::CONE,
    ]
}
