//! Static condensation of a small dense symmetric positive definite block (e.g. a high-order
//! element's interior unknowns): its Schur complement by a dense Cholesky factorisation, and
//! the back-substitution of the eliminated values after the solve of the condensed system.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt::factor::{cholesky_in_place, cholesky_in_place_scratch};
use faer::linalg::matmul::triangular::{BlockStructure, matmul};
use faer::linalg::triangular_solve::solve_lower_triangular_in_place;
use faer::{Accum, MatMut, MatRef, Par};

use crate::error::SolverError;

/// Per-worker scratch of [`CondensedBlock::from_entries`]: faer's workspace of the
/// Cholesky factorisation of an `ni x ni` block.
pub struct CondensationScratch {
    mem: MemBuffer,
}

impl core::fmt::Debug for CondensationScratch {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("CondensationScratch")
            .finish_non_exhaustive()
    }
}

impl CondensationScratch {
    /// Scratch for interior blocks of `ni` unknowns.
    pub fn new(ni: usize) -> Self {
        Self {
            mem: MemBuffer::new(cholesky_in_place_scratch::<f64>(
                ni,
                Par::Seq,
                Default::default(),
            )),
        }
    }
}

/// One dense block (e.g. one element's matrix) after condensation of its interior unknowns.
///
/// # Math
/// With the element dofs split into boundary `B` (on the element's edges) and interior `I`,
/// ```text
/// [K_BB K_BI] [u_B]   [f_B]
/// [K_IB K_II] [u_I] = [f_I]
/// K_II = L L^T                       (Cholesky)
/// W = L^-1 K_IB,   z = L^-1 f_I      (one forward substitution, nb + 1 right-hand sides)
/// S = K_BB - W^T W = K_BB - K_BI K_II^-1 K_IB   (the element's Schur complement)
/// g = - W^T z = - K_BI K_II^-1 f_I              (added to the skeleton load)
/// u_I = L^-T (z - W u_B)             (after the global solve)
/// ```
/// `K_II` is positive definite for a positive definite element energy (interior functions
/// vanish on the element's edges), so its Cholesky factor exists. Only the lower triangles of
/// `K_II` and `K_BB` are read.
#[derive(Debug, Clone)]
pub struct CondensedBlock {
    /// `S`, `nb x nb` (bitwise symmetric, so row- and column-major alike).
    pub schur: Vec<f64>,
    /// `g`, `nb`.
    pub load: Vec<f64>,
    /// `L`, `ni x ni` column-major, lower triangle.
    pub factor: Vec<f64>,
    /// `[W | z]`, `ni x (nb + 1)` column-major.
    pub coupling: Vec<f64>,
}

impl CondensedBlock {
    /// Condenses the element matrix `k` (`l x l` row-major) onto the local dofs `boundary`,
    /// eliminating `interior` (whose load is `f_interior`).
    ///
    /// # Errors
    /// [`SolverError::Singular`] if `K_II` is not positive definite.
    pub fn new(
        k: &[f64],
        l: usize,
        boundary: &[usize],
        interior: &[usize],
        f_interior: &[f64],
    ) -> Result<Self, SolverError> {
        let mut scratch = CondensationScratch::new(interior.len());
        Self::from_entries(
            |i, j| k[i * l + j],
            boundary,
            interior,
            f_interior,
            &mut scratch,
        )
    }

    /// Condenses the element matrix whose entry `(i, j)` (local dofs) is `entry(i, j)`, as
    /// [`Self::new`]; read are all of `K_IB` and the lower triangles of `K_II` and `K_BB`
    /// (in the order of `interior` and `boundary`).
    ///
    /// # Errors
    /// [`SolverError::Singular`] if `K_II` is not positive definite (or not finite).
    pub fn from_entries(
        entry: impl Fn(usize, usize) -> f64,
        boundary: &[usize],
        interior: &[usize],
        f_interior: &[f64],
        scratch: &mut CondensationScratch,
    ) -> Result<Self, SolverError> {
        let (nb, ni) = (boundary.len(), interior.len());
        let mut factor = vec![0.0; ni * ni];
        for (c, &j) in interior.iter().enumerate() {
            for (r, &i) in interior.iter().enumerate().skip(c) {
                factor[c * ni + r] = entry(i, j);
            }
        }
        let m = nb + 1;
        let mut coupling = vec![0.0; ni * m];
        for (c, &j) in boundary.iter().enumerate() {
            for (x, &i) in coupling[c * ni..(c + 1) * ni].iter_mut().zip(interior) {
                *x = entry(i, j);
            }
        }
        coupling[nb * ni..].copy_from_slice(f_interior);
        let mut schur = vec![0.0; nb * nb];
        for (c, &j) in boundary.iter().enumerate() {
            for (r, &i) in boundary.iter().enumerate().skip(c) {
                schur[c * nb + r] = entry(i, j);
            }
        }
        let mut load = vec![0.0; nb];
        if ni > 0 {
            let singular = |j| SolverError::Singular { pivot: Some(j) };
            let stack = MemStack::new(&mut scratch.mem);
            let mut l = MatMut::from_column_major_slice_mut(&mut factor, ni, ni);
            cholesky_in_place(
                l.as_mut(),
                Default::default(),
                Par::Seq,
                stack,
                Default::default(),
            )
            .map_err(|e| match e {
                faer::linalg::cholesky::llt::factor::LltError::NonPositivePivot { index } => {
                    singular(index)
                }
            })?;
            if let Some(j) = (0..ni).find(|&j| !(l[(j, j)] > 0.0 && l[(j, j)].is_finite())) {
                return Err(singular(j));
            }
            let mut wz = MatMut::from_column_major_slice_mut(&mut coupling, ni, m);
            solve_lower_triangular_in_place(l.as_ref(), wz.as_mut(), Par::Seq);
            let w = wz.as_ref().subcols(0, nb);
            let s = MatMut::from_column_major_slice_mut(&mut schur, nb, nb);
            matmul(
                s,
                BlockStructure::TriangularLower,
                Accum::Add,
                w.transpose(),
                BlockStructure::Rectangular,
                w,
                BlockStructure::Rectangular,
                -1.0,
                Par::Seq,
            );
            let z = &coupling[nb * ni..];
            for (g, col) in load.iter_mut().zip(coupling.chunks_exact(ni)) {
                *g = -col.iter().zip(z).map(|(a, b)| a * b).sum::<f64>();
            }
        }
        // the upper triangle mirrors the lower: bitwise symmetric (the assembly and the
        // Cholesky backend rely on it)
        for c in 0..nb {
            for r in c + 1..nb {
                schur[r * nb + c] = schur[c * nb + r];
            }
        }
        Ok(Self {
            schur,
            load,
            factor,
            coupling,
        })
    }

    /// The interior values `u_I = L^-T (z - W u_B)` for the boundary values `u_b`.
    pub fn recover(&self, u_b: &[f64]) -> Vec<f64> {
        let nb = u_b.len();
        let ni = self.coupling.len() / (nb + 1);
        if ni == 0 {
            return vec![];
        }
        let mut x = self.coupling[nb * ni..].to_vec();
        for (col, u) in self.coupling.chunks_exact(ni).zip(u_b) {
            for (xi, w) in x.iter_mut().zip(col) {
                *xi -= w * u;
            }
        }
        let l = MatRef::from_column_major_slice(&self.factor, ni, ni);
        for i in (0..ni).rev() {
            let s: f64 = (i + 1..ni).map(|k| l[(k, i)] * x[k]).sum();
            x[i] = (x[i] - s) / l[(i, i)];
        }
        x
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn condensation_then_recovery_solves_the_whole_system() {
        // a 5 x 5 SPD matrix: boundary {0, 3}, interior {1, 2, 4}
        let n = 5;
        let mut k = vec![0.0; n * n];
        for i in 0..n {
            for j in 0..n {
                k[i * n + j] = 1.0 / (1.0 + i as f64 + j as f64) + if i == j { 1.0 } else { 0.0 };
            }
        }
        let f = [1.0, -2.0, 0.5, 3.0, 1.5];
        let (b, i) = ([0, 3], [1, 2, 4]);
        let e = CondensedBlock::new(&k, n, &b, &i, &[f[1], f[2], f[4]]).unwrap();
        // S u_B = f_B + g
        let s = &e.schur;
        let rb = [f[0] + e.load[0], f[3] + e.load[1]];
        let det = s[0] * s[3] - s[1] * s[2];
        let ub = [
            (rb[0] * s[3] - s[1] * rb[1]) / det,
            (s[0] * rb[1] - s[2] * rb[0]) / det,
        ];
        let ui = e.recover(&ub);
        let u = [ub[0], ui[0], ui[1], ub[1], ui[2]];
        for r in 0..n {
            let ax: f64 = (0..n).map(|c| k[r * n + c] * u[c]).sum();
            assert!((ax - f[r]).abs() < 1e-13, "row {r}"); // round-off of a 5 x 5 solve
        }
    }

    #[test]
    fn an_indefinite_interior_block_is_a_typed_error() {
        // K_II = [[1, 2], [2, 1]] (eigenvalues 3, -1), boundary {0}
        let k = [4.0, 1.0, 0.0, 1.0, 1.0, 2.0, 0.0, 2.0, 1.0];
        let e = CondensedBlock::new(&k, 3, &[0], &[1, 2], &[0.0, 0.0]);
        assert!(matches!(e, Err(SolverError::Singular { .. })));
    }
}
