//! Adding a friction law: one file with the law and its registration; scenes name it at once.
//!
//! Problem: the paper's thick body on the circle (section 3), but the interface is a soft
//! interlayer whose shear strength `cap` bounds the friction traction:
//! ```text
//! t(u, p) = min(1, cap / |mu p|) t_C(u, p)      t_C: regularised Coulomb (Kikuchi–Oden)
//! ```
//! The law is written once against `FrictionLaw` (traction and its consistent tangent),
//! registered under the name `capped-coulomb` with the extra scene key `friction.cap`, and then
//! named from a scene exactly like a built-in law: `--set friction.law='"capped-coulomb"'
//! --set friction.cap=0.3`. Nothing in capstan is edited.
//!
//! Run: `cargo run --release --example extend_friction_law`
//! Look at: with `cap` above every `mu |p|` the law is Coulomb's (same Slip to the last digit);
//! as `cap` falls the interlayer holds less and more of the contact slides.

use capstan::Scene;
use capstan::friction::registry::{self, RegisteredLaw};
use capstan::friction::{
    ContactState, FrictionLaw, RegularisedCoulomb, RegularisedCoulombParams, TractionDerivatives,
};

/// Regularised Coulomb friction capped at a shear strength `cap`.
#[derive(Debug, Clone, Copy)]
struct CappedCoulomb {
    coulomb: RegularisedCoulombParams<f64>,
    cap: f64,
}

impl CappedCoulomb {
    /// The factor `k = min(1, cap / |mu p|)` on Coulomb's traction.
    fn factor(&self, c: &ContactState<f64>) -> f64 {
        (self.cap / (self.coulomb.mu() * c.normal_pressure).abs()).min(1.0)
    }
}

impl FrictionLaw<f64> for CappedCoulomb {
    type Params = ();
    fn traction(&self, c: &ContactState<f64>, _: &()) -> [f64; 2] {
        let k = self.factor(c);
        RegularisedCoulomb.traction(c, &self.coulomb).map(|t| k * t)
    }
    fn traction_derivatives(&self, c: &ContactState<f64>, _: &()) -> TractionDerivatives<f64> {
        let (d, k) = (
            RegularisedCoulomb.traction_derivatives(c, &self.coulomb),
            self.factor(c),
        );
        // capped: t = cap t_C / |mu p| no longer depends on p (t_C is linear in p)
        let d_pressure = if k < 1.0 { [0.0; 2] } else { d.d_pressure };
        TractionDerivatives::new(d.d_slip.map(|row| row.map(|x| k * x)), d_pressure)
    }
}

/// Registers the law (once per process; a second call is refused as a duplicate, which is
/// harmless here).
fn register() {
    let _ = registry::register(RegisteredLaw {
        name: "capped-coulomb",
        summary: "regularised Coulomb friction capped at a shear strength `cap`",
        parameters: &["mu", "eps", "cap"],
        build: |s| {
            let cap = registry::check(
                "friction.cap",
                s.get_or("cap", f64::MAX), // no `friction.cap`: no cap
                "(0, inf)",
                |v| v > 0.0,
            )?;
            Ok(registry::bind(
                CappedCoulomb {
                    coulomb: RegularisedCoulombParams::new(s.mu, s.eps)?,
                    cap,
                },
                (),
            ))
        },
    });
}

/// Slip (the fraction of sliding contact nodes) of the paper's body on a coarse grid with
/// `friction.law = law` and the extra settings `set`.
fn slip(law: &str, set: &[(&str, &str)]) -> f64 {
    let mut scene = Scene::default()
        .with_raw("grid.n2", "61", "example")
        .and_then(|s| s.with_raw("grid.n3", "11", "example"))
        .and_then(|s| s.with_raw("friction.law", &format!("{law:?}"), "example"))
        .expect("valid keys");
    for (key, value) in set {
        scene = scene.with_raw(key, value, "example").expect("valid key");
    }
    let (report, _) = capstan::api::contact_observed(&scene, &mut capstan::solvers::SilentObserver)
        .expect("the body holds at ratio 2");
    report.slip_fraction
}

fn main() {
    register();
    println!("{:>12} {:>10}", "law", "Slip");
    println!("{:>12} {:>10.4}", "coulomb", slip("coulomb", &[]));
    for cap in ["10", "0.6", "0.4", "0.3"] {
        println!(
            "{:>12} {:>10.4}",
            format!("cap = {cap}"),
            slip("capped-coulomb", &[("friction.cap", cap)])
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_high_cap_is_coulomb_and_a_low_cap_slides_more() {
        register();
        let coulomb = slip("coulomb", &[]);
        // |mu p| <= 0.5 * max |sigma_n| < 10 everywhere: the cap never acts
        assert_eq!(slip("capped-coulomb", &[("friction.cap", "10")]), coulomb);
        let capped = slip("capped-coulomb", &[("friction.cap", "0.3")]);
        assert!(
            capped > coulomb + 0.05,
            "capped {capped} vs coulomb {coulomb}"
        );
    }

    #[test]
    fn the_law_refuses_a_non_positive_cap_naming_the_key() {
        register();
        let scene = Scene::default()
            .with_raw("friction.law", "\"capped-coulomb\"", "example")
            .and_then(|s| s.with_raw("friction.cap", "-1", "example"));
        let message = match scene {
            Err(e) => e.to_string(),
            Ok(s) => capstan::api::contact_observed(&s, &mut capstan::solvers::SilentObserver)
                .unwrap_err()
                .to_string(),
        };
        assert!(message.contains("friction.cap"), "{message}");
    }

    #[test]
    fn the_tangent_matches_central_differences() {
        let law = CappedCoulomb {
            coulomb: RegularisedCoulombParams::new(0.5, 1e-3).unwrap(),
            cap: 0.3,
        };
        for (slip, p) in [
            ([2e-3, -1e-3], -0.4),
            ([2e-4, 1e-4], -2.0),
            ([-5e-3, 0.0], -1.0),
        ] {
            let c = ContactState::new(slip, p);
            let d = law.traction_derivatives(&c, &());
            let h = 1e-8;
            for j in 0..2 {
                let mut plus = slip;
                let mut minus = slip;
                plus[j] += h;
                minus[j] -= h;
                let tp = law.traction(&ContactState::new(plus, p), &());
                let tm = law.traction(&ContactState::new(minus, p), &());
                for i in 0..2 {
                    let fd = (tp[i] - tm[i]) / (2.0 * h);
                    // central differences: O(h^2) truncation + O(eps / h) round-off
                    assert!(
                        (d.d_slip[i][j] - fd).abs() < 1e-5 * (1.0 + fd.abs()),
                        "{i}{j}"
                    );
                }
            }
            let tp = law.traction(&ContactState::new(slip, p + h), &());
            let tm = law.traction(&ContactState::new(slip, p - h), &());
            for i in 0..2 {
                let fd = (tp[i] - tm[i]) / (2.0 * h);
                assert!((d.d_pressure[i] - fd).abs() < 1e-5 * (1.0 + fd.abs()));
            }
        }
    }
}
