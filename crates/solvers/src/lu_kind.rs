//! Which factorisation kernel [`crate::SparseLu`] uses.

/// The LU kernel of [`crate::SparseLu`] ([`crate::DirectParams::lu_kind`]).
///
/// Both kernels factor `P A Q = L U` with row pivoting; they differ in the static structure
/// they reserve and therefore in memory and speed:
/// ```text
/// supernodal:    struct(L + U) within struct(R + R^T),  R^T R = Q^T A^T A Q    any pivot row
/// multifrontal:  struct(L + U) within struct(C + C^T),  C^T C = Q^T (A + A^T) Q
///                pivots from the diagonal block of each front (threshold 0.01)
/// ```
/// Measured on the Navier operator (bench `bench_navier` of the elasticity crate, nested
/// dissection, 2 shared cores; `docs/verification.md`):
/// ```text
/// grid        unknowns    peak MiB                 LU s (analyse+factor+solve)
///                         multifrontal supernodal  multifrontal supernodal
/// 250 x 41      20,500        45          76          0.14        0.24
/// 1000 x 161   322,000       778        1677          3.7         7.2
/// 2000 x 321 1,284,000      3378        7881         20.4        26.2
/// ```
/// A matrix whose pivots cannot stay inside the fronts (a pivot below 0.01 of its column's
/// largest entry) is refactorised with the supernodal kernel automatically;
/// [`crate::SparseLu::last_kind`] tells which kernel made the current factors.
#[derive(
    Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize,
)]
#[serde(rename_all = "kebab-case")]
pub enum LuKind {
    /// The recommended kernel: [`LuKind::Multifrontal`] (with its supernodal fallback).
    #[default]
    Auto,
    /// faer's supernodal LU with partial pivoting over all rows, on the structure of `A^T A`
    /// (COLAMD by default).
    Supernodal,
    /// A multifrontal LU on the structure of `A + A^T` (AMD on `A + A^T` by default), with
    /// threshold pivoting inside each front's diagonal block; falls back to
    /// [`LuKind::Supernodal`] when a front has no acceptable pivot.
    Multifrontal,
}

impl LuKind {
    /// The kernel `Auto` stands for; the others are returned unchanged.
    pub fn resolved(self) -> Self {
        match self {
            Self::Auto => Self::Multifrontal,
            kind => kind,
        }
    }
}
