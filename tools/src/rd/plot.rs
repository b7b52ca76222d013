//! Rate-distortion plots, one SVG per mesh, in the manner of thesis
//! Fig. 7.6 (and of the PGC papers it compares with): x = bits per input
//! vertex, y = L2 error in units of 1e-4 of the bounding-box diagonal,
//! one curve per configuration.
//!
//! The y axis is logarithmic: errors span two orders of magnitude between
//! 0.5 and 8 bits per vertex, and equal ratios (what "2× better" means)
//! then look equal at every rate. Points are placed at the rate a file
//! actually reached, not the target. Infeasible rows have no point. Text
//! is left to the SVG viewer's sans-serif font (plotters' `ttf` feature is
//! not needed to write SVG).

use crate::rd::config::Config;
use crate::rd::table::Row;
use plotters::prelude::*;

/// The lowest error drawn, in units of 1e-4 of the diagonal: 1e-7 of the
/// diagonal, the resolution of `f32` coordinates.
const FLOOR: f64 = 1e-3;

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
                .filter_map(|r| Some((r.bpv()?, r.coded.as_ref()?.l2_rel)))
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
    let y_lo = all.clone().map(|p| p.1).fold(f64::INFINITY, f64::min);
    let y_hi = all.map(|p| p.1).fold(0.0, f64::max);
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
        for (i, (config, pts)) in points.iter().enumerate() {
            let color = Palette99::pick(i).to_rgba();
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
