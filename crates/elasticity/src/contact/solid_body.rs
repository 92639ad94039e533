//! The 3-D body's contact model: [`SolidBody::model`] (here, in the contact room, so that the
//! 3-D operator's room `solid` does not import the contact room that builds on it).

use capstan_friction::FrictionLaw;
use capstan_geometry::{ShellChart, Surface};

use crate::contact::error::ContactError;
use crate::contact::model::ContactModel;
use crate::solid::{SolidBody, SolidNavier};

impl<S: Surface<f64> + Clone + Send + Sync> SolidBody<S> {
    /// The contact model with the friction law `law` (stick/slip threshold `slip_threshold`).
    ///
    /// # Errors
    /// See [`ContactModel::new`].
    pub fn model<L: FrictionLaw<f64>>(
        &self,
        law: L,
        params: L::Params,
        slip_threshold: f64,
    ) -> Result<ContactModel<SolidNavier<ShellChart<S>>, L>, ContactError> {
        ContactModel::new(
            |tau0, tau_max| self.operator(tau0, tau_max),
            law,
            params,
            slip_threshold,
        )
    }
}
