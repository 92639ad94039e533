//! Generic assembly of element matrices on any element connectivity: the sparsity pattern
//! built once with the slot of every local entry, and the scatter with symmetric Dirichlet
//! elimination. Used by the 3-D body (hexahedra); the element kernel is the caller's.

use rayon::prelude::*;

use capstan_solvers::SparsityPattern;

use crate::discretisation::LinearSystem;
use crate::error::ElasticityError;

/// No slot: the local entry is dropped (Dirichlet row) or lifted to the right-hand side
/// (Dirichlet column).
const NO_SLOT: u32 = u32::MAX;

/// Element matrices computed in parallel per batch before one sequential scatter (in element
/// order, so the values are bitwise reproducible): batches of about 4 MiB of element
/// matrices, at least 256 and at most 4096 elements (few fork-joins for the small 2-D
/// elements, a bounded buffer for the large 3-D ones).
fn batch(local_entries: usize) -> usize {
    const BYTES: usize = 4 << 20;
    (BYTES / (8 * local_entries.max(1))).clamp(256, 4096)
}

/// The pattern of an operator assembled from elements, with `components` unknowns per node
/// (dof `components * node + c`) and the slot of every local entry.
///
/// # Math
/// Dirichlet conditions are imposed strongly and symmetrically: the row and column of a
/// prescribed dof `d` hold only the diagonal, the column's contributions `K_rd g_d` move to
/// the right-hand side of the free rows, and row `d` becomes `K_dd v_d = K_dd g_d` with the
/// assembled diagonal. With symmetric element matrices the assembled matrix is symmetric and
/// its pattern too, so the row-wise pattern is also the column-wise (CSC) one.
#[derive(Debug, Clone)]
pub struct ElementAssembly {
    pattern: SparsityPattern,
    /// Per element, `l x l` slots (row-major, local dof `components * a + c`).
    slots: Vec<u32>,
    diagonal: Vec<usize>,
    connectivity: Vec<usize>,
    nodes_per_element: usize,
    components: usize,
    /// The rows assembled (all unless [`ElementAssembly::for_rows`]).
    rows: core::ops::Range<usize>,
    /// The number of each element kept among the caller's ([`ElementAssembly::for_rows`];
    /// empty: all, in order).
    element_ids: Vec<usize>,
}

impl ElementAssembly {
    /// The pattern of the elements whose nodes are `connectivity` (`nodes_per_element` per
    /// element, in the element's local order), on `node_count` nodes, for the prescribed
    /// dofs of `dirichlet` (`Some(value)`).
    ///
    /// # Errors
    /// [`ElasticityError::DimensionMismatch`] if `dirichlet` has not one entry per dof or the
    /// connectivity is not whole elements; [`ElasticityError::InvalidParameter`] if the
    /// pattern has more than `u32::MAX` nonzeros.
    pub fn new(
        node_count: usize,
        components: usize,
        nodes_per_element: usize,
        connectivity: Vec<usize>,
        dirichlet: &[Option<f64>],
    ) -> Result<Self, ElasticityError> {
        let ndof = components * node_count;
        ElasticityError::check_length("dirichlet values", ndof, dirichlet.len())?;
        let nen = nodes_per_element;
        ElasticityError::check_length(
            "connectivity",
            connectivity.len().div_ceil(nen.max(1)) * nen,
            connectivity.len(),
        )?;
        let ne = connectivity.len() / nen.max(1);
        // node -> elements, by counting
        let start = bucket_starts(&connectivity, node_count);
        let mut fill = start[..node_count].to_vec();
        let mut elements_of = vec![0usize; connectivity.len()];
        for (k, &m) in connectivity.iter().enumerate() {
            elements_of[fill[m]] = k / nen;
            fill[m] += 1;
        }
        // free columns of every node's rows (sorted)
        let columns_of_node: Vec<Vec<usize>> = (0..node_count)
            .into_par_iter()
            .map(|m| {
                let mut nbrs: Vec<usize> = elements_of[start[m]..start[m + 1]]
                    .iter()
                    .flat_map(|&e| connectivity[e * nen..(e + 1) * nen].iter().copied())
                    .collect();
                nbrs.sort_unstable();
                nbrs.dedup();
                nbrs.iter()
                    .flat_map(|&n| (0..components).map(move |c| components * n + c))
                    .filter(|&d| dirichlet[d].is_none())
                    .collect()
            })
            .collect();
        let mut col_ptr = Vec::with_capacity(ndof + 1);
        col_ptr.push(0);
        let mut row_idx = Vec::new();
        for d in 0..ndof {
            if dirichlet[d].is_some() {
                row_idx.push(d);
            } else {
                row_idx.extend_from_slice(&columns_of_node[d / components]);
            }
            col_ptr.push(row_idx.len());
        }
        drop(columns_of_node);
        if row_idx.len() > u32::MAX as usize {
            return Err(ElasticityError::InvalidParameter {
                field: "pattern nonzeros",
                value: row_idx.len() as f64,
                allowed: "[0, 2^32)",
            });
        }
        let slot = |r: usize, c: usize| -> Option<usize> {
            let row = &row_idx[col_ptr[r]..col_ptr[r + 1]];
            row.binary_search(&c).ok().map(|p| col_ptr[r] + p)
        };
        let l = components * nen;
        let mut slots = vec![NO_SLOT; ne * l * l];
        // one search per (row, element node): a node's kept columns are consecutive in the
        // sorted column (the pattern is symmetric: column r lists the columns of row r)
        slots
            .par_chunks_mut(l * l.max(1))
            .enumerate()
            .for_each(|(e, out)| {
                let nodes = &connectivity[e * nen..(e + 1) * nen];
                for a in 0..l {
                    let r = components * nodes[a / components] + a % components;
                    let base = col_ptr[r];
                    let row = &row_idx[base..col_ptr[r + 1]];
                    let out = &mut out[a * l..(a + 1) * l];
                    for (bn, &m) in nodes.iter().enumerate() {
                        let first = components * m;
                        let mut pos = row.partition_point(|&c| c < first);
                        for d in 0..components {
                            let c = first + d;
                            let keep = if dirichlet[r].is_some() {
                                r == c
                            } else {
                                dirichlet[c].is_none()
                            };
                            if keep {
                                assert!(row.get(pos) == Some(&c), "element entry in the pattern");
                                out[components * bn + d] = (base + pos) as u32;
                                pos += 1;
                            }
                        }
                    }
                }
            });
        let diagonal = (0..ndof)
            .map(|d| slot(d, d).expect("diagonal in the pattern"))
            .collect();
        let pattern = SparsityPattern::from_compressed_columns(ndof, ndof, col_ptr, row_idx)?;
        Ok(Self {
            pattern,
            slots,
            diagonal,
            connectivity,
            nodes_per_element: nen,
            components,
            rows: 0..ndof,
            element_ids: Vec::new(),
        })
    }

    /// As [`ElementAssembly::new`], for the rows `rows` alone (whole nodes: `rows` starts
    /// and ends at multiples of `components`), as one process of a distributed solve holds
    /// them: only the elements with a node in `rows` are kept ([`ElementAssembly::element_id`]
    /// gives their numbers among the caller's), and the pattern has entries in `rows` only
    /// (its other rows are empty). [`ElementAssembly::assemble`] then gives the matrix rows
    /// and right-hand side entries of `rows` exactly as the whole assembly does; the other
    /// right-hand side entries are partial sums.
    ///
    /// # Errors
    /// As [`ElementAssembly::new`]; [`ElasticityError::InvalidParameter`] naming `rows` if
    /// they are not whole nodes inside the dofs.
    pub fn for_rows(
        node_count: usize,
        components: usize,
        nodes_per_element: usize,
        connectivity: &[usize],
        dirichlet: &[Option<f64>],
        rows: core::ops::Range<usize>,
    ) -> Result<Self, ElasticityError> {
        let ndof = components * node_count;
        ElasticityError::check_length("dirichlet values", ndof, dirichlet.len())?;
        let c = components.max(1);
        if rows.end > ndof
            || rows.start > rows.end
            || !rows.start.is_multiple_of(c)
            || !rows.end.is_multiple_of(c)
        {
            return Err(ElasticityError::InvalidParameter {
                field: "rows",
                value: rows.end as f64,
                allowed: "whole nodes inside the dofs",
            });
        }
        let nen = nodes_per_element.max(1);
        let owned_nodes = rows.start / c..rows.end / c;
        let element_ids: Vec<usize> = (0..connectivity.len() / nen)
            .filter(|&e| {
                connectivity[e * nen..(e + 1) * nen]
                    .iter()
                    .any(|m| owned_nodes.contains(m))
            })
            .collect();
        let kept: Vec<usize> = element_ids
            .iter()
            .flat_map(|&e| connectivity[e * nen..(e + 1) * nen].iter().copied())
            .collect();
        let start = bucket_starts(&kept, node_count);
        let mut fill = start[..node_count].to_vec();
        let mut elements_of = vec![0usize; kept.len()];
        for (k, &m) in kept.iter().enumerate() {
            elements_of[fill[m]] = k / nen;
            fill[m] += 1;
        }
        // the owned rows' free columns (sorted), row-wise; then the compressed columns
        let mut row_cols: Vec<Vec<usize>> = Vec::with_capacity(rows.len());
        for d in rows.clone() {
            if dirichlet[d].is_some() {
                row_cols.push(vec![d]);
                continue;
            }
            let m = d / c;
            let mut nbrs: Vec<usize> = elements_of[start[m]..start[m + 1]]
                .iter()
                .flat_map(|&e| kept[e * nen..(e + 1) * nen].iter().copied())
                .collect();
            nbrs.sort_unstable();
            nbrs.dedup();
            row_cols.push(
                nbrs.iter()
                    .flat_map(|&n| (0..c).map(move |k| c * n + k))
                    .filter(|&j| dirichlet[j].is_none())
                    .collect(),
            );
        }
        let mut col_ptr = vec![0usize; ndof + 1];
        for cols in &row_cols {
            for &j in cols {
                col_ptr[j + 1] += 1;
            }
        }
        for j in 0..ndof {
            col_ptr[j + 1] += col_ptr[j];
        }
        if col_ptr[ndof] > u32::MAX as usize {
            return Err(ElasticityError::InvalidParameter {
                field: "pattern nonzeros",
                value: col_ptr[ndof] as f64,
                allowed: "[0, 2^32)",
            });
        }
        let mut row_idx = vec![0usize; col_ptr[ndof]];
        let mut next = col_ptr[..ndof].to_vec();
        for (r, cols) in rows.clone().zip(&row_cols) {
            for &j in cols {
                row_idx[next[j]] = r; // rows visited in increasing order: sorted columns
                next[j] += 1;
            }
        }
        drop(row_cols);
        let pattern = SparsityPattern::from_compressed_columns(ndof, ndof, col_ptr, row_idx)?;
        let l = c * nen;
        let mut slots = vec![NO_SLOT; element_ids.len() * l * l];
        slots
            .par_chunks_mut(l * l)
            .enumerate()
            .for_each(|(e, out)| {
                let nodes = &kept[e * nen..(e + 1) * nen];
                for a in 0..l {
                    let r = c * nodes[a / c] + a % c;
                    if !rows.contains(&r) {
                        continue;
                    }
                    for b in 0..l {
                        let j = c * nodes[b / c] + b % c;
                        let keep = if dirichlet[r].is_some() {
                            r == j
                        } else {
                            dirichlet[j].is_none()
                        };
                        if keep {
                            let s = pattern.slot(r, j).expect("element entry in the pattern");
                            out[a * l + b] = s as u32;
                        }
                    }
                }
            });
        let mut diagonal = vec![usize::MAX; ndof];
        for d in rows.clone() {
            diagonal[d] = pattern.slot(d, d).expect("diagonal in the pattern");
        }
        Ok(Self {
            pattern,
            slots,
            diagonal,
            connectivity: kept,
            nodes_per_element: nen,
            components: c,
            rows,
            element_ids,
        })
    }

    /// The number among the caller's elements of element `e` of this assembly (`e` itself
    /// unless [`ElementAssembly::for_rows`] kept a subset).
    pub fn element_id(&self, e: usize) -> usize {
        self.element_ids.get(e).copied().unwrap_or(e)
    }

    /// The rows this assembly fills (all dofs unless [`ElementAssembly::for_rows`]).
    pub fn rows(&self) -> core::ops::Range<usize> {
        self.rows.clone()
    }

    /// The compressed-column pattern of the assembled matrix.
    pub fn pattern(&self) -> &SparsityPattern {
        &self.pattern
    }

    /// Number of elements.
    pub fn element_count(&self) -> usize {
        self.connectivity.len() / self.nodes_per_element.max(1)
    }

    /// The nodes of element `e`.
    pub fn nodes(&self, e: usize) -> &[usize] {
        &self.connectivity[e * self.nodes_per_element..(e + 1) * self.nodes_per_element]
    }

    /// Assembles the system: `element_matrix(e, out)` writes the `l x l` matrix of element
    /// `e` (row-major, local dof `components * a + c`, symmetric), computed in parallel;
    /// `load` is the assembled load vector (body force and natural boundary terms).
    ///
    /// # Errors
    /// [`ElasticityError::DimensionMismatch`] for a load or Dirichlet vector of the wrong
    /// length; [`ElasticityError::NonFinite`] for a non-finite element matrix entry.
    pub fn assemble(
        &self,
        element_matrix: impl Fn(usize, &mut [f64]) + Sync,
        load: &[f64],
        dirichlet: &[Option<f64>],
    ) -> Result<LinearSystem, ElasticityError> {
        let ndof = self.pattern.ncols();
        ElasticityError::check_length("load", ndof, load.len())?;
        ElasticityError::check_length("dirichlet values", ndof, dirichlet.len())?;
        let l = self.components * self.nodes_per_element;
        let ne = self.element_count();
        let mut values = vec![0.0; self.pattern.nnz()];
        let mut rhs = load.to_vec();
        let batch = batch(l * l);
        let mut buffer = vec![0.0; batch.min(ne.max(1)) * l * l];
        for first in (0..ne).step_by(batch) {
            let last = (first + batch).min(ne);
            let buf = &mut buffer[..(last - first) * l * l];
            buf.par_chunks_mut(l * l).enumerate().for_each(|(i, out)| {
                out.iter_mut().for_each(|x| *x = 0.0);
                element_matrix(first + i, out);
            });
            if let Some(bad) = buf.iter().position(|x| !x.is_finite()) {
                let e = first + bad / (l * l);
                return Err(ElasticityError::NonFinite {
                    what: "element matrix",
                    at: [e as f64, (bad % (l * l)) as f64],
                });
            }
            for e in first..last {
                let local = &buf[(e - first) * l * l..(e - first + 1) * l * l];
                let slots = &self.slots[e * l * l..(e + 1) * l * l];
                let nodes = self.nodes(e);
                for (idx, (&s, &x)) in slots.iter().zip(local).enumerate() {
                    if s != NO_SLOT {
                        values[s as usize] += x;
                    } else {
                        let (a, b) = (idx / l, idx % l);
                        let r = self.components * nodes[a / self.components] + a % self.components;
                        let c = self.components * nodes[b / self.components] + b % self.components;
                        if let (None, Some(g)) = (dirichlet[r], dirichlet[c])
                            && self.rows.contains(&r)
                        {
                            rhs[r] -= x * g;
                        }
                    }
                }
            }
        }
        for d in self.rows.clone() {
            if let Some(g) = dirichlet[d] {
                rhs[d] = values[self.diagonal[d]] * g;
            }
        }
        LinearSystem::from_parts(self.pattern.clone(), values, rhs)
    }
}

/// The first position of each bucket when the `keys` (each `< buckets`) are sorted by
/// counting: `start[b]..start[b + 1]` holds the keys equal to `b` (`start.len() = buckets + 1`).
pub(super) fn bucket_starts(keys: &[usize], buckets: usize) -> Vec<usize> {
    let mut start = vec![0usize; buckets + 1];
    for &k in keys {
        start[k + 1] += 1;
    }
    for b in 0..buckets {
        start[b + 1] += start[b];
    }
    start
}

#[cfg(test)]
mod tests {
    use super::*;
    use capstan_solvers::SparseCholesky;

    /// A 2 x 3 grid of bilinear quads (3 x 4 nodes), 2 unknowns a node that couple, one
    /// Dirichlet node: the element matrix `K_(2a+c, 2b+d) = (1 + a + b) (1 + c + d) + 4 delta`.
    #[allow(clippy::type_complexity)] // (connectivity, Dirichlet values, element kernel)
    fn quads() -> (
        Vec<usize>,
        Vec<Option<f64>>,
        impl Fn(usize, &mut [f64]) + Sync,
    ) {
        let (nx, ny) = (3, 4);
        let mut connectivity = Vec::new();
        for i in 0..nx - 1 {
            for j in 0..ny - 1 {
                let m = |i: usize, j: usize| i * ny + j;
                connectivity.extend([m(i, j), m(i + 1, j), m(i, j + 1), m(i + 1, j + 1)]);
            }
        }
        let mut dirichlet = vec![None; 2 * nx * ny];
        dirichlet[2 * 5] = Some(0.5);
        dirichlet[2 * 5 + 1] = Some(-1.0);
        let element = |e: usize, out: &mut [f64]| {
            for r in 0..8 {
                for c in 0..8 {
                    let (a, b) = ((r / 2 + c / 2) as f64, (r % 2 + c % 2) as f64);
                    out[r * 8 + c] = (1.0 + a) * (1.0 + b) * (1.0 + 0.1 * e as f64)
                        + if r == c { 4.0 } else { 0.0 };
                }
            }
        };
        (connectivity, dirichlet, element)
    }

    #[test]
    fn rows_assembled_apart_equal_the_whole_assembly() {
        let (connectivity, dirichlet, element) = quads();
        let load: Vec<f64> = (0..24).map(|k| k as f64 * 0.25 - 1.0).collect();
        let whole = ElementAssembly::new(12, 2, 4, connectivity.clone(), &dirichlet)
            .unwrap()
            .assemble(&element, &load, &dirichlet)
            .unwrap();
        for size in [1, 2, 3, 5] {
            let mut nnz = 0;
            for rank in 0..size {
                let rows = capstan_solvers::row_distribution::owned_blocks(24, 2, rank, size);
                let part =
                    ElementAssembly::for_rows(12, 2, 4, &connectivity, &dirichlet, rows.clone())
                        .unwrap();
                let ids: Vec<usize> = (0..part.element_count())
                    .map(|e| part.element_id(e))
                    .collect();
                let system = part
                    .assemble(|e, out| element(ids[e], out), &load, &dirichlet)
                    .unwrap();
                nnz += system.pattern.nnz();
                for (r, c) in system.pattern.entries() {
                    assert!(rows.contains(&r), "entry ({r}, {c}) outside the rows");
                    let (a, b) = (
                        system.pattern.slot(r, c).unwrap(),
                        whole.pattern.slot(r, c).unwrap(),
                    );
                    assert_eq!(system.values[a], whole.values[b]); // same sums, same order
                }
                for r in rows {
                    assert_eq!(system.rhs[r], whole.rhs[r]);
                }
            }
            assert_eq!(nnz, whole.pattern.nnz(), "{size} parts");
        }
        assert!(matches!(
            ElementAssembly::for_rows(12, 2, 4, &connectivity, &dirichlet, 1..4),
            Err(ElasticityError::InvalidParameter { field: "rows", .. })
        ));
    }

    /// 1-D linear elements of `-u'' = 0` on `[0, 1]` (4 elements, 2 components that do not
    /// couple): `u(0) = 1`, `u(1) = 3` gives the linear interpolant exactly.
    #[test]
    fn dirichlet_elimination_is_symmetric_and_exact_on_a_line() {
        let n = 5;
        let connectivity: Vec<usize> = (0..n - 1).flat_map(|e| [e, e + 1]).collect();
        let mut dirichlet = vec![None; 2 * n];
        dirichlet[0] = Some(1.0);
        dirichlet[1] = Some(-1.0);
        dirichlet[2 * n - 2] = Some(3.0);
        dirichlet[2 * n - 1] = Some(1.0);
        let asm = ElementAssembly::new(n, 2, 2, connectivity, &dirichlet).unwrap();
        let h = 0.25;
        let system = asm
            .assemble(
                |_, out| {
                    // [[1, -1], [-1, 1]] / h per component, local dof 2 a + c
                    for a in 0..2 {
                        for b in 0..2 {
                            let k = if a == b { 1.0 / h } else { -1.0 / h };
                            for c in 0..2 {
                                out[(2 * a + c) * 4 + 2 * b + c] = k;
                            }
                        }
                    }
                },
                &vec![0.0; 2 * n],
                &dirichlet,
            )
            .unwrap();
        let mut chol = SparseCholesky::default();
        let v = system.solve(&mut chol).unwrap();
        for i in 0..n {
            let x = i as f64 * h;
            assert!((v[2 * i] - (1.0 + 2.0 * x)).abs() < 1e-14);
            assert!((v[2 * i + 1] - (-1.0 + 2.0 * x)).abs() < 1e-14);
        }
    }
}
