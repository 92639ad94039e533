//! The nalgebra views hold exactly the arrays they view, on every kind of obstacle.

use capstan_geometry::nalgebra::Matrix3;
use capstan_geometry::{EllipticalPrism, ShellChart, Sphere, Surface, SurfaceGeometry};

fn check_surface(g: &SurfaceGeometry<f64>) {
    let views = [
        (g.first_form_matrix(), g.first_form),
        (g.first_form_inverse_matrix(), g.first_form_inverse),
        (g.second_form_matrix(), g.second_form),
        (g.mixed_second_form_matrix(), g.mixed_second_form),
        (g.christoffel_matrices()[0], g.christoffel[0]),
        (g.christoffel_matrices()[1], g.christoffel[1]),
    ];
    for (m, a) in views {
        for i in 0..2 {
            for j in 0..2 {
                assert_eq!(m[(i, j)], a[i][j]); // a copy: bit for bit
            }
        }
    }
    let t = g.tangent_matrix();
    for a in 0..2 {
        for k in 0..3 {
            assert_eq!(t[(k, a)], g.tangents[a][k]);
        }
    }
    assert_eq!(g.normal_vector().as_slice(), &g.normal);
    assert_eq!(g.point_vector().as_slice(), &g.point);
}

#[test]
fn surface_views_equal_the_arrays() {
    let ellipse = EllipticalPrism::new(2.0, 1.0).unwrap();
    for t in [-1.2, 0.0, 0.7] {
        check_surface(&ellipse.geometry([0.3, t]).unwrap());
    }
    check_surface(&Sphere::new(1.5).unwrap().geometry([0.4, 0.9]).unwrap());
}

#[test]
fn shell_point_views_equal_the_arrays_and_the_identities_hold() {
    let chart = ShellChart::new(EllipticalPrism::new(2.0, 1.0).unwrap());
    for x in [[0.0, 0.4, 0.2], [1.0, -1.0, 0.7]] {
        let p = chart.point(x).unwrap();
        let pairs = [
            (p.metric_matrix(), p.metric),
            (p.inverse_metric_matrix(), p.inverse_metric),
            (p.christoffel_matrices()[2], p.christoffel[2]),
        ];
        for (m, a) in pairs {
            for i in 0..3 {
                for j in 0..3 {
                    assert_eq!(m[(i, j)], a[i][j]);
                }
            }
        }
        let (g, gd) = (p.covariant_basis_matrix(), p.contravariant_basis_matrix());
        for i in 0..3 {
            for k in 0..3 {
                assert_eq!(g[(k, i)], p.covariant_basis[i][k]);
                assert_eq!(gd[(k, i)], p.contravariant_basis[i][k]);
            }
        }
        // g^i . g_j = delta: round-off of a 3 x 3 product
        assert!((gd.transpose() * g - Matrix3::identity()).norm() < 1e-13);
        assert!((g.transpose() * g - p.metric_matrix()).norm() < 1e-13);
        assert_eq!(p.position_vector().as_slice(), &p.position);
    }
}
