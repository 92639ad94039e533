//! Embedding capstan in another solver: its geometry, friction laws and contact solve used as
//! a library by a host code that has its own loops.
//!
//! Problem: a host code models a belt over an egg-shaped prism
//! `sigma(x1, x2) = (x1, 2 sin x2, 1.5 cos x2 + 0.2 cos 2 x2)` with its own marching scheme, and
//! its own contact elements. It takes from capstan
//! 1. the geometry of a surface it writes itself (only `sigma`): the capstan equation on a
//!    prism is `dT/dx2 = -mu T b_22 / sqrt(a_22)` (turning of the profile per unit `x2`), which
//!    the host integrates with its own classical Runge–Kutta and checks against capstan's own
//!    membrane model on the same profile;
//! 2. a friction law by its registered name (`coulomb`, or any law a user registered), evaluated
//!    pointwise in the host's element loop with its consistent tangent;
//! 3. the thick-body contact solve of the paper's body, whose contact profile the host reads
//!    back and checks against Coulomb's law node by node.
//!
//! Run: `cargo run --release --example embed`
//! Look at: the host's RK4 converges at order 4 to capstan's tension; every node's friction
//! traction is within `mu |sigma_n|`, and at the bound where the node slides.

use capstan::elasticity::contact::{BoundarySolver, ContactSettings, EndLoads, ThickBody};
use capstan::friction::membrane::{MembraneProblem, tension_profile};
use capstan::friction::{
    AnyFrictionLaw, AnyFrictionParams, ContactState, FrictionLaw, FrictionSettings,
};
use capstan::geometry::{ExpressionProfile, GeneralPrism, Obstacle, Scalar, Surface};

/// The host's obstacle: only `sigma` is written.
struct Egg;

impl Surface<f64> for Egg {
    fn sigma<S: Scalar<f64>>(&self, [x1, x2]: [S; 2]) -> [S; 3] {
        [x1, x2.sin() * 2.0, x2.cos() * 1.5 + (x2 * 2.0).cos() * 0.2]
    }
}

/// The host's own marching: `T(theta1)` from `T(theta0) = t0` by classical RK4 in `steps`
/// steps of `dT/dx2 = -mu T b_22 / sqrt(a_22)`, with the forms from capstan's geometry.
fn host_tension(mu: f64, t0: f64, [theta0, theta1]: [f64; 2], steps: usize) -> f64 {
    let rate = |x2: f64, t: f64| {
        let g = Egg.geometry([0.0, x2]).expect("the egg is regular");
        // the paper's sign: H = -b^a_a / 2 > 0 on a convex prism (b_11 = 0), so b_22 < 0
        -mu * t * g.second_form[1][1] / g.first_form[1][1].sqrt()
    };
    let h = (theta1 - theta0) / steps as f64;
    let mut t = t0;
    for k in 0..steps {
        let x = theta0 + k as f64 * h;
        let k1 = rate(x, t);
        let k2 = rate(x + 0.5 * h, t + 0.5 * h * k1);
        let k3 = rate(x + 0.5 * h, t + 0.5 * h * k2);
        let k4 = rate(x + h, t + h * k3);
        t += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    }
    t
}

/// capstan's membrane model on the same profile (written as an expression prism).
fn capstan_tension(mu: f64, t0: f64, [theta0, theta1]: [f64; 2]) -> f64 {
    let profile =
        ExpressionProfile::parse_named("2*sin(t)", "1.5*cos(t) + 0.2*cos(2*t)", ["u", "v"])
            .expect("valid expressions");
    let egg = Obstacle::Prism(GeneralPrism::new(profile));
    let problem = MembraneProblem {
        mu,
        t0,
        theta0,
        theta_max: theta1,
        samples: 2,
        ..Default::default()
    };
    tension_profile(&egg, &problem)
        .expect("convex on the interval")
        .t_max()
}

/// The host's contact element: the friction traction and its slip tangent of capstan's law
/// `name` at a slip `u` under pressure `p`.
fn host_traction(name: &str, u: f64, p: f64) -> (f64, f64) {
    let params = AnyFrictionParams::new(name, &FrictionSettings::default()).expect("registered");
    let c = ContactState::new([u, 0.0], p);
    let t = AnyFrictionLaw.traction(&c, &params)[0];
    let d = AnyFrictionLaw.traction_derivatives(&c, &params).d_slip[0][0];
    (t, d)
}

/// The paper's body (circle `a = b = 2`, `h = 1`, ratio 2) on an `n2 x n3` grid: per contact
/// node, `(|t|, mu |sigma_n|, state)`.
fn contact_nodes(n2: usize, n3: usize) -> Vec<(f64, f64, i8)> {
    let settings = FrictionSettings::default();
    let params = AnyFrictionParams::new("coulomb", &settings).expect("registered");
    let model = ThickBody::paper(n2, n3)
        .expect("a valid body")
        .model(AnyFrictionLaw, params, settings.eps)
        .expect("a valid contact model");
    let solution = BoundarySolver::new(&model, ContactSettings::default())
        .and_then(|solver| solver.solve(EndLoads::new(1.0, 2.0)))
        .expect("ratio 2 is held");
    let c = &solution.contact;
    (0..c.x2.len())
        .map(|i| {
            (
                c.friction_traction[i].abs(),
                settings.mu * c.normal_stress[i].abs(),
                c.state[i],
            )
        })
        .collect()
}

fn main() {
    let interval = [-1.2, 1.2];
    let reference = capstan_tension(0.3, 1.0, interval);
    println!("capstan membrane: T(theta1) = {reference:.15}");
    for steps in [10, 20, 40, 80] {
        let t = host_tension(0.3, 1.0, interval, steps);
        println!(
            "host RK4 {steps:>3} steps: {t:.15}  error {:.3e}",
            (t - reference).abs()
        );
    }
    let (t, d) = host_traction("coulomb", 1e-3, -2.0);
    println!("coulomb at slip 1e-3, p = -2: traction {t:.6}, tangent {d:.3e}");
    let nodes = contact_nodes(61, 11);
    let sliding = nodes.iter().filter(|n| n.2 != 0).count();
    println!("contact: {sliding} of {} nodes slide", nodes.len());
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn host_rk4_converges_at_order_4_to_capstans_membrane() {
        let interval = [-1.2, 1.2];
        let reference = capstan_tension(0.3, 1.0, interval);
        let errors: Vec<f64> = [10, 20, 40]
            .iter()
            .map(|&n| (host_tension(0.3, 1.0, interval, n) - reference).abs())
            .collect();
        let orders: Vec<f64> = errors.windows(2).map(|e| (e[0] / e[1]).log2()).collect();
        for p in &orders {
            assert!(
                (p - 4.0).abs() < 0.3,
                "orders {orders:?}, errors {errors:?}"
            );
        }
        assert!(errors[2] < 1e-7 * reference, "{errors:?}");
    }

    #[test]
    fn host_elements_see_coulombs_law_and_its_tangent() {
        // sliding (|u| > eps = 1e-5): |t| = mu |p| = 1, no tangent along the slip
        let (t, d) = host_traction("coulomb", 1e-3, -2.0);
        assert!((t.abs() - 1.0).abs() < 1e-14 && d.abs() < 1e-14);
        // sticking (|u| < eps): t = mu |p| u / eps, tangent mu |p| / eps
        let (t, d) = host_traction("coulomb", 5e-6, -2.0);
        assert!((t.abs() - 0.5).abs() < 1e-12 && (d.abs() - 1e5).abs() < 1e-6);
    }

    #[test]
    fn contact_tractions_obey_coulomb_node_by_node() {
        let nodes = contact_nodes(61, 11);
        let mut sliding = 0;
        for &(t, bound, state) in &nodes {
            assert!(t <= bound * (1.0 + 1e-9) + 1e-12, "{t} > {bound}");
            if state != 0 {
                sliding += 1;
                assert!(
                    (t - bound).abs() <= 1e-9 * bound.max(1e-12),
                    "{t} vs {bound}"
                );
            }
        }
        assert!(sliding > 0 && sliding < nodes.len(), "{sliding}");
    }
}
