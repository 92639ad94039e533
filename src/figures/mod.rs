//! Figures: the paper's figures and tables of sections 2 and 3 regenerated from built-in
//! scenes ([`paper`], `capstan figure` in [`command`]), and the report files of the membrane
//! commands ([`reports`]). The thick body's field files are [`crate::output::body`] and
//! [`crate::output::solid_body`] (re-exported here under their old paths).

pub mod command;
pub mod paper;
pub mod reports;
pub mod settings;
pub mod threshold_trend;

pub use crate::output::{body, solid_body};
