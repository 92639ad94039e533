//! Scene files: a complete, validated description of a run (TOML + `--set KEY=VALUE`).
//!
//! Every key has a default, so an empty scene is the paper's default setting (section 3:
//! semi-elliptical prism `a = b = 2`, `nu_F = 1/2`, `tau0 = 1`, `tau_max = 2`, `h = 1`,
//! `E = 1e3`, `nu = 1/4`, `eps = 1e-5`, grid 250 x 41). Keys are a public contract: they are
//! only ever added, never renamed.

use std::f64::consts::FRAC_PI_2;
use std::path::Path;

use capstan_elasticity::finite_element::DiscretisationMethod;
use capstan_geometry::{
    CircularCylinder, EllipticalPrism, ExpressionProfile, GeneralCone, GeneralPrism, Obstacle,
    RightCircularCone,
};
use serde::{Deserialize, Serialize};

use crate::error::CliError;

/// A whole run: obstacle, friction, membrane, loads, body, grid and solver settings.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
#[serde(deny_unknown_fields, default)]
pub struct Scene {
    /// `[obstacle]`: the rigid obstacle.
    pub obstacle: ObstacleSpec,
    /// `[friction]`: the friction law and its parameters.
    pub friction: FrictionSpec,
    /// `[membrane]`: the membrane (capstan) problem.
    pub membrane: MembraneSpec,
    /// `[loads]`: external loads and end tractions.
    pub loads: LoadsSpec,
    /// `[body]`: the thick elastic body.
    pub body: BodySpec,
    /// `[grid]`: the discretisation grid of the thick body.
    pub grid: GridSpec,
    /// `[solver]`: linear and nonlinear solver backends.
    pub solver: SolverSpec,
    /// `[discretisation]`: how the thick body's Navier operator is discretised.
    pub discretisation: DiscretisationSpec,
}

/// The obstacle's shape (`obstacle.shape`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Shape {
    /// Circular cylinder of `obstacle.radius`.
    Cylinder,
    /// Elliptical prism `(x1, a sin x2, b cos x2)` with `obstacle.a`, `obstacle.b`.
    Ellipse,
    /// General prism `(x1, u(x2), v(x2))` from expressions `obstacle.u`, `obstacle.v`.
    Prism,
    /// Right circular cone of half-aperture `obstacle.half_angle`.
    CircularCone,
    /// General cone `x1 (1, ubar(x2), vbar(x2))` from `obstacle.ubar`, `obstacle.vbar`.
    Cone,
}

/// `[obstacle]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ObstacleSpec {
    /// `cylinder | ellipse | prism | circular-cone | cone`.
    pub shape: Shape,
    /// Cylinder radius.
    pub radius: f64,
    /// Ellipse horizontal semi-axis.
    pub a: f64,
    /// Ellipse vertical semi-axis.
    pub b: f64,
    /// Right circular cone half-aperture (radians).
    pub half_angle: f64,
    /// Prism profile `u(t)`.
    pub u: String,
    /// Prism profile `v(t)`.
    pub v: String,
    /// Cone profile `ubar(t)`.
    pub ubar: String,
    /// Cone profile `vbar(t)`.
    pub vbar: String,
}

impl Default for ObstacleSpec {
    fn default() -> Self {
        Self {
            shape: Shape::Ellipse,
            radius: 2.0,
            a: 2.0,
            b: 2.0,
            half_angle: std::f64::consts::FRAC_PI_6,
            u: "2*sin(t)".into(),
            v: "2*cos(t)".into(),
            ubar: "0.5*sin(t)".into(),
            vbar: "0.5*cos(t)".into(),
        }
    }
}

impl ObstacleSpec {
    /// Builds the obstacle, validating its parameters.
    ///
    /// # Errors
    /// [`CliError::Geometry`] naming the bad field.
    pub fn build(&self) -> Result<Obstacle, CliError> {
        Ok(match self.shape {
            Shape::Cylinder => Obstacle::Cylinder(CircularCylinder::new(self.radius)?),
            Shape::Ellipse => Obstacle::Ellipse(EllipticalPrism::new(self.a, self.b)?),
            Shape::Prism => Obstacle::Prism(GeneralPrism::new(ExpressionProfile::parse_named(
                &self.u,
                &self.v,
                ["obstacle.u", "obstacle.v"],
            )?)),
            Shape::CircularCone => Obstacle::CircularCone(RightCircularCone::new(self.half_angle)?),
            Shape::Cone => Obstacle::Cone(GeneralCone::new(ExpressionProfile::parse_named(
                &self.ubar,
                &self.vbar,
                ["obstacle.ubar", "obstacle.vbar"],
            )?)),
        })
    }
}

/// `[friction]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct FrictionSpec {
    /// The friction law (`coulomb`: regularised Coulomb of Kikuchi–Oden).
    pub law: String,
    /// Coefficient of friction `mu` (the paper's `mu_F`, `nu_F`).
    pub mu: f64,
    /// Regularisation width `eps` (physical slip length).
    pub eps: f64,
}

impl Default for FrictionSpec {
    fn default() -> Self {
        Self {
            law: "coulomb".into(),
            mu: 0.5,
            eps: 1e-5,
        }
    }
}

/// `[membrane]`: the capstan problem.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct MembraneSpec {
    /// Tension `T0` at `theta0`.
    pub t0: f64,
    /// Start of the contact interval (radians, profile parameter).
    pub theta0: f64,
    /// End of the contact interval.
    pub theta_max: f64,
    /// Number of evenly spaced output samples on `[theta0, theta_max]`, both ends included.
    pub samples: usize,
    /// Measured tension at `theta_max` (for `infer-mu`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub t_max: Option<f64>,
}

impl Default for MembraneSpec {
    fn default() -> Self {
        Self {
            t0: 1.0,
            theta0: -FRAC_PI_2,
            theta_max: FRAC_PI_2,
            samples: 101,
            t_max: None,
        }
    }
}

/// `[loads]`: body forces on the membrane and end tractions on the thick body.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct LoadsSpec {
    /// Gravitational acceleration `g`; gravity is `(0, 0, -g)` in Euclidean coordinates.
    pub gravity: f64,
    /// Mass per unit volume of the membrane.
    pub density: f64,
    /// Membrane width `l`.
    pub width: f64,
    /// Membrane thickness `h`.
    pub thickness: f64,
    /// Steady belt speed `V` (Euclidean).
    pub speed: f64,
    /// End traction at `x2 = theta0` of the thick body.
    pub tau0: f64,
    /// End traction at `x2 = theta_max` of the thick body.
    pub tau_max: f64,
}

impl Default for LoadsSpec {
    fn default() -> Self {
        Self {
            gravity: 0.0,
            density: 0.0,
            width: 1.0,
            thickness: 1.0,
            speed: 0.0,
            tau0: 1.0,
            tau_max: 2.0,
        }
    }
}

/// `[body]`: the thick elastic body.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct BodySpec {
    /// Thickness `h`.
    pub thickness: f64,
    /// Young's modulus `E`.
    pub young: f64,
    /// Poisson's ratio `nu`.
    pub poisson: f64,
}

impl Default for BodySpec {
    fn default() -> Self {
        Self {
            thickness: 1.0,
            young: 1e3,
            poisson: 0.25,
        }
    }
}

/// `[grid]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct GridSpec {
    /// Points along `x2`.
    pub n2: usize,
    /// Points along `x3` (through the thickness).
    pub n3: usize,
}

impl Default for GridSpec {
    fn default() -> Self {
        Self { n2: 250, n3: 41 }
    }
}

/// `[solver]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SolverSpec {
    /// `lu | cholesky | jacobi | gauss-seidel`.
    pub linear: String,
    /// `newton | jacobi-newton`.
    pub nonlinear: String,
}

impl Default for SolverSpec {
    fn default() -> Self {
        Self {
            linear: "lu".into(),
            nonlinear: "newton".into(),
        }
    }
}

/// `[discretisation]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
#[serde(deny_unknown_fields, default)]
pub struct DiscretisationSpec {
    /// `fd` (finite differences, the default) | `fem-q1` | `fem-q2` (finite elements on the
    /// same grid; Q2 needs odd `grid.n2`, `grid.n3`).
    pub method: DiscretisationMethod,
}

impl Scene {
    /// Loads a scene from an optional TOML file and applies `--set KEY=VALUE` overrides.
    ///
    /// A value is read as a TOML value (`1.5`, `true`, `"text"`); anything that is not valid
    /// TOML is taken as a string, so `--set obstacle.u=2*sin(t)` needs no quotes.
    ///
    /// # Errors
    /// [`CliError::Io`] if the file cannot be read, [`CliError::Scene`] for malformed TOML,
    /// unknown keys or wrong types (naming the key), [`CliError::Set`] for a malformed override.
    pub fn load(path: Option<&Path>, sets: &[String]) -> Result<Self, CliError> {
        let mut table = match path {
            Some(p) => {
                let text = std::fs::read_to_string(p).map_err(|source| CliError::Io {
                    path: p.display().to_string(),
                    source,
                })?;
                text.parse::<toml::Table>().map_err(|e| CliError::Scene {
                    origin: p.display().to_string(),
                    message: e.to_string(),
                })?
            }
            None => toml::Table::new(),
        };
        for set in sets {
            apply_set(&mut table, set)?;
        }
        let origin = path.map_or_else(|| "--set".to_string(), |p| p.display().to_string());
        check_known_keys(&table, &origin)?;
        Scene::deserialize(toml::Value::Table(table)).map_err(|e| CliError::Scene {
            origin,
            message: e.to_string(),
        })
    }
}

/// Every key a scene accepts, as dotted names (from the defaults, plus optional keys).
pub fn known_keys() -> Vec<String> {
    let table = toml::Table::try_from(Scene::default()).expect("the default scene serialises");
    let mut keys = vec!["membrane.t_max".to_string()];
    for (section, value) in &table {
        if let toml::Value::Table(t) = value {
            keys.extend(t.keys().map(|k| format!("{section}.{k}")));
        }
    }
    keys.sort();
    keys
}

fn check_known_keys(table: &toml::Table, origin: &str) -> Result<(), CliError> {
    let known = known_keys();
    for (section, value) in table {
        let toml::Value::Table(t) = value else {
            return Err(CliError::Scene {
                origin: origin.into(),
                message: format!("`{section}` must be a table such as [{section}]"),
            });
        };
        for key in t.keys() {
            let dotted = format!("{section}.{key}");
            if !known.contains(&dotted) {
                let hint: Vec<&str> = known
                    .iter()
                    .filter(|k| k.starts_with(&format!("{section}.")))
                    .map(String::as_str)
                    .collect();
                return Err(CliError::Scene {
                    origin: origin.into(),
                    message: if hint.is_empty() {
                        format!("unknown key `{dotted}` (unknown table `[{section}]`)")
                    } else {
                        format!(
                            "unknown key `{dotted}`; expected one of {}",
                            hint.join(", ")
                        )
                    },
                });
            }
        }
    }
    Ok(())
}

fn apply_set(table: &mut toml::Table, set: &str) -> Result<(), CliError> {
    let bad = |why: &str| CliError::Set {
        set: set.to_string(),
        message: why.to_string(),
    };
    let (key, raw) = set
        .split_once('=')
        .ok_or_else(|| bad("expected KEY=VALUE"))?;
    let key = key.trim();
    let (section, field) = key
        .split_once('.')
        .ok_or_else(|| bad("KEY must be `table.key`, e.g. obstacle.radius"))?;
    if section.is_empty() || field.is_empty() || field.contains('.') {
        return Err(bad("KEY must be `table.key`, e.g. obstacle.radius"));
    }
    let raw = raw.trim();
    let value = format!("v = {raw}")
        .parse::<toml::Table>()
        .ok()
        .and_then(|mut t| t.remove("v"))
        .unwrap_or_else(|| toml::Value::String(raw.to_string()));
    let entry = table
        .entry(section.to_string())
        .or_insert_with(|| toml::Value::Table(toml::Table::new()));
    let toml::Value::Table(t) = entry else {
        return Err(bad("that table is not a table in the scene file"));
    };
    t.insert(field.to_string(), value);
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn empty_scene_is_the_paper_default() {
        let s = Scene::load(None, &[]).unwrap();
        assert_eq!(s, Scene::default());
        assert_eq!(s.grid.n2, 250);
        assert_eq!(s.body.young, 1e3);
    }

    #[test]
    fn set_overrides_numbers_and_strings() {
        let s = Scene::load(
            None,
            &[
                "obstacle.shape=prism".into(),
                "obstacle.u=2*sin(t) + 0.2*sin(2*t)".into(),
                "friction.mu=0.3".into(),
            ],
        )
        .unwrap();
        assert_eq!(s.obstacle.shape, Shape::Prism);
        assert_eq!(s.obstacle.u, "2*sin(t) + 0.2*sin(2*t)");
        assert_eq!(s.friction.mu, 0.3);
    }

    #[test]
    fn discretisation_method_defaults_to_fd_and_accepts_fem() {
        assert_eq!(
            Scene::default().discretisation.method,
            DiscretisationMethod::Fd
        );
        assert!(known_keys().contains(&"discretisation.method".to_string()));
        let s = Scene::load(None, &["discretisation.method=fem-q2".into()]).unwrap();
        assert_eq!(s.discretisation.method, DiscretisationMethod::FemQ2);
        let e = Scene::load(None, &["discretisation.method=fem-q3".into()])
            .unwrap_err()
            .to_string();
        assert!(e.contains("fem-q3"), "{e}");
    }

    #[test]
    fn unknown_keys_and_wrong_types_name_the_key() {
        let e = Scene::load(None, &["obstacle.radiu=2".into()])
            .unwrap_err()
            .to_string();
        assert!(e.contains("obstacle.radiu"), "{e}");
        let e = Scene::load(None, &["friction.mu=abc".into()])
            .unwrap_err()
            .to_string();
        assert!(e.contains("mu"), "{e}");
        let e = Scene::load(None, &["nonsense".into()])
            .unwrap_err()
            .to_string();
        assert!(e.contains("KEY=VALUE"), "{e}");
    }
}
