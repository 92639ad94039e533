//! [`Scene::build`]: the one place a scene's values become the typed [`Problem`].

use capstan_elasticity::Material;

use super::Scene;
use crate::error::CliError;
use crate::problem::{
    Body, Dimension, EndLoads, Friction, Problem, SolveMethod, Solver, nonlinear_registry,
};

impl Scene {
    /// The thick-body contact problem the scene describes: `obstacle.*`, `body.*`, `grid.*`,
    /// `discretisation.*`, the contact interval `[membrane.theta0, membrane.theta_max]`,
    /// `friction.*`, the end tractions `loads.tau0`, `loads.tau_max`, the body force
    /// `loads.body_force` and `solver.*`.
    ///
    /// # Errors
    /// [`CliError::Scene`] naming the key: a cone under a plane-strain body
    /// (`obstacle.shape`), a 3-D body reaching the cone's apex (`body.x1`), an unknown solver
    /// (`solver.linear`, `solver.nonlinear`); the constructors' errors (material,
    /// discretisation, friction law), which name their scene keys.
    pub fn build(&self) -> Result<Problem, CliError> {
        let obstacle = self.obstacle.build()?;
        let b = &self.body;
        let dimension = if b.dimension == 3 {
            let x1 = [b.x1 - 0.5 * b.width, b.x1 + 0.5 * b.width];
            if obstacle.is_cone() && x1[0] <= 0.0 {
                return Err(CliError::Scene {
                    origin: "body.x1".into(),
                    message: format!(
                        "`body.x1` = {} puts the body's side x1 = {} at or past the cone's apex (x1 = 0); allowed: body.x1 > body.width / 2 = {}",
                        b.x1,
                        x1[0],
                        0.5 * b.width
                    ),
                });
            }
            Dimension::Solid {
                x1,
                n1: self.grid.n1,
                sides: b.sides,
            }
        } else {
            if !obstacle.is_prism() {
                return Err(CliError::Scene {
                    origin: "obstacle.shape".into(),
                    message: "the plane-strain thick body needs a prism (cylinder, ellipse or prism); a cone needs body.dimension = 3".into(),
                });
            }
            Dimension::Plane
        };
        let d = &self.discretisation;
        let body = Body {
            surface: obstacle,
            dimension,
            theta: [self.membrane.theta0, self.membrane.theta_max],
            thickness: b.thickness,
            material: Material::new(b.young, b.poisson)?,
            n2: self.grid.n2,
            n3: self.grid.n3,
            method: d.method,
            settings: d.settings()?,
            body_force: self.loads.body_force_field(b.dimension)?,
            contact: self.contact.kind()?,
        };
        Ok(Problem {
            body,
            friction: Friction::named(self.friction.law.clone(), self.friction.settings()),
            loads: EndLoads::new(self.loads.tau0, self.loads.tau_max),
            solver: Solver {
                method: self.solve_method()?,
                budgets: self.solver.contact_settings(),
                max_sweeps: self.solver.max_sweeps,
                relaxation: self.solver.relaxation,
            },
        })
    }

    /// The solver `solver.nonlinear` and `solver.linear` name.
    ///
    /// # Errors
    /// [`CliError::Scene`] for an unknown name, or `multigrid` with another method than
    /// `full-newton`.
    fn solve_method(&self) -> Result<SolveMethod, CliError> {
        let s = &self.solver;
        crate::features::register_feature_backends();
        if s.linear == "petsc" && !crate::features::PETSC_ENABLED {
            return Err(CliError::Scene {
                origin: "solver.linear".into(),
                message: "`solver.linear` = \"petsc\" needs a build with the cargo feature `petsc` (cargo build --release --features petsc); the Python package is built without it (its wheel links no system PETSc or Open MPI, and the PETSc session lives for one CLI command: MPI cannot start again in a process once it has ended, so a Python process could solve once at most); from Python, run the CLI under mpirun: subprocess.run([\"mpirun\", \"-n\", \"2\", \"capstan\", \"contact\", ...]) (docs/scale-out.md, Python)".into(),
            });
        }
        if matches!(s.linear.as_str(), "multigrid" | "petsc" | "matrix-free-mg")
            && s.nonlinear != "full-newton"
        {
            return Err(CliError::Scene {
                origin: "solver.linear".into(),
                message: format!(
                    "`solver.linear` = \"{}\" is the bulk solver of `solver.nonlinear` = \"full-newton\", not of `{}`",
                    s.linear, s.nonlinear
                ),
            });
        }
        let linear = s
            .linear
            .parse()
            .map_err(
                |e: capstan_elasticity::solvers::SolverError| CliError::Scene {
                    origin: "solver.linear".into(),
                    message: e.to_string(),
                },
            )?;
        Ok(nonlinear_registry::build(
            &s.nonlinear,
            &nonlinear_registry::NonlinearSettings { linear },
        )?)
    }
}
