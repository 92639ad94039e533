//! capstan: friction between elastic bodies and rough rigid curved obstacles.
//!
//! # Quick start
//! A contact problem in code ([`Problem`]: body, friction, loads, solver; the same for 2-D and
//! 3-D bodies), or from a scene file ([`Scene::build`] is the one place scene values become a
//! `Problem`):
//! ```
//! use capstan::{Problem, Scene};
//! use capstan::problem::{EndLoads, Friction};
//! let problem = Problem::paper()
//!     .with_grid(41, 9)
//!     .with_friction(Friction::coulomb(0.5, 1e-5))
//!     .with_loads(EndLoads::new(1.0, 2.0));
//! let solved = problem.solve().unwrap();
//! assert!(solved.solution.slip_fraction > 0.0 && solved.solution.slip_fraction < 1.0);
//! // the same problem from scene keys
//! let scene = Scene::default().with_raw("grid.n2", "41", "set").unwrap().with_raw("grid.n3", "9", "set").unwrap();
//! let from_scene = scene.build().unwrap().solve().unwrap();
//! assert_eq!(from_scene.solution.slip_fraction, solved.solution.slip_fraction);
//! ```
//!
//! The studies of the command line over scenes, as library calls ([`api`]: tension,
//! infer-mu, threshold, geometry, sweep, contact; the CLI and the Python package are thin
//! layers over them):
//! ```
//! use capstan::{Scene, api};
//! // the default scene: a membrane over a semi-elliptical prism a = b = 2, mu = 1/2, half a turn
//! let scene = Scene::default();
//! let tension = api::tension(&scene).unwrap();
//! assert!((tension.tension_ratio - (0.5 * std::f64::consts::PI).exp()).abs() < 1e-9);
//! // any scene key, checked as `--set` checks it
//! let coarse = scene.with_raw("grid.n2", "41", "set").unwrap().with_raw("grid.n3", "9", "set").unwrap();
//! let (report, _) = api::contact_observed(&coarse, &mut capstan::solvers::SilentObserver).unwrap();
//! assert!(report.converged && report.slip_fraction > 0.0);
//! ```
//!
//! The facade re-exports the member crates and provides scene files, the command line and
//! output writers. See the README for the two problems it solves.
#![warn(missing_docs)]

pub mod api;
/// The binary's command line (argument parsing, dispatch): not library API.
#[doc(hidden)]
pub mod cli;
/// The binary's commands (text tables, files, benches): not library API; the library calls
/// are [`api`] and [`Problem`].
#[doc(hidden)]
pub mod commands;
pub mod error;
mod features;
pub mod figures;
pub mod output;
pub mod problem;
pub mod progress;
pub mod provenance;
pub mod scale;
pub mod scene;
mod shard_error;

pub use capstan_elasticity as elasticity;
pub use capstan_elasticity::solvers;
pub use capstan_friction as friction;
pub use capstan_geometry as geometry;
pub use error::CliError;
pub use problem::Problem;
pub use scene::Scene;
