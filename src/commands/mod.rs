//! One module per subcommand.

pub mod accuracy;
pub mod bench;
pub mod compare;
pub mod contact;
pub mod contact_output;
pub mod contact_path;
pub mod export_system;
pub mod geometry;
pub mod infer_mu;
pub mod membrane_path;
mod scene_args;
pub mod solid_contact;
pub mod solid_report;
pub mod stress;
mod study_args;
pub mod sweep;
pub mod tension;
pub mod threshold;
pub mod verify;

pub use scene_args::SceneArgs;
pub use study_args::StudyArgs;
