//! Qp hexahedra (GLL nodes) for the 3-D body: manufactured solutions on cones (observed L2
//! order `p + 1`), and `p = 1, 2` against the Q1/Q2 hexahedra.

use capstan_elasticity::finite_element::ElementOrder;
use capstan_elasticity::solid::HexElement;
use capstan_elasticity::solid::samples::SolidMms;
use capstan_elasticity::solvers::SparseCholesky;
use capstan_elasticity::verification::observed_order;

fn table(points: &[(f64, f64)]) -> String {
    points
        .iter()
        .map(|(h, e)| format!("h {h:.4e} error {e:.3e}"))
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn manufactured_solutions_converge_at_order_p_plus_one_for_qp_hexahedra() {
    // (p, elements per direction, bound on the finest relative L2 error)
    let cases: [(usize, [usize; 3], f64); 4] = [
        (1, [2, 4, 8], 2.5e-3),
        (2, [2, 4, 8], 6e-5),
        (3, [2, 3, 4], 1e-3),
        (4, [2, 3, 4], 1e-4),
    ];
    for mms in [SolidMms::circular_cone(), SolidMms::elliptical_cone()] {
        for (p, grids, finest) in cases {
            let points: Vec<(f64, f64)> = grids
                .iter()
                .map(|&m| mms.relative_error(m, HexElement::Gll(p)).unwrap())
                .collect();
            let order = observed_order(&points);
            println!("{} Q{p}: order {order:.3}\n{}", mms.name, table(&points));
            assert!(
                (order - (p as f64 + 1.0)).abs() < 0.15,
                "{} Q{p}: order {order:.3}\n{}",
                mms.name,
                table(&points)
            );
            assert!(
                points[2].1 < finest,
                "{} Q{p}\n{}",
                mms.name,
                table(&points)
            );
        }
    }
}

#[test]
fn qp_of_degree_one_and_two_is_the_q1_q2_operator_to_round_off() {
    let mms = SolidMms::elliptical_cone();
    for (order, p, n) in [(ElementOrder::Q1, 1, 4), (ElementOrder::Q2, 2, 5)] {
        let q = mms.operator([n, n + 2, n], order).unwrap();
        let g = mms.operator([n, n + 2, n], HexElement::Gll(p)).unwrap();
        let (a, b) = (q.system(), g.system());
        assert_eq!(a.pattern, b.pattern);
        let max = |v: &[f64]| v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let diff = |x: &[f64], y: &[f64]| {
            x.iter()
                .zip(y)
                .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
                / max(x)
        };
        let (dm, dr) = (diff(&a.values, &b.values), diff(&a.rhs, &b.rhs));
        let u = q.solve(&mut SparseCholesky::default()).unwrap();
        let v = g.solve(&mut SparseCholesky::default()).unwrap();
        let du = diff(&u, &v);
        println!("Q{p}: matrix {dm:.2e}, load {dr:.2e}, solution {du:.2e}");
        assert!(
            dm < 1e-13 && dr < 1e-13 && du < 1e-12,
            "Q{p}: {dm:e} {dr:e} {du:e}"
        );
        // the node positions agree too
        for m in 0..q.grid().node_count() {
            let (x, y) = (
                q.grid().coordinates(q.grid().node(m)),
                g.grid().coordinates(g.grid().node(m)),
            );
            for c in 0..3 {
                assert!((x[c] - y[c]).abs() < 1e-15);
            }
        }
    }
}
