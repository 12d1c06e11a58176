//! PNG plots of the benchmark with plotters. Text uses the Ubuntu Light font
//! that egui ships, so no system font is needed.

use std::path::Path;
use std::sync::Once;

use plotters::prelude::*;

use super::{ErrorRow, ScalingRow};

type PlotResult = Result<(), Box<dyn std::error::Error>>;

pub(super) fn register_font() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        // Only fails for bytes that are not a font; these are.
        let _ = plotters::style::register_font(
            "sans-serif",
            FontStyle::Normal,
            epaint_default_fonts::UBUNTU_LIGHT,
        );
    });
}

/// The range of positive values, padded by a factor for a log axis.
pub(super) fn log_range(values: impl Iterator<Item = f64>) -> std::ops::Range<f64> {
    let (lo, hi) = values
        .filter(|v| v.is_finite() && *v > 0.0)
        .fold((f64::MAX, f64::MIN), |(lo, hi), v| (lo.min(v), hi.max(v)));
    if lo > hi {
        return 1e-3..1.0;
    }
    lo / 1.5..hi * 1.5
}

/// Time (x) against RMSE (y), log scales: every point, the Pareto front as
/// a line, the viewer's defaults as a large mark.
pub fn pareto(
    path: &Path,
    scene: &str,
    rows: &[&ErrorRow],
    front: &[ErrorRow],
    default: Option<&ErrorRow>,
) -> PlotResult {
    register_font();
    let root = BitMapBackend::new(path, (800, 560)).into_drawing_area();
    root.fill(&WHITE)?;
    // A point with no error at all (RMSE 0) cannot sit on a log axis: it is
    // drawn at the bottom of the range.
    let errors = log_range(rows.iter().map(|r| r.rmse));
    let floor = errors.start;
    let mut chart = ChartBuilder::on(&root)
        .caption(format!("{scene}: time against error"), ("sans-serif", 26))
        .margin(12)
        .x_label_area_size(46)
        .y_label_area_size(70)
        .build_cartesian_2d(
            log_range(rows.iter().map(|r| r.time_ms)).log_scale(),
            errors.log_scale(),
        )?;
    chart
        .configure_mesh()
        .x_desc("GPU frame time (ms)")
        .y_desc("RMSE against the converged reference")
        .label_style(("sans-serif", 15))
        .draw()?;
    let at = |r: &ErrorRow| (r.time_ms, r.rmse.max(floor));
    chart
        .draw_series(
            rows.iter()
                .map(|r| Circle::new(at(r), 3, BLUE.mix(0.35).filled())),
        )?
        .label("sweep points")
        .legend(|(x, y)| Circle::new((x, y), 3, BLUE.filled()));
    chart
        .draw_series(LineSeries::new(front.iter().map(at), RED.stroke_width(2)))?
        .label("Pareto front")
        .legend(|(x, y)| PathElement::new(vec![(x - 8, y), (x + 8, y)], RED.stroke_width(2)));
    if let Some(d) = default {
        chart
            .draw_series(std::iter::once(TriangleMarker::new(
                at(d),
                9,
                BLACK.filled(),
            )))?
            .label("viewer defaults")
            .legend(|(x, y)| TriangleMarker::new((x, y), 6, BLACK.filled()));
    }
    chart
        .configure_series_labels()
        .label_font(("sans-serif", 15))
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .draw()?;
    root.present()?;
    Ok(())
}

/// Frame time against the number of spheres, log-log, with and without the
/// BVH.
pub fn scaling(path: &Path, rows: &[ScalingRow]) -> PlotResult {
    let points = |time: fn(&ScalingRow) -> f64| -> Vec<(f64, f64)> {
        rows.iter().map(|r| (r.spheres as f64, time(r))).collect()
    };
    log_log_lines(
        path,
        "Frame time against the number of spheres",
        ("spheres", "GPU frame time (ms)"),
        &[
            ("with the BVH".to_string(), points(|r| r.bvh_ms)),
            ("loop over all spheres".to_string(), points(|r| r.loop_ms)),
        ],
    )
}

/// Lines with dots on log-log axes, one per `(label, points)` (red, blue,
/// green, ...), with a legend.
pub fn log_log_lines(
    path: &Path,
    title: &str,
    (x_desc, y_desc): (&str, &str),
    series: &[(String, Vec<(f64, f64)>)],
) -> PlotResult {
    register_font();
    let root = BitMapBackend::new(path, (800, 560)).into_drawing_area();
    root.fill(&WHITE)?;
    let all = || series.iter().flat_map(|(_, p)| p.iter());
    let xs = log_range(all().map(|p| p.0));
    // At least a decade, so that the log axis has labelled marks.
    let ys = log_range(all().map(|p| p.1));
    let ys = ys.start.min(ys.end / 10.0)..ys.end;
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 26))
        .margin(12)
        .x_label_area_size(46)
        .y_label_area_size(70)
        .build_cartesian_2d(xs.log_scale(), ys.log_scale())?;
    chart
        .configure_mesh()
        .x_desc(x_desc)
        .y_desc(y_desc)
        .label_style(("sans-serif", 15))
        .draw()?;
    for ((label, points), color) in series
        .iter()
        .zip([RED, BLUE, GREEN, MAGENTA].iter().cycle())
    {
        let color = *color;
        chart
            .draw_series(LineSeries::new(points.clone(), color.stroke_width(2)))?
            .label(label)
            .legend(move |(x, y)| {
                PathElement::new(vec![(x - 8, y), (x + 8, y)], color.stroke_width(2))
            });
        chart.draw_series(points.iter().map(|&p| Circle::new(p, 4, color.filled())))?;
    }
    chart
        .configure_series_labels()
        .label_font(("sans-serif", 15))
        .position(SeriesLabelPosition::UpperLeft)
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .draw()?;
    root.present()?;
    Ok(())
}
