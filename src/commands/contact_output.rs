//! The outputs of `capstan contact`: the plain-text summary, `contact.csv` and the body files
//! (`displacement.csv`, `body.vtu` and plots) of a solved scene.

use crate::commands::contact::{ContactReport, ContactRun, Extremum, Solved};
use crate::error::CliError;
use crate::output::Table;
use crate::provenance::report_dir;
use crate::scene::Scene;

/// Writes the outputs of a solved scene into `dir`: `contact.json`, `scene.toml`,
/// `contact.csv`, and the body (plane strain: `displacement.csv`, `body.vtu` and plots;
/// 3-D: `body.vtu` on hexahedra).
///
/// # Errors
/// Geometry or output errors.
pub fn write_run(
    dir: &std::path::Path,
    report: &ContactReport,
    run: &ContactRun,
    scene: &Scene,
) -> Result<(), CliError> {
    match run {
        ContactRun::Plane(solved) => write_out(dir, report, solved, scene),
        ContactRun::Solid { solution, model } => {
            // contact.csv: `x1` and `x2` per node with both tangential components
            let out = report_dir(dir, "contact", report, Some(scene))?;
            out.write_csv("contact.csv", &contact_table(report))?;
            if let Some(solid) = model.solid() {
                crate::commands::solid_contact::write_body(&out, scene, solid, solution)?;
            }
            if let Some(mesh) = model.mesh() {
                // a mesh discretisation (fem-qp-corner): the displacement at every mesh node
                let nodes = (0..mesh.node_count()).map(|m| mesh.node_position(m));
                let (x2, x3): (Vec<f64>, Vec<f64>) = nodes.map(|[a, b]| (a, b)).unzip();
                let v = &solution.displacement;
                let table = Table::new()
                    .f64("x2", x2)
                    .f64("x3", x3)
                    .f64("v2", v.iter().step_by(2).copied().collect::<Vec<f64>>())
                    .f64(
                        "v3",
                        v.iter().skip(1).step_by(2).copied().collect::<Vec<f64>>(),
                    );
                out.write_csv("displacement.csv", &table)?;
            }
            Ok(())
        }
    }
}

/// A plain-text summary.
pub fn table(r: &ContactReport) -> String {
    let mut s = format!(
        "contact: tau0 = {}, tau_max = {} (ratio {:.6}), grid {} x {} ({}), {}\n",
        r.tau0, r.tau_max, r.tension_ratio, r.grid[0], r.grid[1], r.discretisation, r.method
    );
    s += &format!(
        "  status {}: {} Newton iterations ({} continuation steps), residual {:.2e}, setup {:.3} s, solve {:.3} s\n",
        r.status,
        r.newton_iterations,
        r.continuation_steps,
        r.residual,
        r.setup_seconds,
        r.solve_seconds
    );
    if let Some(c) = r.solver_choice.as_ref().filter(|c| c.auto) {
        s += &format!(
            "  solver auto: {} with {} ({})\n",
            c.nonlinear, c.linear, c.reason
        );
    }
    let e = |x: &Extremum| format!("{:+.6e} at (x2, x3) = ({:.6}, {:.6})", x.value, x.x2, x.x3);
    if let Some(solid) = &r.solid {
        let [n1, n2, n3] = solid.grid;
        s += &format!(
            "  3-D body: grid {n1} x {n2} x {n3}, x1 in [{}, {}], sides {:?}, {} contact unknowns\n",
            solid.x1[0], solid.x1[1], solid.sides, solid.contact_unknowns
        );
    }
    s += &format!("  max |v2| {}\n", e(&r.max_azimuthal_displacement));
    s += &format!("  max |v3| {}\n", e(&r.max_radial_displacement));
    s += &format!("  Slip {:.6}\n", r.slip_fraction);
    s += &quantities_table(r);
    if let Some(a) = &r.accuracy {
        s += &a.table();
    }
    match r.stick_interval {
        Some([a, b]) => s += &format!("  stick ({a:.6}, {b:.6})\n"),
        None => s += "  stick: none\n",
    }
    for i in &r.slip_intervals {
        s += &format!("  slip {:+} [{:.6}, {:.6}]\n", i.state, i.from, i.to);
    }
    for [a, b] in r.lift_off_intervals.iter().flatten() {
        s += &format!("  lifted off [{a:.6}, {b:.6}]\n");
    }
    if let Some([lo, hi]) = r.limiting_ratios {
        let f =
            |x: Option<f64>, unbounded: &str| x.map_or(unbounded.to_owned(), |x| format!("{x:.6}"));
        s += &format!(
            "  limiting tension ratios (rigid sliding): [{}, {}]\n",
            f(lo, "-inf (none)"),
            f(hi, "inf (none)")
        );
    }
    s
}

/// The converging quantities with their estimated errors (`+- e`), as [`table`] prints them.
fn quantities_table(r: &ContactReport) -> String {
    let Some(q) = &r.quantities else {
        return String::new();
    };
    let estimate = |name: &str| {
        r.estimated_error
            .as_ref()
            .and_then(|e| e.quantities.get(name).copied().flatten())
            .map_or_else(String::new, |e| format!(" +- {e:.1e}"))
    };
    let mut s = format!(
        "  slip measure {:.6}{} of {:.6} (physical {:.6}{})\n",
        q.slip_measure,
        estimate("slip_measure"),
        q.contact_measure,
        q.slip_physical_measure,
        estimate("slip_physical_measure")
    );
    for (i, p) in q.normal_stress_probes.iter().enumerate() {
        s += &format!(
            "  sigma_n({:.6}) = {:+.6e}{}\n",
            p.x2,
            p.value,
            estimate(&format!("normal_stress_probe_{i}"))
        );
    }
    if let Some(e) = &r.estimated_error {
        let named = ["stick_from", "stick_to", "max_abs_v2", "max_abs_v3"]
            .iter()
            .filter_map(|n| {
                Some(format!(
                    "{n} {:.1e}",
                    e.quantities.get(*n).copied().flatten()?
                ))
            })
            .collect::<Vec<_>>();
        s += &format!(
            "  estimated errors (vs grid {:?}): {}\n",
            e.coarser_grid,
            named.join(", ")
        );
    }
    s
}

/// Writes `contact.json`, `contact.csv` (contact surface), `displacement.csv` (nodes),
/// `body.vtu` (every field on the curved body, see [`crate::output::body::VTU_ARRAYS`]) and the
/// plots `body_v2`, `body_v3` (displacement colour maps) and `body_state` (stick/slip strip),
/// each as SVG and PNG.
///
/// # Errors
/// Output errors.
pub fn write_out(
    dir: &std::path::Path,
    report: &ContactReport,
    sol: &Solved,
    scene: &Scene,
) -> Result<(), CliError> {
    let out = report_dir(dir, "contact", report, Some(scene))?;
    let table = contact_table(report);
    out.write_csv("contact.csv", &table)?;
    let nodes = Table::new()
        .f64("x2", sol.nodes.x2.clone())
        .f64("x3", sol.nodes.x3.clone())
        .f64("v2", sol.nodes.v2.clone())
        .f64("v3", sol.nodes.v3.clone());
    out.write_csv("displacement.csv", &nodes)?;
    crate::output::body::write_body(
        &out,
        "body",
        &sol.obstacle,
        &sol.fields,
        &sol.solution.contact,
        crate::output::body::BodyFiles {
            time: None,
            plots: true,
            compression: scene.output.vtu_compression,
            obstacle: scene.output.vtu_obstacle,
        },
    )?;
    Ok(())
}

/// The contact surface as a table (`contact.csv`): `x2, v2, v3, normal_stress, shear_stress,
/// slip, friction_traction, state` (and `separated`, 0 or 1, under unilateral contact); a 3-D body adds `x1`, `v1`, `shear_stress_1`, `slip_1`,
/// `friction_traction_1` beside their `x2` counterparts.
pub fn contact_table(report: &ContactReport) -> Table {
    let c = &report.contact;
    let solid = report.solid.as_ref().map(|s| &s.contact);
    let mut table = Table::new();
    if let Some(s) = solid {
        table = table.f64("x1", s.x1.clone());
    }
    table = table.f64("x2", c.x2.clone());
    if let Some(s) = solid {
        table = table.f64("v1", s.v1.clone());
    }
    table = table
        .f64("v2", c.v2.clone())
        .f64("v3", c.v3.clone())
        .f64("normal_stress", c.normal_stress.clone());
    for (name, plane, across) in [
        (
            "shear_stress",
            &c.shear_stress,
            solid.map(|s| &s.shear_stress_1),
        ),
        ("slip", &c.slip, solid.map(|s| &s.slip_1)),
        (
            "friction_traction",
            &c.friction_traction,
            solid.map(|s| &s.friction_traction_1),
        ),
    ] {
        if let Some(values) = across {
            table = table.f64(format!("{name}_1"), values.clone());
        }
        table = table.f64(name, plane.clone());
    }
    table = table.i32(
        "state",
        c.state.iter().map(|&s| i32::from(s)).collect::<Vec<_>>(),
    );
    if let Some(separated) = &c.separated {
        table = table.i32(
            "separated",
            separated.iter().map(|&s| i32::from(s)).collect::<Vec<_>>(),
        );
    }
    table
}
