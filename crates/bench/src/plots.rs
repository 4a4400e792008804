//! The report's charts as SVG text (plotters' SVG backend): box plots of a metric per
//! strategy (as Holz et al.'s Figure 8) and line charts (time vs robot count as the
//! multi-robot study's Figures 2–3; coverage over distance).
//!
//! plotters is built without font features, so its naive text layout is used and text
//! becomes SVG `<text>` elements that the browser renders: no font files are needed. (If
//! another crate of the workspace ever enabled plotters' `ab_glyph` feature, text would need
//! a registered font; keep plotters' features in this crate only.)

use plotters::prelude::*;

use crate::error::BenchError;

const W: u32 = 720;
const H: u32 = 400;

fn err(e: impl std::fmt::Display) -> BenchError {
    BenchError::Other(format!("plot: {e}"))
}

/// Padded range of the finite values in `values` (never empty).
fn range_of(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in values.filter(|v| v.is_finite()) {
        lo = lo.min(v);
        hi = hi.max(v);
    }
    if !lo.is_finite() {
        return (0.0, 1.0);
    }
    let pad = ((hi - lo) * 0.08).max(hi.abs() * 0.02).max(1e-9);
    (lo - pad, hi + pad)
}

/// A box plot of `data[i]` (one sample per label), quartiles with 1.5 IQR whiskers.
pub fn box_plot(
    title: &str,
    y_desc: &str,
    labels: &[String],
    data: &[Vec<f64>],
) -> Result<String, BenchError> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (W, H)).into_drawing_area();
        root.fill(&WHITE).map_err(err)?;
        let (lo, hi) = range_of(data.iter().flatten().copied());
        let mut chart = ChartBuilder::on(&root)
            .caption(title, ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(60)
            .build_cartesian_2d(labels.into_segmented(), (lo as f32)..(hi as f32))
            .map_err(err)?;
        chart
            .configure_mesh()
            .disable_x_mesh()
            .y_desc(y_desc)
            .draw()
            .map_err(err)?;
        let boxes = labels
            .iter()
            .zip(data)
            .filter(|(_, d)| !d.is_empty())
            .map(|(l, d)| {
                Boxplot::new_vertical(SegmentValue::CenterOf(l), &Quartiles::new(d))
                    .width(24)
                    .style(BLUE)
            });
        chart.draw_series(boxes).map_err(err)?;
        root.present().map_err(err)?;
    }
    Ok(svg)
}

/// A line chart of `series` (label, points), with a legend.
pub fn line_chart(
    title: &str,
    x_desc: &str,
    y_desc: &str,
    series: &[(String, Vec<(f64, f64)>)],
) -> Result<String, BenchError> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (W, H)).into_drawing_area();
        root.fill(&WHITE).map_err(err)?;
        let (x0, x1) = range_of(series.iter().flat_map(|(_, p)| p.iter().map(|q| q.0)));
        let (y0, y1) = range_of(series.iter().flat_map(|(_, p)| p.iter().map(|q| q.1)));
        let mut chart = ChartBuilder::on(&root)
            .caption(title, ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(60)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(err)?;
        chart
            .configure_mesh()
            .x_desc(x_desc)
            .y_desc(y_desc)
            .draw()
            .map_err(err)?;
        for (i, (label, points)) in series.iter().enumerate() {
            let color = Palette99::pick(i).to_rgba();
            chart
                .draw_series(LineSeries::new(
                    points.iter().copied(),
                    color.stroke_width(2),
                ))
                .map_err(err)?
                .label(label.as_str())
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 16, y)], color));
            if points.len() <= 16 {
                chart
                    .draw_series(points.iter().map(|&p| Circle::new(p, 3, color.filled())))
                    .map_err(err)?;
            }
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .position(SeriesLabelPosition::UpperRight)
            .draw()
            .map_err(err)?;
        root.present().map_err(err)?;
    }
    Ok(svg)
}
