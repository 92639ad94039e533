//! The optional features of this build that register themselves in the member crates'
//! registries (feature `petsc`: the linear backend `petsc`). Below `scene` and `scale`: scene
//! validation and [`crate::Scene::build`] call [`register_feature_backends`] before they parse
//! `solver.linear`.

/// Whether this build has the PETSc backend (`solver.linear = "petsc"`, cargo feature `petsc`).
pub const PETSC_ENABLED: bool = cfg!(feature = "petsc");

/// Whether the linear backend `linear` (a `solver.linear` value) solves collectively over MPI
/// ranks (`petsc`): every rank must then make the same PETSc and MPI calls in the same order,
/// from the thread that started PETSc, so a command runs such solves one after another on
/// that thread, never two at once (two solves on two threads interleave their messages
/// differently on different ranks: `MPI_ERR_TRUNCATE` in the first gather).
pub fn collective_backend(linear: &str) -> bool {
    linear == "petsc"
}

/// Registers the linear backends of this build's optional features in
/// `capstan_solvers::linear_registry` (feature `petsc`: `petsc`), once per process; scene
/// validation and [`crate::Scene::build`] call it before they parse `solver.linear`.
pub fn register_feature_backends() {
    #[cfg(feature = "petsc")]
    {
        static ONCE: std::sync::Once = std::sync::Once::new();
        ONCE.call_once(|| {
            // a program that registered it itself first keeps its entry
            let _ =
                capstan_elasticity::solvers::linear_registry::register(capstan_petsc::REGISTRATION);
        });
    }
}
