//! Rate-distortion plots, one SVG per mesh, in the manner of thesis
//! Fig. 7.6 (and of the PGC papers it compares with): x = bits per input
//! vertex, y = L2 error in units of 1e-4 of the bounding-box diagonal,
//! one curve per configuration.
//!
//! The y axis is logarithmic: errors span two orders of magnitude between
//! 0.5 and 8 bits per vertex, and equal ratios (what "2× better" means)
//! then look equal at every rate. Points are placed at the rate a file
//! actually reached, not the target. Rows without a file have no point. Text
//! is left to the SVG viewer's sans-serif font (plotters' `ttf` feature is
//! not needed to write SVG).

use crate::rd::config::Config;
use crate::rd::table::Row;
use plotters::prelude::*;

/// The lowest error drawn, in units of 1e-4 of the diagonal: 1e-7 of the
/// diagonal, the resolution of `f32` coordinates.
const FLOOR: f64 = 1e-3;

/// Each configuration's colour, the same in every plot (from the first
/// entries of plotters' `Palette99`, yellow skipped: it vanishes on white;
/// the automatic mode in black, grey and brown, from most effort to least).
fn color(config: Config) -> RGBColor {
    match config {
        Config::Lossless => RGBColor(230, 25, 75),
        Config::Baseline => RGBColor(60, 180, 75),
        Config::Auto => RGBColor(0, 0, 0),
        Config::AutoDefault => RGBColor(128, 128, 128),
        Config::AutoFast => RGBColor(170, 110, 40),
        Config::Swing => RGBColor(67, 99, 216),
        Config::SwingPlain => RGBColor(70, 153, 144),
        Config::SwingSharpen => RGBColor(245, 130, 49),
        Config::SwingSharpenBend => RGBColor(145, 30, 180),
        Config::SwingOnSurface => RGBColor(66, 212, 244),
        Config::SwingAdaptive => RGBColor(128, 128, 0),
        Config::Displaced => RGBColor(220, 190, 255),
    }
}

/// The plot of `rows` (one mesh's) as an SVG document.
pub fn svg(title: &str, rows: &[&Row]) -> Result<String, String> {
    let mut configs: Vec<Config> = rows.iter().map(|r| r.config).collect();
    configs.sort();
    configs.dedup();
    let points: Vec<(Config, Vec<(f64, f64)>)> = configs
        .iter()
        .map(|&c| {
            let mut pts: Vec<(f64, f64)> = rows
                .iter()
                .filter(|r| r.config == c)
                .filter_map(|r| Some((r.bpv()?, r.coded()?.l2_rel)))
                .collect();
            pts.sort_by(|a, b| a.0.total_cmp(&b.0));
            (c, pts)
        })
        .collect();
    // Every plot of a table spans the same rates.
    let rates = rows.iter().map(|r| r.rate_bpv);
    let all = points.iter().flat_map(|(_, p)| p.iter());
    let x_max = rates.chain(all.clone().map(|p| p.0)).fold(1.0, f64::max) * 1.05;
    // Exact coding (error 0, or rounding noise of 1e-13) has no place on
    // a log axis: such points sit on the floor.
    // A mesh no configuration coded (`swing` alone on a torus) gets empty
    // axes: an infinite log range would make plotters loop over ticks.
    let y_lo = all.clone().map(|p| p.1).fold(f64::INFINITY, f64::min);
    let y_hi = all.map(|p| p.1).fold(0.0, f64::max);
    let (y_lo, y_hi) = if y_lo.is_finite() {
        (y_lo, y_hi)
    } else {
        (1.0, 1.0)
    };
    let y_lo = (y_lo / 1.5).max(FLOOR);
    let y_hi = (y_hi * 1.5).max(y_lo * 10.0);

    let mut out = String::new();
    {
        let root = SVGBackend::with_string(&mut out, (720, 480)).into_drawing_area();
        let e = |e: DrawingAreaErrorKind<_>| e.to_string();
        root.fill(&WHITE).map_err(e)?;
        let mut chart = ChartBuilder::on(&root)
            .caption(title, ("sans-serif", 20))
            .margin(14)
            .x_label_area_size(44)
            .y_label_area_size(60)
            .build_cartesian_2d(0f64..x_max, (y_lo..y_hi).log_scale())
            .map_err(|e| e.to_string())?;
        chart
            .configure_mesh()
            .light_line_style(TRANSPARENT)
            .x_label_formatter(&|x| format!("{x}"))
            .y_label_formatter(&|y| format!("{y}"))
            .x_desc("bits per input vertex")
            .y_desc("L2 error (1e-4 of the bbox diagonal)")
            .draw()
            .map_err(|e| e.to_string())?;
        for (config, pts) in &points {
            let color = color(*config).to_rgba();
            let pts: Vec<(f64, f64)> = pts.iter().map(|&(x, y)| (x, y.max(y_lo))).collect();
            chart
                .draw_series(LineSeries::new(pts.clone(), color.stroke_width(2)))
                .map_err(|e| e.to_string())?
                .label(config.name())
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
                });
            chart
                .draw_series(pts.iter().map(|&p| Circle::new(p, 4, color.filled())))
                .map_err(|e| e.to_string())?;
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .draw()
            .map_err(|e| e.to_string())?;
        root.present().map_err(e)?;
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::svg;
    use crate::rd::config::Config;
    use crate::rd::table::{Outcome, Row};

    /// A mesh without a single coded row (`swing` alone on a torus) still
    /// gets a plot, promptly.
    #[test]
    fn a_plot_without_points_has_empty_axes() {
        let row = Row {
            mesh: "generated:torus".into(),
            rate_bpv: 2.0,
            config: Config::Swing,
            vertices: 1536,
            budget_bytes: 384,
            samples: 1000,
            outcome: Outcome::NotApplicable { why: String::new() },
        };
        let out = svg("torus", &[&row]).expect("an SVG");
        assert!(out.starts_with("<svg") && out.trim_end().ends_with("</svg>"));
        assert!(out.len() < 100_000, "{} bytes", out.len());
    }
}
