//! Scene files: a complete, validated description of a run (TOML + `--set KEY=VALUE`).
//!
//! Every key has a default, so an empty scene is the paper's default setting (section 3:
//! semi-elliptical prism `a = b = 2`, `nu_F = 1/2`, `tau0 = 1`, `tau_max = 2`, `h = 1`,
//! `E = 1e3`, `nu = 1/4`, `eps = 1e-5`, grid 250 x 41). Keys are a public contract: they are
//! only ever added, never renamed.

use std::collections::{HashMap, HashSet};
use std::f64::consts::FRAC_PI_2;
use std::path::Path;

use capstan_elasticity::finite_element::{DiscretisationMethod, VolumetricIntegration};
use capstan_elasticity::solvers::LinearBackend;
use capstan_friction::{AnyFrictionParams, FrictionLawKind, FrictionSettings};
use capstan_geometry::expression::Expression;
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
///
/// Unknown keys are refused by the scene's key check ([`known_keys`]: the fields below and the
/// parameters of every registered law, [`capstan_friction::registry`]), so `extra` holds only
/// parameters of laws registered outside the friction crate.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct FrictionSpec {
    /// The friction law (`coulomb`: regularised Coulomb of Kikuchi–Oden).
    pub law: String,
    /// Coefficient of friction `mu` (the paper's `mu_F`, `nu_F`).
    pub mu: f64,
    /// Regularisation width `eps` (physical slip length).
    pub eps: f64,
    /// The Tresca bound `g` (`friction.law = "tresca"`).
    pub bound: f64,
    /// Howell's exponent `n` in `|t| = mu |p|^n` (`friction.law = "howell"`).
    pub exponent: f64,
    /// `mu_2` along the second orthotropy axis (`friction.law = "orthotropic-coulomb"`).
    pub mu2: f64,
    /// First orthotropy axis from the slip frame's first axis, radians
    /// (`friction.law = "orthotropic-coulomb"`).
    pub axis_angle: f64,
    /// Parameters of other registered laws, by key.
    #[serde(flatten)]
    pub extra: std::collections::BTreeMap<String, f64>,
}

impl Default for FrictionSpec {
    fn default() -> Self {
        let d = FrictionSettings::default();
        Self {
            law: "coulomb".into(),
            mu: 0.5,
            eps: 1e-5,
            bound: d.bound,
            exponent: d.exponent,
            mu2: d.mu2,
            axis_angle: d.axis_angle,
            extra: d.extra,
        }
    }
}

impl FrictionSpec {
    /// The settings every friction law draws its parameters from.
    pub fn settings(&self) -> FrictionSettings {
        FrictionSettings {
            mu: self.mu,
            eps: self.eps,
            mu2: self.mu2,
            axis_angle: self.axis_angle,
            bound: self.bound,
            exponent: self.exponent,
            extra: self.extra.clone(),
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
    /// `full` (default) | `reduced`: how the finite elements integrate the volumetric part
    /// `lambda (div v)(div w) sqrt(g)` of the stiffness; `reduced` is selective reduced
    /// integration (Q1: 1 point, Q2: 2 x 2; the shear part keeps the full rule), the remedy
    /// for volumetric locking as `body.poisson -> 1/2`. `fd` accepts only `full`.
    pub volumetric: VolumetricIntegration,
}

impl Scene {
    /// Loads a scene from an optional TOML file, applies `--set KEY=VALUE` overrides and
    /// validates every field ([`Scene::validate`]).
    ///
    /// A value is read as a TOML value (`1.5`, `true`, `"text"`); anything that is not valid
    /// TOML is taken as a string, so `--set obstacle.u=2*sin(t)` needs no quotes.
    ///
    /// Errors about a value that came from the file name its line (`scene.toml:12`); values
    /// from `--set` are named as `--set`.
    ///
    /// # Errors
    /// [`CliError::Io`] if the file cannot be read, [`CliError::Scene`] for malformed TOML,
    /// unknown keys, wrong types or values outside their allowed range (naming the key, the
    /// value and the range), [`CliError::Set`] for a malformed override.
    pub fn load(path: Option<&Path>, sets: &[String]) -> Result<Self, CliError> {
        let mut origins = Origins::default();
        let mut text = String::new();
        let mut table = match path {
            Some(p) => {
                text = std::fs::read_to_string(p).map_err(|source| {
                    if source.kind() == std::io::ErrorKind::InvalidData {
                        CliError::Scene {
                            origin: p.display().to_string(),
                            message: "not a text file (a TOML scene must be UTF-8)".into(),
                        }
                    } else {
                        CliError::Io {
                            path: p.display().to_string(),
                            source,
                        }
                    }
                })?;
                origins.file = Some(p.display().to_string());
                let table = text.parse::<toml::Table>().map_err(|e| CliError::Scene {
                    origin: p.display().to_string(),
                    message: e.to_string(),
                })?;
                origins.lines = key_lines(&text);
                table
            }
            None => toml::Table::new(),
        };
        for set in sets {
            let key = apply_set(&mut table, set)?;
            origins.set.insert(key);
        }
        check_known_keys(&table, &origins)?;
        let scene = match Scene::deserialize(toml::Value::Table(table)) {
            Ok(scene) => scene,
            Err(e) => {
                // The merged table carries no spans: when the file alone is already wrong,
                // report the file's error, which points to the line.
                if let Some(file) = &origins.file
                    && let Err(file_error) = toml::from_str::<Scene>(&text)
                {
                    return Err(CliError::Scene {
                        origin: file.clone(),
                        message: file_error.to_string(),
                    });
                }
                let origin = if sets.is_empty() {
                    origins.file.clone().unwrap_or_else(|| "scene".into())
                } else {
                    "--set".into()
                };
                return Err(CliError::Scene {
                    origin,
                    message: e.to_string(),
                });
            }
        };
        scene.validate_with(&origins)?;
        Ok(scene)
    }
}

/// Every key a scene accepts, as dotted names (from the defaults, plus optional keys).
pub fn known_keys() -> Vec<String> {
    let table = toml::Table::try_from(Scene::default()).expect("the default scene serialises");
    let mut keys = vec!["membrane.t_max".to_string()];
    for law in capstan_friction::registry::registry() {
        keys.extend(law.parameters.iter().map(|p| format!("friction.{p}")));
    }
    for (section, value) in &table {
        if let toml::Value::Table(t) = value {
            keys.extend(t.keys().map(|k| format!("{section}.{k}")));
        }
    }
    keys.sort();
    keys.dedup();
    keys
}

fn check_known_keys(table: &toml::Table, origins: &Origins) -> Result<(), CliError> {
    let known = known_keys();
    for (section, value) in table {
        let toml::Value::Table(t) = value else {
            return Err(CliError::Scene {
                origin: origins.locate(section),
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
                    origin: origins.locate(&dotted),
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

/// Applies one `--set KEY=VALUE`; returns the dotted key.
fn apply_set(table: &mut toml::Table, set: &str) -> Result<String, CliError> {
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
    Ok(format!("{section}.{field}"))
}

/// Where each key's value came from, for error messages: a line of the scene file, `--set`,
/// or the built-in default.
#[derive(Debug, Clone, Default)]
pub struct Origins {
    /// The scene file, if any.
    file: Option<String>,
    /// 1-based line of each dotted key in the file.
    lines: HashMap<String, usize>,
    /// Dotted keys given by `--set` (they override the file).
    set: HashSet<String>,
}

impl Origins {
    /// `file:line` for a key from the file, `--set` for an override, else
    /// `(built-in default)` (a default or a scene built in code).
    pub fn locate(&self, key: &str) -> String {
        if self.set.contains(key) {
            return "--set".into();
        }
        match (&self.file, self.lines.get(key)) {
            (Some(file), Some(line)) => format!("{file}:{line}"),
            (Some(file), None) if !key.contains('.') => file.clone(),
            _ => "(built-in default)".into(),
        }
    }
}

/// The 1-based line of every key of a TOML text, as dotted names (`section` and
/// `section.key`); empty if the text does not parse.
fn key_lines(text: &str) -> HashMap<String, usize> {
    let line_of = |offset: usize| text[..offset.min(text.len())].matches('\n').count() + 1;
    let mut lines = HashMap::new();
    let Ok(doc) = toml::de::DeTable::parse(text) else {
        return lines;
    };
    for (section, value) in doc.get_ref() {
        lines.insert(section.get_ref().to_string(), line_of(section.span().start));
        if let Some(t) = value.get_ref().as_table() {
            for (key, _) in t {
                lines.insert(
                    format!("{}.{}", section.get_ref(), key.get_ref()),
                    line_of(key.span().start),
                );
            }
        }
    }
    lines
}

/// Largest `grid.n2` accepted before any memory estimate.
pub const MAX_N2: usize = 10_000_000;
/// Largest `grid.n3` accepted before any memory estimate.
pub const MAX_N3: usize = 1_000_000;
/// Largest `membrane.samples` (as in the membrane models).
pub const MAX_SAMPLES: usize = 10_000_000;
/// Sample points at which obstacle expressions are checked finite on the contact interval.
const EXPRESSION_CHECK_SAMPLES: usize = 1025;

/// A conservative estimate of the peak memory of a thick-body contact solve, by the
/// boundary-only solver (`condensed`, `solver.nonlinear = newton`) or the full-system solvers.
///
/// # Math
/// ```text
/// N     = 2 n2 n3                          unknowns (plane strain)
/// bytes = 190 N log2(N)  (x2 for fem-q2)   sparse system, Jacobian and multifrontal LU
///       + 2^27                             factors (nested dissection): fits the measured
///                                          VmHWM of `capstan contact` (fd, default scene)
///                                          from above: full-newton 1.12 GB / 4.70 GB /
///                                          19.9 GB at 1000x161 / 2000x321 / 4000x640,
///                                          condensed 1.65 GB at 1000x161 (8-12% margin)
///   condensed only:
///       + 32 n2^2                          four dense m x m condensed matrices, m ~ n2
///       + 2^29                             the condensation's blocks of right-hand sides,
///                                          residuals and corrections
/// ```
/// Not covered: a matrix whose pivots leave the multifrontal fronts falls back to faer's
/// supernodal LU, which needs up to ~2.3x more (see `capstan_solvers::LuKind`).
pub fn memory_estimate(n2: usize, n3: usize, method: DiscretisationMethod, condensed: bool) -> f64 {
    let (n2, n3) = (n2 as f64, n3 as f64);
    let unknowns = 2.0 * n2 * n3;
    let width = if method == DiscretisationMethod::FemQ2 {
        2.0
    } else {
        1.0
    };
    let system =
        MEMORY_BYTES_PER_N_LOG_N * width * unknowns * unknowns.log2().max(1.0) + 134_217_728.0;
    if condensed {
        system + 32.0 * n2 * n2 + 536_870_912.0
    } else {
        system
    }
}

/// The constant of [`memory_estimate`]: bytes per `N log2 N`.
pub const MEMORY_BYTES_PER_N_LOG_N: f64 = 190.0;

/// `MemAvailable` from `/proc/meminfo`, in bytes; `None` where there is no such file.
pub fn available_memory() -> Option<f64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kib: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024.0)
}

/// Bytes in human units (`1.2 GiB`).
pub fn human_bytes(bytes: f64) -> String {
    const UNITS: [&str; 5] = ["B", "KiB", "MiB", "GiB", "TiB"];
    let mut b = bytes;
    let mut unit = 0;
    while b >= 1024.0 && unit + 1 < UNITS.len() {
        b /= 1024.0;
        unit += 1;
    }
    format!("{b:.1} {}", UNITS[unit])
}

impl Scene {
    /// Checks every field against its allowed range (see [`Scene::load`], which calls it).
    ///
    /// Ranges: `obstacle.radius, a, b > 0`; `obstacle.half_angle` in `(0, pi/2)`; the
    /// shape's expressions parse and are finite with finite first and second derivatives on
    /// `[membrane.theta0, membrane.theta_max]`; `friction.law` is one of
    /// [`FrictionLawKind::names`],
    /// `friction.mu >= 0`, `friction.eps > 0`; `membrane.t0 > 0`, `theta0 < theta_max`,
    /// `samples` in `[2, 10^7]`, `t_max > 0` when given; `loads.gravity, density >= 0`,
    /// `loads.width, thickness > 0`; `body.thickness > 0`, `body.young > 0`, `body.poisson`
    /// in `(-1, 1/2)`; `discretisation.volumetric = "reduced"` only with `fem-q1`, `fem-q2`;
    /// `grid.n2, n3 >= 3` (odd for `fem-q2`), at most [`MAX_N2`], [`MAX_N3`],
    /// and a thick-body solve that fits in the available memory ([`memory_estimate`]); known
    /// solver names. Every number must be finite (TOML allows `nan` and `inf`).
    ///
    /// Whether the interval is convex is checked by the models that need it (the membrane
    /// models report [`capstan_friction::FrictionError::NonPositiveCurvature`], exit code 3).
    ///
    /// # Errors
    /// [`CliError::Scene`] naming the key, the value and the allowed range.
    pub fn validate(&self) -> Result<(), CliError> {
        self.validate_with(&Origins::default())
    }

    fn validate_with(&self, at: &Origins) -> Result<(), CliError> {
        let bad = |key: &str, value: String, allowed: &str| CliError::Scene {
            origin: at.locate(key),
            message: format!("`{key}` = {value} is outside {allowed}"),
        };
        let real = |key: &str, v: f64, allowed: &str, ok: bool| {
            if v.is_finite() && ok {
                Ok(())
            } else {
                Err(bad(key, format!("{v}"), allowed))
            }
        };
        let o = &self.obstacle;
        let m = &self.membrane;
        real("membrane.theta0", m.theta0, "finite values", true)?;
        real(
            "membrane.theta_max",
            m.theta_max,
            "(membrane.theta0, inf)",
            m.theta_max > m.theta0,
        )?;
        match o.shape {
            Shape::Cylinder => real("obstacle.radius", o.radius, "(0, inf)", o.radius > 0.0)?,
            Shape::Ellipse => {
                real("obstacle.a", o.a, "(0, inf)", o.a > 0.0)?;
                real("obstacle.b", o.b, "(0, inf)", o.b > 0.0)?;
            }
            Shape::CircularCone => real(
                "obstacle.half_angle",
                o.half_angle,
                "(0, pi/2)",
                o.half_angle > 0.0 && o.half_angle < FRAC_PI_2,
            )?,
            Shape::Prism | Shape::Cone => {}
        }
        for (key, src) in [
            ("obstacle.u", &o.u),
            ("obstacle.v", &o.v),
            ("obstacle.ubar", &o.ubar),
            ("obstacle.vbar", &o.vbar),
        ] {
            let used = matches!(
                (o.shape, key),
                (Shape::Prism, "obstacle.u" | "obstacle.v")
                    | (Shape::Cone, "obstacle.ubar" | "obstacle.vbar")
            );
            let expression = Expression::parse(src).map_err(|e| CliError::Scene {
                origin: at.locate(key),
                message: format!("`{key}` = {src:?}: {e}"),
            })?;
            if used {
                expression
                    .check_finite_on(m.theta0, m.theta_max, EXPRESSION_CHECK_SAMPLES)
                    .map_err(|e| CliError::Scene {
                        origin: at.locate(key),
                        message: format!(
                            "`{key}` = {src:?} must be finite with finite first and second derivatives on [membrane.theta0, membrane.theta_max] = [{}, {}]: {e}",
                            m.theta0, m.theta_max
                        ),
                    })?;
            }
        }
        let f = &self.friction;
        if FrictionLawKind::parse(&f.law).is_none() {
            return Err(bad(
                "friction.law",
                format!("{:?}", f.law),
                &FrictionLawKind::names(),
            ));
        }
        real("friction.mu", f.mu, "[0, inf)", f.mu >= 0.0)?;
        real("friction.eps", f.eps, "(0, inf)", f.eps > 0.0)?;
        real("friction.bound", f.bound, "[0, inf)", f.bound >= 0.0)?;
        real(
            "friction.exponent",
            f.exponent,
            "(0, 2]",
            f.exponent > 0.0 && f.exponent <= 2.0,
        )?;
        real("friction.mu2", f.mu2, "[0, inf)", f.mu2 >= 0.0)?;
        real("friction.axis_angle", f.axis_angle, "finite values", true)?;
        if let Some(kind) = FrictionLawKind::parse(&f.law) {
            // The law's own checks (e.g. orthotropic: not both coefficients zero).
            AnyFrictionParams::of_kind(kind, &f.settings()).map_err(|e| CliError::Scene {
                origin: at.locate("friction.law"),
                message: e.to_string(),
            })?;
        }
        real("membrane.t0", m.t0, "(0, inf)", m.t0 > 0.0)?;
        if !(2..=MAX_SAMPLES).contains(&m.samples) {
            return Err(bad("membrane.samples", m.samples.to_string(), "[2, 10^7]"));
        }
        if let Some(t_max) = m.t_max {
            real("membrane.t_max", t_max, "(0, inf)", t_max > 0.0)?;
        }
        let l = &self.loads;
        real("loads.gravity", l.gravity, "[0, inf)", l.gravity >= 0.0)?;
        real("loads.density", l.density, "[0, inf)", l.density >= 0.0)?;
        real("loads.width", l.width, "(0, inf)", l.width > 0.0)?;
        real(
            "loads.thickness",
            l.thickness,
            "(0, inf)",
            l.thickness > 0.0,
        )?;
        real("loads.speed", l.speed, "finite values", true)?;
        real("loads.tau0", l.tau0, "finite values", true)?;
        real("loads.tau_max", l.tau_max, "finite values", true)?;
        let b = &self.body;
        real("body.thickness", b.thickness, "(0, inf)", b.thickness > 0.0)?;
        real("body.young", b.young, "(0, inf)", b.young > 0.0)?;
        real(
            "body.poisson",
            b.poisson,
            "(-1, 1/2)",
            b.poisson > -1.0 && b.poisson < 0.5,
        )?;
        self.validate_grid(at)?;
        if self.discretisation.method == DiscretisationMethod::Fd
            && self.discretisation.volumetric != VolumetricIntegration::Full
        {
            return Err(bad(
                "discretisation.volumetric",
                format!("{:?}", self.discretisation.volumetric.name()),
                "{\"full\"} for discretisation.method = \"fd\" (finite differences have no quadrature rule to reduce; \"reduced\" needs \"fem-q1\" or \"fem-q2\")",
            ));
        }
        if self.solver.linear.parse::<LinearBackend>().is_err() {
            return Err(bad(
                "solver.linear",
                format!("{:?}", self.solver.linear),
                LinearBackend::NAMES,
            ));
        }
        if !matches!(
            self.solver.nonlinear.as_str(),
            "newton" | "full-newton" | "jacobi-newton"
        ) {
            return Err(bad(
                "solver.nonlinear",
                format!("{:?}", self.solver.nonlinear),
                "{\"newton\", \"full-newton\", \"jacobi-newton\"}",
            ));
        }
        Ok(())
    }

    fn validate_grid(&self, at: &Origins) -> Result<(), CliError> {
        let g = &self.grid;
        let method = self.discretisation.method;
        let q2 = method == DiscretisationMethod::FemQ2;
        for (key, n, max, allowed, allowed_q2) in [
            (
                "grid.n2",
                g.n2,
                MAX_N2,
                "[3, 10^7]",
                "odd values in [3, 10^7] (fem-q2)",
            ),
            (
                "grid.n3",
                g.n3,
                MAX_N3,
                "[3, 10^6]",
                "odd values in [3, 10^6] (fem-q2)",
            ),
        ] {
            if !(3..=max).contains(&n) || (q2 && n % 2 == 0) {
                return Err(CliError::Scene {
                    origin: at.locate(key),
                    message: format!(
                        "`{key}` = {n} is outside {}",
                        if q2 { allowed_q2 } else { allowed }
                    ),
                });
            }
        }
        let need = memory_estimate(g.n2, g.n3, method, self.solver.nonlinear == "newton");
        if let Some(have) = available_memory()
            && need > have
        {
            return Err(CliError::Scene {
                origin: at.locate("grid.n2"),
                message: format!(
                    "grid {} x {} ({method}) needs about {} for the sparse system and its LU factors (estimate: {MEMORY_BYTES_PER_N_LOG_N} bytes x N log2 N, N = {} unknowns: contact solves measured up to 4000 x 640), more than the {} available (MemAvailable in /proc/meminfo); use a coarser grid",
                    g.n2,
                    g.n3,
                    human_bytes(need),
                    2 * g.n2 * g.n3,
                    human_bytes(have)
                ),
            });
        }
        Ok(())
    }
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
        let s = Scene::load(
            None,
            &[
                "discretisation.method=fem-q2".into(),
                "grid.n2=251".into(), // Q2 needs odd node counts
            ],
        )
        .unwrap();
        assert_eq!(s.discretisation.method, DiscretisationMethod::FemQ2);
        let e = Scene::load(None, &["discretisation.method=fem-q3".into()])
            .unwrap_err()
            .to_string();
        assert!(e.contains("fem-q3"), "{e}");
    }

    #[test]
    fn discretisation_volumetric_defaults_to_full_and_is_refused_for_fd() {
        assert_eq!(
            Scene::default().discretisation.volumetric,
            VolumetricIntegration::Full
        );
        assert!(known_keys().contains(&"discretisation.volumetric".to_string()));
        let s = Scene::load(
            None,
            &[
                "discretisation.method=fem-q1".into(),
                "discretisation.volumetric=reduced".into(),
            ],
        )
        .unwrap();
        assert_eq!(s.discretisation.volumetric, VolumetricIntegration::Reduced);
        let e = Scene::load(None, &["discretisation.volumetric=reduced".into()])
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("`discretisation.volumetric` = \"reduced\" is outside")
                && e.contains("fem-q1"),
            "{e}"
        );
        let e = Scene::load(None, &["discretisation.volumetric=selective".into()])
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("selective") && e.contains("`full`") && e.contains("`reduced`"),
            "{e}"
        );
    }

    #[test]
    fn validate_names_key_value_and_range() {
        let mut s = Scene::default();
        assert!(s.validate().is_ok());
        s.body.poisson = 0.5;
        let e = s.validate().unwrap_err().to_string();
        assert!(
            e.contains("`body.poisson` = 0.5 is outside (-1, 1/2)"),
            "{e}"
        );
        assert!(e.contains("(built-in default)"), "{e}");
    }

    #[test]
    fn key_lines_point_to_the_key() {
        let lines = key_lines("# c\n[friction]\nmu = 1\n\n[grid]\nn2 = 5\n");
        assert_eq!(lines["friction.mu"], 3);
        assert_eq!(lines["grid.n2"], 6);
        assert_eq!(lines["grid"], 5);
        assert!(key_lines("[broken").is_empty());
    }

    #[test]
    fn memory_estimate_brackets_the_measured_peaks() {
        // Measured VmHWM of `capstan contact` (nested dissection): full-newton 1.12 GB at
        // 1000x161, 4.70 GB at 2000x321 and 19.9 GB at 4000x640, condensed 1.65 GB at
        // 1000x161; the estimate is above, by less than 1.25x.
        let fd = DiscretisationMethod::Fd;
        let gb = |b: f64| b / 1e9;
        assert!((1.12..1.4).contains(&gb(memory_estimate(1000, 161, fd, false))));
        assert!((4.70..5.9).contains(&gb(memory_estimate(2000, 321, fd, false))));
        assert!((19.9..24.9).contains(&gb(memory_estimate(4000, 640, fd, false))));
        assert!((1.65..2.1).contains(&gb(memory_estimate(1000, 161, fd, true))));
        assert_eq!(human_bytes(1536.0), "1.5 KiB");
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
