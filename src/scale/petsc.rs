//! `mpirun -n K capstan contact scene.toml --set solver.linear='"petsc"'` (feature `petsc`):
//! PETSc running for the length of one command.
//!
//! Every rank runs the whole command: it reads the scene and owns a contiguous block of rows
//! (whole nodes: [`capstan_petsc::owned_blocks`]). On more than one rank a
//! [`capstan_petsc::PetscDistribution`] is installed, so the 3-D body assembles only its rows
//! and the contact model gathers its residuals, evaluates the friction law on the contact
//! sites of its rows and sums its stick/slip counts over the ranks; the plane-strain body is
//! assembled whole on every rank. On the 3-D body the full-system Newton holds its vectors as
//! each rank's rows (`capstan_solvers::DistributedNewton`; `-capstan_owned_newton false` keeps
//! them whole) and each step is one distributed PETSc solve on those rows; the continuation and
//! the outputs read the converged iterate whole. Rank 0 alone prints and writes the outputs;
//! the other ranks end quietly when the solve is done.

use capstan_petsc::Session;

use crate::error::CliError;
use crate::scene::Scene;

/// PETSc for one command.
#[derive(Debug)]
pub struct PetscRun {
    session: Session,
}

impl PetscRun {
    /// Starts PETSc when the scene asks for it (`solver.linear = "petsc"`) with
    /// `solver.petsc_options`; `None` otherwise. Ranks other than 0 are made quiet (no
    /// progress output).
    ///
    /// # Errors
    /// [`CliError::Scene`] naming `solver.petsc_options` when PETSc refuses to start or the
    /// options cannot be passed to it.
    pub fn start(scene: &Scene) -> Result<Option<Self>, CliError> {
        if scene.solver.linear != "petsc" {
            return Ok(None);
        }
        let options = scene.solver.petsc_options.as_deref().unwrap_or("");
        let session = Session::start(options).map_err(|e| CliError::Scene {
            origin: "solver.petsc_options".into(),
            message: e.to_string(),
        })?;
        if session.rank() != 0 {
            crate::progress::set_flags(true, 0);
        }
        if session.size() > 1 {
            // the 3-D body assembles this rank's rows only; residuals gathered
            let distribution =
                capstan_petsc::PetscDistribution::new(&session).map_err(|e| CliError::Scene {
                    origin: "solver.linear".into(),
                    message: e.to_string(),
                })?;
            capstan_elasticity::solvers::row_distribution::install(std::sync::Arc::new(
                distribution,
            ));
        }
        Ok(Some(Self { session }))
    }

    /// Whether this process is rank 0 (the one that prints and writes).
    pub fn is_root(&self) -> bool {
        self.session.rank() == 0
    }

    /// The number of ranks.
    pub fn ranks(&self) -> usize {
        self.session.size()
    }

    /// Peak resident memory of this rank so far, bytes (PETSc's measure).
    pub fn peak_memory(&self) -> f64 {
        self.session.peak_memory().unwrap_or(0.0)
    }

    /// Ends PETSc (and MPI) on a rank other than 0 and exits with status 0; rank 0 returns
    /// and ends PETSc when `self` is dropped, after writing.
    pub fn end_unless_root(self) -> Self {
        if self.is_root() {
            return self;
        }
        drop(self);
        std::process::exit(0)
    }
}
