//! The registry of obstacles that scenes can name (`obstacle.shape`).
//!
//! An obstacle becomes usable from scenes by writing its file and registering it once: a
//! [`RegisteredObstacle`] names it, lists the keys under `[obstacle]` it reads (with defaults
//! and ranges) and builds the [`Obstacle`] from the scene's [`ObstacleSettings`] (validating
//! them). The built-in obstacles are listed in `obstacles/mod.rs` (a new one in this crate is
//! its file there plus one line in that list); a crate that embeds capstan adds its own with
//! [`register`] before it reads scenes. A user surface enters through
//! [`Obstacle::prism_over`], [`Obstacle::cone_over`] or [`Obstacle::surface`] and reaches the
//! membrane models (through the general method of its class) and the thick bodies.
//!
//! # Example
//! A trough `(x1, 2 sin t, 2 cos t - c sin^2 t)` with its sag `c` as the scene key
//! `obstacle.sag` (the same code as in docs/guide.md):
//! ```
//! use capstan_geometry::registry::{self, ObstacleParameter, ParameterDefault, RegisteredObstacle};
//! use capstan_geometry::{Obstacle, ObstacleSettings, ProfileCurve, Scalar, Surface};
//!
//! #[derive(Debug)]
//! struct Trough { sag: f64 }
//! impl ProfileCurve<f64> for Trough {
//!     fn profile<S: Scalar<f64>>(&self, t: S) -> [S; 2] {
//!         [t.sin() * 2.0, t.cos() * 2.0 - t.sin() * t.sin() * self.sag]
//!     }
//! }
//! registry::register(RegisteredObstacle {
//!     name: "doc-trough",
//!     summary: "a circle of radius 2 with its top sagging by `sag`",
//!     parameters: &[ObstacleParameter { key: "sag", default: ParameterDefault::Number(0.5), allowed: "[0, 1)" }],
//!     build: |s| {
//!         let sag = registry::check("obstacle.sag", s.number("sag")?, "[0, 1)", |c| (0.0..1.0).contains(&c))?;
//!         Ok(Obstacle::prism_over(Trough { sag }))
//!     },
//! })
//! .unwrap();
//!
//! // a scene's `[obstacle]` table: shape = "doc-trough" (sag at its default, 0.5)
//! let trough = registry::build("doc-trough", &ObstacleSettings::new()).unwrap();
//! let h = trough.geometry([0.0, 0.0]).unwrap().mean_curvature;
//! assert!((h - 0.375).abs() < 1e-15); // H = (1 + sag)/4 at the top
//! let bad = ObstacleSettings::new().with("sag", registry::ParameterValue::Number(1.5));
//! assert!(registry::build("doc-trough", &bad).unwrap_err().to_string().contains("obstacle.sag"));
//! ```

use std::sync::{LazyLock, RwLock};

use crate::error::GeometryError;
use crate::obstacle::Obstacle;

pub use crate::error::check;
pub use crate::registration::{
    ObstacleParameter, ObstacleSettings, ParameterDefault, ParameterValue, RegisteredObstacle,
};

static REGISTRY: LazyLock<RwLock<Vec<&'static RegisteredObstacle>>> =
    LazyLock::new(|| RwLock::new(crate::obstacles::builtin()));

fn obstacles() -> std::sync::RwLockReadGuard<'static, Vec<&'static RegisteredObstacle>> {
    REGISTRY
        .read()
        .unwrap_or_else(std::sync::PoisonError::into_inner)
}

/// Every registered obstacle, built-ins first, then in the order of [`register`].
pub fn registry() -> Vec<&'static RegisteredObstacle> {
    obstacles().clone()
}

/// The obstacle named `name`, if registered.
pub fn find(name: &str) -> Option<&'static RegisteredObstacle> {
    obstacles().iter().copied().find(|o| o.name == name)
}

/// The registered names, comma-separated (for error messages).
pub fn names() -> String {
    obstacles()
        .iter()
        .map(|o| o.name)
        .collect::<Vec<_>>()
        .join(", ")
}

/// Whether `key` (without the `obstacle.` prefix) is a parameter of some registered obstacle.
pub fn is_parameter(key: &str) -> bool {
    obstacles().iter().any(|o| o.parameter(key).is_some())
}

/// The obstacle `name` built from `settings` (defaults for what they do not give).
///
/// # Errors
/// [`GeometryError::UnknownObstacle`] listing the registered names; the builder's errors,
/// naming the scene key.
pub fn build(name: &str, settings: &ObstacleSettings) -> Result<Obstacle, GeometryError> {
    find(name)
        .ok_or_else(|| GeometryError::UnknownObstacle {
            name: name.to_string(),
            allowed: names(),
        })?
        .build_from(settings)
}

/// Adds `obstacle` to the registry, so that scenes can name it.
///
/// # Errors
/// [`GeometryError::DuplicateObstacle`] if an obstacle of that name is registered already.
pub fn register(obstacle: RegisteredObstacle) -> Result<(), GeometryError> {
    let mut all = REGISTRY
        .write()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    if all.iter().any(|o| o.name == obstacle.name) {
        return Err(GeometryError::DuplicateObstacle {
            name: obstacle.name,
        });
    }
    all.push(Box::leak(Box::new(obstacle)));
    Ok(())
}
