//! `capstan verify`: the convergence studies of the elasticity discretisations.

use capstan_elasticity::studies;
use capstan_elasticity::verification::{Study, StudyReport};
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

/// Runs the studies of [`capstan_elasticity::studies()`].
///
/// # Errors
/// Any elasticity error of a study (a failure here is a bug: the studies are fixed problems).
pub fn report(quick: bool) -> Result<VerifyReport, CliError> {
    report_of(&studies(), quick)
}

/// Runs `studies` (all grids, or the three coarsest with `quick`).
///
/// # Errors
/// Any elasticity error of a study.
pub fn report_of(studies: &[Box<dyn Study>], quick: bool) -> Result<VerifyReport, CliError> {
    let studies = studies
        .iter()
        .map(|s| s.run(quick))
        .collect::<Result<Vec<_>, _>>()?;
    Ok(VerifyReport { quick, studies })
}

impl VerifyReport {
    /// The studies whose observed L2 order fell short of their expected order
    /// ([`StudyReport::meets_expected_order`]), as `name [discretisation]: observed (expected)`.
    pub fn missed(&self) -> Vec<String> {
        self.studies
            .iter()
            .filter(|s| !s.meets_expected_order)
            .map(|s| {
                format!(
                    "{} [{}]: L2 order {:.3} (expected {} - {})",
                    s.name, s.discretisation, s.order_l2, s.expected_order, s.order_tolerance
                )
            })
            .collect()
    }
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

#[cfg(test)]
mod tests {
    use super::*;
    use capstan_elasticity::ElasticityError;
    use capstan_elasticity::samples::{MmsBoundaries, PrismMms};
    use capstan_elasticity::verification::{GridLevel, StudyPoint};

    /// A study that claims `extra` more than its method's order.
    struct Overclaimed {
        inner: PrismMms,
        extra: f64,
    }

    impl Study for Overclaimed {
        fn name(&self) -> String {
            self.inner.name()
        }
        fn geometry(&self) -> String {
            self.inner.geometry()
        }
        fn discretisation(&self) -> &'static str {
            self.inner.discretisation()
        }
        fn levels(&self) -> Vec<GridLevel> {
            self.inner.levels()
        }
        fn expected_order(&self) -> f64 {
            self.inner.expected_order() + self.extra
        }
        fn run_level(&self, level: GridLevel) -> Result<StudyPoint, ElasticityError> {
            self.inner.run_level(level)
        }
    }

    #[test]
    fn a_study_below_its_expected_order_is_reported_missed_and_exits_6() {
        let study = |extra| -> Box<dyn Study> {
            Box::new(Overclaimed {
                inner: PrismMms::ellipse(0.5, MmsBoundaries::TractionContact),
                extra,
            })
        };
        // the FD study observes about 1.96 on its three coarsest grids: 2 passes, 3 misses
        let honest = report_of(&[study(0.0)], true).unwrap();
        assert!(honest.missed().is_empty(), "{}", table(&honest));
        let r = report_of(&[study(0.0), study(1.0)], true).unwrap();
        let missed = r.missed();
        assert_eq!(missed.len(), 1, "{}", table(&r));
        assert!(missed[0].contains("(expected 3 - 0.3)"), "{missed:?}");
        assert!(table(&r).contains("MISSED"));
        let e = CliError::VerificationFailed {
            output: table(&r),
            missed,
        };
        assert_eq!(e.exit_code(), 6);
        assert!(e.stdout().unwrap().contains("observed order"));
    }

    #[test]
    fn every_registered_study_meets_its_order_on_the_quick_grids() {
        let r = report(true).unwrap();
        assert!(r.missed().is_empty(), "{:?}", r.missed());
    }
}
