//! SVG line plots for the reports (`plotters`), drawn on log10 axes by hand: values are
//! plotted as their base-10 logarithm on a linear axis labelled with the values (`3e-12`), which keeps one
//! code path for every combination of linear and logarithmic axes.

use std::path::Path;

use anyhow::{Context, Result, anyhow};
use plotters::prelude::*;

/// One line of a panel.
#[derive(Clone, Debug)]
pub struct Series {
    /// Legend label.
    pub name: String,
    /// Points `(x, y)` in data units (before any log transform), in drawing order.
    pub points: Vec<(f64, f64)>,
}

/// One chart of a grid.
#[derive(Clone, Debug)]
pub struct Panel {
    /// Caption above the chart.
    pub title: String,
    /// X axis label.
    pub x_desc: String,
    /// Y axis label.
    pub y_desc: String,
    /// Whether x is plotted on a log10 scale.
    pub x_log: bool,
    /// Whether y is plotted on a log10 scale.
    pub y_log: bool,
    /// Values below this are drawn at it on a log axis (zeros, exact answers).
    pub y_floor: f64,
    /// The lines; series `i` gets colour `i` in every panel of a grid.
    pub series: Vec<Series>,
}

fn tx(v: f64, log: bool, floor: f64) -> f64 {
    if log { v.max(floor).log10() } else { v }
}

fn range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(v), b.max(v))
        });
    if lo > hi {
        (0.0, 1.0)
    } else if hi - lo < 1e-9 {
        (lo - 0.5, hi + 0.5)
    } else {
        let pad = 0.04 * (hi - lo);
        (lo - pad, hi + pad)
    }
}

fn tick_label(v: f64, log: bool) -> String {
    if log {
        // Ticks fall at arbitrary log positions: print the value they stand for.
        format!("{:.0e}", 10f64.powf(v))
    } else if v.abs() >= 1e4 || (v != 0.0 && v.abs() < 1e-2) {
        format!("{v:.0e}")
    } else {
        format!("{v}")
    }
}

/// Draws `panels` in a grid of `cols` columns into the SVG file `path`, `size` pixels overall;
/// the legend is drawn in the first panel.
pub fn grid_svg(path: &Path, panels: &[Panel], cols: usize, size: (u32, u32)) -> Result<()> {
    let rows = panels.len().div_ceil(cols.max(1));
    let root = SVGBackend::new(path, size).into_drawing_area();
    root.fill(&WHITE).map_err(|e| anyhow!("{e}"))?;
    let areas = root.split_evenly((rows, cols));
    for (k, (panel, area)) in panels.iter().zip(areas.iter()).enumerate() {
        let xs = panel.series.iter().flat_map(|s| {
            s.points
                .iter()
                .map(|p| tx(p.0, panel.x_log, f64::MIN_POSITIVE))
        });
        let ys = panel
            .series
            .iter()
            .flat_map(|s| s.points.iter().map(|p| tx(p.1, panel.y_log, panel.y_floor)));
        let (x0, x1) = range(xs);
        let (y0, y1) = range(ys);
        let mut chart = ChartBuilder::on(area)
            .caption(&panel.title, ("sans-serif", 16))
            .margin(8)
            .x_label_area_size(34)
            .y_label_area_size(56)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(|e| anyhow!("{e}"))?;
        let (xl, yl) = (panel.x_log, panel.y_log);
        chart
            .configure_mesh()
            .x_desc(panel.x_desc.as_str())
            .y_desc(panel.y_desc.as_str())
            .x_label_formatter(&|v| tick_label(*v, xl))
            .y_label_formatter(&|v| tick_label(*v, yl))
            .x_labels(8)
            .y_labels(8)
            .label_style(("sans-serif", 11))
            .draw()
            .map_err(|e| anyhow!("{e}"))?;
        for (i, s) in panel.series.iter().enumerate() {
            let color = Palette99::pick(i).to_rgba();
            let pts: Vec<(f64, f64)> = s
                .points
                .iter()
                .map(|&(x, y)| (tx(x, xl, f64::MIN_POSITIVE), tx(y, yl, panel.y_floor)))
                .collect();
            let line = chart
                .draw_series(LineSeries::new(pts.clone(), color.stroke_width(2)))
                .map_err(|e| anyhow!("{e}"))?;
            if k == 0 {
                line.label(s.name.as_str()).legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 16, y)], color.stroke_width(2))
                });
            }
            chart
                .draw_series(pts.iter().map(|&p| Circle::new(p, 2, color.filled())))
                .map_err(|e| anyhow!("{e}"))?;
        }
        if k == 0 {
            chart
                .configure_series_labels()
                .position(SeriesLabelPosition::UpperLeft)
                .background_style(WHITE.mix(0.85))
                .border_style(BLACK)
                .label_font(("sans-serif", 11))
                .draw()
                .map_err(|e| anyhow!("{e}"))?;
        }
    }
    root.present()
        .map_err(|e| anyhow!("{e}"))
        .with_context(|| format!("cannot write {}", path.display()))
}
