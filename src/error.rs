//! The command line's error type and exit codes.

use capstan_friction::{ErrorCategory, FrictionError};
use capstan_geometry::GeometryError;

/// Everything the command line can report; each maps to an exit code.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum CliError {
    /// A file could not be read or written.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: String,
        /// The underlying error.
        source: std::io::Error,
    },
    /// The scene is malformed (TOML syntax, unknown key, wrong type).
    #[error("scene {origin}: {message}")]
    Scene {
        /// File name or `--set`.
        origin: String,
        /// What is wrong, naming the key.
        message: String,
    },
    /// A `--set KEY=VALUE` argument is malformed.
    #[error("--set {set}: {message}")]
    Set {
        /// The argument.
        set: String,
        /// What is wrong.
        message: String,
    },
    /// An obstacle parameter or expression is invalid.
    #[error(transparent)]
    Geometry(#[from] GeometryError),
    /// An elasticity problem failed (bad material, grid or boundary data: exit code 2).
    #[error(transparent)]
    Elasticity(capstan_elasticity::ElasticityError),
    /// A membrane capstan model failed: bad input (exit code 2), no limiting equilibrium on
    /// the interval (lift-off, slack, non-convex, no `mu`: 3), or non-convergence (4).
    #[error(transparent)]
    Friction(FrictionError),
    /// A thick-body contact problem failed: bad input (exit code 2), no static equilibrium
    /// (tension ratio beyond what friction holds: 3), or non-convergence (4).
    #[error(transparent)]
    Contact(capstan_elasticity::contact::ContactError),
    /// A thick-body solve ran out of a work budget that scene keys set (exit code 4): the
    /// contact error, then the budget keys with their values and what to change.
    #[error("{source}; work budget: {budget}")]
    ContactBudget {
        /// The solver's error.
        source: capstan_elasticity::contact::ContactError,
        /// The scene keys with their values and what to change.
        budget: String,
    },
    /// The run passed its `--timeout` (exit code 5, status `timed out`); nothing was written.
    #[error(
        "timed out after {seconds} s (--timeout {seconds}): no output was written; raise --timeout"
    )]
    TimedOut {
        /// The limit.
        seconds: f64,
    },
    /// An output file could not be written (I/O, NaN refused, malformed data).
    #[error(transparent)]
    Output(#[from] crate::output::OutputError),
    /// `capstan verify`: a study's observed L2 order fell short of its expected order (exit
    /// code 6). `output` is the report (table or JSON), printed to stdout before the error.
    #[error("{} of the studies missed the expected order of convergence: {}", missed.len(), missed.join("; "))]
    VerificationFailed {
        /// The whole report, as the command prints it on success.
        output: String,
        /// The studies that missed, with observed and expected orders.
        missed: Vec<String>,
    },
    /// An accuracy target (`accuracy.tol`) was not reached within its work budget
    /// (`accuracy.max_unknowns`; exit code 4).
    #[error("{message}")]
    AccuracyNotReached {
        /// What was reached, naming the keys.
        message: String,
    },
    /// Sweep parts that cannot be run or merged (bad `--shard`, parts that do not belong
    /// together, missing or duplicate points: exit code 2).
    #[error(transparent)]
    Shard(#[from] crate::shard_error::ShardError),
}

/// The scene key of a library constructor's API parameter: the library's errors name the
/// parameter (`Material::new`: `young`, `poisson`; the friction laws' parameters: `mu`, `eps`,
/// ...; `ContactModel::new`: `slip_threshold`), the command line's the key a scene sets.
/// Names without a scene key (and names that are scene keys already) are kept.
///
/// `friction` picks the friction law's keys (`mu` is `friction.mu` there).
pub fn scene_key(field: &'static str, friction: bool) -> &'static str {
    const FRICTION: [(&str, &str); 6] = [
        ("mu", "friction.mu"),
        ("mu2", "friction.mu2"),
        ("eps", "friction.eps"),
        ("bound", "friction.bound"),
        ("exponent", "friction.exponent"),
        ("axis_angle", "friction.axis_angle"),
    ];
    const ELASTICITY: [(&str, &str); 3] = [
        ("young", "body.young"),
        ("poisson", "body.poisson"),
        ("slip_threshold", "friction.eps"),
    ];
    let table: &[(&str, &str)] = if friction { &FRICTION } else { &ELASTICITY };
    table
        .iter()
        .find(|(api, _)| *api == field)
        .map_or(field, |(_, key)| key)
}

/// `e` with an invalid parameter named by its scene key ([`scene_key`]).
fn keyed_friction(e: FrictionError) -> FrictionError {
    match e {
        FrictionError::InvalidParameter {
            field,
            value,
            allowed,
        } => FrictionError::InvalidParameter {
            field: scene_key(field, true),
            value,
            allowed,
        },
        other => other,
    }
}

/// `e` with an invalid parameter named by its scene key ([`scene_key`]).
fn keyed_elasticity(e: capstan_elasticity::ElasticityError) -> capstan_elasticity::ElasticityError {
    use capstan_elasticity::ElasticityError;
    match e {
        ElasticityError::InvalidParameter {
            field,
            value,
            allowed,
        } => ElasticityError::InvalidParameter {
            field: scene_key(field, false),
            value,
            allowed,
        },
        other => other,
    }
}

impl From<FrictionError> for CliError {
    fn from(e: FrictionError) -> Self {
        Self::Friction(keyed_friction(e))
    }
}

impl From<capstan_elasticity::ElasticityError> for CliError {
    fn from(e: capstan_elasticity::ElasticityError) -> Self {
        Self::Elasticity(keyed_elasticity(e))
    }
}

impl From<capstan_elasticity::contact::ContactError> for CliError {
    fn from(e: capstan_elasticity::contact::ContactError) -> Self {
        use capstan_elasticity::contact::ContactError;
        Self::Contact(match e {
            ContactError::Elasticity(e) => ContactError::Elasticity(keyed_elasticity(e)),
            ContactError::Friction(e) => ContactError::Friction(keyed_friction(e)),
            other => other,
        })
    }
}

impl From<crate::problem::ProblemError> for CliError {
    fn from(e: crate::problem::ProblemError) -> Self {
        use crate::problem::ProblemError;
        match e {
            ProblemError::Friction(e) => e.into(),
            ProblemError::Elasticity(e) => e.into(),
            ProblemError::Contact(e) => e.into(),
            e @ ProblemError::AccuracyNotReached { .. } => Self::AccuracyNotReached {
                message: e.to_string(),
            },
            e @ (ProblemError::UnknownNonlinearMethod { .. }
            | ProblemError::DuplicateNonlinearMethod { .. }) => Self::Scene {
                origin: "solver.nonlinear".into(),
                message: e.to_string(),
            },
        }
    }
}

impl CliError {
    /// What the command printed before it failed, for standard output (the report of a
    /// `capstan verify` that missed an order); `None` for every other error.
    pub fn stdout(&self) -> Option<&str> {
        match self {
            Self::VerificationFailed { output, .. } => Some(output),
            _ => None,
        }
    }

    /// Process exit code: 2 for bad input, 3 when no limiting equilibrium exists, 4 for
    /// non-convergence (a work budget ran out), 5 when stopped (`--timeout`: `timed out`; an
    /// observer's stop: `interrupted`), 6 when `capstan verify` finds a study below its
    /// expected order, 1 otherwise.
    pub fn exit_code(&self) -> i32 {
        match self {
            Self::Io { .. } | Self::Output(_) => 1,
            Self::ContactBudget { .. } | Self::AccuracyNotReached { .. } => 4,
            Self::TimedOut { .. } => 5,
            Self::VerificationFailed { .. } => 6,
            Self::Scene { .. }
            | Self::Set { .. }
            | Self::Geometry(_)
            | Self::Elasticity(_)
            | Self::Shard(_) => 2,
            Self::Contact(e) => match e.kind() {
                capstan_elasticity::contact::ContactErrorKind::InvalidInput => 2,
                capstan_elasticity::contact::ContactErrorKind::NoEquilibrium => 3,
                capstan_elasticity::contact::ContactErrorKind::NotConverged => 4,
                // stopped by its observer: a wall-clock limit (5, `timed out`)
                capstan_elasticity::contact::ContactErrorKind::Interrupted => 5,
            },
            Self::Friction(e) => match e.category() {
                ErrorCategory::InvalidInput => 2,
                ErrorCategory::NoEquilibrium => 3,
                ErrorCategory::NotConverged => 4,
                _ => 1,
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use capstan_elasticity::{ElasticityError, Material};
    use capstan_friction::RegularisedCoulombParams;

    #[test]
    fn library_errors_name_the_api_parameter_and_cli_errors_the_scene_key() {
        let e = Material::new(1.0, 0.7).unwrap_err();
        assert!(matches!(
            e,
            ElasticityError::InvalidParameter {
                field: "poisson",
                ..
            }
        ));
        assert!(
            CliError::from(e)
                .to_string()
                .contains("`body.poisson` = 0.7")
        );
        let e = RegularisedCoulombParams::new(-1.0, 1e-3).unwrap_err();
        assert!(e.to_string().contains("`mu` = -1"), "{e}");
        let cli = CliError::from(e);
        assert!(cli.to_string().contains("`friction.mu` = -1"), "{cli}");
        assert_eq!(cli.exit_code(), 2);
        // through the library API: the problem names `eps`, the CLI `friction.eps`
        let problem = crate::Problem::paper()
            .with_grid(21, 5)
            .with_friction(crate::problem::Friction::coulomb(0.5, -1.0));
        let e = problem.solve().unwrap_err();
        assert!(e.to_string().contains("`eps`"), "{e}");
        assert!(CliError::from(e).to_string().contains("`friction.eps`"));
        // an elasticity name that is not a constructor's parameter is kept
        assert_eq!(scene_key("grid.n2", false), "grid.n2");
        assert_eq!(scene_key("mu", false), "mu");
    }
}
