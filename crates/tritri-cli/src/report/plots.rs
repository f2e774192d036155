//! The report's plots, as SVG text (plotters' SVG backend; the browser sets
//! the text, so no font is needed here). Rates and counts span decades,
//! so the value axes are logarithmic; a zero has no place on such an axis
//! and is drawn on the axis' floor with a hollow marker (the tables beside
//! the plots give the numbers).

use super::{Report, SceneSection, WidthRow};
use plotters::prelude::*;
use tritri_rtl::pipeline::RareCasePath;

const SIZE: (u32, u32) = (720, 440);
const FONT: (&str, u32) = ("sans-serif", 14);

/// One line of points over the widths.
struct Series {
    label: String,
    colour: RGBColor,
    points: Vec<(u32, f64)>,
}

/// The x axis: the widths, with a margin.
fn width_range(rows: &[WidthRow]) -> std::ops::Range<u32> {
    let lo = rows.iter().map(|r| r.width).min().unwrap_or(8);
    let hi = rows.iter().map(|r| r.width).max().unwrap_or(32);
    lo.saturating_sub(2)..hi + 2
}

/// Decades that hold every positive value (and `floor`, where zeros go).
fn decades(values: impl Iterator<Item = f64>, floor: f64) -> std::ops::Range<f64> {
    let mut hi: f64 = floor * 10.0;
    for v in values.filter(|v| *v > 0.0 && v.is_finite()) {
        hi = hi.max(v);
    }
    floor..10f64.powf(hi.log10().floor() + 1.0)
}

/// The legend goes to the half of the plot with fewer points: the bottom
/// when most values sit in the upper half of the log axis.
fn legend_corner(
    series: &[Series],
    references: &[(String, f64, RGBColor)],
    range: &std::ops::Range<f64>,
) -> SeriesLabelPosition {
    let (lo, hi) = (range.start.log10(), range.end.log10());
    let height = |v: f64| (v.max(range.start).log10() - lo) / (hi - lo).max(f64::MIN_POSITIVE);
    let heights: Vec<f64> = series
        .iter()
        .flat_map(|s| s.points.iter().map(|p| height(p.1)))
        .chain(references.iter().map(|r| height(r.1)))
        .collect();
    let upper = heights.iter().filter(|&&h| h > 0.5).count();
    if 2 * upper > heights.len() {
        SeriesLabelPosition::LowerRight
    } else {
        SeriesLabelPosition::UpperRight
    }
}

/// A log-scale plot of `series` over the widths; zeros sit at `floor`.
fn width_plot(
    title: &str,
    y_label: &str,
    rows: &[WidthRow],
    series: &[Series],
    floor: f64,
    references: &[(String, f64, RGBColor)],
) -> anyhow::Result<String> {
    let mut svg = String::new();
    let range = decades(
        series
            .iter()
            .flat_map(|s| s.points.iter().map(|p| p.1))
            .chain(references.iter().map(|r| r.1)),
        floor,
    );
    let legend = legend_corner(series, references, &range);
    // A decade of headroom keeps an upper legend off the highest line.
    let range = if matches!(legend, SeriesLabelPosition::UpperRight) {
        range.start..range.end * 10.0
    } else {
        range
    };
    {
        let root = SVGBackend::with_string(&mut svg, SIZE).into_drawing_area();
        root.fill(&WHITE)?;
        let mut chart = ChartBuilder::on(&root)
            .caption(title, ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(70)
            .build_cartesian_2d(width_range(rows), range.log_scale())?;
        chart
            .configure_mesh()
            .x_desc("coordinate width W (bits)")
            .y_desc(y_label)
            .x_labels(rows.len() + 4)
            .label_style(FONT)
            .y_label_formatter(&|v| format!("{v:.0e}"))
            .draw()?;
        let range = width_range(rows);
        for (label, value, colour) in references {
            let colour = *colour;
            chart
                .draw_series(LineSeries::new(
                    vec![(range.start, *value), (range.end, *value)],
                    colour.stroke_width(3),
                ))?
                .label(label.clone())
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 18, y)], colour.stroke_width(3))
                });
        }
        // A series with no point has no line, so it gets no legend entry.
        for s in series.iter().filter(|s| !s.points.is_empty()) {
            let colour = s.colour;
            let points: Vec<(u32, f64)> = s
                .points
                .iter()
                .map(|&(w, v)| (w, if v > 0.0 { v } else { floor }))
                .collect();
            chart
                .draw_series(LineSeries::new(points.clone(), colour.stroke_width(2)))?
                .label(s.label.clone())
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 18, y)], colour.stroke_width(2))
                });
            let zero: Vec<bool> = s.points.iter().map(|p| p.1 <= 0.0).collect();
            chart.draw_series(points.iter().zip(zero).map(|(&p, z)| {
                Circle::new(
                    p,
                    4,
                    if z {
                        colour.stroke_width(2)
                    } else {
                        colour.filled()
                    },
                )
            }))?;
        }
        chart
            .configure_series_labels()
            .label_font(FONT)
            .border_style(BLACK)
            .background_style(WHITE.mix(0.85))
            .position(legend)
            .draw()?;
        root.present()?;
    }
    Ok(svg)
}

const COLOURS: [RGBColor; 6] = [
    RED,
    BLUE,
    RGBColor(0, 140, 0),
    MAGENTA,
    RGBColor(200, 120, 0),
    BLACK,
];

/// The software baselines' lines, by arithmetic (exact, f64, f32, Möller).
fn baseline_colour(arithmetic: &str) -> RGBColor {
    match arithmetic {
        "f64" => RGBColor(0, 150, 150),
        "f32" => RGBColor(170, 110, 0),
        "moller" => RGBColor(90, 0, 160),
        _ => RGBColor(120, 120, 120),
    }
}

/// Error against W: wrong verdicts without certificates and their split,
/// and the verdicts the certificates leave to the host.
pub fn errors(report: &Report) -> anyhow::Result<Option<String>> {
    let rows: Vec<&WidthRow> = report.widths.iter().filter(|r| r.error.is_some()).collect();
    if rows.is_empty() {
        return Ok(None);
    }
    let percent = |f: &dyn Fn(&super::eval::Row) -> usize| -> Vec<(u32, f64)> {
        rows.iter()
            .map(|r| {
                (
                    r.width,
                    100.0 * f(r.error.as_ref().unwrap()) as f64 / r.pairs.max(1) as f64,
                )
            })
            .collect()
    };
    let series = [
        Series {
            label: "wrong, no certificates".into(),
            colour: COLOURS[0],
            points: percent(&|e| e.wrong),
        },
        Series {
            label: "false positives".into(),
            colour: COLOURS[3],
            points: percent(&|e| e.false_positives),
        },
        Series {
            label: "false negatives".into(),
            colour: COLOURS[4],
            points: percent(&|e| e.false_negatives),
        },
        Series {
            label: "uncertain (host re-checks)".into(),
            colour: COLOURS[1],
            points: percent(&|e| e.uncertain.unwrap_or(0)),
        },
    ];
    let floor = 1e-4
        * rows
            .iter()
            .map(|r| 1e6 / r.pairs.max(1) as f64)
            .fold(1e-2, f64::min)
            .max(1e-6);
    let references: Vec<(String, f64, RGBColor)> = report
        .baselines
        .iter()
        .filter(|b| b.wrong > 0)
        .map(|b| {
            (
                format!("{} wrong", b.arithmetic),
                100.0 * b.wrong as f64 / rows[0].pairs.max(1) as f64,
                baseline_colour(&b.arithmetic),
            )
        })
        .collect();
    let owned: Vec<WidthRow> = rows.into_iter().cloned().collect();
    Ok(Some(width_plot(
        "Error against W",
        "% of pairs",
        &owned,
        &series,
        floor,
        &references,
    )?))
}

/// Hardware cost against W: Xilinx 7-series and ECP5 resources.
pub fn cost(report: &Report) -> anyhow::Result<Option<String>> {
    let rows: Vec<WidthRow> = report
        .widths
        .iter()
        .filter(|r| r.xilinx.is_some())
        .cloned()
        .collect();
    if rows.is_empty() {
        return Ok(None);
    }
    let of = |f: &dyn Fn(&WidthRow) -> Option<u64>| -> Vec<(u32, f64)> {
        rows.iter()
            .filter_map(|r| Some((r.width, f(r)? as f64)))
            .collect()
    };
    let series = [
        Series {
            label: "LUT (xc7)".into(),
            colour: COLOURS[0],
            points: of(&|r| Some(r.xilinx.as_ref()?.lut)),
        },
        Series {
            label: "FF (xc7)".into(),
            colour: COLOURS[1],
            points: of(&|r| Some(r.xilinx.as_ref()?.ff)),
        },
        Series {
            label: "DSP48E1 (xc7)".into(),
            colour: COLOURS[2],
            points: of(&|r| Some(r.xilinx.as_ref()?.dsp48e1)),
        },
        Series {
            label: "SRL (xc7)".into(),
            colour: COLOURS[4],
            points: of(&|r| Some(r.xilinx.as_ref()?.srl)),
        },
        Series {
            label: "MULT18X18D (ECP5)".into(),
            colour: COLOURS[3],
            points: of(&|r| Some(r.ecp5.as_ref()?.mult18x18d)),
        },
    ];
    Ok(Some(width_plot(
        "Hardware cost of one pipeline against W",
        "cells",
        &rows,
        &series,
        10.0,
        &[],
    )?))
}

/// Speed against W: the routed pipelines' pairs/s, and the software
/// baselines on this machine (one thread).
pub fn speed(report: &Report) -> anyhow::Result<Option<String>> {
    let rows: Vec<WidthRow> = report.widths.clone();
    let hardware: Vec<(u32, f64)> = rows
        .iter()
        .filter_map(|r| Some((r.width, r.pairs_per_second?)))
        .collect();
    let software: Vec<(u32, f64)> = rows
        .iter()
        .filter_map(|r| Some((r.width, 1e9 / r.error.as_ref()?.kernel_ns_per_pair?)))
        .collect();
    if hardware.is_empty() && software.is_empty() {
        return Ok(None);
    }
    let series = [
        Series {
            label: "hardware: post-route Fmax x the pipelines that fit (ECP5-85)".into(),
            colour: COLOURS[0],
            points: hardware,
        },
        Series {
            label: "fixed-point kernel in software, one thread".into(),
            colour: COLOURS[1],
            points: software,
        },
    ];
    let references: Vec<(String, f64, RGBColor)> = report
        .baselines
        .iter()
        .filter(|b| b.ns_per_pair > 0.0)
        .map(|b| {
            (
                format!("{} in software", b.arithmetic),
                1e9 / b.ns_per_pair,
                baseline_colour(&b.arithmetic),
            )
        })
        .collect();
    Ok(Some(width_plot(
        "Speed against W",
        "pairs per second",
        &rows,
        &series,
        1e4,
        &references,
    )?))
}

/// Throughput per multiplier against wrong verdicts, the routed widths;
/// the Pareto front joined.
pub fn pareto(report: &Report) -> anyhow::Result<Option<String>> {
    let points: Vec<(String, f64, f64, bool)> = report
        .widths
        .iter()
        .filter_map(|r| {
            Some((
                match r.rare_cases {
                    RareCasePath::Parallel => format!("W = {}", r.width),
                    RareCasePath::Shared => format!("W = {}, rare cases shared", r.width),
                },
                100.0 * r.wrong_rate()?,
                r.pairs_per_second_per_multiplier?,
                r.pareto,
            ))
        })
        .collect();
    if points.is_empty() {
        return Ok(None);
    }
    let floor = 1e-4;
    let x_hi = points.iter().map(|p| p.1).fold(floor * 10.0, f64::max) * 10.0;
    let y_hi = points.iter().map(|p| p.2).fold(1.0, f64::max) * 1.3;
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, SIZE).into_drawing_area();
        root.fill(&WHITE)?;
        let mut chart = ChartBuilder::on(&root)
            .caption(
                "Throughput per multiplier against error",
                ("sans-serif", 18),
            )
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(80)
            .build_cartesian_2d((floor..x_hi).log_scale(), 0.0..y_hi)?;
        chart
            .configure_mesh()
            .x_desc("wrong verdicts without certificates (% of pairs; 0 drawn at the left edge)")
            .y_desc("pairs/s per MULT18X18D")
            .label_style(FONT)
            .x_label_formatter(&|v| format!("{v:.0e}"))
            .y_label_formatter(&|v| format!("{v:.1e}"))
            .draw()?;
        let mut front: Vec<(f64, f64)> = points
            .iter()
            .filter(|p| p.3)
            .map(|p| (p.1.max(floor), p.2))
            .collect();
        front.sort_by(|a, b| a.0.total_cmp(&b.0));
        chart
            .draw_series(LineSeries::new(front, RED.stroke_width(2)))?
            .label("Pareto front")
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], RED.stroke_width(2)));
        chart.draw_series(points.iter().map(|(name, e, s, on)| {
            let style = if *on { RED.filled() } else { BLUE.filled() };
            EmptyElement::at((e.max(floor), *s))
                + Circle::new((0, 0), 5, style)
                + Text::new(name.clone(), (8, -16), FONT)
        }))?;
        chart
            .configure_series_labels()
            .label_font(FONT)
            .border_style(BLACK)
            .background_style(WHITE.mix(0.85))
            .draw()?;
        root.present()?;
    }
    Ok(Some(svg))
}

/// The scene: time from first triangle in to last pair out at each width,
/// against the software's.
pub fn scene(scene: &SceneSection, rows: &[WidthRow]) -> anyhow::Result<String> {
    let chosen: Vec<WidthRow> = rows
        .iter()
        .filter(|r| scene.rows.iter().any(|s| s.width == r.width))
        .cloned()
        .collect();
    let routed: Vec<(u32, f64)> = scene
        .rows
        .iter()
        .filter(|r| r.clock.is_post_route())
        .map(|r| (r.width, 1e3 * r.whole_seconds))
        .collect();
    let assumed: Vec<(u32, f64)> = scene
        .rows
        .iter()
        .map(|r| (r.width, 1e3 * r.cycles_at(super::scene::ASSUMED_CLOCK_MHZ)))
        .collect();
    let series = [
        Series {
            label: "hardware at the post-route Fmax".into(),
            colour: COLOURS[0],
            points: routed,
        },
        Series {
            label: format!("hardware at {} MHz", super::scene::ASSUMED_CLOCK_MHZ),
            colour: COLOURS[1],
            points: assumed,
        },
    ];
    let software = vec![(
        "software: box sweep + exact predicates, one thread".to_string(),
        1e3 * scene.software_seconds,
        RGBColor(90, 90, 90),
    )];
    let floor = 10f64.powf(
        (scene
            .rows
            .iter()
            .map(|r| 1e3 * r.whole_seconds)
            .fold(f64::INFINITY, f64::min)
            .min(1e3 * scene.software_seconds))
        .log10()
        .floor()
            - 1.0,
    );
    width_plot(
        &format!(
            "{} x {}: first triangle in to last pair out",
            scene.a, scene.b
        ),
        "ms",
        &chosen,
        &series,
        floor,
        &software,
    )
}

/// The scene's error against W: verdicts without a certificate, and the
/// grid's pairs missing or extra against exact f64 on the originals, as
/// shares of the pairs tested.
pub fn scene_errors(scene: &SceneSection, rows: &[WidthRow]) -> anyhow::Result<String> {
    let chosen: Vec<WidthRow> = rows
        .iter()
        .filter(|r| scene.rows.iter().any(|s| s.width == r.width))
        .cloned()
        .collect();
    let share = |f: &dyn Fn(&super::scene::SceneRow) -> usize| -> Vec<(u32, f64)> {
        scene
            .rows
            .iter()
            .map(|r| (r.width, 100.0 * f(r) as f64 / r.pairs_tested.max(1) as f64))
            .collect()
    };
    let series = [
        Series {
            label: "uncertain (host re-checks)".into(),
            colour: COLOURS[1],
            points: share(&|r| r.uncertain),
        },
        Series {
            label: "missing, no certificates".into(),
            colour: COLOURS[4],
            points: share(&|r| r.missing),
        },
        Series {
            label: "extra, no certificates".into(),
            colour: COLOURS[3],
            points: share(&|r| r.extra),
        },
        Series {
            label: "wrong with certificates".into(),
            colour: COLOURS[2],
            points: share(&|r| r.certified_missing + r.certified_extra),
        },
    ];
    let floor = 10f64.powf(
        (100.0
            / scene
                .rows
                .iter()
                .map(|r| r.pairs_tested)
                .max()
                .unwrap_or(1)
                .max(1) as f64)
            .log10()
            .floor()
            - 1.0,
    );
    width_plot(
        &format!("{} x {}: error against W", scene.a, scene.b),
        "% of the pairs tested",
        &chosen,
        &series,
        floor,
        &[],
    )
}
