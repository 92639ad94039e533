//! Every registered study on its grids: second order, max and L2.

use capstan_elasticity::studies;

#[test]
#[ignore = "full 4-level studies; run with --ignored (about 10 s at opt-level 1)"]
fn registered_studies_full() {
    for study in studies() {
        let report = study.run(false).unwrap();
        println!("{}", report.table());
    }
}
