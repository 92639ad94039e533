//! The 3-D part of the contact report (`capstan contact --json` key `solid`).

use capstan_elasticity::contact::SolidContactProfile;
use capstan_elasticity::solid::SideFaces;
use serde::Serialize;

/// The `x1` fields of a 3-D body's contact surface, one entry per contact node (node order:
/// `x2` fastest, then `x1`): the solver's profile as reported (the report's `contact.slip` is
/// along `e_2 = a^2/|a^2|`, `slip_1` along `e_1 = a_1/|a_1|`).
pub type SolidContactArrays = SolidContactProfile;

/// The 3-D part of `capstan contact --json` (key `solid`; absent in plane strain).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SolidReport {
    /// `3`.
    pub dimension: u8,
    /// `[n1, n2, n3]`.
    pub grid: [usize; 3],
    /// `[x1a, x1b]`.
    pub x1: [f64; 2],
    /// `free` or `plane-strain`.
    pub sides: SideFaces,
    /// Contact unknowns (tangential entries with friction: two per contact node).
    pub contact_unknowns: usize,
    /// The `x1` fields on the contact surface.
    pub contact: SolidContactArrays,
}
