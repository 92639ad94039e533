//! Scene files: a complete, validated description of a run (TOML + `--set KEY=VALUE`).
//!
//! Every key has a default, so an empty scene is the paper's default setting (section 3:
//! semi-elliptical prism `a = b = 2`, `nu_F = 1/2`, `tau0 = 1`, `tau_max = 2`, `h = 1`,
//! `E = 1e3`, `nu = 1/4`, `eps = 1e-5`, grid 250 x 41). Keys are a public contract: they are
//! only ever added, never renamed.

use capstan_elasticity::ElasticityError;
use capstan_elasticity::finite_element::{DiscretisationMethod, Grading, VolumetricIntegration};
use capstan_elasticity::solvers::LinearBackend;
use capstan_friction::{AnyFrictionParams, FrictionLawKind};
use capstan_geometry::GeometryError;
use capstan_geometry::expression::Expression;
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
mod problem_specs;
#[cfg(test)]
mod tests;
mod validate;

use memory::EXPRESSION_CHECK_SAMPLES;
pub use memory::{
    MAX_N2, MAX_N3, MAX_SAMPLES, MEMORY_BYTES_PER_N_LOG_N, PETSC_MEMORY_PLANE, PETSC_MEMORY_SOLID,
    PetscMemory, PetscMemoryRefusal, SOLID_BYTES_PER_N_4_3,
    SOLID_MATRIX_FREE_BYTES_PER_CHART_POINT, SOLID_MATRIX_FREE_BYTES_PER_COARSE_UNKNOWN,
    available_memory, human_bytes, memory_estimate, mpi_ranks, petsc_memory, petsc_memory_check,
    petsc_memory_estimate_per_rank, solid_fill_factor, solid_matrix_free_bytes_per_unknown,
    solid_matrix_free_memory_estimate, solid_memory_estimate, solid_multigrid_memory_estimate,
};
pub use origins::Origins;
pub use problem_specs::{
    BeltSpeedRule, BodySpec, FrictionSpec, LoadsSpec, MembraneModel, MembraneSpec, ObstacleSpec,
};
