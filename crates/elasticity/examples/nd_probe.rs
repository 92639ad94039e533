use capstan_elasticity::Discretisation;
use capstan_elasticity::contact::ThickBody;
use capstan_solvers::{ColumnOrdering, DirectParams, GridShape, LinearSolver, SparseLu};
fn main() {
    for (n2, n3) in [(500, 81), (1000, 161), (2000, 321)] {
        let body = ThickBody::paper(n2, n3).unwrap();
        let sys = body.discretisation(1.0, 2.0).unwrap().system().unwrap();
        let grid = GridShape {
            n2,
            n3,
            dofs_per_node: 2,
            periodic: false,
        };
        for (name, ordering) in [
            ("auto", ColumnOrdering::Auto),
            (
                "nd1",
                ColumnOrdering::NestedDissection {
                    grid,
                    separator_width: 1,
                },
            ),
            (
                "end1",
                ColumnOrdering::ElementNestedDissection { grid, degree: 1 },
            ),
        ] {
            let mut lu = SparseLu::new(DirectParams {
                ordering,
                ..Default::default()
            })
            .unwrap();
            let t = std::time::Instant::now();
            lu.analyse(&sys.pattern).unwrap();
            let ta = t.elapsed().as_secs_f64();
            let t = std::time::Instant::now();
            let ok = if n2 <= 1000 {
                lu.factor(&sys.values).is_ok()
            } else {
                true
            };
            let tf = t.elapsed().as_secs_f64();
            println!(
                "{n2}x{n3} {name}: entries {:?} analyse {ta:.2} s factor {tf:.2} s ok {ok}",
                lu.multifrontal_factor_entries()
            );
        }
    }
}
