//! The log-log plot of docs/solid.md: CPU time and peak memory against unknowns of the 3-D
//! contact solve, matrix-free Newton (`solver.linear = "matrix-free-mg"`) beside the assembled
//! full-system Newton with GMRES and multigrid, from the measurements in
//! `docs/data/matrix_free_scaling.csv` (rows `path,unknowns,cpu_seconds,peak_mib`, `#`
//! comments; `path` is `matrix-free`, `matrix-free-sequenced` (grid sequencing) or
//! `assembled`), with the ratio assembled / matrix-free (each matrix-free path) printed and
//! written on the figure where both were measured. The axes span the table's rows (a 1e7 row
//! widens them).
//!
//! Run: `cargo run --example matrix_free_scaling_plot -- [CSV] [SVG]` (defaults
//! `docs/data/matrix_free_scaling.csv`, `docs/figures/matrix-free-scaling.svg`).

use plotters::prelude::*;

type Row = (String, f64, f64, f64);

/// The paths of the table and their colours.
const PATHS: &[(&str, RGBColor)] = &[
    ("matrix-free", BLUE),
    ("matrix-free-sequenced", GREEN),
    ("assembled", RED),
];

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let csv = args
        .first()
        .map_or("docs/data/matrix_free_scaling.csv", String::as_str);
    let svg = args
        .get(1)
        .map_or("docs/figures/matrix-free-scaling.svg", String::as_str);
    let rows: Vec<Row> = std::fs::read_to_string(csv)?
        .lines()
        .filter(|l| !l.trim().is_empty() && !l.starts_with('#'))
        .map(|l| -> Result<Row, Box<dyn std::error::Error>> {
            let f: Vec<&str> = l.split(',').collect();
            if f.len() != 4 {
                return Err(
                    format!("{csv}: `{l}` is not path,unknowns,cpu_seconds,peak_mib").into(),
                );
            }
            Ok((f[0].to_owned(), f[1].parse()?, f[2].parse()?, f[3].parse()?))
        })
        .collect::<Result<_, _>>()?;
    if rows.is_empty() {
        return Err(format!("{csv}: no rows").into());
    }
    if let Some(r) = rows.iter().find(|r| !PATHS.iter().any(|p| p.0 == r.0)) {
        return Err(format!(
            "{csv}: path `{}` is not one of {:?}",
            r.0,
            PATHS.iter().map(|p| p.0).collect::<Vec<_>>()
        )
        .into());
    }
    if let Some(r) = rows
        .iter()
        .find(|r| !(r.1 >= 1.0 && r.2 > 0.0 && r.3 > 0.0 && r.2.is_finite() && r.3.is_finite()))
    {
        return Err(
            format!("{csv}: row {r:?} needs unknowns >= 1 and positive time and memory").into(),
        );
    }
    // assembled / matrix-free at every size where both were measured:
    // (matrix-free path, unknowns, time ratio, memory ratio)
    let mut ratios: Vec<(&str, f64, f64, f64)> = Vec::new();
    for a in rows.iter().filter(|r| r.0 == "assembled") {
        for path in PATHS.iter().map(|p| p.0).filter(|&p| p != "assembled") {
            if let Some(m) = rows.iter().find(|r| r.0 == path && r.1 == a.1) {
                println!(
                    "{} unknowns: assembled / {path}  time {:.2}x  memory {:.2}x",
                    a.1,
                    a.2 / m.2,
                    a.3 / m.3
                );
                ratios.push((path, a.1, a.2 / m.2, a.3 / m.3));
            }
        }
    }
    let (x_lo, x_hi) = rows.iter().fold((f64::INFINITY, 0.0f64), |(a, b), r| {
        (a.min(r.1), b.max(r.1))
    });
    // capstan's bundled fonts (plotters' ab_glyph backend has none of its own); the figure is
    // drawn into memory and written whole, so a failed run leaves no partial file
    capstan::output::register_fonts();
    let mut text = String::new();
    {
        let root = SVGBackend::with_string(&mut text, (900, 400)).into_drawing_area();
        root.fill(&WHITE)?;
        let panels = root.split_evenly((1, 2));
        for (panel, (title, column)) in panels
            .iter()
            .zip([("CPU seconds", 2usize), ("peak memory (MiB)", 3)])
        {
            let value = |r: &Row| if column == 2 { r.2 } else { r.3 };
            let ys: Vec<f64> = rows.iter().map(value).collect();
            let (lo, hi) = ys
                .iter()
                .fold((f64::INFINITY, 0.0f64), |(a, b), &y| (a.min(y), b.max(y)));
            let mut chart = ChartBuilder::on(panel)
                .caption(title, ("sans-serif", 18))
                .margin(10)
                .x_label_area_size(35)
                .y_label_area_size(55)
                .build_cartesian_2d(
                    (x_lo / 3.0..x_hi * 3.0).log_scale(),
                    (lo / 2.0..hi * 2.0).log_scale(),
                )?;
            chart
                .configure_mesh()
                .x_desc("unknowns")
                .x_label_formatter(&|x| format!("{x:.0e}"))
                .draw()?;
            for &(path, colour) in PATHS {
                let points: Vec<(f64, f64)> = rows
                    .iter()
                    .filter(|r| r.0 == path)
                    .map(|r| (r.1, value(r)))
                    .collect();
                chart
                    .draw_series(LineSeries::new(points.clone(), colour))?
                    .label(path)
                    .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 15, y)], colour));
                chart.draw_series(points.iter().map(|&p| Circle::new(p, 4, colour.filled())))?;
            }
            // the ratio assembled / sequenced matrix-free (else plain matrix-free) under each
            // assembled point
            for a in rows.iter().filter(|r| r.0 == "assembled") {
                let ratio = ratios
                    .iter()
                    .find(|q| q.0 == "matrix-free-sequenced" && q.1 == a.1)
                    .or_else(|| ratios.iter().find(|q| q.1 == a.1));
                if let Some(q) = ratio {
                    let r = if column == 2 { q.2 } else { q.3 };
                    chart.draw_series(std::iter::once(Text::new(
                        format!("{r:.1}x"),
                        (a.1, value(a) * 1.5),
                        ("sans-serif", 13).into_font().color(&RED),
                    )))?;
                }
            }
            chart
                .configure_series_labels()
                .background_style(WHITE.mix(0.8))
                .border_style(BLACK)
                .draw()?;
        }
        root.present()?;
    }
    std::fs::write(svg, text)?;
    println!("wrote {svg}");
    Ok(())
}
