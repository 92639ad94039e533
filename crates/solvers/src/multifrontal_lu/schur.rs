//! The partial multifrontal factorisation that stops before the trailing positions and
//! returns their dense Schur complement (see [`crate::schur_complement`]).

use faer::Par;

use super::{FrontFailure, FrontalStructure};

/// Smallest accepted `|pivot| / max |entry of its column in the front|` of the partial
/// factorisation: looser than the LU's 0.01 (no fallback kernel here; the caller checks the
/// complement against a solve, [`crate::schur_complement`]).
pub(super) const SCHUR_PIVOT_THRESHOLD: f64 = 1e-3;
use crate::sparsity_pattern::SparsityPattern;

impl FrontalStructure {
    /// The dense Schur complement `S = A'_TT - A'_TI A'_II^-1 A'_IT` of `A' = Q^T A Q` onto the
    /// trailing positions `T = stop..n` (column-major, `(n - stop)^2` entries, position
    /// `stop + i` is row and column `i`).
    ///
    /// # Math
    /// The fronts of the supernodes before `stop` are factorised as in
    /// [`FrontalStructure::factor`] (a supernode straddling `stop` eliminates only its columns
    /// before it); their contribution blocks that reach past `stop`, and the entries of `A'`
    /// with both positions in `T`, are extend-added into `S`. The factors are not kept.
    pub(crate) fn schur_complement(
        &self,
        pattern: &SparsityPattern,
        values: &[f64],
        stop: usize,
        par: Par,
    ) -> Result<Vec<f64>, FrontFailure> {
        let n = self.perm_fwd.len();
        let k = n - stop;
        let row_idx = pattern.row_idx();
        let mut schur = vec![0.0; k * k];
        let mut pos = vec![0u32; n];
        let mut swaps = vec![0u32; n];
        let mut front: Vec<f64> = Vec::new();
        let mut contributions: Vec<Option<Vec<f64>>> = vec![None; self.n_supernodes()];
        // extend-adds a contribution block with the rows (positions, all >= stop) `rows`
        let add_into = |schur: &mut [f64], rows: &[usize], cb: &[f64]| {
            let nc = rows.len();
            for (bb, &jb) in rows.iter().enumerate() {
                let col = k * (jb - stop);
                for (a, &ia) in rows.iter().enumerate() {
                    schur[col + ia - stop] += cb[a + nc * bb];
                }
            }
        };
        for s in 0..self.n_supernodes() {
            let (b, e) = (self.begin[s], self.begin[s + 1]);
            if b >= stop {
                for &(slot, col) in &self.assembly[self.assembly_ptr[s]..self.assembly_ptr[s + 1]] {
                    let slot = slot as usize;
                    let i = self.perm_inv[row_idx[slot]] - stop;
                    let j = self.perm_inv[col as usize] - stop;
                    schur[i + k * j] += values[slot];
                }
                for &c in &self.children[self.child_ptr[s]..self.child_ptr[s + 1]] {
                    let c = c as usize;
                    if let Some(cb) = contributions[c].take() {
                        let rows: Vec<usize> =
                            self.off_block_rows(c).iter().map(|&i| i as usize).collect();
                        add_into(&mut schur, &rows, &cb);
                    }
                }
                continue;
            }
            let r = self.off_block_rows(s);
            let (ns, m) = (e - b, e - b + r.len());
            for t in 0..ns {
                pos[b + t] = t as u32;
            }
            for (t, &i) in r.iter().enumerate() {
                pos[i as usize] = (ns + t) as u32;
            }
            self.assemble_front(s, m, &pos, row_idx, values, &mut contributions, &mut front);
            let eliminated = e.min(stop) - b;
            self.eliminate(
                &mut front,
                m,
                eliminated,
                &mut swaps[b..],
                b,
                SCHUR_PIVOT_THRESHOLD,
                par,
            )?;
            let rest = m - eliminated;
            if rest == 0 {
                continue;
            }
            let mut cb = Vec::with_capacity(rest * rest);
            for t in eliminated..m {
                cb.extend_from_slice(&front[m * t + eliminated..m * (t + 1)]);
            }
            if e > stop {
                // straddles `stop`: its remaining rows are all trailing
                let rows: Vec<usize> = (b + eliminated..e)
                    .chain(r.iter().map(|&i| i as usize))
                    .collect();
                add_into(&mut schur, &rows, &cb);
            } else {
                contributions[s] = Some(cb);
            }
        }
        Ok(schur)
    }
}
