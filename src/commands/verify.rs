//! `capstan verify`: the convergence studies of the elasticity discretisations.

use capstan_elasticity::studies;
use capstan_elasticity::verification::StudyReport;
use serde::Serialize;

use crate::error::CliError;

/// Every registered study with its grids, errors and observed orders.
#[derive(Debug, Clone, Serialize)]
pub struct VerifyReport {
    /// Whether only the three coarsest grids were run.
    pub quick: bool,
    /// One report per study, in registration order.
    pub studies: Vec<StudyReport>,
}

/// Runs the studies of [`capstan_elasticity::studies`].
///
/// # Errors
/// Any elasticity error of a study (a failure here is a bug: the studies are fixed problems).
pub fn report(quick: bool) -> Result<VerifyReport, CliError> {
    let studies = studies()
        .iter()
        .map(|s| s.run(quick))
        .collect::<Result<Vec<_>, _>>()?;
    Ok(VerifyReport { quick, studies })
}

/// Human-readable tables, one per study.
pub fn table(r: &VerifyReport) -> String {
    let mut s = format!(
        "capstan verify: {} studies ({} grids each)\n\n",
        r.studies.len(),
        if r.quick { "3 coarsest" } else { "all" }
    );
    for study in &r.studies {
        s += &study.table();
        s.push('\n');
    }
    s
}
