//! Refinement toward the stick/slip transitions on the default scene (the paper's body on the
//! circle, ratio 2): the slip measure, threshold and max `|v2|` of `fem-qp-corner` of order
//! `p` on `12 x 2` cells with and without the second pass graded toward the transitions
//! ([`capstan::problem::Problem::solve_transition_graded`]), their errors against the contact
//! work-precision reference (docs/work-precision.md: slip 3.1123305, threshold 3.34292196,
//! max |v2| 3.5878775e-3, itself good to 1.7e-5, 3.1e-9, 4.4e-6), and wall times.
//!
//! Run: `cargo run --release --example transition_slip -- [P_MIN] [P_MAX] [LAYERS]`
//! (default 2 6 4). The slip error is relative to the face's x2-length `pi`, as
//! `accuracy.tol` scales it. Give `uptime` with the times.

use std::time::Instant;

use capstan::Scene;
use capstan::elasticity::contact::{ThresholdSettings, default_probes};
use capstan::elasticity::finite_element::DiscretisationMethod;
use capstan::problem::{Problem, Solved};

const SLIP_REF: f64 = 3.1123305;
const THRESHOLD_REF: f64 = 3.34292196;
const V2_REF: f64 = 3.5878775e-3;

fn slip_of(s: &Solved) -> Result<f64, Box<dyn std::error::Error>> {
    let probes = default_probes([-core::f64::consts::FRAC_PI_2, core::f64::consts::FRAC_PI_2]);
    Ok(s.quantities(&probes)?.slip_measure)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let arg = |i: usize, d: usize| -> usize {
        std::env::args()
            .nth(i)
            .and_then(|x| x.parse().ok())
            .unwrap_or(d)
    };
    let (p0, p1, layers) = (arg(1, 2), arg(2, 6), arg(3, 4));
    let base: Problem = Scene::default().build()?;
    let pi = core::f64::consts::PI;
    println!(
        "{:>2} {:>9} {:>10} {:>9} {:>10} {:>9} {:>9} {:>8} {:>8} {:>8}",
        "p", "dofs 2nd", "slip 1st", "err", "slip 2nd", "err", "v2 err", "t 1st", "t 2nd", "t thr"
    );
    for p in p0..=p1 {
        let mut q = base.clone().with_grid(12 * p + 1, 2 * p + 1);
        q.body.method = DiscretisationMethod::FemQpCorner;
        q.body.settings.order = p;
        let t = Instant::now();
        let first = q.solve()?;
        let t1 = t.elapsed().as_secs_f64();
        let transitions = first.transitions();
        let graded = q.graded_toward(transitions.clone(), layers, 0.3)?;
        let t = Instant::now();
        let second = graded.solve()?;
        let t2 = t.elapsed().as_secs_f64();
        let (s1, s2) = (slip_of(&first)?, slip_of(&second)?);
        let v2 = second.solution.max_azimuthal_displacement.value.abs();
        let t = Instant::now();
        let threshold = q.threshold_with(ThresholdSettings {
            tolerance: 1e-8,
            bracket_at_limit: true,
            ..Default::default()
        });
        let tt = t.elapsed().as_secs_f64();
        let thr_err = threshold
            .map(|r| format!("{:.2e}", (r.ratio - THRESHOLD_REF).abs() / THRESHOLD_REF))
            .unwrap_or_else(|e| format!("({e})"));
        let dofs = second.model.operator().dof_count();
        println!(
            "{p:>2} {dofs:>9} {s1:>10.7} {:>9.2e} {s2:>10.7} {:>9.2e} {:>9.2e} {t1:>8.3} {t2:>8.3} {tt:>8.3}  thr err {thr_err}  transitions {transitions:?}",
            (s1 - SLIP_REF).abs() / pi,
            (s2 - SLIP_REF).abs() / pi,
            (v2 - V2_REF).abs() / V2_REF,
        );
    }
    Ok(())
}
