//! The reference problems with exact or manufactured solutions ([`samples`]), each built for
//! any plane-strain discretisation ([`ProblemParts`]: the FD, Q1/Q2 and Qp operators of one
//! problem), and the registry of convergence studies that `capstan verify` runs
//! ([`studies`]: observed orders against the expected ones).
//!
//! This room sits above the discretisations (it builds every one of them); nothing below
//! imports it.

mod column_forcing;
mod fem;
pub(crate) mod high_order;
mod parts;
pub mod samples;
pub mod signorini;
pub mod solid;
pub mod solid_signorini;

pub use column_forcing::{ColumnCache, Dual2, ForcingColumn};
pub use fem::{FemProblem, FemStudy, fem_studies, lame_parts, mms_parts, paper_parts};
pub use high_order::{HighOrderStudy, high_order_studies};
pub use parts::{ProblemParts, SampleChart};
pub use signorini::{SignoriniMms, SignoriniPoint};
pub use solid_signorini::{SolidSignoriniMms, SolidSignoriniPoint};

use crate::finite_element::ElementOrder;
use crate::verification::Study;
use samples::{LameCylinder, MmsBoundaries, PrismMms};
use solid::{SolidMms, SolidStudy};

/// The registered studies, in report order: the finite-difference studies, then the same
/// problems with finite elements, then the 3-D body. New discretisations append theirs.
pub fn studies() -> Vec<Box<dyn Study>> {
    let mut studies: Vec<Box<dyn Study>> = vec![
        Box::new(PrismMms::ellipse(0.5, MmsBoundaries::TractionContact)),
        Box::new(PrismMms::ellipse(2.0, MmsBoundaries::BilateralContact)),
        Box::new(PrismMms::expression_prism(MmsBoundaries::TractionContact)),
        Box::new(PrismMms::expression_prism(MmsBoundaries::BilateralContact)),
        Box::new(LameCylinder::default()),
    ];
    studies.extend(fem_studies());
    studies.extend(high_order_studies());
    // the 3-D body: cones (one with g_12 != 0) and a prism of finite width
    for mms in [
        SolidMms::circular_cone(),
        SolidMms::elliptical_cone(),
        SolidMms::expression_prism(),
    ] {
        for order in [ElementOrder::Q1, ElementOrder::Q2] {
            studies.push(Box::new(SolidStudy {
                mms: mms.clone(),
                order,
            }));
        }
    }
    studies
}
