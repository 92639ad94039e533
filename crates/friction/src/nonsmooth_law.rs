//! Nonsmooth friction laws (exact Coulomb and its orthotropic cone): the return map onto the
//! friction set with its generalised (Clarke) Jacobian, for semismooth Newton methods.
//!
//! A smooth [`crate::FrictionLaw`] gives the traction as a function of the slip. Exact Coulomb
//! friction is not a function of the slip (at zero slip any traction inside the friction disc
//! is admissible), so a nonsmooth law is written as a projection instead (Alart–Curnier,
//! De Saxcé): with the trial traction
//! ```text
//! t* = t - r du            du: slip increment of the step (physical length), r > 0
//! ```
//! the friction law holds if and only if `t = P_C(t*)`, `C = C(sigma_n)` the friction set
//! (a disc of radius `mu |sigma_n|` for Coulomb, an ellipse for the orthotropic cone, empty of
//! all but 0 where `sigma_n >= 0`). Stick (`|t| < mu |sigma_n|`, `du = 0`) is the interior,
//! slip (`t = -mu |sigma_n| du/|du|`) the boundary. A semismooth Newton method solves
//! `t - P_C(t - r du) = 0` with the derivatives in [`Projection`]; any `r > 0` gives the same
//! solution, `r` only changes the iteration (take `r` of the order of the contact stiffness).
//!
//! In 1-D (a membrane, slip along one tangent) the trial is `(0, t*)` and the projection is
//! the clamp `t = max(-g, min(g, t*))`, `g = mu |sigma_n|`.

use std::fmt::Debug;
use std::sync::Arc;

use capstan_geometry::Real;

use crate::error::FrictionError;
use crate::registration::FrictionSettings;

/// The state of one contact point after the return map.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum FrictionState {
    /// The trial traction lies inside the friction set: no further slip (`t = t*`).
    Stick,
    /// The trial traction lies outside: the point slides, the traction is on the limit surface.
    Slip,
    /// No compression (`sigma_n >= 0`): the friction set is `{0}` and the traction vanishes.
    Separated,
}

impl FrictionState {
    /// `"stick"`, `"slip"` or `"separated"` (for reports and JSON).
    pub fn name(self) -> &'static str {
        match self {
            Self::Stick => "stick",
            Self::Slip => "slip",
            Self::Separated => "separated",
        }
    }
}

/// The return map at one point: the projected traction, its generalised derivatives and the
/// state.
///
/// # Math
/// ```text
/// traction    t = P_C(sigma_n)(t*)
/// d_trial     dt_i/dt*_j          (an element of the Clarke Jacobian; exact away from the kink)
/// d_pressure  dt_i/dsigma_n
/// ```
/// Stick: `d_trial = I`, `d_pressure = 0`. Separated: both zero. On the boundary of `C` the
/// stick branch is returned (either choice is in the generalised Jacobian).
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct Projection<F> {
    /// The traction `t = P_C(t*)`.
    pub traction: [F; 2],
    /// `dt_i/dt*_j`, indexed `[i][j]`.
    pub d_trial: [[F; 2]; 2],
    /// `dt_i/dsigma_n`.
    pub d_pressure: [F; 2],
    /// Stick, slip or separated.
    pub state: FrictionState,
}

impl<F: Real> Projection<F> {
    /// A projection with the given parts.
    pub fn new(
        traction: [F; 2],
        d_trial: [[F; 2]; 2],
        d_pressure: [F; 2],
        state: FrictionState,
    ) -> Self {
        Self {
            traction,
            d_trial,
            d_pressure,
            state,
        }
    }

    /// The stick branch: `t = t*`, `d_trial = I`, `d_pressure = 0`.
    pub fn stick(trial: [F; 2]) -> Self {
        let (o, z) = (F::one(), F::zero());
        Self::new(trial, [[o, z], [z, o]], [z, z], FrictionState::Stick)
    }

    /// The separated branch: `t = 0` with zero derivatives.
    pub fn separated() -> Self {
        let z = F::zero();
        Self::new([z, z], [[z, z], [z, z]], [z, z], FrictionState::Separated)
    }
}

/// The trial traction of an augmented-Lagrangian step: `t* = t_old - r du`.
///
/// `t_old` is the current traction iterate, `du` the slip increment of the load step and
/// `r > 0` the augmentation parameter.
pub fn trial_traction<F: Real>(t_old: [F; 2], slip_increment: [F; 2], r: F) -> [F; 2] {
    [
        t_old[0] - r * slip_increment[0],
        t_old[1] - r * slip_increment[1],
    ]
}

/// A nonsmooth pointwise friction law: the return map onto its friction set.
///
/// # Example
/// ```
/// use capstan_friction::{ExactCoulomb, ExactCoulombParams, FrictionState, NonsmoothFrictionLaw};
/// let p = ExactCoulombParams::<f64>::new(0.5).unwrap();
/// // sigma_n = -2: the disc of radius 1; a trial (3, 4) lands on (0.6, 0.8)
/// let pr = ExactCoulomb.project([3.0, 4.0], -2.0, &p).unwrap();
/// assert!((pr.traction[0] - 0.6).abs() < 1e-15 && (pr.traction[1] - 0.8).abs() < 1e-15);
/// assert_eq!(pr.state, FrictionState::Slip);
/// ```
pub trait NonsmoothFrictionLaw<F: Real> {
    /// Per-point parameters (`mu`, orthotropy axes, ...).
    type Params: Clone + Debug;

    /// The projection of the trial traction `trial` onto the friction set of the normal
    /// stress `normal_pressure` (`sigma_n`, negative in compression), with its derivatives.
    ///
    /// # Errors
    /// [`FrictionError::NewtonNotConverged`] if an inner iteration (the ellipse's multiplier)
    /// exhausts its budget; [`FrictionError::NonFinite`] for a non-finite input.
    fn project(
        &self,
        trial: [F; 2],
        normal_pressure: F,
        params: &Self::Params,
    ) -> Result<Projection<F>, FrictionError>;
}

/// A nonsmooth law with its parameters bound: what a scene's nonsmooth law is at run time.
pub trait DynNonsmoothLaw: Send + Sync + Debug {
    /// [`NonsmoothFrictionLaw::project`] with the bound parameters.
    ///
    /// # Errors
    /// As [`NonsmoothFrictionLaw::project`].
    fn project(
        &self,
        trial: [f64; 2],
        normal_pressure: f64,
    ) -> Result<Projection<f64>, FrictionError>;
}

#[derive(Debug)]
struct BoundNonsmooth<L, P> {
    law: L,
    params: P,
}

impl<L, P> DynNonsmoothLaw for BoundNonsmooth<L, P>
where
    L: NonsmoothFrictionLaw<f64, Params = P> + Send + Sync + Debug,
    P: Send + Sync + Debug + Clone,
{
    fn project(
        &self,
        trial: [f64; 2],
        normal_pressure: f64,
    ) -> Result<Projection<f64>, FrictionError> {
        self.law.project(trial, normal_pressure, &self.params)
    }
}

/// `law` with its `params`, as the registry stores it.
pub fn bind_nonsmooth<L, P>(law: L, params: P) -> Arc<dyn DynNonsmoothLaw>
where
    L: NonsmoothFrictionLaw<f64, Params = P> + Send + Sync + Debug + 'static,
    P: Send + Sync + Debug + Clone + 'static,
{
    Arc::new(BoundNonsmooth { law, params })
}

/// A nonsmooth friction law that scenes can name (`friction.law`), registered beside the
/// smooth ones ([`crate::registry::register_nonsmooth`]).
#[derive(Debug, Clone, Copy)]
pub struct RegisteredNonsmoothLaw {
    /// The value of `friction.law` that selects it (e.g. `"exact-coulomb"`).
    pub name: &'static str,
    /// One line for listings and docs.
    pub summary: &'static str,
    /// The keys under `[friction]` it reads (without the `friction.` prefix).
    pub parameters: &'static [&'static str],
    /// Builds the law from the scene's values, validating those it reads.
    ///
    /// # Errors
    /// [`FrictionError::InvalidParameter`] naming the scene key of the first bad value.
    pub build: fn(&FrictionSettings) -> Result<Arc<dyn DynNonsmoothLaw>, FrictionError>,
}

/// The finiteness check every law runs on its input.
pub(crate) fn check_finite_input<F: Real>(
    trial: [F; 2],
    normal_pressure: F,
) -> Result<(), FrictionError> {
    use crate::error::{check, to_f64};
    for t in trial {
        check("trial traction", to_f64(t), "finite values", |_| true)?;
    }
    check(
        "normal stress",
        to_f64(normal_pressure),
        "finite values",
        |_| true,
    )?;
    Ok(())
}
