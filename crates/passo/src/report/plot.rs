//! The work-precision picture: error against cost, log-log, one panel per
//! case, one line per method, and one legend for all of them in the panel
//! left after the cases (a legend inside each panel covered its lines).

use super::Report;
use super::cases::{METHODS, cases, methods_for};
use anyhow::{Result, anyhow};
use plotters::prelude::*;
use std::path::Path;

const COLOURS: [RGBColor; 6] = [
    RGBColor(228, 108, 58),
    RGBColor(240, 170, 130),
    RGBColor(58, 142, 228),
    RGBColor(140, 190, 240),
    RGBColor(92, 184, 92),
    RGBColor(163, 92, 214),
];

/// The methods' colours and names, one a line, in `panel`.
fn legend<DB: DrawingBackend>(panel: &DrawingArea<DB, plotters::coord::Shift>) -> Result<()> {
    let (x, mut y) = (40, 70);
    panel
        .draw(&Text::new("method", (x, y - 40), ("sans-serif", 20)))
        .map_err(|e| anyhow!("{e:?}"))?;
    for (i, method) in METHODS.iter().enumerate() {
        let colour = COLOURS[i % COLOURS.len()];
        panel
            .draw(&PathElement::new(
                vec![(x, y + 9), (x + 36, y + 9)],
                colour.stroke_width(3),
            ))
            .map_err(|e| anyhow!("{e:?}"))?;
        panel
            .draw(&Text::new(method.name, (x + 48, y), ("sans-serif", 18)))
            .map_err(|e| anyhow!("{e:?}"))?;
        y += 32;
    }
    panel
        .draw(&Text::new(
            "_plain: drag and friction in their plain explicit form",
            (x, y + 10),
            ("sans-serif", 14),
        ))
        .map_err(|e| anyhow!("{e:?}"))?;
    Ok(())
}

/// Draws the panels into a PNG at `path`.
pub(crate) fn work_precision(report: &Report, path: &Path) -> Result<()> {
    plotters::style::register_font(
        "sans-serif",
        FontStyle::Normal,
        epaint_default_fonts::UBUNTU_LIGHT,
    )
    .map_err(|_| anyhow!("the built-in font did not load"))?;
    let (w, h) = (1500u32, 1400u32);
    let mut rgb = vec![0u8; (w * h * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut rgb, (w, h)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| anyhow!("{e}"))?;
        let (title, body) = root.split_vertically(40);
        title
            .titled(
                "Passo: error against cost (log-log; lower left is better)",
                ("sans-serif", 26),
            )
            .map_err(|e| anyhow!("{e}"))?;
        let all = cases();
        let panels = body.split_evenly((3, 4));
        for (case, panel) in all.iter().zip(panels.iter()) {
            let rows: Vec<_> = report
                .rows
                .iter()
                .filter(|r| r.case == case.name && !r.unstable() && r.error > 0.0)
                .collect();
            if rows.is_empty() {
                continue;
            }
            let (mut x0, mut x1, mut y0, mut y1) = (f64::INFINITY, 0.0f64, f64::INFINITY, 0.0f64);
            for r in &rows {
                x0 = x0.min(r.ns_per_body());
                x1 = x1.max(r.ns_per_body());
                y0 = y0.min(r.error);
                y1 = y1.max(r.error);
            }
            let mut chart = ChartBuilder::on(panel)
                .caption(case.name, ("sans-serif", 20))
                .margin(8)
                .x_label_area_size(30)
                .y_label_area_size(55)
                .build_cartesian_2d(
                    (x0 * 0.7..x1 * 1.4).log_scale(),
                    (y0 * 0.5..y1 * 2.0).log_scale(),
                )
                .map_err(|e| anyhow!("{e}"))?;
            chart
                .configure_mesh()
                .x_desc("ns per body")
                .y_desc("error (m)")
                .x_labels(4)
                .y_labels(5)
                .x_label_formatter(&|v| format!("{v:.0e}"))
                .y_label_formatter(&|v| format!("{v:.0e}"))
                .label_style(("sans-serif", 12))
                .draw()
                .map_err(|e| anyhow!("{e}"))?;
            for method in methods_for(case) {
                // One colour per method, the same in every panel.
                let i = METHODS.iter().position(|m| *m == method).unwrap_or(0);
                let colour = COLOURS[i % COLOURS.len()];
                let points: Vec<(f64, f64)> = rows
                    .iter()
                    .filter(|r| r.method == method.name)
                    .map(|r| (r.ns_per_body(), r.error))
                    .collect();
                chart
                    .draw_series(LineSeries::new(points.clone(), colour.stroke_width(2)))
                    .map_err(|e| anyhow!("{e}"))?;
                chart
                    .draw_series(points.iter().map(|&p| Circle::new(p, 3, colour.filled())))
                    .map_err(|e| anyhow!("{e}"))?;
            }
        }
        if let Some(panel) = panels.get(all.len()) {
            legend(panel)?;
        }
        root.present().map_err(|e| anyhow!("{e}"))?;
    }
    let image = passo_render::RgbaImage {
        width: w,
        height: h,
        pixels: rgb
            .chunks_exact(3)
            .flat_map(|p| [p[0], p[1], p[2], 255])
            .collect(),
    };
    image.save_png(path)?;
    Ok(())
}
