//! Scene files: a complete, validated description of a run (TOML + `--set KEY=VALUE`).
//!
//! Every key has a default, so an empty scene is the paper's default setting (section 3:
//! semi-elliptical prism `a = b = 2`, `nu_F = 1/2`, `tau0 = 1`, `tau_max = 2`, `h = 1`,
//! `E = 1e3`, `nu = 1/4`, `eps = 1e-5`, grid 250 x 41). Keys are a public contract: they are
//! only ever added, never renamed.

use std::f64::consts::FRAC_PI_2;

use capstan_elasticity::ElasticityError;
use capstan_elasticity::finite_element::{DiscretisationMethod, Grading, VolumetricIntegration};
use capstan_elasticity::solid::SideFaces;
use capstan_elasticity::solvers::LinearBackend;
use capstan_friction::membrane::MembraneLoads;
use capstan_friction::{AnyFrictionParams, FrictionLawKind, FrictionSettings};
use capstan_geometry::GeometryError;
use capstan_geometry::expression::Expression;
use capstan_geometry::{Obstacle, ObstacleSettings};
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
    /// `[output]`: how files are written.
    pub output: OutputSpec,
    /// `[contact]`: the kind of contact on the thick body's face `x3 = 0`.
    pub contact: ContactSpec,
    /// `[accuracy]`: an accuracy target (capstan chooses discretisation and grid).
    pub accuracy: AccuracySpec,
}

/// `[accuracy]`: with `tol` set, `contact`, `threshold`, `sweep` and `figure` choose the
/// discretisation and grid themselves and refine until every reported quantity's estimated
/// error is below `tol` relative ([`crate::problem::AccuracyTarget`]); `grid.*` and
/// `discretisation.*` are then not used (plane strain; a 3-D body refines its own grid).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct AccuracySpec {
    /// The relative tolerance, `1e-9 ..= 0.1`; unset (default): the scene's own grid.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tol: Option<f64>,
    /// The work budget: the most unknowns a refinement step may have (default 300,000).
    pub max_unknowns: usize,
}

impl Default for AccuracySpec {
    fn default() -> Self {
        Self {
            tol: None,
            max_unknowns: crate::problem::AccuracyTarget::DEFAULT_MAX_UNKNOWNS,
        }
    }
}

/// `[contact]`: bilateral (the paper's `v^3 = 0`, default) or unilateral (Signorini) contact
/// on the thick body's face `x3 = 0`, with an initial gap.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ContactSpec {
    /// `bilateral` (default) or `unilateral`.
    pub kind: String,
    /// The initial gap `g >= 0` between the face and the obstacle (unilateral only): an
    /// expression in `t = x2` (the angle on a circle), the same for every `x1`; default `"0"`
    /// (a conforming body).
    pub gap: String,
}

impl Default for ContactSpec {
    fn default() -> Self {
        Self {
            kind: "bilateral".into(),
            gap: "0".into(),
        }
    }
}

impl ContactSpec {
    /// The contact kind the keys describe.
    ///
    /// # Errors
    /// [`CliError::Scene`] naming `contact.kind` for an unknown kind, `contact.gap` for a gap
    /// that does not parse or is given with bilateral contact.
    pub fn kind(&self) -> Result<capstan_elasticity::contact::ContactKind, CliError> {
        use capstan_elasticity::contact::{ContactKind, Gap};
        match self.kind.as_str() {
            "bilateral" => match self.gap.trim() {
                "0" => Ok(ContactKind::Bilateral),
                _ => Err(CliError::Scene {
                    origin: "contact.gap".into(),
                    message: "`contact.gap` needs `contact.kind = \"unilateral\"` (bilateral contact keeps v^3 = 0)".into(),
                }),
            },
            "unilateral" => {
                let text = &self.gap;
                let gap = Expression::parse(text).map_err(|e| CliError::Scene {
                    origin: "contact.gap".into(),
                    message: format!("`contact.gap` = {text:?}: {e}"),
                })?;
                Ok(ContactKind::Unilateral {
                    gap: Gap::new(move |x: [f64; 2]| gap.eval(x[1])),
                })
            }
            other => Err(CliError::Scene {
                origin: "contact.kind".into(),
                message: format!(
                    "`contact.kind` = {other:?} is not a contact kind; allowed: {}",
                    ContactKind::NAMES.join(", ")
                ),
            }),
        }
    }
}

impl AccuracySpec {
    /// The target `tol` asks for, `None` without one.
    ///
    /// # Errors
    /// [`CliError::Elasticity`] naming `accuracy.tol` outside its range.
    pub fn target(&self) -> Result<Option<crate::problem::AccuracyTarget>, CliError> {
        self.tol
            .map(|tol| {
                Ok(crate::problem::AccuracyTarget::new(tol)?.with_max_unknowns(self.max_unknowns))
            })
            .transpose()
    }
}

/// `[output]`: how `--out` writes its files (the numbers are the same either way).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct OutputSpec {
    /// `none` (default) | `zlib`: VTU arrays compressed with zlib (VTK's
    /// `vtkZLibDataCompressor`; ParaView, VTK and meshio read both).
    pub vtu_compression: crate::output::VtuCompression,
    /// `true`: body VTU files get the obstacle surface (a ribbon of `sigma` around the contact
    /// interval) as a second piece, so ParaView shows body and obstacle together. Off by
    /// default: a reader that merges pieces (meshio) then sees both meshes as one.
    pub vtu_obstacle: bool,
    /// Where `capstan contact` reports the normal stress `sigma_n` of the contact face
    /// (`normal_stress_probes`): `x2` values inside `[membrane.theta0, membrane.theta_max]`
    /// (a 3-D body: on the middle `x1` line). Unset: the quarter points of the interval.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub probe_x2: Option<Vec<f64>>,
    /// `true` (default): `capstan contact` and `capstan threshold` solve again one grid level
    /// coarser and report `estimated_error` for every converging quantity
    /// (`src/commands/accuracy.rs`); `false` skips that solve.
    pub error_estimate: bool,
}

impl Default for OutputSpec {
    fn default() -> Self {
        Self {
            vtu_compression: crate::output::VtuCompression::default(),
            vtu_obstacle: false,
            probe_x2: None,
            error_estimate: true,
        }
    }
}

/// `[obstacle]`.
///
/// `shape` names a registered obstacle ([`capstan_geometry::registry`]); the fields below are
/// the parameters of the paper's obstacles, and any other key of the table (a parameter of an
/// obstacle registered elsewhere, a number or an expression) is in `extra`. Unknown keys are
/// refused by the scene's key check ([`known_keys`]).
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
/// Unknown keys are refused by the scene's key check ([`known_keys`]: the fields below and the
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

/// `[grid]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct GridSpec {
    /// Points along `x2`.
    pub n2: usize,
    /// Points along `x3` (through the thickness).
    pub n3: usize,
    /// Points along `x1` (across the width of a 3-D body, `body.dimension = 3`).
    pub n1: usize,
}

impl Default for GridSpec {
    fn default() -> Self {
        Self {
            n2: 250,
            n3: 41,
            n1: 5,
        }
    }
}

/// `[solver]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SolverSpec {
    /// `lu | cholesky | jacobi | gauss-seidel | multigrid | petsc` (`multigrid`: GMRES with the
    /// geometric multigrid of the 3-D body, `full-newton` only; `petsc`: PETSc's KSP over the
    /// MPI ranks of `mpirun`, `full-newton` only, builds with the feature `petsc`).
    pub linear: String,
    /// `auto | newton | full-newton | jacobi-newton` (`auto`, the default: the method
    /// [`crate::problem::Solver::resolved`] picks, `newton` today; the choice is
    /// `solver_choice` in the report).
    pub nonlinear: String,
    /// Work budget: contact Newton iterations per load step (every nonlinear solver; with
    /// `full-newton` per grid-sequencing level too), default 60.
    pub max_iterations: usize,
    /// Work budget: steps of the load continuation (and of the slip homotopy), default 400.
    pub max_continuation_steps: usize,
    /// Smallest load step of the continuation before giving up, default `1e-4`.
    pub min_load_step: f64,
    /// Work budget: Jacobi / Gauss–Seidel sweeps per linear solve (`solver.linear = "jacobi"`
    /// or `"gauss-seidel"`, and `jacobi-newton`), GMRES / CG iterations per linear solve with
    /// `"multigrid"`; unset: 10,000 (10^7 for `jacobi-newton`, 500 for `multigrid`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_sweeps: Option<usize>,
    /// The relaxation weight `w` in `(0, 2)` of the Jacobi / Gauss–Seidel iterations
    /// (`x += w D^-1 (b - A x)`; `w < 1` damps Jacobi, `w > 1` is SOR): the library's
    /// `IterativeParams::relaxation`. Unset: 1, and 1/2 for `jacobi-newton`; `1` is the
    /// paper's undamped Jacobi.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub relaxation: Option<f64>,
    /// PETSc options for `solver.linear = "petsc"`, in PETSc's command-line syntax, over the
    /// defaults `-ksp_type gmres -ksp_gmres_restart 100 -pc_type gamg -mg_levels_ksp_type
    /// chebyshev -mg_levels_pc_type sor -ksp_rtol 1e-8 -ksp_max_it 2000` (e.g. `"-ksp_type cg -pc_type gamg"`, or MUMPS:
    /// `"-ksp_type preonly -pc_type lu -pc_factor_mat_solver_type mumps"`); unset: the defaults.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub petsc_options: Option<String>,
}

impl SolverSpec {
    /// Whether the contact problem is solved condensed (`newton`, or `auto`, which condenses
    /// every body today: [`crate::problem::Solver::resolved`]).
    pub fn condenses(&self) -> bool {
        let settings = crate::problem::nonlinear_registry::NonlinearSettings::default();
        crate::problem::nonlinear_registry::find(&self.nonlinear)
            .and_then(|m| (m.build)(&settings).ok())
            .is_some_and(|m| m.condenses())
    }

    /// Whether the contact problem is solved by the matrix-free Newton
    /// (`solver.linear = "matrix-free-mg"` with `full-newton`).
    pub fn matrix_free(&self) -> bool {
        self.nonlinear == "full-newton" && self.linear == "matrix-free-mg"
    }
}

impl Default for SolverSpec {
    fn default() -> Self {
        let contact = capstan_elasticity::contact::ContactSettings::default();
        Self {
            linear: "lu".into(),
            nonlinear: "auto".into(),
            max_iterations: contact.max_iterations,
            max_continuation_steps: contact.max_continuation_steps,
            min_load_step: contact.min_load_step,
            max_sweeps: None,
            relaxation: None,
            petsc_options: None,
        }
    }
}

impl SolverSpec {
    /// The contact solvers' settings with the scene's budgets (`solver.max_iterations`,
    /// `max_continuation_steps`, `min_load_step`) and its linear backend (`solver.linear`, for
    /// the condensed bulk).
    pub fn contact_settings(&self) -> capstan_elasticity::contact::ContactSettings {
        capstan_elasticity::contact::ContactSettings {
            // (`validate` refused a name that no backend is registered under)
            linear: self.linear.parse().unwrap_or_default(),
            max_iterations: self.max_iterations,
            max_continuation_steps: self.max_continuation_steps,
            min_load_step: self.min_load_step,
            ..Default::default()
        }
    }
}

/// `[discretisation]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct DiscretisationSpec {
    /// `fd` (finite differences, the default) | `fem-q1` | `fem-q2` (finite elements on the
    /// same grid; Q2 needs odd `grid.n2`, `grid.n3`) | `fem-qp` (tensor-product elements of
    /// order `discretisation.order` with GLL nodes; `grid.n2 - 1`, `grid.n3 - 1` multiples of
    /// it).
    pub method: DiscretisationMethod,
    /// The order `p` of `fem-qp`, `1..=10` (default 4). Other methods refuse any other value.
    pub order: usize,
    /// `full` (default) | `reduced`: how the finite elements integrate the volumetric part
    /// `lambda (div v)(div w) sqrt(g)` of the stiffness; `reduced` is selective reduced
    /// integration (Q1: 1 point, Q2: 2 x 2; the shear part keeps the full rule), the remedy
    /// for volumetric locking as `body.poisson -> 1/2`. `fd` accepts only `full`.
    pub volumetric: VolumetricIntegration,
    /// The ratio `sigma` of geometrically graded `fem-qp` elements toward both ends of `x2` and
    /// `x3` (`0.05 <= sigma <= 1`, `1` uniform; absent: uniform elements). With `n` layers the
    /// uniform partition into `e - 2n + 2` elements of size `H` has its two end elements split
    /// into layers `H sigma^k`, `k = 0 ... n - 1` (the hp meshes of the corner singularities:
    /// [`Grading`]). Only with `discretisation.method = "fem-qp"` and `body.dimension = 2`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub grading: Option<f64>,
    /// Geometric layers per graded end, `1..=12` (default [`DiscretisationSpec::DEFAULT_LAYERS`]);
    /// needs `discretisation.grading` and at least `2 n` elements along `x2` and `x3`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub layers: Option<usize>,
    /// Geometric layers per corner of `fem-qp-corner`, `0..=16` (absent: 5; `0` is the uniform
    /// `fem-qp` mesh): each corner cell of the grid's `e2 x e3` element cells is cut into that
    /// many L-shaped layers of two trapezoids. Only with `discretisation.method = "fem-qp-corner"`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub corner_layers: Option<usize>,
    /// The ratio of successive corner layers of `fem-qp-corner`, `0.05..=0.95` (absent: 0.3).
    /// Only with `discretisation.method = "fem-qp-corner"`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub corner_ratio: Option<f64>,
}

impl Default for DiscretisationSpec {
    fn default() -> Self {
        Self {
            method: DiscretisationMethod::default(),
            order: DiscretisationMethod::DEFAULT_ORDER,
            volumetric: VolumetricIntegration::default(),
            grading: None,
            layers: None,
            corner_layers: None,
            corner_ratio: None,
        }
    }
}

impl DiscretisationSpec {
    /// `discretisation.layers` when only `discretisation.grading` is given: 4 layers, the
    /// smallest element `H sigma^3` (`sigma = 0.15 ... 0.5`, Schwab's range, gives `3e-3 H ...
    /// 0.125 H`).
    pub const DEFAULT_LAYERS: usize = 4;

    /// The element grading of `fem-qp`: [`Grading::UNIFORM`] without `discretisation.grading`,
    /// else geometric with `discretisation.layers` (default [`Self::DEFAULT_LAYERS`]) layers.
    ///
    /// # Errors
    /// [`ElasticityError::InvalidParameter`] naming `discretisation.grading` (ratio outside
    /// `[0.05, 1]`) or `discretisation.layers` (outside `1..=12`).
    pub fn grading(&self) -> Result<Grading, ElasticityError> {
        self.grading_only()
    }

    /// The settings of the registered method (order, volumetric rule, grading, corner keys).
    ///
    /// # Errors
    /// See [`DiscretisationSpec::grading`].
    pub fn settings(
        &self,
    ) -> Result<capstan_elasticity::registration::DiscretisationSettings, ElasticityError> {
        use capstan_elasticity::registration::DiscretisationSettings as S;
        Ok(S {
            order: self.order,
            volumetric: self.volumetric,
            grading: self.grading()?,
            corner_layers: self.corner_layers.unwrap_or(S::DEFAULT_CORNER_LAYERS),
            corner_ratio: self.corner_ratio.unwrap_or(S::DEFAULT_CORNER_RATIO),
            ..Default::default()
        })
    }

    /// [`DiscretisationSpec::grading`].
    fn grading_only(&self) -> Result<Grading, ElasticityError> {
        match self.grading {
            None => Ok(Grading::UNIFORM),
            Some(ratio) => Grading::geometric(ratio, self.layers.unwrap_or(Self::DEFAULT_LAYERS)),
        }
    }
}

/// Every key a scene accepts, as dotted names (from the defaults, plus optional keys).
pub fn known_keys() -> Vec<String> {
    let table = toml::Table::try_from(Scene::default()).expect("the default scene serialises");
    let mut keys = vec![
        "membrane.t_max".to_string(),
        "solver.max_sweeps".to_string(),
        "solver.relaxation".to_string(),
        "solver.petsc_options".to_string(),
        "discretisation.grading".to_string(),
        "discretisation.layers".to_string(),
        "discretisation.corner_layers".to_string(),
        "discretisation.corner_ratio".to_string(),
        "loads.f_t".to_string(),
        "loads.f_n".to_string(),
        "loads.body_force".to_string(),
        "loads.path".to_string(),
        "accuracy.tol".to_string(),
    ];
    for law in capstan_friction::registry::registry() {
        keys.extend(law.parameters.iter().map(|p| format!("friction.{p}")));
    }
    for law in capstan_friction::registry::nonsmooth_registry() {
        keys.extend(law.parameters.iter().map(|p| format!("friction.{p}")));
    }
    for obstacle in capstan_geometry::registry::registry() {
        keys.extend(
            obstacle
                .parameters
                .iter()
                .map(|p| format!("obstacle.{}", p.key)),
        );
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

mod build;
mod follow;
mod load;
mod memory;
mod origins;
#[cfg(test)]
mod tests;
mod validate;

use memory::EXPRESSION_CHECK_SAMPLES;
pub use memory::{
    MAX_N2, MAX_N3, MAX_SAMPLES, MEMORY_BYTES_PER_N_LOG_N, PETSC_MEMORY_PLANE, PETSC_MEMORY_SOLID,
    PetscMemory, PetscMemoryRefusal, SOLID_BYTES_PER_N_4_3, available_memory, human_bytes,
    memory_estimate, mpi_ranks, petsc_memory, petsc_memory_check, petsc_memory_estimate_per_rank,
    solid_fill_factor, solid_matrix_free_bytes_per_unknown, solid_matrix_free_memory_estimate,
    solid_memory_estimate, solid_multigrid_memory_estimate,
};
pub use origins::Origins;
