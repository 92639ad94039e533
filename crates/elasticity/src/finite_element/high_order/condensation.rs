//! Static condensation of the element-interior unknowns: the Schur complement of each
//! element's interior block (a small dense Cholesky) and the back-substitution of the interior
//! values after the global solve.

use crate::error::ElasticityError;

/// In-place Cholesky `A = L L^T` of a dense symmetric positive definite `n x n` matrix
/// (row-major; the lower triangle receives `L`).
///
/// # Errors
/// [`ElasticityError::Solver`] (`Singular`) at a pivot that is not positive and finite.
pub fn cholesky_in_place(a: &mut [f64], n: usize) -> Result<(), ElasticityError> {
    for j in 0..n {
        let mut d = a[j * n + j];
        for k in 0..j {
            d -= a[j * n + k] * a[j * n + k];
        }
        if !(d > 0.0 && d.is_finite()) {
            return Err(capstan_solvers::SolverError::Singular { pivot: Some(j) }.into());
        }
        let d = d.sqrt();
        a[j * n + j] = d;
        for i in j + 1..n {
            let mut s = a[i * n + j];
            for k in 0..j {
                s -= a[i * n + k] * a[j * n + k];
            }
            a[i * n + j] = s / d;
        }
    }
    Ok(())
}

/// Solves `L L^T x = b` in place for `m` right-hand sides stored as the columns of `b`
/// (`n x m`, row-major), `L` from [`cholesky_in_place`].
pub fn cholesky_solve(l: &[f64], n: usize, b: &mut [f64], m: usize) {
    for i in 0..n {
        for k in 0..i {
            let lik = l[i * n + k];
            if lik != 0.0 {
                for c in 0..m {
                    b[i * m + c] -= lik * b[k * m + c];
                }
            }
        }
        let d = l[i * n + i];
        for c in 0..m {
            b[i * m + c] /= d;
        }
    }
    for i in (0..n).rev() {
        for k in i + 1..n {
            let lki = l[k * n + i];
            if lki != 0.0 {
                for c in 0..m {
                    b[i * m + c] -= lki * b[k * m + c];
                }
            }
        }
        let d = l[i * n + i];
        for c in 0..m {
            b[i * m + c] /= d;
        }
    }
}

/// One element after condensation.
///
/// # Math
/// With the element dofs split into boundary `B` (on the element's edges) and interior `I`,
/// ```text
/// [K_BB K_BI] [u_B]   [f_B]
/// [K_IB K_II] [u_I] = [f_I]
/// S   = K_BB - K_BI K_II^-1 K_IB      (the element's Schur complement, symmetric)
/// g   = - K_BI K_II^-1 f_I            (added to the skeleton load)
/// u_I = y - X u_B,   X = K_II^-1 K_IB,   y = K_II^-1 f_I   (after the global solve)
/// ```
/// `K_II` is positive definite for a positive definite element energy (interior functions
/// vanish on the element's edges), so its Cholesky factor exists.
#[derive(Debug, Clone)]
pub struct CondensedElement {
    /// `S`, `nb x nb` row-major (bitwise symmetric).
    pub schur: Vec<f64>,
    /// `g`, `nb`.
    pub load: Vec<f64>,
    /// `X`, `ni x nb` row-major.
    pub coupling: Vec<f64>,
    /// `y`, `ni`.
    pub interior: Vec<f64>,
}

impl CondensedElement {
    /// Condenses the element matrix `k` (`l x l` row-major) onto the local dofs `boundary`,
    /// eliminating `interior` (whose load is `f_interior`).
    ///
    /// # Errors
    /// [`ElasticityError::Solver`] if `K_II` is not positive definite.
    pub fn new(
        k: &[f64],
        l: usize,
        boundary: &[usize],
        interior: &[usize],
        f_interior: &[f64],
    ) -> Result<Self, ElasticityError> {
        let (nb, ni) = (boundary.len(), interior.len());
        let mut kii = vec![0.0; ni * ni];
        for (r, &i) in interior.iter().enumerate() {
            for (c, &j) in interior.iter().enumerate() {
                kii[r * ni + c] = k[i * l + j];
            }
        }
        cholesky_in_place(&mut kii, ni)?;
        // [X | y] = K_II^-1 [K_IB | f_I]
        let m = nb + 1;
        let mut rhs = vec![0.0; ni * m];
        for (r, &i) in interior.iter().enumerate() {
            for (c, &j) in boundary.iter().enumerate() {
                rhs[r * m + c] = k[i * l + j];
            }
            rhs[r * m + nb] = f_interior[r];
        }
        cholesky_solve(&kii, ni, &mut rhs, m);
        // S = K_BB - K_BI X, g = -K_BI y: rows of K_BI times rows of [X | y] (contiguous)
        let mut schur = vec![0.0; nb * nb];
        let mut load = vec![0.0; nb];
        let mut row = vec![0.0; m];
        for (r, &i) in boundary.iter().enumerate() {
            row.iter_mut().for_each(|x| *x = 0.0);
            for (q, &iq) in interior.iter().enumerate() {
                let kiq = k[i * l + iq];
                if kiq != 0.0 {
                    for (x, y) in row.iter_mut().zip(&rhs[q * m..(q + 1) * m]) {
                        *x += kiq * y;
                    }
                }
            }
            for (c, &j) in boundary.iter().enumerate() {
                schur[r * nb + c] = k[i * l + j] - row[c];
            }
            load[r] = -row[nb];
        }
        // bitwise symmetric (the assembly and the Cholesky backend rely on it)
        for r in 0..nb {
            for c in r + 1..nb {
                let s = 0.5 * (schur[r * nb + c] + schur[c * nb + r]);
                schur[r * nb + c] = s;
                schur[c * nb + r] = s;
            }
        }
        let mut coupling = vec![0.0; ni * nb];
        let mut y = vec![0.0; ni];
        for r in 0..ni {
            coupling[r * nb..(r + 1) * nb].copy_from_slice(&rhs[r * m..r * m + nb]);
            y[r] = rhs[r * m + nb];
        }
        Ok(Self {
            schur,
            load,
            coupling,
            interior: y,
        })
    }

    /// The interior values `u_I = y - X u_B` for the boundary values `u_b`.
    pub fn recover(&self, u_b: &[f64]) -> Vec<f64> {
        let nb = u_b.len();
        self.interior
            .iter()
            .enumerate()
            .map(|(r, y)| {
                let row = &self.coupling[r * nb..(r + 1) * nb];
                y - row.iter().zip(u_b).map(|(x, u)| x * u).sum::<f64>()
            })
            .collect()
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
        let e = CondensedElement::new(&k, n, &b, &i, &[f[1], f[2], f[4]]).unwrap();
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
    fn cholesky_rejects_an_indefinite_matrix() {
        let mut a = vec![1.0, 2.0, 2.0, 1.0];
        assert!(cholesky_in_place(&mut a, 2).is_err());
    }
}
