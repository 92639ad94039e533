//! The scene tables that say what the problem is: `[obstacle]`, `[friction]`, `[membrane]`,
//! `[loads]` and `[body]` (the solver, grid, discretisation and output tables are in
//! `scene/mod.rs`).

use std::f64::consts::FRAC_PI_2;

use capstan_elasticity::solid::SideFaces;
use capstan_friction::FrictionSettings;
use capstan_friction::membrane::MembraneLoads;
use capstan_geometry::expression::Expression;
use capstan_geometry::{Obstacle, ObstacleSettings};
use serde::{Deserialize, Serialize};

use crate::error::CliError;

/// `[obstacle]`.
///
/// `shape` names a registered obstacle ([`capstan_geometry::registry`]); the fields below are
/// the parameters of the paper's obstacles, and any other key of the table (a parameter of an
/// obstacle registered elsewhere, a number or an expression) is in `extra`. Unknown keys are
/// refused by the scene's key check ([`known_keys`](super::known_keys)).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct ObstacleSpec {
    /// A registered obstacle: `cylinder | ellipse | prism | circular-cone | cone` or one
    /// registered at run time.
    pub shape: String,
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
    /// Parameters of other registered obstacles, by key (numbers or expressions).
    #[serde(flatten)]
    pub extra: std::collections::BTreeMap<String, toml::Value>,
}

impl Default for ObstacleSpec {
    fn default() -> Self {
        Self {
            shape: "ellipse".into(),
            radius: 2.0,
            a: 2.0,
            b: 2.0,
            half_angle: std::f64::consts::FRAC_PI_6,
            u: "2*sin(t)".into(),
            v: "2*cos(t)".into(),
            ubar: "0.5*sin(t)".into(),
            vbar: "0.5*cos(t)".into(),
            extra: Default::default(),
        }
    }
}

impl ObstacleSpec {
    /// The values every registered obstacle draws its parameters from.
    ///
    /// # Errors
    /// [`CliError::Scene`] naming an `extra` key that is neither a number nor a string.
    pub fn settings(&self) -> Result<ObstacleSettings, CliError> {
        use capstan_geometry::registry::ParameterValue::{Expression, Number};
        let mut s = ObstacleSettings::new()
            .with("radius", Number(self.radius))
            .with("a", Number(self.a))
            .with("b", Number(self.b))
            .with("half_angle", Number(self.half_angle))
            .with("u", Expression(self.u.clone()))
            .with("v", Expression(self.v.clone()))
            .with("ubar", Expression(self.ubar.clone()))
            .with("vbar", Expression(self.vbar.clone()));
        for (key, value) in &self.extra {
            let value = match value {
                toml::Value::Float(x) => Number(*x),
                toml::Value::Integer(i) => Number(*i as f64),
                toml::Value::String(e) => Expression(e.clone()),
                other => {
                    return Err(CliError::Scene {
                        origin: format!("obstacle.{key}"),
                        message: format!(
                            "`obstacle.{key}` = {other} must be a number or an expression (a string)"
                        ),
                    });
                }
            };
            s.insert(key, value);
        }
        Ok(s)
    }

    /// Builds the obstacle `shape` names, validating its parameters.
    ///
    /// # Errors
    /// [`CliError::Geometry`] naming the bad field (or listing the registered shapes).
    pub fn build(&self) -> Result<Obstacle, CliError> {
        Ok(capstan_geometry::registry::build(
            &self.shape,
            &self.settings()?,
        )?)
    }
}

/// `[friction]`.
///
/// Unknown keys are refused by the scene's key check ([`known_keys`](super::known_keys): the fields below and the
/// parameters of every registered law, [`capstan_friction::registry`]), so `extra` holds only
/// parameters of laws registered outside the friction crate.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct FrictionSpec {
    /// The friction law (`coulomb`: regularised Coulomb of Kikuchi–Oden; the nonsmooth
    /// `exact-coulomb` for `capstan membrane-path`).
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
    /// Work budget: panels of adaptive quadrature (prism turning angle, the general cone's
    /// nested quadrature), default `2^16`.
    pub max_subdivisions: usize,
    /// Work budget: steps of the ODE integrator (membranes with weight), default 100,000.
    pub max_steps: usize,
    /// Smallest ODE step before giving up (0, the default: the round-off floor only).
    pub min_step: f64,
    /// Work budget: iterations of `infer-mu`'s root finder (Brent), default 200.
    pub max_root_iterations: usize,
    /// Work budget: Newton iterations of the membrane displacement model
    /// (`infer-mu --model membrane`), default 100.
    pub max_newton_iterations: usize,
    /// Nodes of the membrane displacement model on `[theta0, theta_max]` (`capstan
    /// membrane-path`), default 801.
    pub nodes: usize,
    /// `finite` (default: Theorem 1, tension `T` of a membrane of width `loads.width` and
    /// thickness `loads.thickness`) | `infinite` (Corollary 1: the tensile stress `tau` of a
    /// membrane infinitely long in `x1`, any Poisson's ratio; `membrane.t0` is `tau0`, the loads
    /// are volume densities, `loads.width` and `loads.thickness` are not used).
    pub model: MembraneModel,
    /// How a steady belt speed `loads.speed` enters: `corrected` (default: the acceleration is
    /// normal to the path, only the normal load changes) | `paper` (the printed transform, which
    /// also adds `g_r2 = -rho_l Gamma^2_22 V^2`; erratum 4).
    pub belt_speed_rule: BeltSpeedRule,
}

/// `membrane.model`: which of the paper's membrane results a scene computes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum MembraneModel {
    /// Theorem 1: a membrane of finite width with zero Poisson's ratio; tension `T` (force).
    #[default]
    Finite,
    /// Corollary 1: infinitely long in `x1`, any Poisson's ratio; tensile stress `tau`.
    Infinite,
}

/// `membrane.belt_speed_rule`: the steady-speed transform (erratum 4).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum BeltSpeedRule {
    /// Only the normal load changes: `g_r3 -> g_r3 + 2 rho_l H V^2`.
    #[default]
    Corrected,
    /// The paper's printed rule: also `g_r2 -> g_r2 - rho_l Gamma^2_22 V^2`.
    Paper,
}

impl MembraneSpec {
    /// The work budgets of the membrane models (`membrane.max_subdivisions`, `max_steps`,
    /// `min_step`, `max_root_iterations`).
    pub fn budget(&self) -> capstan_friction::membrane::MembraneBudget {
        capstan_friction::membrane::MembraneBudget {
            max_subdivisions: self.max_subdivisions,
            max_steps: self.max_steps,
            min_step: self.min_step,
            max_root_iterations: self.max_root_iterations,
        }
    }
}

impl Default for MembraneSpec {
    fn default() -> Self {
        Self {
            t0: 1.0,
            theta0: -FRAC_PI_2,
            theta_max: FRAC_PI_2,
            samples: 101,
            t_max: None,
            max_subdivisions: capstan_friction::membrane::MembraneBudget::default()
                .max_subdivisions,
            max_steps: capstan_friction::membrane::MembraneBudget::default().max_steps,
            min_step: 0.0,
            max_root_iterations: capstan_friction::membrane::MembraneBudget::default()
                .max_root_iterations,
            max_newton_iterations: 100,
            nodes: 801,
            model: MembraneModel::default(),
            belt_speed_rule: BeltSpeedRule::default(),
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
    /// Tangential force density `f_t(t)` on the membrane, an expression in `t = x2 = theta`:
    /// force per unit length along the unit tangent (towards `theta_max`); a volume density
    /// with `membrane.model = "infinite"`. Adds to gravity and speed.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub f_t: Option<String>,
    /// Normal force density `f_n(t)` on the membrane, an expression in `t`: force per unit
    /// length along the outward normal (away from the obstacle).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub f_n: Option<String>,
    /// A body force on the thick body (force per unit volume): its physical components along
    /// the body's coordinate lines as expressions, `[f<2>, f<3>]` in `x2`, `x3` for
    /// `body.dimension = 2`, `[f<1>, f<2>, f<3>]` in `x1`, `x2`, `x3` for 3 (see
    /// [`capstan_elasticity::contact::BodyForceField`]). Held at its full value while the
    /// solvers drive the end tractions.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub body_force: Option<Vec<String>>,
    /// A load path: the end load at `theta_max` in successive states, each solved from the
    /// previous one with friction on the slip increment (`capstan membrane-path`: the
    /// membrane's tension at `theta_max`, starting from the membrane wrapped at the uniform
    /// tension `membrane.t0`), e.g. `[2.0, 1.0, 2.0]`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub path: Option<Vec<f64>>,
}

impl Default for LoadsSpec {
    /// The membrane's defaults ([`MembraneLoads::default`]), end tractions `tau0 = 1`,
    /// `tau_max = 2`.
    fn default() -> Self {
        let MembraneLoads {
            gravity,
            density,
            width,
            thickness,
            speed,
        } = MembraneLoads::default();
        Self {
            gravity,
            density,
            width,
            thickness,
            speed,
            tau0: 1.0,
            tau_max: 2.0,
            f_t: None,
            f_n: None,
            body_force: None,
            path: None,
        }
    }
}

impl LoadsSpec {
    /// The load expressions `loads.f_t`, `loads.f_n` (none given: an empty load).
    ///
    /// # Errors
    /// [`capstan_friction::FrictionError::Geometry`] naming `loads.f_t` or `loads.f_n` for
    /// text that does not parse.
    pub fn expression_load(
        &self,
    ) -> Result<capstan_friction::membrane::ExpressionLoad, capstan_friction::FrictionError> {
        capstan_friction::membrane::ExpressionLoad::parse(self.f_t.as_deref(), self.f_n.as_deref())
    }

    /// The parsed `loads.body_force` of a body of `dimension` 2 or 3 (`None` when unset).
    ///
    /// # Errors
    /// [`CliError::Scene`] naming `loads.body_force`: not one expression per component
    /// (2 for `body.dimension = 2`, 3 for 3), or an expression that does not parse (its
    /// variables are `x2`, `x3`, and `x1` in 3-D).
    pub fn body_force_field(
        &self,
        dimension: u8,
    ) -> Result<Option<capstan_elasticity::contact::BodyForceField>, CliError> {
        let Some(sources) = &self.body_force else {
            return Ok(None);
        };
        let key = "loads.body_force";
        let (count, variables): (usize, &[&str]) = if dimension == 3 {
            (3, &["x1", "x2", "x3"])
        } else {
            (2, &["x2", "x3"])
        };
        if sources.len() != count {
            return Err(CliError::Scene {
                origin: key.into(),
                message: format!(
                    "`{key}` has {} expressions; body.dimension = {dimension} takes {count}: {}",
                    sources.len(),
                    if count == 3 {
                        "[f<1>, f<2>, f<3>] in x1, x2, x3"
                    } else {
                        "[f<2>, f<3>] in x2, x3"
                    }
                ),
            });
        }
        let parsed = sources
            .iter()
            .map(|src| {
                Expression::parse_in(src, variables).map_err(|e| CliError::Scene {
                    origin: key.into(),
                    message: format!("`{key}` = {src:?}: {e}"),
                })
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Some(capstan_elasticity::contact::BodyForceField::physical(
            move |x| match &parsed[..] {
                [f2, f3] => [0.0, f2.eval_at(&x[1..]), f3.eval_at(&x[1..])],
                [f1, f2, f3] => [f1.eval_at(&x), f2.eval_at(&x), f3.eval_at(&x)],
                _ => [f64::NAN; 3],
            },
        )))
    }

    /// The body forces on the membrane (every key but the thick body's end tractions).
    pub fn membrane(&self) -> MembraneLoads {
        MembraneLoads {
            gravity: self.gravity,
            density: self.density,
            width: self.width,
            thickness: self.thickness,
            speed: self.speed,
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
    /// `2` (default): plane strain on the `(x2, x3)` rectangle of a prism; `3`: the 3-D body on
    /// the box `[x1 - width/2, x1 + width/2] x [theta0, theta_max] x [0, h]` of any obstacle
    /// (prisms and cones), finite elements (`discretisation.method = fem-q1 | fem-q2`).
    pub dimension: u8,
    /// The extent of a 3-D body along `x1` (`body.dimension = 3`).
    pub width: f64,
    /// The centre of a 3-D body along `x1` (on a cone: the distance of the centre from the apex
    /// along the axis, above `width/2`).
    pub x1: f64,
    /// The side faces `x1 = const` of a 3-D body: `free` (default, a body of finite width) or
    /// `plane-strain` (`v^1 = 0`: the 2-D body extruded).
    pub sides: SideFaces,
}

impl Default for BodySpec {
    fn default() -> Self {
        Self {
            thickness: 1.0,
            young: 1e3,
            poisson: 0.25,
            dimension: 2,
            width: 1.0,
            x1: 1.0,
            sides: SideFaces::Free,
        }
    }
}
