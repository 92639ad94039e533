//! nalgebra views of the geometry: the bases, metrics and fundamental forms as `Matrix3`,
//! `Matrix2`, `Vector3`, so an embedding solver gets the types it already uses.
//!
//! The kernels keep their plain arrays (indexing mirrors the formulas and measures faster on
//! these sizes); the views are copies made on request. Row `i`, column `j` of a form is
//! `form[i][j]`; a basis matrix holds the basis vectors as columns, so `G^T G = g_ij`.

use nalgebra::{Matrix2, Matrix3, Matrix3x2, Scalar as NalgebraScalar, Vector3};

use crate::shell::ShellPoint;
use crate::surface::SurfaceGeometry;

fn m2<F: NalgebraScalar + Copy>(a: &[[F; 2]; 2]) -> Matrix2<F> {
    Matrix2::from_fn(|i, j| a[i][j])
}

fn m3<F: NalgebraScalar + Copy>(a: &[[F; 3]; 3]) -> Matrix3<F> {
    Matrix3::from_fn(|i, j| a[i][j])
}

/// Vectors `v[j]` as the columns of a matrix.
fn columns3<F: NalgebraScalar + Copy>(v: &[[F; 3]; 3]) -> Matrix3<F> {
    Matrix3::from_fn(|i, j| v[j][i])
}

impl<F: NalgebraScalar + Copy> SurfaceGeometry<F> {
    /// `a_ab` (first fundamental form, the surface metric) as a `Matrix2`.
    ///
    /// # Example
    /// ```
    /// use capstan_geometry::{EllipticalPrism, Surface};
    /// let g = EllipticalPrism::new(2.0, 1.0).unwrap().geometry([0.0, 0.3]).unwrap();
    /// let a = g.first_form_matrix();
    /// assert_eq!(a[(1, 1)], g.first_form[1][1]);
    /// // a_ab = a_a . a_b: the tangents as columns T give T^T T
    /// let t = g.tangent_matrix();
    /// assert!((t.transpose() * t - a).norm() < 1e-14);
    /// ```
    pub fn first_form_matrix(&self) -> Matrix2<F> {
        m2(&self.first_form)
    }

    /// `a^ab` as a `Matrix2`.
    pub fn first_form_inverse_matrix(&self) -> Matrix2<F> {
        m2(&self.first_form_inverse)
    }

    /// `b_ab` (second fundamental form) as a `Matrix2`.
    pub fn second_form_matrix(&self) -> Matrix2<F> {
        m2(&self.second_form)
    }

    /// `b^a_b` (row `a`, column `b`) as a `Matrix2`.
    pub fn mixed_second_form_matrix(&self) -> Matrix2<F> {
        m2(&self.mixed_second_form)
    }

    /// The tangents `a_1`, `a_2` as the columns of a `Matrix3x2`.
    pub fn tangent_matrix(&self) -> Matrix3x2<F> {
        Matrix3x2::from_fn(|i, j| self.tangents[j][i])
    }

    /// The unit normal `N` as a `Vector3`.
    pub fn normal_vector(&self) -> Vector3<F> {
        Vector3::from(self.normal)
    }

    /// `sigma(x)` as a `Vector3`.
    pub fn point_vector(&self) -> Vector3<F> {
        Vector3::from(self.point)
    }

    /// `[Gamma^1, Gamma^2]`, each `Gamma^c_ab` as a `Matrix2` (row `a`, column `b`).
    pub fn christoffel_matrices(&self) -> [Matrix2<F>; 2] {
        [m2(&self.christoffel[0]), m2(&self.christoffel[1])]
    }
}

impl<F: NalgebraScalar + Copy> ShellPoint<F> {
    /// The covariant basis `g_1, g_2, g_3` as the columns of a `Matrix3`.
    ///
    /// # Example
    /// ```
    /// use capstan_geometry::{EllipticalPrism, ShellChart};
    /// let chart = ShellChart::new(EllipticalPrism::new(2.0, 1.0).unwrap());
    /// let p = chart.point([0.0, 0.4, 0.2]).unwrap();
    /// let g = p.covariant_basis_matrix();
    /// // g_ij = g_i . g_j, and g^ij is its inverse
    /// assert!((g.transpose() * g - p.metric_matrix()).norm() < 1e-13);
    /// assert!((p.inverse_metric_matrix() * p.metric_matrix() - capstan_geometry::nalgebra::Matrix3::identity()).norm() < 1e-13);
    /// ```
    pub fn covariant_basis_matrix(&self) -> Matrix3<F> {
        columns3(&self.covariant_basis)
    }

    /// The contravariant basis `g^1, g^2, g^3` as the columns of a `Matrix3`.
    pub fn contravariant_basis_matrix(&self) -> Matrix3<F> {
        columns3(&self.contravariant_basis)
    }

    /// `g_ij` as a `Matrix3`.
    pub fn metric_matrix(&self) -> Matrix3<F> {
        m3(&self.metric)
    }

    /// `g^ij` as a `Matrix3`.
    pub fn inverse_metric_matrix(&self) -> Matrix3<F> {
        m3(&self.inverse_metric)
    }

    /// `Theta(x)` as a `Vector3`.
    pub fn position_vector(&self) -> Vector3<F> {
        Vector3::from(self.position)
    }

    /// `[Gamma^1, Gamma^2, Gamma^3]`, each `Gamma^k_ij` as a `Matrix3` (row `i`, column `j`).
    pub fn christoffel_matrices(&self) -> [Matrix3<F>; 3] {
        [
            m3(&self.christoffel[0]),
            m3(&self.christoffel[1]),
            m3(&self.christoffel[2]),
        ]
    }
}
