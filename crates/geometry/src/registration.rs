//! What an obstacle registers: its name, its scene parameters with defaults and ranges, and
//! how to build it from the scene's values ([`RegisteredObstacle`]); the values themselves
//! ([`ObstacleSettings`]). The registry is [`crate::registry`].

use std::collections::BTreeMap;

use crate::error::GeometryError;
use crate::obstacle::Obstacle;

/// The default of an obstacle's scene parameter, which also fixes its kind.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ParameterDefault {
    /// A number (e.g. `obstacle.radius = 2`).
    Number(f64),
    /// A math expression in `t` (e.g. `obstacle.u = "2*sin(t)"`); a scene checks it finite,
    /// with finite first and second derivatives, on the wrap interval.
    Expression(&'static str),
}

/// One scene key under `[obstacle]` that an obstacle reads.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ObstacleParameter {
    /// The key without the `obstacle.` prefix (e.g. `radius`).
    pub key: &'static str,
    /// Its value when the scene does not give it.
    pub default: ParameterDefault,
    /// The allowed values in words (e.g. `(0, inf)`), for listings and docs; the builder
    /// enforces them.
    pub allowed: &'static str,
}

/// The value of one obstacle parameter.
#[derive(Debug, Clone, PartialEq)]
pub enum ParameterValue {
    /// A number.
    Number(f64),
    /// A math expression in `t`.
    Expression(String),
}

impl From<ParameterDefault> for ParameterValue {
    fn from(d: ParameterDefault) -> Self {
        match d {
            ParameterDefault::Number(v) => Self::Number(v),
            ParameterDefault::Expression(e) => Self::Expression(e.to_string()),
        }
    }
}

/// The values of a scene's `[obstacle]` table that obstacles draw their parameters from,
/// by key (without the `obstacle.` prefix).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ObstacleSettings {
    values: BTreeMap<String, ParameterValue>,
}

impl ObstacleSettings {
    /// No values (every parameter takes its registered default).
    pub fn new() -> Self {
        Self::default()
    }
    /// These settings with `key` set to `value`.
    pub fn with(mut self, key: &str, value: ParameterValue) -> Self {
        self.insert(key, value);
        self
    }
    /// Sets `key` to `value`.
    pub fn insert(&mut self, key: &str, value: ParameterValue) {
        self.values.insert(key.to_string(), value);
    }
    /// The value of `key`, if given.
    pub fn get(&self, key: &str) -> Option<&ParameterValue> {
        self.values.get(key)
    }
    /// The number `key`.
    ///
    /// # Errors
    /// [`GeometryError::ParameterKind`] if it is an expression;
    /// [`GeometryError::UndeclaredParameter`] if it is not given (a builder reading a key its
    /// registration does not declare: [`RegisteredObstacle::build_from`] fills in defaults).
    pub fn number(&self, key: &'static str) -> Result<f64, GeometryError> {
        match self.values.get(key) {
            Some(ParameterValue::Number(v)) => Ok(*v),
            Some(ParameterValue::Expression(_)) => Err(GeometryError::ParameterKind {
                key,
                expected: "a number",
            }),
            None => Err(GeometryError::UndeclaredParameter { key: key.into() }),
        }
    }
    /// The expression `key`.
    ///
    /// # Errors
    /// As [`ObstacleSettings::number`], with kinds swapped.
    pub fn expression(&self, key: &'static str) -> Result<&str, GeometryError> {
        match self.values.get(key) {
            Some(ParameterValue::Expression(e)) => Ok(e),
            Some(ParameterValue::Number(_)) => Err(GeometryError::ParameterKind {
                key,
                expected: "an expression in t (a string)",
            }),
            None => Err(GeometryError::UndeclaredParameter { key: key.into() }),
        }
    }
}

/// An obstacle that scenes can name (`obstacle.shape`).
#[derive(Debug, Clone, Copy)]
pub struct RegisteredObstacle {
    /// The value of `obstacle.shape` that selects it (e.g. `"ellipse"`).
    pub name: &'static str,
    /// One line for listings and docs.
    pub summary: &'static str,
    /// The keys under `[obstacle]` it reads, with defaults and ranges.
    pub parameters: &'static [ObstacleParameter],
    /// Builds the obstacle from the scene's values, validating those it reads. Called through
    /// [`RegisteredObstacle::build_from`], which fills in the defaults first.
    ///
    /// # Errors
    /// [`GeometryError::InvalidParameter`] or [`GeometryError::Expression`] naming the scene
    /// key of the first bad value.
    pub build: fn(&ObstacleSettings) -> Result<Obstacle, GeometryError>,
}

impl RegisteredObstacle {
    /// The obstacle for `settings`, each parameter it does not give at its default.
    ///
    /// # Errors
    /// As [`RegisteredObstacle::build`].
    pub fn build_from(&self, settings: &ObstacleSettings) -> Result<Obstacle, GeometryError> {
        let mut filled = settings.clone();
        for p in self.parameters {
            if filled.get(p.key).is_none() {
                filled.insert(p.key, p.default.into());
            }
        }
        (self.build)(&filled)
    }
    /// The parameter `key`, if the obstacle reads it.
    pub fn parameter(&self, key: &str) -> Option<&'static ObstacleParameter> {
        self.parameters.iter().find(|p| p.key == key)
    }
}
