//! The 3-D part of the contact report (`capstan contact --json` key `solid`).

use capstan_elasticity::solid::SideFaces;
use serde::Serialize;

/// The `x1` fields of a 3-D body's contact surface, one entry per contact node (node order:
/// `x2` fastest, then `x1`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SolidContactArrays {
    /// `x1` of the contact nodes.
    pub x1: Vec<f64>,
    /// `v^1`.
    pub v1: Vec<f64>,
    /// `T^3_1`.
    pub shear_stress_1: Vec<f64>,
    /// Physical slip along `e_1 = a_1/|a_1|` (the report's `contact.slip` is along
    /// `e_2 = a^2/|a^2|`).
    pub slip_1: Vec<f64>,
    /// Physical friction traction on the body along `e_1`.
    pub friction_traction_1: Vec<f64>,
}

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
