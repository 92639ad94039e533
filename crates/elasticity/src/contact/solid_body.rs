//! The 3-D body's contact model: [`SolidBody::model`] and its operator with a body force
//! ([`SolidBody::operator_with_force`]), here in the contact room so that the
//! 3-D operator's room `solid` does not import the contact room that builds on it).

use capstan_friction::FrictionLaw;
use capstan_geometry::{ShellChart, Surface};

use crate::ElasticityError;
use crate::contact::body_force::BodyForceField;
use crate::contact::error::ContactError;
use crate::contact::model::ContactModel;
use crate::finite_element::high_order::CornerSettings;
use crate::solid::{SolidBody, SolidBoundary, SolidCornerNavier, SolidNavier};

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

impl<S: Surface<f64> + Clone + Send + Sync + 'static> SolidBody<S> {
    /// [`SolidBody::operator`] with the body force `force` (physical components, converted
    /// to the covariant ones on the body's chart).
    ///
    /// # Errors
    /// As [`SolidBody::operator`]; [`ElasticityError::NonFinite`] where the force is not
    /// finite.
    pub fn operator_with_force(
        &self,
        tau0: f64,
        tau_max: f64,
        force: Option<&BodyForceField>,
    ) -> Result<SolidNavier<ShellChart<S>>, ElasticityError> {
        let chart = ShellChart::new(self.surface.clone());
        let covariant = force.map(|f| f.solid(chart.clone()));
        SolidNavier::new(
            chart,
            self.material,
            self.grid()?,
            &self.boundary(tau0, tau_max),
            covariant.as_ref(),
            self.order,
            self.volumetric,
        )
    }

    /// The operator of the body on the corner-refined mesh `layout` extruded along `x1`
    /// ([`SolidCornerNavier`]: Qp hexahedra, layers toward the four edges where the contact
    /// and top faces meet the loaded ends) with the face conditions `boundary`
    /// ([`SolidBody::boundary`] or [`SolidBody::boundary_free_face`]) and the body force
    /// `force` (physical components).
    ///
    /// # Errors
    /// As [`SolidCornerNavier::new`] (naming `grid.n1`, `layers`, `ratio`, ...); grid and
    /// geometry errors; [`ElasticityError::NonFinite`] where the force is not finite.
    pub fn corner_operator(
        &self,
        layout: CornerSettings,
        boundary: &SolidBoundary,
        force: Option<&BodyForceField>,
    ) -> Result<SolidCornerNavier<ShellChart<S>>, ElasticityError> {
        let chart = ShellChart::new(self.surface.clone());
        let covariant = force.map(|f| f.solid(chart.clone()));
        SolidCornerNavier::new(
            chart,
            self.material,
            self.grid()?,
            boundary,
            covariant.as_ref(),
            layout,
        )
    }
}
