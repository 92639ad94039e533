//! Rows toward the contact face (`Problem::face_graded`, issue 28's contact reference): the
//! stick zone of the default scene (`0.03` long) is a feature of the face that the `x2`
//! grading toward its ends resolves along the face but a coarse row (`0.25` high on `12 x 4`
//! cells) does not through the thickness. With three rows of `0.3` toward the face the slip
//! measure and the stick ends of order 4 on `12 x 4` cells are within `4e-7` of `pi` of the
//! reference; without them `2e-4` off, however the columns are graded.

use capstan::commands::accuracy::probes;
use capstan::problem::{DEFAULT_TRANSITION_GRADING, Problem};
use capstan::scene::Scene;

/// The default scene's slip measure and stick ends: the face-graded reference (p 10 on
/// `24 x 8` cells, 3 rows of `0.3` toward the face, docs/data/contact_graded_ladder.json
/// `graded-p10-24x8-f3`), good to `1e-8` of `pi` (docs/verification.md, "The contact reference
/// to 1e-7").
const REFERENCE: [(&str, f64); 3] = [
    ("slip_measure", SLIP),
    ("stick_from", STICK_FROM),
    ("stick_to", STICK_TO),
];
const SLIP: f64 = 3.112_298_879;
const STICK_FROM: f64 = -0.923_422_277;
const STICK_TO: f64 = -0.894_128_502;

/// The errors (relative to `pi`) of the located quantities of order 4 on `12 x 4` cells,
/// graded toward the reference's transitions, with `face_layers` rows toward the face.
fn located_errors(face_layers: usize) -> Vec<f64> {
    let scene = Scene::default();
    let base: Problem = scene.build().unwrap();
    let (layers, ratio) = DEFAULT_TRANSITION_GRADING;
    let mut problem = base
        .corner_mesh(4, [12, 4])
        .graded_toward(vec![STICK_FROM, STICK_TO], layers, ratio)
        .unwrap()
        .face_graded(face_layers)
        .unwrap();
    problem.body.settings.corner_layers = 7;
    let solved = problem.solve().unwrap();
    let s = solved.scalars(&probes(&scene)).unwrap();
    REFERENCE
        .iter()
        .map(|(name, value)| (s[*name] - value).abs() / core::f64::consts::PI)
        .collect()
}

#[test]
fn rows_toward_the_face_locate_the_stick_zone_500_times_closer() {
    // measured (release): without rows 2.1e-4, 1.1e-4, 1.1e-4 of pi; with three rows
    // 3.8e-7, 2.3e-7, 1.5e-7 (11,938 unknowns against 5,314)
    let without = located_errors(0);
    let with = located_errors(3);
    for (w, f) in without.iter().zip(&with) {
        assert!(*w > 5e-5, "without rows: {without:?}");
        assert!(*f < 1e-6, "with rows: {with:?} (without: {without:?})");
        assert!(w / f > 100.0, "with {with:?}, without {without:?}");
    }
}

#[test]
fn face_rows_need_the_corner_mesh() {
    let scene = Scene::default();
    let base: Problem = scene.build().unwrap();
    // the default scene's FD grid has no rows to grade
    assert!(base.face_graded(3).is_err());
    // and 17 rows are over the layer limit
    assert!(base.corner_mesh(2, [12, 2]).face_graded(17).is_err());
    assert!(base.corner_mesh(2, [12, 2]).face_graded(16).is_ok());
}
