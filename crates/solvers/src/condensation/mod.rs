//! Static condensation: the elimination of a set of unknowns `I` from a linear system onto the
//! rest `B`, and the recovery of the eliminated values after the condensed system is solved.
//!
//! # Math
//! ```text
//! [A_BB A_BI] [x_B]   [b_B]
//! [A_IB A_II] [x_I] = [b_I]
//! S   = A_BB - A_BI A_II^-1 A_IB        the Schur complement onto B
//! g   = b_B  - A_BI A_II^-1 b_I         the condensed right-hand side
//! S x_B = g,    x_I = A_II^-1 (b_I - A_IB x_B)
//! ```
//! This is the one place in the workspace that computes `S`. Two kernels serve the two shapes
//! the callers have:
//! - [`CondensedBlock`] (dense): a small symmetric positive definite block, e.g. one
//!   high-order element's interior unknowns; `A_II` by a dense Cholesky factorisation, `S`,
//!   `g` and the recovery of `x_I` from the stored factor. The high-order operators condense
//!   every element with it (`capstan-elasticity`'s `HighOrderNavier` and the corner mesh).
//! - [`schur_complement`] (sparse): a large sparse square `A` condensed onto a few trailing
//!   unknowns `T` by one partial multifrontal factorisation of the interior (no solves), `S`
//!   dense; e.g. the elastic bulk onto the contact face (`capstan-elasticity`'s condensed
//!   contact solver). Where it reports that the interior needs pivoting across fronts, the
//!   caller condenses by `|T|` solves with a full factorisation instead.

mod dense;
mod sparse;

pub use dense::{CondensationScratch, CondensedBlock};
pub use sparse::schur_complement;
