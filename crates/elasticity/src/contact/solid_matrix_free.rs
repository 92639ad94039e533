//! The 3-D body with its bulk operator matrix-free ([`crate::solid::SolidMatrixFree`]): a
//! [`ContactOperator`] whose model is solved by [`crate::contact::MatrixFreeNewton`].

use std::sync::Arc;

use capstan_friction::FrictionLaw;
use capstan_geometry::{ShellChart, Surface};
use capstan_solvers::{
    CsrMatrix, LinearOperator, MultigridParams, OperatorLevel, OperatorMultigrid,
};

use crate::contact::error::ContactError;
use crate::contact::model::ContactModel;
use crate::contact::operator::{ContactOperator, Extremum, MatrixFreeBulk};
use crate::discretisation::{ContactNode, LinearSystem};
use crate::error::ElasticityError;
use crate::shell_geometry::ShellGeometry;
use crate::solid::{SolidBody, SolidMatrixFree, SolidMultigridParams};

/// An intermediate p-level of the V-cycle ([`crate::solid::PLevel`]) with its diagonal and
/// the transfer (and its transpose) from the level below it (the next p-level, or Q1).
struct SharedPLevel {
    operator: Arc<dyn LinearOperator + Send>,
    diagonal: Vec<f64>,
    bytes: usize,
    from_below: CsrMatrix,
    to_below: CsrMatrix,
}

/// What every load's operator of one matrix-free body shares: the operator, its diagonal
/// and the transfers and assembled coarse level of its V-cycle.
struct Shared<G> {
    operator: Arc<SolidMatrixFree<G>>,
    diagonal: Vec<f64>,
    /// From the Q1 level to the fine level (the V-cycle's `P_0` without p-levels; grid
    /// sequencing's prolongation in any case).
    prolongation: CsrMatrix,
    restriction: CsrMatrix,
    /// With p-levels: from the first p-level to the fine level, and its transpose.
    fine_transfer: Option<(CsrMatrix, CsrMatrix)>,
    p_levels: Vec<SharedPLevel>,
    coarse: CsrMatrix,
    below: Arc<[CsrMatrix]>,
    multigrid: MultigridParams,
}

/// `A + F`: the matrix-free bulk plus the sparse face term (rows `face_rows` only).
struct StepOperator {
    bulk: Arc<dyn LinearOperator + Send>,
    face: CsrMatrix,
    face_rows: Vec<usize>,
    diagonal: Vec<f64>,
}

impl StepOperator {
    /// `bulk + face` with the diagonal `bulk_diagonal + diag(face)`.
    fn new(bulk: Arc<dyn LinearOperator + Send>, bulk_diagonal: &[f64], face: CsrMatrix) -> Self {
        let mut diagonal = bulk_diagonal.to_vec();
        let mut face_rows = Vec::new();
        for (i, d) in diagonal.iter_mut().enumerate() {
            let (cols, vals) = face.row(i);
            if cols.is_empty() {
                continue;
            }
            face_rows.push(i);
            if let Some(k) = cols.iter().position(|&c| c as usize == i) {
                *d += vals[k];
            }
        }
        Self {
            bulk,
            face,
            face_rows,
            diagonal,
        }
    }
}

impl LinearOperator for StepOperator {
    fn dimension(&self) -> usize {
        self.diagonal.len()
    }

    fn apply(&self, x: &[f64], y: &mut [f64]) {
        self.bulk.apply(x, y);
        for &i in &self.face_rows {
            let (cols, vals) = self.face.row(i);
            y[i] += cols
                .iter()
                .zip(vals)
                .map(|(&j, v)| v * x[j as usize])
                .sum::<f64>();
        }
    }

    fn diagonal(&self) -> Vec<f64> {
        self.diagonal.clone()
    }
}

/// `a + b` for matrices of one shape (rows merged, columns sorted).
fn sum(a: &CsrMatrix, b: &CsrMatrix) -> Result<CsrMatrix, ElasticityError> {
    let n = a.nrows();
    let mut ptr = Vec::with_capacity(n + 1);
    let mut cols: Vec<u32> = Vec::with_capacity(a.nnz() + b.nnz());
    let mut vals = Vec::with_capacity(a.nnz() + b.nnz());
    ptr.push(0);
    let mut row: Vec<(u32, f64)> = Vec::new();
    for i in 0..n {
        let (ca, va) = a.row(i);
        let (cb, vb) = b.row(i);
        if cb.is_empty() {
            cols.extend_from_slice(ca);
            vals.extend_from_slice(va);
        } else {
            row.clear();
            row.extend(ca.iter().copied().zip(va.iter().copied()));
            row.extend(cb.iter().copied().zip(vb.iter().copied()));
            row.sort_unstable_by_key(|e| e.0);
            for &(c, v) in &row {
                if cols.len() > ptr[i] && *cols.last().expect("a column") == c {
                    *vals.last_mut().expect("a value") += v;
                } else {
                    cols.push(c);
                    vals.push(v);
                }
            }
        }
        ptr.push(cols.len());
    }
    Ok(CsrMatrix::new(n, a.ncols(), ptr, cols, vals)?)
}

impl<G: ShellGeometry + Send + Sync + 'static> MatrixFreeBulk for Shared<G> {
    fn bulk(&self) -> &dyn LinearOperator {
        self.operator.as_ref()
    }

    fn step_operator(&self, face: CsrMatrix) -> Arc<dyn LinearOperator + Send> {
        Arc::new(StepOperator::new(
            Arc::clone(&self.operator) as Arc<dyn LinearOperator + Send>,
            &self.diagonal,
            face,
        ))
    }

    /// The V-cycle of `A + F`: the fine level `step`; each p-level `A_l + F_l` with the face
    /// term carried down by Galerkin products (`F_{l+1} = P_l^T F_l P_l`, `F_0 = F`); the
    /// assembled Q1 level `A_c + P^T F_m P`.
    fn preconditioner(
        &self,
        step: Arc<dyn LinearOperator + Send>,
        face: &CsrMatrix,
        estimates: Option<&[f64]>,
    ) -> Result<OperatorMultigrid, ElasticityError> {
        let Some((p0, r0)) = &self.fine_transfer else {
            let coarse_face = face.galerkin(&self.prolongation, &self.restriction);
            let coarse = sum(&self.coarse, &coarse_face)?;
            return Ok(OperatorMultigrid::with_estimates(
                vec![OperatorLevel {
                    operator: step,
                    prolongation: self.prolongation.clone(),
                }],
                coarse,
                Arc::clone(&self.below),
                self.multigrid,
                estimates,
            )?);
        };
        let mut levels = vec![OperatorLevel {
            operator: step,
            prolongation: p0.clone(),
        }];
        let mut level_face = face.galerkin(p0, r0);
        for level in &self.p_levels {
            let next_face = level_face.galerkin(&level.from_below, &level.to_below);
            levels.push(OperatorLevel {
                operator: Arc::new(StepOperator::new(
                    Arc::clone(&level.operator),
                    &level.diagonal,
                    level_face,
                )),
                prolongation: level.from_below.clone(),
            });
            level_face = next_face;
        }
        let coarse = sum(&self.coarse, &level_face)?;
        Ok(OperatorMultigrid::with_estimates(
            levels,
            coarse,
            Arc::clone(&self.below),
            self.multigrid,
            estimates,
        )?)
    }

    fn prolongation(&self) -> &CsrMatrix {
        &self.prolongation
    }

    fn bytes(&self) -> usize {
        self.operator.bytes()
            + 8 * self.diagonal.len()
            + self.prolongation.bytes()
            + self.restriction.bytes()
            + self
                .fine_transfer
                .as_ref()
                .map_or(0, |(p, r)| p.bytes() + r.bytes())
            + self
                .p_levels
                .iter()
                .map(|l| l.bytes + 8 * l.diagonal.len() + l.from_below.bytes() + l.to_below.bytes())
                .sum::<usize>()
            + self.coarse.bytes()
            + self.below.iter().map(CsrMatrix::bytes).sum::<usize>()
    }
}

/// The 3-D body with its bulk operator matrix-free, for one load: the operator (shared by
/// the loads), the load's right-hand side and an empty assembled pattern
/// ([`ContactOperator::matrix_free`]).
pub struct SolidMatrixFreeBody<G> {
    shared: Arc<Shared<G>>,
    rhs: Vec<f64>,
}

impl<G> core::fmt::Debug for SolidMatrixFreeBody<G> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("SolidMatrixFreeBody")
            .field("dofs", &self.rhs.len())
            .finish_non_exhaustive()
    }
}

impl<G: ShellGeometry + Send + Sync + 'static> ContactOperator for SolidMatrixFreeBody<G> {
    fn method(&self) -> &'static str {
        self.shared.operator.element().method_name()
    }

    fn dof_count(&self) -> usize {
        self.rhs.len()
    }

    /// An empty pattern and the load's right-hand side: the bulk is
    /// [`ContactOperator::matrix_free`].
    fn contact_system(&self) -> Result<LinearSystem, ElasticityError> {
        let mut system = LinearSystem::from_entries(self.rhs.len(), &[])?;
        system.rhs.clone_from(&self.rhs);
        Ok(system)
    }

    fn contact_entries(&self) -> Result<Vec<ContactNode>, ElasticityError> {
        self.shared.operator.setup.contact_entries()
    }

    fn extremes(&self, v: &[f64]) -> [Extremum; 2] {
        self.shared.operator.setup.extremes(v)
    }

    fn solid(&self) -> Option<&dyn crate::solid::SolidOutput> {
        Some(self.shared.operator.as_ref())
    }

    fn matrix_free(&self) -> Option<Arc<dyn MatrixFreeBulk + Send + Sync>> {
        Some(Arc::clone(&self.shared) as Arc<dyn MatrixFreeBulk + Send + Sync>)
    }
}

/// The matrix-free operator of one body for every pair of end loads: the shared operator and
/// the unit-load right-hand sides ([`SolidBody::matrix_free_loads`]).
pub struct MatrixFreeLoads<G> {
    shared: Arc<Shared<G>>,
    rhs: [Vec<f64>; 2],
}

impl<G> MatrixFreeLoads<G> {
    /// The body with end loads `tau0`, `tau_max` (right-hand sides by superposition:
    /// `b = tau0 b(1, 0) + tau_max b(0, 1)`).
    pub fn at(&self, tau0: f64, tau_max: f64) -> SolidMatrixFreeBody<G> {
        SolidMatrixFreeBody {
            shared: Arc::clone(&self.shared),
            rhs: self.rhs[0]
                .iter()
                .zip(&self.rhs[1])
                .map(|(a, b)| tau0 * a + tau_max * b)
                .collect(),
        }
    }

    /// Bytes held by the operator, its V-cycle's transfers and coarse level, and the two
    /// right-hand sides.
    pub fn bytes(&self) -> usize
    where
        G: ShellGeometry + Send + Sync + 'static,
    {
        self.shared.bytes() + 16 * self.rhs[0].len()
    }
}

impl<S: Surface<f64> + Clone + Send + Sync + 'static> SolidBody<S> {
    /// The matrix-free operator of the body ([`crate::solid::SolidMatrixFree`], one for both
    /// end loads) with the V-cycle's transfers and coarse level by `multigrid`.
    ///
    /// # Errors
    /// The operator's errors ([`SolidMatrixFree::new`]: e.g. reduced integration is refused
    /// naming `discretisation.volumetric`), the multigrid's ([`SolidMultigridParams::parts`]).
    pub fn matrix_free_loads(
        &self,
        multigrid: SolidMultigridParams,
    ) -> Result<MatrixFreeLoads<ShellChart<S>>, ElasticityError> {
        let unit = self.boundary(1.0, 0.0);
        let operator = SolidMatrixFree::new(
            ShellChart::new(self.surface.clone()),
            self.material,
            self.grid()?,
            &unit,
            None,
            self.order,
            self.volumetric,
        )?;
        let rhs = [
            operator.rhs().to_vec(),
            operator.rhs_for(&self.boundary(0.0, 1.0), None)?,
        ];
        let parts = multigrid.parts(&operator, &unit)?;
        // with p-levels: the transfer of each level from the one below it
        let (fine_transfer, p_levels) = match &parts.p_coarse {
            None => (None, Vec::new()),
            Some(_) => {
                let transfers = parts.transfers();
                let levels = parts
                    .p_levels
                    .iter()
                    .zip(&transfers[1..])
                    .map(|(l, &p)| SharedPLevel {
                        diagonal: l.operator.diagonal(),
                        operator: Arc::clone(&l.operator),
                        bytes: l.bytes,
                        to_below: p.transpose(),
                        from_below: p.clone(),
                    })
                    .collect();
                let p0 = transfers[0];
                (Some((p0.clone(), p0.transpose())), levels)
            }
        };
        let shared = Arc::new(Shared {
            diagonal: operator.diagonal(),
            operator: Arc::new(operator),
            restriction: parts.prolongation.transpose(),
            prolongation: parts.prolongation,
            fine_transfer,
            p_levels,
            coarse: parts.coarse,
            below: parts.below,
            multigrid: multigrid.multigrid,
        });
        Ok(MatrixFreeLoads { shared, rhs })
    }

    /// The contact model with the bulk operator matrix-free ([`SolidBody::matrix_free_loads`]),
    /// solved by [`crate::contact::MatrixFreeNewton`].
    ///
    /// # Errors
    /// [`SolidBody::matrix_free_loads`]'s, [`ContactModel::new`]'s.
    pub fn matrix_free_model<L: FrictionLaw<f64>>(
        &self,
        law: L,
        params: L::Params,
        slip_threshold: f64,
        multigrid: SolidMultigridParams,
    ) -> Result<ContactModel<SolidMatrixFreeBody<ShellChart<S>>, L>, ContactError> {
        let loads = self.matrix_free_loads(multigrid)?;
        ContactModel::new(
            |tau0, tau_max| Ok(loads.at(tau0, tau_max)),
            law,
            params,
            slip_threshold,
        )
    }
}
