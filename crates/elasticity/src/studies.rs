//! The registry of convergence studies that `capstan verify` runs.

use crate::finite_element::ElementOrder;
use crate::finite_element::fem_studies;
use crate::samples::{LameCylinder, MmsBoundaries, PrismMms};
use crate::solid::samples::{SolidMms, SolidStudy};
use crate::verification::Study;

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
    studies.extend(crate::finite_element::high_order::high_order_studies());
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
