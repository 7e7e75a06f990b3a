//! Charts as SVG files (plotters): the pressure chart of a solution, for slides and papers,
//! and log-log charts of curves (the tour's handout draws its inf-sup and work–precision steps
//! with them).
//!
//! The chart is the terminal lab's main chart drawn with a pen: the raw pressure p of (12) as
//! the function of Q_h through the rule's points (steps for gauss1, segments and the points
//! themselves otherwise) and the smoothed p̄ of (16)–(17) as a line through the vertices,
//! along Γ_C, mirrored to the full width for a half model. Files are written atomically and
//! never overwritten unless asked.

use std::ffi::OsStr;
use std::fs;
use std::io::{self, Write as _};
use std::path::{Path, PathBuf};

use plotters::drawing::DrawingAreaErrorKind;
use plotters::prelude::*;

use crate::contact::solution::Solution;
use crate::contact::{ContactPoints, Method, Rule};
use crate::mesh::Element;
use crate::scheme::Scheme;

/// The size of the SVG chart in pixels.
pub const SIZE: (u32, u32) = (960, 540);
/// Samples per edge of a non-constant Q_h function.
const SAMPLES_PER_EDGE: usize = 9;
/// The colour of the raw pressure (the terminal's yellow, darkened for white paper).
const RAW: RGBColor = RGBColor(214, 110, 0);
/// The colour of the smoothed pressure (the terminal's cyan, darkened).
const SMOOTH: RGBColor = RGBColor(0, 110, 190);

/// The chart's title: "hertz-paper: M1 (q1 + gauss1), level 1, ε = 1e-6" (`exact` is called
/// the exact constraint, other methods are named with their parameters).
pub fn chart_title(scenario: &str, element: Element, level: u32, sol: &Solution) -> String {
    let rule = sol.params.rule;
    let scheme = match Scheme::new(element, rule).name() {
        Some(m) => format!("{m} ({} + {})", element.name(), rule.name()),
        None => format!("{} + {}", element.name(), rule.name()),
    };
    let epsilon = match sol.params.method {
        Method::Penalty => format!("ε = {:e}", sol.params.epsilon),
        Method::Exact => "ε = 0 (exact constraint)".to_string(),
        m if m.uses_epsilon() => format!("{}, ε = {:e}", m.label(), sol.params.epsilon),
        m => m.label(),
    };
    format!("{scenario}: {scheme}, level {level}, {epsilon}")
}

/// The raw pressure as the function of Q_h, one polyline per edge: on each edge the Lagrange
/// interpolant through the edge's rule points (a constant for one point), sampled from end to
/// end. Values that are not finite are left out.
pub fn raw_pressure_edges(points: &ContactPoints, p: &[f64]) -> Vec<Vec<(f64, f64)>> {
    let mut out = Vec::with_capacity(points.edge_points.len());
    for (e, idx) in points.edge_points.iter().enumerate() {
        let (Some(&x0), Some(&x1)) = (points.vertex_x.get(e), points.vertex_x.get(e + 1)) else {
            continue;
        };
        let (xs, ps): (Vec<f64>, Vec<f64>) = idx
            .iter()
            .filter_map(|&i| Some((points.points.get(i)?.x, *p.get(i)?)))
            .unzip();
        if xs.is_empty() {
            continue;
        }
        let n = if xs.len() == 1 { 2 } else { SAMPLES_PER_EDGE };
        let edge: Vec<(f64, f64)> = (0..n)
            .map(|k| {
                let x = x0 + (x1 - x0) * k as f64 / (n - 1) as f64;
                (x, lagrange(&xs, &ps, x))
            })
            .filter(|(x, y)| x.is_finite() && y.is_finite())
            .collect();
        out.push(edge);
    }
    out
}

/// The polynomial through (xs[i], ys[i]) at x.
fn lagrange(xs: &[f64], ys: &[f64], x: f64) -> f64 {
    (0..xs.len())
        .map(|i| {
            let basis: f64 = (0..xs.len())
                .filter(|&j| j != i)
                .map(|j| (x - xs[j]) / (xs[i] - xs[j]))
                .product();
            ys[i] * basis
        })
        .sum()
}

/// `pts` and their mirror image in x = 0, in ascending x, when `half_model`.
fn mirrored(pts: &[(f64, f64)], half_model: bool) -> Vec<(f64, f64)> {
    let mut out = Vec::with_capacity(2 * pts.len());
    if half_model {
        out.extend(pts.iter().rev().map(|&(x, y)| (-x, y)));
    }
    out.extend_from_slice(pts);
    out
}

/// Polylines `edges` (each in ascending x) and their mirror images, when `half_model`.
fn mirrored_edges(edges: &[Vec<(f64, f64)>], half_model: bool) -> Vec<Vec<(f64, f64)>> {
    let mut out = Vec::with_capacity(2 * edges.len());
    if half_model {
        out.extend(
            edges
                .iter()
                .rev()
                .map(|e| e.iter().rev().map(|&(x, y)| (-x, y)).collect()),
        );
    }
    out.extend(edges.iter().cloned());
    out
}

/// A "nice" upper bound ≥ `x` (1, 1.2, 1.5, 2, 2.5, 3, 4, 5, 6, 8 × 10^k); 1 for x ≤ 0.
pub fn nice_ceil(x: f64) -> f64 {
    if !x.is_finite() || x <= 0.0 {
        return 1.0;
    }
    let p = 10f64.powf(x.log10().floor());
    [1.0, 1.2, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 8.0, 10.0]
        .into_iter()
        .map(|m| m * p)
        .find(|&v| v >= x * (1.0 - 1e-12))
        .unwrap_or(10.0 * p)
}

/// A tick label: at most four significant digits, no trailing zeros ("-8", "2.5", "350").
fn label(v: f64) -> String {
    let s = format!("{:.4}", (v * 1e4).round() / 1e4);
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" { "0".into() } else { s.to_string() }
}

/// A log axis's tick label: three significant digits, plain or scientific as
/// [`crate::text::num`] writes it ("0.02", "1e-5").
fn log_label(v: f64) -> String {
    crate::text::num(format!("{v:.2e}").parse().unwrap_or(v))
}

/// Why a chart was not drawn or not written.
#[derive(Debug, thiserror::Error)]
pub enum PlotError {
    /// plotters failed to draw.
    #[error("drawing the chart: {0}")]
    Draw(#[from] DrawingAreaErrorKind<io::Error>),
    /// The file exists and was not to be overwritten.
    #[error("{}: exists; not overwritten", path.display())]
    Exists {
        /// The file.
        path: PathBuf,
    },
    /// The file could not be written.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// Why.
        source: io::Error,
    },
}

/// The pressure chart of `sol` as SVG text, titled `title`, mirrored to the full width when
/// `half_model`.
pub fn pressure_svg_string(title: &str, sol: &Solution, half_model: bool) -> Result<String, PlotError> {
    let points = &sol.points;
    let raw_edges = raw_pressure_edges(points, &sol.p);
    let raw: Vec<Vec<(f64, f64)>> = if points.rule == Rule::Gauss1 {
        // One connected staircase: the risers join the constants of neighbouring edges.
        let steps: Vec<(f64, f64)> = raw_edges.iter().flatten().copied().collect();
        vec![mirrored(&steps, half_model)]
    } else {
        mirrored_edges(&raw_edges, half_model)
    };
    let marks: Vec<(f64, f64)> = if points.rule == Rule::Gauss1 {
        Vec::new()
    } else {
        let pts: Vec<(f64, f64)> = points
            .points
            .iter()
            .zip(&sol.p)
            .map(|(q, &p)| (q.x, p))
            .filter(|(x, p)| x.is_finite() && p.is_finite())
            .collect();
        // The point x = 0 of a half model is its own mirror image.
        let mut all = mirrored(&pts, half_model);
        all.dedup_by(|a, b| a.0 == b.0);
        all
    };
    let pbar_pts: Vec<(f64, f64)> = points
        .vertex_x
        .iter()
        .copied()
        .zip(sol.pbar.iter().copied())
        .filter(|(x, p)| x.is_finite() && p.is_finite())
        .collect();
    let pbar = mirrored(&pbar_pts, half_model);

    let xs = || points.vertex_x.iter().copied().filter(|x| x.is_finite());
    let (mut xlo, mut xhi) = (
        xs().fold(f64::INFINITY, f64::min),
        xs().fold(f64::NEG_INFINITY, f64::max),
    );
    if half_model {
        xhi = xhi.max(-xlo);
        xlo = -xhi;
    }
    if !(xlo.is_finite() && xhi.is_finite() && xhi > xlo) {
        (xlo, xhi) = (-1.0, 1.0);
    }
    let peak = raw
        .iter()
        .flatten()
        .chain(&pbar)
        .map(|&(_, p)| p)
        .fold(0.0f64, f64::max);
    let ymax = nice_ceil(peak * 1.08);

    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, SIZE).into_drawing_area();
        root.fill(&WHITE)?;
        let mut chart = ChartBuilder::on(&root)
            .caption(title, ("sans-serif", 24))
            .margin(18)
            .x_label_area_size(56)
            .y_label_area_size(84)
            .build_cartesian_2d(xlo..xhi, 0.0..ymax)?;
        chart
            .configure_mesh()
            .x_desc(if half_model {
                "x along Γ_C (length; half model mirrored)"
            } else {
                "x along Γ_C (length)"
            })
            .y_desc("pressure (units of E)")
            .x_label_formatter(&|v| label(*v))
            .y_label_formatter(&|v| label(*v))
            .axis_desc_style(("sans-serif", 18))
            .label_style(("sans-serif", 15))
            .light_line_style(RGBColor(246, 246, 246))
            .bold_line_style(RGBColor(210, 210, 210))
            .draw()?;

        let raw_style = RAW.stroke_width(2);
        let dotted = !marks.is_empty();
        let raw_label = format!("raw p ({}, at the rule's points)", points.rule.name());
        for (i, line) in raw.iter().enumerate() {
            let series = chart.draw_series(LineSeries::new(line.iter().copied(), raw_style))?;
            if i == 0 {
                series.label(raw_label.as_str()).legend(move |(x, y)| {
                    EmptyElement::at((x, y))
                        + PathElement::new(vec![(0, 0), (24, 0)], raw_style)
                        + Circle::new((12, 0), if dotted { 3 } else { 0 }, RAW.filled())
                });
            }
        }
        chart.draw_series(marks.iter().map(|&c| Circle::new(c, 3, RAW.filled())))?;
        let smooth_style = SMOOTH.stroke_width(3);
        chart
            .draw_series(LineSeries::new(pbar.iter().copied(), smooth_style))?
            .label("smoothed p̄ (16)–(17), at the vertices")
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 24, y)], smooth_style));
        legend(&mut chart, SeriesLabelPosition::UpperRight)?;
        root.present()?;
    }
    Ok(svg)
}

/// Write the pressure chart of `sol` to `path` as SVG (see [`pressure_svg_string`]).
/// The file is written to a temporary name in the same directory and then moved into place;
/// an existing `path` is replaced only when `overwrite`, otherwise it is an error.
pub fn pressure_svg(
    path: &Path,
    title: &str,
    sol: &Solution,
    half_model: bool,
    overwrite: bool,
) -> Result<(), PlotError> {
    let svg = pressure_svg_string(title, sol, half_model)?;
    write_file(path, svg.as_bytes(), overwrite).map_err(|source| match source.kind() {
        io::ErrorKind::AlreadyExists => PlotError::Exists {
            path: path.to_path_buf(),
        },
        _ => PlotError::Io {
            path: path.to_path_buf(),
            source,
        },
    })
}

/// Whether `path` may be written: a name that does not exist, or (when `overwrite`) a
/// regular file. A symbolic link, a FIFO, a device or a directory is never replaced, even
/// with `overwrite`. Checked before any work is done, and again by [`write_file`].
pub fn check_target(path: &Path, overwrite: bool) -> io::Result<()> {
    match fs::symlink_metadata(path) {
        Err(e) if e.kind() == io::ErrorKind::NotFound => Ok(()),
        Err(e) => Err(e),
        Ok(meta) if !meta.file_type().is_file() => Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            "is not a regular file (a link, FIFO, device or directory): never replaced",
        )),
        Ok(_) if overwrite => Ok(()),
        Ok(_) => Err(io::ErrorKind::AlreadyExists.into()),
    }
}

/// How many fresh temporary names [`write_file`] tries before it gives up.
const TEMPORARY_TRIES: usize = 8;

/// A new temporary file for `name` in `dir`: `.NAME.PID.RANDOM.tmp`, its random part drawn
/// from the operating system's entropy, so that nobody can plant a file or a link at it in
/// advance; created exclusively (`create_new`: never through an existing name or link). A
/// name that is taken is passed over, never removed; the error after [`TEMPORARY_TRIES`] taken
/// names is not [`io::ErrorKind::AlreadyExists`], which would say the target exists.
fn create_temporary(dir: &Path, name: &OsStr) -> io::Result<(fs::File, PathBuf)> {
    use std::hash::{BuildHasher as _, Hasher as _};
    for _ in 0..TEMPORARY_TRIES {
        // RandomState's keys are random per thread and advance with each state made.
        let mut h = std::collections::hash_map::RandomState::new().build_hasher();
        h.write_u64(u64::from(std::process::id()));
        let tmp = dir.join(format!(
            ".{}.{}.{:016x}.tmp",
            name.to_string_lossy(),
            std::process::id(),
            h.finish()
        ));
        match fs::File::create_new(&tmp) {
            Ok(f) => return Ok((f, tmp)),
            Err(e) if e.kind() == io::ErrorKind::AlreadyExists => continue,
            Err(e) => return Err(e),
        }
    }
    Err(io::Error::other(format!(
        "no fresh temporary name in {} after {TEMPORARY_TRIES} tries",
        dir.display()
    )))
}

/// Write `bytes` to `path` atomically: to a fresh temporary file in the same directory
/// (`create_temporary`: an unpredictable name, created exclusively), then moved into place.
/// Unless `overwrite`, an existing `path` is left alone and the error is of kind
/// [`io::ErrorKind::AlreadyExists`] (a hard link is made, which fails if the name is taken even
/// under a race; where hard links are not supported, a
/// rename onto a name that does not exist). The temporary file is gone afterwards in every
/// case, and no other file is ever removed.
pub fn write_file(path: &Path, bytes: &[u8], overwrite: bool) -> io::Result<()> {
    check_target(path, overwrite)?;
    let name = path
        .file_name()
        .ok_or_else(|| io::Error::new(io::ErrorKind::InvalidInput, "not a file name"))?;
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let (mut f, tmp) = create_temporary(&dir, name)?;
    // Whether the temporary was renamed into place (its name then no longer riplab's).
    let mut renamed = false;
    let result = f.write_all(bytes).and_then(|()| f.sync_all()).and_then(|()| {
        if overwrite {
            renamed = true;
            return fs::rename(&tmp, path);
        }
        match fs::hard_link(&tmp, path) {
            Ok(()) => Ok(()),
            Err(e) if e.kind() == io::ErrorKind::AlreadyExists => Err(e),
            Err(_) if fs::symlink_metadata(path).is_err() => {
                renamed = true;
                fs::rename(&tmp, path)
            }
            Err(e) => Err(e),
        }
    });
    drop(f);
    // The temporary is riplab's own (created exclusively above) unless a rename moved it.
    if !(renamed && result.is_ok()) {
        let _ = fs::remove_file(&tmp);
    }
    result
}

/// The legend of `chart`'s series at `position`: a light box with a grey border.
fn legend<'a, CT: CoordTranslate>(
    chart: &mut ChartContext<'a, SVGBackend<'a>, CT>,
    position: SeriesLabelPosition,
) -> Result<(), DrawingAreaErrorKind<io::Error>> {
    chart
        .configure_series_labels()
        .position(position)
        .margin(12)
        .label_font(("sans-serif", 16))
        .background_style(WHITE.mix(0.9))
        .border_style(RGBColor(160, 160, 160))
        .draw()
}

/// One curve of a log-log chart: its name in the legend and its points (x, y), positive.
pub struct LogCurve {
    /// The name in the legend.
    pub name: String,
    /// The points, in values (not log10 values); those not positive and finite are left out.
    pub points: Vec<(f64, f64)>,
}

/// The colours of a log-log chart's curves, in order (the terminal's red, yellow, green, blue,
/// cyan and magenta, darkened for white paper).
const CURVE_COLORS: [RGBColor; 6] = [
    RGBColor(200, 30, 30),
    RGBColor(190, 140, 0),
    RGBColor(0, 140, 60),
    RGBColor(30, 70, 200),
    SMOOTH,
    RGBColor(160, 40, 160),
];

/// A log-log chart as SVG text, titled `title`, its axes described by `x_desc` and `y_desc`:
/// each curve a line with a dot at every point (the inf-sup chart's β_h/√h against h, the
/// work–precision chart's error against solve time). The axes span the decades of the data.
pub fn loglog_svg_string(
    title: &str,
    x_desc: &str,
    y_desc: &str,
    curves: &[LogCurve],
) -> Result<String, PlotError> {
    let shown: Vec<Vec<(f64, f64)>> = curves
        .iter()
        .map(|c| {
            c.points
                .iter()
                .copied()
                .filter(|&(x, y)| x > 0.0 && y > 0.0 && x.is_finite() && y.is_finite())
                .collect()
        })
        .collect();
    let range = |pick: fn(&(f64, f64)) -> f64| {
        let (lo, hi) = shown
            .iter()
            .flatten()
            .map(pick)
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
                (lo.min(v), hi.max(v))
            });
        if lo.is_finite() && hi > lo {
            // A twentieth of the span in log10 either side.
            let pad = 10f64.powf((hi / lo).log10() / 20.0);
            (lo / pad)..(hi * pad)
        } else if lo.is_finite() {
            (lo / 2.0)..(lo * 2.0)
        } else {
            0.1..1.0
        }
    };
    let (xr, yr) = (range(|p| p.0), range(|p| p.1));
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, SIZE).into_drawing_area();
        root.fill(&WHITE)?;
        let mut chart = ChartBuilder::on(&root)
            .caption(title, ("sans-serif", 24))
            .margin(18)
            .x_label_area_size(56)
            .y_label_area_size(84)
            .build_cartesian_2d(xr.log_scale(), yr.log_scale())?;
        chart
            .configure_mesh()
            .x_desc(x_desc)
            .y_desc(y_desc)
            .x_label_formatter(&|v| log_label(*v))
            .y_label_formatter(&|v| log_label(*v))
            .axis_desc_style(("sans-serif", 18))
            .label_style(("sans-serif", 15))
            .light_line_style(RGBColor(246, 246, 246))
            .bold_line_style(RGBColor(210, 210, 210))
            .draw()?;
        for (i, (curve, points)) in curves.iter().zip(&shown).enumerate() {
            let color = CURVE_COLORS[i % CURVE_COLORS.len()];
            let style = color.stroke_width(2);
            chart
                .draw_series(LineSeries::new(points.iter().copied(), style))?
                .label(curve.name.as_str())
                .legend(move |(x, y)| {
                    EmptyElement::at((x, y))
                        + PathElement::new(vec![(0, 0), (24, 0)], style)
                        + Circle::new((12, 0), 4, color.filled())
                });
            chart.draw_series(points.iter().map(|&p| Circle::new(p, 4, color.filled())))?;
        }
        legend(&mut chart, SeriesLabelPosition::LowerRight)?;
        root.present()?;
    }
    Ok(svg)
}
