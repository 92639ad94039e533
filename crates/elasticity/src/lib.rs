//! Curvilinear linear elasticity: Navier operator, discretisations, contact.
