//! Unilateral (Signorini) contact on `x3 = 0`: the kind of constraint on the contact face and
//! the complementarity rows that replace the bilateral `v^3 = 0`.

use crate::boundary::PointFunction;
use crate::contact::error::ContactError;
use crate::discretisation::{ContactNode, LinearSystem};
use crate::error::ElasticityError;

/// The initial normal gap `g(x1, x2)` between the body's face `x3 = 0` and the obstacle
/// (length, `>= 0`; `x1 = 0` in plane strain): the obstacle lies at `x3 = -g`, so the face
/// can move `g` towards it before touching.
pub type Gap = PointFunction<[f64; 2]>;

/// The kind of constraint on the contact face `x3 = 0` (`contact.kind` in scenes).
///
/// # Math
/// ```text
/// bilateral:   v^3 = 0                                           (the paper's contact)
/// unilateral:  v^3 + g >= 0,  lambda >= 0,  (v^3 + g) lambda = 0  (Signorini)
/// ```
/// `lambda` is the contact reaction of the node (compression positive): the residual of the
/// free (traction-free) normal balance row. Friction acts only where the node is in contact.
#[derive(Debug, Clone, Default)]
pub enum ContactKind {
    /// `v^3 = 0` everywhere on the face (default; the paper's results).
    #[default]
    Bilateral,
    /// Signorini contact with the initial gap `gap` (zero for the conforming body).
    Unilateral {
        /// `g(x1, x2)`.
        gap: Gap,
    },
}

impl ContactKind {
    /// The registered names, in the order of `contact.kind`.
    pub const NAMES: [&'static str; 2] = ["bilateral", "unilateral"];

    /// Unilateral contact with zero gap (a conforming body).
    pub fn unilateral() -> Self {
        Self::Unilateral { gap: Gap::zero() }
    }

    /// `bilateral` or `unilateral`.
    pub fn name(&self) -> &'static str {
        match self {
            Self::Bilateral => "bilateral",
            Self::Unilateral { .. } => "unilateral",
        }
    }

    /// Whether the body can lift off.
    pub fn is_unilateral(&self) -> bool {
        matches!(self, Self::Unilateral { .. })
    }
}

/// The Signorini condition at one contact node: its normal dof, gap and free balance row.
#[derive(Debug, Clone)]
pub(crate) struct NormalRow {
    /// Dof (and row) of `v^3`.
    pub dof: usize,
    /// `g` at the node.
    pub gap: f64,
    /// `|a_kk|`, the diagonal of the free row (the row scale).
    pub scale: f64,
    /// `sign(a_kk)`: the reaction is `sign (a . v - b_k) / scale`.
    pub sign: f64,
    /// `(column, value, slot of the entry in the system's values)` of the free row.
    pub entries: Vec<(usize, f64, usize)>,
    /// Slot of the diagonal in the system's values.
    pub diagonal: usize,
}

impl NormalRow {
    /// The reaction `lambda = sign (a . v - b_k) / scale` (compression positive, in units of
    /// displacement).
    pub fn reaction(&self, v: &[f64], rhs: &[f64]) -> f64 {
        let av: f64 = self.entries.iter().map(|&(c, a, _)| a * v[c]).sum();
        self.sign * (av - rhs[self.dof]) / self.scale
    }

    /// `v^3 + g`: the distance to the obstacle.
    pub fn opening(&self, v: &[f64]) -> f64 {
        v[self.dof] + self.gap
    }

    /// Whether the node is in contact at `v`: `v^3 + g <= lambda` (the `min` picks the gap).
    pub fn in_contact(&self, v: &[f64], rhs: &[f64]) -> bool {
        self.opening(v) <= self.reaction(v, rhs)
    }
}

/// The unilateral rows of a contact model.
#[derive(Debug, Clone)]
pub(crate) struct Unilateral {
    pub rows: Vec<NormalRow>,
    /// The normal row of each friction site (index into `rows`), `None` where `v^3` is
    /// prescribed by another condition.
    pub site_row: Vec<Option<usize>>,
}

impl Unilateral {
    /// From the system `free` of the body with a traction-free contact face (same numbering
    /// as the bilateral body; `site_of(a)` the friction site of contact node `a`): the free normal rows of the contact `nodes` are kept here, and
    /// `free` becomes the all-in-contact system (those rows replaced by `scale v^3`, their
    /// columns kept) that the stuck start and the Jacobian start from.
    ///
    /// # Errors
    /// [`ElasticityError::InvalidParameter`] naming `contact.gap` for a negative or
    /// non-finite gap, or naming `contact.kind` for a contact node whose free normal row has
    /// no diagonal.
    pub fn new(
        free: &mut LinearSystem,
        nodes: &[ContactNode],
        site_of: impl Fn(usize) -> Option<usize>,
        sites: usize,
        gap: &Gap,
    ) -> Result<Self, ContactError> {
        let n = free.dimension();
        let mut row_of = vec![usize::MAX; n];
        let mut rows: Vec<NormalRow> = Vec::new();
        let mut site_row = vec![None; sites];
        for (a, node) in nodes.iter().enumerate() {
            let dof = node.normal_dof;
            if row_of[dof] == usize::MAX {
                let g = gap.eval([node.x1, node.x2]);
                if !(g.is_finite() && g >= 0.0) {
                    return Err(ContactError::from(ElasticityError::InvalidParameter {
                        field: "contact.gap",
                        value: g,
                        allowed: "finite values >= 0 on the contact face",
                    }));
                }
                row_of[dof] = rows.len();
                rows.push(NormalRow {
                    dof,
                    gap: g,
                    scale: 0.0,
                    sign: 1.0,
                    entries: Vec::new(),
                    diagonal: usize::MAX,
                });
            }
            if let Some(site) = site_of(a) {
                site_row[site] = Some(row_of[dof]);
            }
        }
        for (slot, (i, j)) in free.pattern.entries().enumerate() {
            let k = row_of[i];
            if k == usize::MAX {
                continue;
            }
            let a = free.values[slot];
            rows[k].entries.push((j, a, slot));
            if i == j {
                rows[k].diagonal = slot;
                rows[k].scale = a.abs();
                rows[k].sign = if a < 0.0 { -1.0 } else { 1.0 };
            }
        }
        for row in &rows {
            if row.diagonal == usize::MAX || row.scale.is_nan() || row.scale <= 0.0 {
                return Err(ContactError::from(ElasticityError::InvalidParameter {
                    field: "contact.kind",
                    value: row.dof as f64,
                    allowed: "contact nodes whose free normal row has a diagonal (`unilateral` needs a discretisation with a traction-free contact face)",
                }));
            }
        }
        for row in &rows {
            for &(_, _, slot) in &row.entries {
                free.values[slot] = 0.0;
            }
            free.values[row.diagonal] = row.scale;
        }
        Ok(Self { rows, site_row })
    }

    /// `b` with the normal rows set to `scale (-g)`, or to zero with `gap = false`: the
    /// right-hand side of the all-in-contact system (`v^3 = -g`, the closed start).
    pub fn closed_rows(&self, b: &mut [f64], gap: bool) {
        for row in &self.rows {
            b[row.dof] = if gap { -row.scale * row.gap } else { 0.0 };
        }
    }

    /// Per row, whether the node is in contact at `v`.
    pub fn contact_set(&self, v: &[f64], rhs: &[f64]) -> Vec<bool> {
        self.rows.iter().map(|r| r.in_contact(v, rhs)).collect()
    }

    /// The complementarity residual `scale min(v^3 + g, lambda)` of every row into `r`.
    pub fn residual_into(&self, v: &[f64], rhs: &[f64], r: &mut [f64]) {
        for row in &self.rows {
            r[row.dof] = row.scale * row.opening(v).min(row.reaction(v, rhs));
        }
    }

    /// Its generalised Jacobian: rows in contact `scale e_k` (already in `values`, from the
    /// all-in-contact system); separated rows `sign a_k` (the free balance row).
    pub fn jacobian_into(&self, v: &[f64], rhs: &[f64], a_slot: &[usize], values: &mut [f64]) {
        for row in &self.rows {
            if row.in_contact(v, rhs) {
                continue;
            }
            values[a_slot[row.diagonal]] -= row.scale;
            for &(_, a, slot) in &row.entries {
                values[a_slot[slot]] += row.sign * a;
            }
        }
    }
}
