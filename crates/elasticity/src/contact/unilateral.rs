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

    /// The largest compressive normal stress the friction law may use at the node, from the
    /// contact reaction spread over the node's traction weight `weight`:
    /// `scale (lambda - (v^3 + g)) / weight` (see [`FRICTION_PRESSURE_CAP`]); `>= 0` where the
    /// node is in contact, zero where it switches to separated.
    pub fn friction_cap(&self, v: &[f64], rhs: &[f64], weight: f64) -> f64 {
        FRICTION_PRESSURE_CAP * self.scale * (self.reaction(v, rhs) - self.opening(v)) / weight
    }

    /// `d friction_cap / d v` as `(column, value)` pairs (the free row's columns and the
    /// normal dof; a column may repeat).
    pub fn friction_cap_gradient(&self, weight: f64) -> impl Iterator<Item = (usize, f64)> + '_ {
        let k = FRICTION_PRESSURE_CAP / weight;
        self.entries
            .iter()
            .map(move |&(c, a, _)| (c, k * self.sign * a))
            .chain(std::iter::once((self.dof, -k * self.scale)))
    }
}

/// Factor on the contact reaction in the cap on the friction law's normal stress under
/// unilateral contact.
///
/// # Math
/// ```text
/// p_k = min(-min(sigma_n, 0), c F_k / w_k),   F_k = scale_k (lambda_k - (v^3_k + g_k)) >= 0
/// ```
/// The law reads `sigma_n = T^3_3` recovered from the displacement, which does not vanish
/// where a node is about to lift off (its reaction `lambda_k -> 0`): without the cap the
/// friction force `w_k mu |sigma_n|` jumps to zero when the node separates, the residual is
/// discontinuous there, and Newton stalls when an equilibrium lies at the jump (found on the
/// 3-D cone, `3 x 20 x 3`, ratio 1.35: a site lifting off with `sigma_n = -1.38`, the residual
/// jumping from `6e-4` to `3.3e-2`). With the cap the friction force is at most `c` times the
/// contact reaction `F_k` (Coulomb on the reaction), continuous at lift-off; at a node that
/// presses (reaction well above `w_k |sigma_n| / c`) the law is unchanged, so unilateral
/// contact still equals bilateral where every node presses.
pub(crate) const FRICTION_PRESSURE_CAP: f64 = 2.0;

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

#[cfg(test)]
mod tests {
    use super::*;

    /// A normal row `2 v0 - v1 + 0.5 v2` on dof 0 (diagonal 2, slots 0..3), gap 0.1.
    fn row() -> NormalRow {
        NormalRow {
            dof: 0,
            gap: 0.1,
            scale: 2.0,
            sign: 1.0,
            entries: vec![(0, 2.0, 0), (1, -1.0, 1), (2, 0.5, 2)],
            diagonal: 0,
        }
    }

    #[test]
    fn the_friction_cap_vanishes_where_the_node_switches_to_separated() {
        let r = row();
        let rhs = [0.3, 0.0, 0.0];
        // v0 = -0.05: opening 0.05; reaction (2 v0 - v1 + v2/2 - 0.3) / 2 = 0.05 at v1 = -0.5
        let v = [-0.05, -0.5, 0.0];
        assert!((r.opening(&v) - r.reaction(&v, &rhs)).abs() < 1e-15);
        // continuous across the switch: zero there, positive in contact, negative beyond
        assert!(r.friction_cap(&v, &rhs, 0.25).abs() < 1e-14);
        let pressed = [-0.05, -0.6, 0.0];
        assert!(r.in_contact(&pressed, &rhs));
        // cap = c scale (lambda - opening) / w = 2 * 2 * (0.1 - 0.05) / 0.25
        let expected = FRICTION_PRESSURE_CAP * 2.0 * 0.05 / 0.25;
        assert!((r.friction_cap(&pressed, &rhs, 0.25) - expected).abs() < 1e-12);
        let lifted = [-0.05, -0.4, 0.0];
        assert!(!r.in_contact(&lifted, &rhs));
        assert!(r.friction_cap(&lifted, &rhs, 0.25) < 0.0);
    }

    #[test]
    fn the_friction_cap_gradient_matches_central_differences() {
        let r = row();
        let rhs = [0.3, 0.0, 0.0];
        let v = [-0.02, -0.7, 0.3];
        let mut gradient = [0.0; 3];
        for (c, g) in r.friction_cap_gradient(0.25) {
            gradient[c] += g;
        }
        for c in 0..3 {
            let h = 1e-6;
            let (mut plus, mut minus) = (v, v);
            plus[c] += h;
            minus[c] -= h;
            let fd = (r.friction_cap(&plus, &rhs, 0.25) - r.friction_cap(&minus, &rhs, 0.25))
                / (2.0 * h);
            // affine in v: central differences exact up to round-off
            assert!((fd - gradient[c]).abs() < 1e-8, "{c}: {fd} {}", gradient[c]);
        }
    }
}
