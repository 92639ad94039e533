//! The 3-D corner-refined body (`SolidCornerNavier`) in the contact solves: with no layers it
//! is the tensor grid's `fem-qp` body (same contact profiles, slip and extremes), and with
//! layers its face is listed by `x1` line in increasing `x2` and its weights sum to the face.

use capstan_elasticity::contact::{
    BoundarySolver, ContactModel, ContactOperator, ContactSettings, EndLoads, FullSystemSettings,
    FullSystemSolver,
};
use capstan_elasticity::finite_element::high_order::CornerSettings;
use capstan_elasticity::friction::{RegularisedCoulomb, RegularisedCoulombParams};
use capstan_elasticity::solid::{HexElement, SolidBody, SolidCornerNavier};
use capstan_geometry::{EllipticalPrism, ShellChart};

const EPS: f64 = 1e-5;

fn body(p: usize, ne: [usize; 3], b: f64) -> SolidBody<EllipticalPrism<f64>> {
    SolidBody {
        order: HexElement::Gll(p),
        ..SolidBody::new(
            EllipticalPrism::new(2.0, b).unwrap(),
            [-0.5, 0.5],
            ne.map(|e| p * e + 1),
        )
    }
}

fn corner_model(
    b: &SolidBody<EllipticalPrism<f64>>,
    settings: CornerSettings,
) -> ContactModel<SolidCornerNavier<ShellChart<EllipticalPrism<f64>>>, RegularisedCoulomb> {
    ContactModel::new(
        |tau0, tau_max| {
            SolidCornerNavier::new(
                ShellChart::new(b.surface),
                b.material,
                b.grid()?,
                &b.boundary(tau0, tau_max),
                None,
                settings,
            )
        },
        RegularisedCoulomb,
        RegularisedCoulombParams::new(0.5, EPS).unwrap(),
        EPS,
    )
    .unwrap()
}

fn max_abs(v: &[f64]) -> f64 {
    v.iter().fold(0.0f64, |m, x| m.max(x.abs()))
}

fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
}

#[test]
fn no_layers_give_the_tensor_grid_contact_solution() {
    let (p, ne) = (2, [2, 4, 2]);
    let b = body(p, ne, 1.5);
    let settings = CornerSettings {
        order: p,
        cells: [ne[1], ne[2]],
        layers: 0,
        ratio: 0.3,
    };
    let corner = corner_model(&b, settings);
    let tensor = b
        .model(
            RegularisedCoulomb,
            RegularisedCoulombParams::new(0.5, EPS).unwrap(),
            EPS,
        )
        .unwrap();
    let loads = EndLoads::ratio(1.5);
    let sc = FullSystemSolver::new(&corner, FullSystemSettings::default())
        .unwrap()
        .solve(loads)
        .unwrap();
    let st = FullSystemSolver::new(&tensor, FullSystemSettings::default())
        .unwrap()
        .solve(loads)
        .unwrap();
    let (c, t) = (&sc.contact, &st.contact);
    assert!(max_diff(&c.x2, &t.x2) < 1e-13);
    let rel = |a: &[f64], b: &[f64]| max_diff(a, b) / max_abs(b);
    let errors = [
        rel(&c.v2, &t.v2),
        rel(&c.normal_stress, &t.normal_stress),
        rel(&c.shear_stress, &t.shear_stress),
        rel(&c.slip, &t.slip),
        rel(&c.friction_traction, &t.friction_traction),
    ];
    println!("3-D corner contact, no layers against fem-qp: {errors:?}");
    assert!(errors.iter().all(|&e| e < 1e-9), "{errors:?}");
    assert!((sc.slip_fraction - st.slip_fraction).abs() < 1e-12);
    let (mc, mt) = (
        sc.max_azimuthal_displacement.value,
        st.max_azimuthal_displacement.value,
    );
    assert!((mc - mt).abs() < 1e-9 * mt.abs(), "{mc} {mt}");
    // the condensed solver on the same operator
    let cond = BoundarySolver::new(&corner, ContactSettings::default())
        .unwrap()
        .solve(loads)
        .unwrap();
    assert!(rel(&cond.contact.v2, &t.v2) < 1e-7);
    // with layers: the full-system Newton converges on the refined face, near the tensor
    // grid's answer (the layers move max |v2| by the discretisation error only)
    let layered = corner_model(
        &b,
        CornerSettings {
            layers: 3,
            ..settings
        },
    );
    let sl = FullSystemSolver::new(&layered, FullSystemSettings::default())
        .unwrap()
        .solve(loads)
        .unwrap();
    let ml = sl.max_azimuthal_displacement.value;
    println!("max |v2|: layers 3 {ml}, fem-qp {mt}");
    assert!((ml - mt).abs() < 0.1 * mt.abs(), "{ml} {mt}");
    assert!(sl.contact.x2.windows(2).take(8).all(|w| w[1] > w[0]));
}

#[test]
fn layered_face_is_ordered_in_x2_and_its_weights_sum_to_the_face() {
    let (p, ne) = (3, [2, 4, 2]);
    let b = body(p, ne, 2.0);
    let settings = CornerSettings {
        order: p,
        cells: [ne[1], ne[2]],
        layers: 3,
        ratio: 0.3,
    };
    let op = SolidCornerNavier::new(
        ShellChart::new(b.surface),
        b.material,
        b.grid().unwrap(),
        &b.boundary(1.0, 2.0),
        None,
        settings,
    )
    .unwrap();
    let entries = op.contact_entries().unwrap();
    let n1 = p * ne[0] + 1;
    // p nodes more per layer at each end of every x1 line
    let per_line = p * ne[1] + 1 + 2 * 3 * p;
    assert_eq!(settings.face_node_count(), per_line);
    assert_eq!(op.node_count(), n1 * settings.node_count());
    assert_eq!(entries.len(), 2 * n1 * per_line);
    let mut area = 0.0;
    for (k, pair) in entries.chunks(2).enumerate() {
        let (i1, rank) = (k / per_line, k % per_line);
        assert_eq!((pair[0].i1, pair[0].node[0], pair[0].site), (i1, rank, k));
        if rank > 0 {
            assert!(pair[0].x2 > entries[2 * (k - 1)].x2);
        }
        area += pair[0].traction_weight;
    }
    // the face of the circle's prism: width 1 times the arc 2 pi (sqrt(g) sqrt(g^33) = 2 at
    // x3 = 0: the face weights integrate it exactly)
    let arc = 2.0 * core::f64::consts::PI;
    assert!((area - arc).abs() < 1e-12 * arc, "{area} {arc}");
}
