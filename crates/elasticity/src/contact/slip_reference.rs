//! The slip the law sees: the slip reference of a load path (the model whose friction acts
//! on the slip increment from a previous state, [`ContactModel::with_slip_reference`]) and
//! the site slip measured from it.

use std::sync::Arc;

use capstan_friction::FrictionLaw;

use super::{ContactModel, add_slip};
use crate::contact::error::ContactError;
use crate::error::ElasticityError;

impl<D, L: FrictionLaw<f64>> ContactModel<D, L> {
    /// The same model with friction acting on the slip *increment* from `reference`, the
    /// displacement of the previous load state of a path (`None`: from rest, the model as
    /// built); nothing is assembled again. Its [`crate::contact::BoundarySolver`] reuses a
    /// solver's condensation ([`crate::contact::BoundarySolver::with_model`]).
    ///
    /// # Math
    /// Quasi-static steps `n = 1, 2, ...`, each from the state `v_{n-1}` of the previous one:
    /// the tangential velocity of the law is the increment over the step,
    /// ```text
    /// u_k = F_k (x_k - x_k^{n-1})      (x_k: the site's v^alpha, F_k its frame)
    /// t_k = t(u_k, sigma_k)             (regularised: t = mu sigma u / max(|u|, eps))
    /// ```
    /// so stick means no further slip (`|u| < eps`; exact friction: `u = 0`) and the traction
    /// of a sticking site is whatever equilibrium asks within the friction set. The model
    /// without a reference is the one of rest, `x^0 = 0`, bit for bit.
    ///
    /// # Errors
    /// [`ElasticityError::DimensionMismatch`] unless `reference` has one value per unknown.
    pub fn with_slip_reference(&self, reference: Option<Vec<f64>>) -> Result<Self, ContactError>
    where
        L: Clone,
    {
        if let Some(r) = &reference
            && r.len() != self.dof_count()
        {
            return Err(ElasticityError::DimensionMismatch {
                quantity: "slip reference",
                expected: self.dof_count(),
                found: r.len(),
            }
            .into());
        }
        let mut model = self.with_params(self.params.clone());
        model.reference = reference.map(Arc::new);
        Ok(model)
    }

    /// The displacement the slip is measured from ([`ContactModel::with_slip_reference`]),
    /// `None` from rest.
    pub fn slip_reference(&self) -> Option<&[f64]> {
        self.reference.as_deref().map(Vec::as_slice)
    }

    /// The reference value of unknown `dof` (zero from rest).
    pub(crate) fn reference_of(&self, dof: usize) -> f64 {
        self.reference.as_ref().map_or(0.0, |r| r[dof])
    }

    /// The physical slip the law sees at site `j`, `u = sum_e (beta frame_e) (x_e - x_e^ref)`,
    /// for the entries' displacements `x(k)` (`k` an active index; `x^ref` the slip reference
    /// of a load path, [`ContactModel::with_slip_reference`], zero from rest).
    #[track_caller]
    pub fn site_slip(&self, j: usize, beta: f64, x: impl Fn(usize) -> f64) -> [f64; 2] {
        let Some(reference) = &self.reference else {
            return self.site_frame_slip(j, beta, x);
        };
        self.site_frame_slip(j, beta, |k| {
            x(k) - reference[self.active_node(k).tangential_dof]
        })
    }

    /// The physical vector `sum_e (beta frame_e) w_e` of site `j` for the entries' values
    /// `w(k)`, with no slip reference (a direction such as a rigid sliding mode).
    #[track_caller]
    pub fn site_frame_slip(&self, j: usize, beta: f64, w: impl Fn(usize) -> f64) -> [f64; 2] {
        let mut u = [0.0; 2];
        for &k in &self.sites.members[j] {
            add_slip(&mut u, beta, self.active_node(k).frame, w(k));
        }
        u
    }
}

/// A slide of length `size` (signed by `direction = +-1`) along a site's frame slip `w` of a
/// sliding mode: `direction size w / |w|`, or along `x2` (`[0, direction size]`) at a site the
/// mode does not move (`w = 0`, or not finite).
pub(crate) fn slide_along(w: [f64; 2], direction: f64, size: f64) -> [f64; 2] {
    let norm = (w[0] * w[0] + w[1] * w[1]).sqrt();
    if norm > 0.0 && norm.is_finite() {
        [
            direction * size * w[0] / norm,
            direction * size * w[1] / norm,
        ]
    } else {
        [0.0, direction * size]
    }
}
