//! Reference problems shared by tests, benches and examples: model linear systems and small
//! nonlinear systems with known roots. All are deterministic (random ones take a seed).

use core::convert::Infallible;

use crate::problem::{Jacobian, Residual};
use crate::sparsity_pattern::SparsityPattern;

/// An assembled linear system `A x = b`.
#[derive(Clone, Debug, PartialEq)]
pub struct LinearSystem {
    /// Pattern of `A`.
    pub pattern: SparsityPattern,
    /// Values of `A` in pattern order.
    pub values: Vec<f64>,
    /// Right-hand side `b`.
    pub rhs: Vec<f64>,
}

impl LinearSystem {
    /// Assembles from `(row, col, value)` contributions (duplicates are summed) and `rhs`.
    ///
    /// # Panics
    /// If a contribution lies outside `n x n` (programmer error in a sample).
    #[track_caller]
    pub fn from_triplets(n: usize, triplets: &[(usize, usize, f64)], rhs: Vec<f64>) -> Self {
        let entries: Vec<(usize, usize)> = triplets.iter().map(|&(r, c, _)| (r, c)).collect();
        let (pattern, slots) =
            SparsityPattern::from_entries(n, n, &entries).expect("sample entries in bounds");
        let mut values = vec![0.0; pattern.nnz()];
        for (k, &(_, _, v)) in triplets.iter().enumerate() {
            values[slots[k]] += v;
        }
        Self {
            pattern,
            values,
            rhs,
        }
    }

    /// Dimension `n`.
    pub fn dimension(&self) -> usize {
        self.pattern.nrows()
    }

    /// `|b - A x|_2`.
    ///
    /// # Panics
    /// If `x.len() != n`.
    #[track_caller]
    pub fn residual_norm(&self, x: &[f64]) -> f64 {
        self.pattern.residual_norm(&self.values, x, &self.rhs)
    }
}

/// The 5-point Laplacian on the unit square, `n x n` interior points, zero Dirichlet data,
/// source `f = 1`; symmetric positive definite and weakly diagonally dominant.
///
/// # Math
/// ```text
/// -Δu = 1 on (0,1)^2, u = 0 on the boundary,  h = 1/(n+1),  unknown k = i + n j
/// 4 u_k - u_E - u_W - u_N - u_S = h^2        (neighbours outside the grid are 0)
/// ```
/// Jacobi needs `O(n^2)` iterations: its spectral radius is `cos(pi h)`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Poisson2d {
    /// Interior points per direction.
    pub n: usize,
}

impl Poisson2d {
    /// The problem on an `n x n` interior grid.
    pub fn new(n: usize) -> Self {
        Self { n }
    }

    /// The assembled system.
    pub fn system(&self) -> LinearSystem {
        ConvectionDiffusion2d::new(self.n, [0.0, 0.0]).system()
    }
}

/// Convection–diffusion with central differences: a nonsymmetric, weakly diagonally dominant
/// system while the cell Péclet numbers `|v_x h/2|, |v_y h/2|` are below 1.
///
/// # Math
/// ```text
/// -Δu + v . grad u = 1 on (0,1)^2, u = 0 on the boundary,  h = 1/(n+1)
/// 4 u_k - (1 - v_x h/2) u_E - (1 + v_x h/2) u_W - (1 - v_y h/2) u_N - (1 + v_y h/2) u_S = h^2
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ConvectionDiffusion2d {
    /// Interior points per direction.
    pub n: usize,
    /// Velocity `(v_x, v_y)`.
    pub velocity: [f64; 2],
}

impl ConvectionDiffusion2d {
    /// The problem on an `n x n` interior grid with `velocity`.
    pub fn new(n: usize, velocity: [f64; 2]) -> Self {
        Self { n, velocity }
    }

    /// The assembled system.
    pub fn system(&self) -> LinearSystem {
        let n = self.n;
        let h = 1.0 / (n as f64 + 1.0);
        let (px, py) = (self.velocity[0] * h / 2.0, self.velocity[1] * h / 2.0);
        let mut t = Vec::with_capacity(5 * n * n);
        for j in 0..n {
            for i in 0..n {
                let k = i + n * j;
                t.push((k, k, 4.0));
                if i + 1 < n {
                    t.push((k, k + 1, -1.0 + px));
                }
                if i > 0 {
                    t.push((k, k - 1, -1.0 - px));
                }
                if j + 1 < n {
                    t.push((k, k + n, -1.0 + py));
                }
                if j > 0 {
                    t.push((k, k - n, -1.0 - py));
                }
            }
        }
        LinearSystem::from_triplets(n * n, &t, vec![h * h; n * n])
    }
}

/// A random nonsymmetric, strictly diagonally dominant matrix (SplitMix64, fixed seed).
///
/// # Math
/// ```text
/// each row i: `off_diagonals` random columns j != i with a_ij uniform in [-1, 1]
/// a_ii = 1 + sum_j |a_ij|,   b_i uniform in [-1, 1]
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RandomDiagonallyDominant {
    /// Dimension.
    pub n: usize,
    /// Off-diagonal entries drawn per row (repeats are summed).
    pub off_diagonals: usize,
    /// Seed of the generator.
    pub seed: u64,
}

impl RandomDiagonallyDominant {
    /// The assembled system.
    pub fn system(&self) -> LinearSystem {
        let mut rng = SplitMix64(self.seed);
        let mut t = Vec::with_capacity(self.n * (self.off_diagonals + 1));
        for i in 0..self.n {
            let mut sum = 0.0;
            if self.n > 1 {
                for _ in 0..self.off_diagonals {
                    let mut j = (rng.next_u64() % self.n as u64) as usize;
                    if j == i {
                        j = (j + 1) % self.n;
                    }
                    let v = rng.uniform();
                    sum += v.abs();
                    t.push((i, j, v));
                }
            }
            t.push((i, i, 1.0 + sum));
        }
        let rhs = (0..self.n).map(|_| rng.uniform()).collect();
        LinearSystem::from_triplets(self.n, &t, rhs)
    }
}

/// SplitMix64: a tiny deterministic generator for samples (not for cryptography).
#[derive(Clone, Debug)]
pub struct SplitMix64(pub u64);

impl SplitMix64 {
    /// Next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in `[-1, 1)`.
    pub fn uniform(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }
}

/// `u^3 + A u = b` with a manufactured root: smooth, with a nonsingular, diagonally dominant
/// Jacobian, so Newton converges quadratically and Jacobi–Newton converges.
///
/// # Math
/// ```text
/// r_i(u) = u_i^3 + (A u)_i - b_i,     A = tridiag(-1, 3, -1)  (n x n)
/// u*_i   = 1 + sin(2 pi (i + 1) / (n + 1)),   b = u*^3 + A u*
/// J(u)   = diag(3 u_i^2) + A
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct CubicReaction {
    pattern: SparsityPattern,
    rhs: Vec<f64>,
}

impl CubicReaction {
    /// The problem with `n` unknowns.
    pub fn new(n: usize) -> Self {
        let mut entries = Vec::with_capacity(3 * n);
        for i in 0..n {
            entries.push((i, i));
            if i + 1 < n {
                entries.push((i, i + 1));
                entries.push((i + 1, i));
            }
        }
        let (pattern, _) = SparsityPattern::from_entries(n, n, &entries).expect("in bounds");
        let mut problem = Self {
            pattern,
            rhs: vec![0.0; n],
        };
        let exact = problem.exact_solution();
        let mut r = vec![0.0; n];
        let Ok(()) = problem.residual(&exact, &mut r);
        problem.rhs = r;
        problem
    }

    /// The manufactured root `u*`.
    pub fn exact_solution(&self) -> Vec<f64> {
        let n = self.pattern.nrows();
        (0..n)
            .map(|i| {
                1.0 + (2.0 * core::f64::consts::PI * (i as f64 + 1.0) / (n as f64 + 1.0)).sin()
            })
            .collect()
    }
}

impl Residual<f64> for CubicReaction {
    type Error = Infallible;
    fn residual(&self, u: &[f64], r: &mut [f64]) -> Result<(), Infallible> {
        let n = u.len();
        for i in 0..n {
            let left = if i > 0 { u[i - 1] } else { 0.0 };
            let right = if i + 1 < n { u[i + 1] } else { 0.0 };
            r[i] = u[i] * u[i] * u[i] + 3.0 * u[i] - left - right - self.rhs[i];
        }
        Ok(())
    }
}

impl Jacobian<f64> for CubicReaction {
    fn pattern(&self) -> &SparsityPattern {
        &self.pattern
    }
    fn jacobian(&self, u: &[f64], values: &mut [f64]) -> Result<(), Infallible> {
        let (ptr, rows) = (self.pattern.col_ptr(), self.pattern.row_idx());
        for (j, &uj) in u.iter().enumerate() {
            for s in ptr[j]..ptr[j + 1] {
                values[s] += if rows[s] == j {
                    3.0 * uj * uj + 3.0
                } else {
                    -1.0
                };
            }
        }
        Ok(())
    }
}

/// A problem `r_i(u) = f(u_i)` on the diagonal pattern: the struct, `new(n)`, [`Residual`]
/// and [`Jacobian`] (`J = diag(f'(u_i))`), from `f` and `f'` written once.
macro_rules! componentwise_problem {
    ($(#[$doc:meta])* $name:ident, residual: |$u:ident| $f:expr, derivative: |$v:ident| $df:expr) => {
        $(#[$doc])*
        #[derive(Clone, Debug, PartialEq)]
        pub struct $name {
            pattern: SparsityPattern,
        }

        impl $name {
            /// The problem with `n` unknowns.
            pub fn new(n: usize) -> Self {
                let entries: Vec<(usize, usize)> = (0..n).map(|i| (i, i)).collect();
                let (pattern, _) =
                    SparsityPattern::from_entries(n, n, &entries).expect("in bounds");
                Self { pattern }
            }
        }

        impl Residual<f64> for $name {
            type Error = Infallible;
            fn residual(&self, u: &[f64], r: &mut [f64]) -> Result<(), Infallible> {
                for (ri, &$u) in r.iter_mut().zip(u) {
                    *ri = $f;
                }
                Ok(())
            }
        }

        impl Jacobian<f64> for $name {
            fn pattern(&self) -> &SparsityPattern {
                &self.pattern
            }
            fn jacobian(&self, u: &[f64], values: &mut [f64]) -> Result<(), Infallible> {
                for (value, &$v) in values.iter_mut().zip(u) {
                    *value += $df;
                }
                Ok(())
            }
        }
    };
}

componentwise_problem!(
    /// `atan(u_i) = 0` componentwise: the classic case where the full Newton step overshoots
    /// (for `|u_0| > 1.39` the iterates grow without bound) and a line search is needed.
    ///
    /// # Math
    /// ```text
    /// r_i(u) = atan(u_i),   J = diag(1 / (1 + u_i^2)),   root u* = 0
    /// ```
    Arctangent,
    residual: |u| u.atan(),
    derivative: |u| 1.0 / (1.0 + u * u)
);

componentwise_problem!(
    /// `cbrt(u_i) = 0` componentwise: the full Newton step maps `u` to `-2 u`, so the residual
    /// grows by `2^(1/3)` per iteration (divergence), while a damped step converges.
    ///
    /// # Math
    /// ```text
    /// r_i(u) = u_i^(1/3),   J = diag(u_i^(-2/3) / 3),   u_{k+1} = u_k - 3 u_k = -2 u_k
    /// ```
    CubeRoot,
    residual: |u| u.cbrt(),
    derivative: |u| 1.0 / (3.0 * u.abs().cbrt().powi(2))
);

#[cfg(test)]
mod tests {
    use super::*;

    fn jacobian_matches_central_differences<P: Jacobian<f64, Error = Infallible>>(
        p: &P,
        u: &[f64],
    ) {
        let n = u.len();
        let mut values = vec![0.0; p.pattern().nnz()];
        let Ok(()) = p.jacobian(u, &mut values);
        let step = 1e-6;
        let (mut rp, mut rm) = (vec![0.0; n], vec![0.0; n]);
        for j in 0..n {
            let mut up = u.to_vec();
            let mut um = u.to_vec();
            up[j] += step;
            um[j] -= step;
            let Ok(()) = p.residual(&up, &mut rp);
            let Ok(()) = p.residual(&um, &mut rm);
            for i in 0..n {
                let fd = (rp[i] - rm[i]) / (2.0 * step);
                let exact = p.pattern().slot(i, j).map_or(0.0, |s| values[s]);
                // central difference: O(step^2) truncation plus O(eps/step) round-off
                assert!(
                    (fd - exact).abs() < 1e-6 * (1.0 + exact.abs()),
                    "J[{i},{j}]"
                );
            }
        }
    }

    #[test]
    fn cubic_reaction_root_and_jacobian() {
        let p = CubicReaction::new(7);
        let mut r = vec![0.0; 7];
        let Ok(()) = p.residual(&p.exact_solution(), &mut r);
        assert!(r.iter().all(|v| v.abs() < 1e-14)); // b built from u*: round-off only
        jacobian_matches_central_differences(&p, &[0.3, -0.2, 1.0, 2.0, 0.0, -1.5, 0.7]);
    }

    #[test]
    fn arctangent_and_cube_root_jacobians() {
        jacobian_matches_central_differences(&Arctangent::new(3), &[0.5, -2.0, 10.0]);
        jacobian_matches_central_differences(&CubeRoot::new(2), &[0.5, -2.0]);
    }

    #[test]
    fn samples_are_deterministic_and_dominant() {
        let a = RandomDiagonallyDominant {
            n: 50,
            off_diagonals: 4,
            seed: 7,
        }
        .system();
        assert_eq!(
            a,
            RandomDiagonallyDominant {
                n: 50,
                off_diagonals: 4,
                seed: 7
            }
            .system()
        );
        let (ptr, rows) = (a.pattern.col_ptr(), a.pattern.row_idx());
        let mut off = vec![0.0; 50];
        let mut diag = vec![0.0; 50];
        for j in 0..50 {
            for s in ptr[j]..ptr[j + 1] {
                if rows[s] == j {
                    diag[j] = a.values[s];
                } else {
                    off[rows[s]] += a.values[s].abs();
                }
            }
        }
        assert!(diag.iter().zip(&off).all(|(d, o)| *d >= o + 1.0 - 1e-12));
    }

    #[test]
    fn poisson_has_five_point_structure() {
        let s = Poisson2d::new(4).system();
        assert_eq!(s.dimension(), 16);
        assert_eq!(s.pattern.nnz(), 16 + 2 * 2 * 4 * 3); // diagonal + 2 directions x 2 signs
        assert!(s.values.iter().sum::<f64>() > 0.0);
    }
}
