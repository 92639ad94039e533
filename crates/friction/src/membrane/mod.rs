//! Membrane capstan models (Hypothesis 1 of the paper): the tension `T(theta)` of a membrane
//! (or string) at limiting equilibrium on a rough rigid prism or cone, forward and inverse.
//!
//! # Math
//! Hypothesis 1 is Coulomb's law for force densities: `|f_r^alpha| = mu f_r^3`. For a membrane
//! along a curve with arclength `s`, unit tangent `t`, outward normal `N`, normal curvature
//! `kappa > 0` (convex obstacle), external load `q` per unit length, line density `rho_l` and
//! steady speed `V` (acceleration `-V^2 kappa N`), the balance of forces is
//! ```text
//! R     = kappa (T - rho_l V^2) - q . N     >= 0  (else the membrane lifts off)
//! dT/ds = mu R - q . t                            (friction opposes slip towards theta_max)
//! ```
//! On a prism `(x1, u(t), v(t))`, `ds = sqrt(a_22) dt` and `kappa sqrt(a_22) = Psi'(t) =
//! (v'u'' - u'v'')/(u'^2 + v'^2)`, the continuous turning angle's rate. Without loads
//! `T = T0 exp(mu (Psi(theta) - Psi(theta0)))` (Theorem 1); with steady speed only,
//! `T - rho_l V^2` obeys the same law; with gravity `(0, 0, -g)` the linear ODE
//! `dT/dt = mu Psi' (T - rho_l V^2) + rho_l g (mu u' + v')` reproduces eq. capGrav on a
//! cylinder. On a cone the membrane follows geodesics (straight lines of the development) and
//! `d ln T/ds = mu kappa_n`, which gives Theorem 2.
//!
//! # Where the paper needs care
//! See `docs/errata.md`: the principal branch of `atan(v'/u')` (we use `Psi`), the ellipse
//! continuation past `pi/2` (`a/b`, not `b/a`), the steady transform (only the normal load
//! changes), Theorem 2's validity (`|phi| < pi/2`, `D > 0`).
//!
//! # References
//! Paper section 2 (eqs. PrismEqn02, capGrav, PrismEqn, PrismEqnPlot; Theorems 1, 2; Corollary 1).

mod budget;
pub mod closed_form;
mod cone;
mod development;
mod equilibrium;
mod geodesic_strip;
mod infinite;
mod load_field;
mod obstacle;
mod prism;
mod problem;
mod turning_angle;
mod validity;

pub use budget::MembraneBudget;
pub use cone::{ConeMembrane, ConePoint};
pub use development::{DevelopmentPoint, development};
pub use equilibrium::{LocalEquilibrium, MembraneEquilibrium};
pub use geodesic_strip::GeodesicStrip;
pub use infinite::InfiniteMembrane;
pub use load_field::{ExpressionLoad, Gravity, LoadField, LoadSum, NoLoad, PaperSpeedTransform};
pub use obstacle::{
    FrictionEstimate, infer_mu, infer_mu_within, tension_profile, tension_profile_with_load,
    tension_profile_within,
};
pub use prism::PrismMembrane;
pub use problem::{MembraneLoads, MembraneProblem, Method, TensionProfile};
pub use turning_angle::{ProfilePoint, turning_angles, turning_angles_within};
