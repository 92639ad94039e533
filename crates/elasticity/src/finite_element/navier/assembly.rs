//! Assembly: the sparsity pattern built once with the slot of every element entry, the
//! element matrices, and the scatter with symmetric Dirichlet elimination.

use rayon::prelude::*;

use super::{FiniteElementNavier, PACK};
use crate::boundary::Component;
use crate::discretisation::Discretisation;
use crate::finite_element::assembly::bucket_starts;
use crate::finite_element::volumetric::VolumetricIntegration;
use crate::shell_geometry::ShellGeometry;
use capstan_solvers::SparsityPattern;

/// No slot: the local entry is dropped (Dirichlet row) or lifted to the right-hand side
/// (Dirichlet column).
pub(super) const NO_SLOT: u32 = u32::MAX;

/// Elements whose local matrices are computed in parallel before one sequential scatter.
const BATCH: usize = 2048;

impl<G: ShellGeometry + Sync> FiniteElementNavier<G> {
    /// Builds the row-wise pattern and the slot of every local element entry.
    pub(super) fn build_pattern(&mut self) {
        let g = self.problem.grid;
        let n2 = g.n2();
        let ndof = self.dof_count();
        let nen = self.nodes_per_element();
        // contact extras: the columns of T^3_j in each free tangential row on x3 = 0
        let mut extras: Vec<Vec<usize>> = vec![vec![]; n2];
        for (i, extra) in extras.iter_mut().enumerate() {
            let d = self.dof([i, 0], Component::X2);
            if self.dirichlet[d].is_none() {
                let rows = self.contact_rows(i);
                extra.extend(rows.iter().flat_map(|r| r.columns.iter().copied()));
            }
        }
        let rows: Vec<Vec<usize>> = (0..g.node_count())
            .into_par_iter()
            .map(|node| {
                let [i2, i3] = g.node(node);
                let mut neighbours = Vec::with_capacity(25);
                for e2 in self.elements_along(i2, self.elements[0], g.is_periodic()) {
                    for e3 in self.elements_along(i3, self.elements[1], false) {
                        let mut nn = [0; 9];
                        self.element_nodes(e2 * self.elements[1] + e3, &mut nn);
                        neighbours.extend_from_slice(&nn[..nen]);
                    }
                }
                neighbours.sort_unstable();
                neighbours.dedup();
                let mut cols = Vec::with_capacity(2 * neighbours.len());
                for m in neighbours {
                    for c in 0..2 {
                        if self.dirichlet[2 * m + c].is_none() {
                            cols.push(2 * m + c);
                        }
                    }
                }
                cols
            })
            .collect();
        let mut row_ptr = Vec::with_capacity(ndof + 1);
        let mut columns = Vec::with_capacity(ndof * 20);
        row_ptr.push(0);
        for d in 0..ndof {
            let node = d / 2;
            if self.dirichlet[d].is_some() {
                columns.push(d);
            } else {
                let start = columns.len();
                columns.extend_from_slice(&rows[node]);
                let [i2, i3] = g.node(node);
                if i3 == 0 && d % 2 == 0 {
                    columns.extend_from_slice(&extras[i2]);
                }
                columns[start..].sort_unstable();
                let mut w = start;
                for r in start..columns.len() {
                    if r == start || columns[r] != columns[w - 1] {
                        columns[w] = columns[r];
                        w += 1;
                    }
                }
                columns.truncate(w);
            }
            row_ptr.push(columns.len());
        }
        let slot = |r: usize, c: usize| -> Option<usize> {
            let row = &columns[row_ptr[r]..row_ptr[r + 1]];
            row.binary_search(&c).ok().map(|p| row_ptr[r] + p)
        };
        let ne = self.elements[0] * self.elements[1];
        let l = 2 * nen;
        let mut local_slots = vec![NO_SLOT; ne * l * l];
        // in parallel over elements; one search per (row, element node): the node's two
        // columns are neighbours in the sorted row (one of them absent if prescribed)
        let (row_ptr_ref, columns_ref, dirichlet) = (&row_ptr, &columns, &self.dirichlet);
        local_slots
            .par_chunks_mut(l * l)
            .enumerate()
            .for_each(|(e, out)| {
                let mut nodes = [0; 9];
                self.element_nodes(e, &mut nodes);
                for a in 0..l {
                    let r = 2 * nodes[a / 2] + a % 2;
                    let base = row_ptr_ref[r];
                    let row = &columns_ref[base..row_ptr_ref[r + 1]];
                    let out = &mut out[a * l..(a + 1) * l];
                    for (bn, &m) in nodes[..nen].iter().enumerate() {
                        let first = 2 * m;
                        let pos = row.partition_point(|&c| c < first);
                        for d in 0..2 {
                            let c = first + d;
                            let keep = if dirichlet[r].is_some() {
                                r == c
                            } else {
                                dirichlet[c].is_none()
                            };
                            if keep {
                                let p = if row.get(pos) == Some(&c) {
                                    pos
                                } else {
                                    pos + 1
                                };
                                assert!(row.get(p) == Some(&c), "element entry in the pattern");
                                out[2 * bn + d] = (base + p) as u32;
                            }
                        }
                    }
                }
            });
        // the compressed columns: the row-wise pattern transposed by a counting pass (rows come
        // out increasing in each column), and every row-wise slot mapped to its column slot
        let col_ptr = bucket_starts(&columns, ndof);
        let mut next = col_ptr[..ndof].to_vec();
        let mut row_idx = vec![0usize; columns.len()];
        let mut column_slot = vec![0u32; columns.len()];
        for r in 0..ndof {
            for k in row_ptr[r]..row_ptr[r + 1] {
                let c = columns[k];
                row_idx[next[c]] = r;
                column_slot[k] = next[c] as u32;
                next[c] += 1;
            }
        }
        local_slots.par_iter_mut().for_each(|s| {
            if *s != NO_SLOT {
                *s = column_slot[*s as usize];
            }
        });
        self.diagonal_slots = (0..ndof)
            .map(|d| column_slot[slot(d, d).expect("diagonal in the pattern")] as usize)
            .collect();
        self.pattern = SparsityPattern::from_compressed_columns(ndof, ndof, col_ptr, row_idx)
            .expect("rows increase in each column by construction");
        self.local_slots = local_slots;
    }

    /// The element matrix of element `e` into `out` (`2 nen x 2 nen`, row-major, local dof
    /// `2 a + c`), exactly symmetric.
    pub(super) fn element_matrix(&self, e: usize, out: &mut [f64]) {
        let (nq, nen) = (self.quadrature_points(), self.nodes_per_element());
        let l = 2 * nen;
        out.iter_mut().for_each(|x| *x = 0.0);
        let mut kb = [[[0.0f64; 2]; 6]; 9];
        for q in 0..nq {
            let packed = &self.stiffness[e * nq + q];
            let kq: [[f64; 6]; 6] =
                core::array::from_fn(|r| core::array::from_fn(|s| packed[PACK[r][s]]));
            let phi = &self.shape[q * nen..(q + 1) * nen];
            for (b, kbb) in kb.iter_mut().enumerate().take(nen) {
                let f = phi[b];
                for (row, kr) in kbb.iter_mut().enumerate() {
                    for (d, x) in kr.iter_mut().enumerate() {
                        *x = kq[row][d] * f[0] + kq[row][2 + d] * f[1] + kq[row][4 + d] * f[2];
                    }
                }
            }
            for a in 0..nen {
                let f = phi[a];
                for c in 0..2 {
                    let row = &mut out[(2 * a + c) * l..(2 * a + c + 1) * l];
                    for (b, kbb) in kb.iter().enumerate().take(nen) {
                        for d in 0..2 {
                            row[2 * b + d] +=
                                f[0] * kbb[c][d] + f[1] * kbb[2 + c][d] + f[2] * kbb[4 + c][d];
                        }
                    }
                }
            }
        }
        if self.volumetric == VolumetricIntegration::Reduced {
            // lambda (div v)(div w) sqrt(g) at the reduced points: a rank-one update per point
            // with the discrete divergence d_(a c) = t_c N_a + t_(2+c) d_2 N_a + t_(4+c) d_3 N_a
            let nr = self.order.degree().pow(2);
            let mut d = [0.0f64; 18];
            for r in 0..nr {
                let [c, t @ ..] = self.reduced_divergence[e * nr + r];
                let phi = &self.reduced_shape[r * nen..(r + 1) * nen];
                for (a, f) in phi.iter().enumerate() {
                    for comp in 0..2 {
                        d[2 * a + comp] = t[comp] * f[0] + t[2 + comp] * f[1] + t[4 + comp] * f[2];
                    }
                }
                for i in 0..l {
                    let ci = c * d[i];
                    for (x, dj) in out[i * l..(i + 1) * l].iter_mut().zip(&d[..l]) {
                        *x += ci * dj;
                    }
                }
            }
        }
        for i in 0..l {
            for j in i + 1..l {
                let s = 0.5 * (out[i * l + j] + out[j * l + i]);
                out[i * l + j] = s;
                out[j * l + i] = s;
            }
        }
    }

    /// The assembled values (in `pattern` order, that of `entries()`) and right-hand side.
    pub(super) fn assemble(&self, rhs: &mut [f64]) -> Vec<f64> {
        let nen = self.nodes_per_element();
        let l = 2 * nen;
        let ne = self.elements[0] * self.elements[1];
        let mut values = vec![0.0; self.pattern.nnz()];
        rhs.copy_from_slice(&self.load);
        let mut buffer = vec![0.0; BATCH.min(ne) * l * l];
        let mut nodes = [0; 9];
        for start in (0..ne).step_by(BATCH) {
            let end = (start + BATCH).min(ne);
            let buf = &mut buffer[..(end - start) * l * l];
            buf.par_chunks_mut(l * l)
                .enumerate()
                .for_each(|(i, out)| self.element_matrix(start + i, out));
            for e in start..end {
                let local = &buf[(e - start) * l * l..(e - start + 1) * l * l];
                let slots = &self.local_slots[e * l * l..(e + 1) * l * l];
                self.element_nodes(e, &mut nodes);
                for (idx, (&s, &x)) in slots.iter().zip(local).enumerate() {
                    if s != NO_SLOT {
                        values[s as usize] += x;
                    } else {
                        let (a, b) = (idx / l, idx % l);
                        let r = 2 * nodes[a / 2] + a % 2;
                        let c = 2 * nodes[b / 2] + b % 2;
                        if let (None, Some(g)) = (self.dirichlet[r], self.dirichlet[c]) {
                            rhs[r] -= x * g;
                        }
                    }
                }
            }
        }
        for (d, g) in self.dirichlet.iter().enumerate() {
            if let Some(g) = g {
                rhs[d] = values[self.diagonal_slots[d]] * g;
            }
        }
        values
    }
}
