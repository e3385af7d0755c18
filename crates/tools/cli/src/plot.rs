//! PNG plots for the command-line analyses: line charts, scatter charts and heat maps.
//!
//! A thin layer over `plotters` so that every analysis draws the same way. Values are
//! plotted as given: callers convert SI values to labelled human units (deg) first.

use plotters::prelude::*;
use std::fmt;
use std::path::Path;

/// Size of every figure, pixels.
const SIZE: (u32, u32) = (900, 600);

/// An error while drawing or writing a figure.
#[derive(Debug, Clone, PartialEq)]
pub struct PlotError(pub String);

impl fmt::Display for PlotError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "plot: {}", self.0)
    }
}

impl std::error::Error for PlotError {}

fn err<E: fmt::Display>(e: E) -> PlotError {
    PlotError(e.to_string())
}

/// Title and axis labels of a figure.
#[derive(Debug, Clone, Copy)]
pub struct Axes<'a> {
    pub title: &'a str,
    pub x_label: &'a str,
    pub y_label: &'a str,
}

/// One named data series of (x, y) points.
#[derive(Debug, Clone)]
pub struct Series<'a> {
    pub label: &'a str,
    pub points: Vec<(f64, f64)>,
}

/// A scalar field sampled on a regular grid: `values[iy * xs.len() + ix]` at
/// `(xs[ix], ys[iy])`; `None` marks points outside the domain (drawn white).
#[derive(Debug, Clone)]
pub struct Grid {
    pub xs: Vec<f64>,
    pub ys: Vec<f64>,
    pub values: Vec<Option<f64>>,
}

/// How the points of a series are drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Mark {
    Line,
    Dot,
}

/// Writes a line chart of the series to `path` (PNG).
pub fn line_chart(path: &Path, axes: &Axes, series: &[Series]) -> Result<(), PlotError> {
    xy_chart(path, axes, series, Mark::Line)
}

/// Writes a scatter chart (one dot per point) of the series to `path` (PNG).
pub fn scatter_chart(path: &Path, axes: &Axes, series: &[Series]) -> Result<(), PlotError> {
    xy_chart(path, axes, series, Mark::Dot)
}

/// Finite range of a set of values, widened when it is empty or a single value.
fn range(values: impl Iterator<Item = f64>) -> Result<(f64, f64), PlotError> {
    let (lo, hi) = values
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
    if lo > hi {
        return Err(PlotError("no finite value to plot".into()));
    }
    let pad = if hi > lo {
        0.02 * (hi - lo)
    } else {
        0.5 * lo.abs().max(1.0)
    };
    Ok((lo - pad, hi + pad))
}

/// Width of the area left of the plot for the y tick labels and the y label, pixels
/// (wide enough for "-150.0" and the rotated label beside it).
const Y_LABEL_AREA: u32 = 90;
/// The plot's own area, pixels (the figure less the label areas, margins and caption).
const PLOT_AREA: (f64, f64) = (
    (SIZE.0 - Y_LABEL_AREA - 24) as f64,
    (SIZE.1 - 45 - 24 - 30) as f64,
);

/// Size of the legend box of `labels`, as fractions of the plot area (one 20-pixel row
/// per label and about 7 pixels per character, with the line sample and margins).
fn legend_size(labels: &[&str]) -> (f64, f64) {
    let longest = labels.iter().map(|l| l.chars().count()).max().unwrap_or(0);
    let width = 7.0 * longest as f64 + 50.0;
    let height = 20.0 * labels.len() as f64 + 14.0;
    (width / PLOT_AREA.0, height / PLOT_AREA.1)
}

/// Where the legend goes so that it covers no point: the first corner (upper right,
/// upper left, lower right, lower left) whose box of `size` (fractions of the plot)
/// holds no point; when every corner holds points, the upper right with the top of the
/// y range raised until the box lies above them all. Returns the corner and the y range.
fn legend_place(
    points: &[(f64, f64)],
    (x0, x1): (f64, f64),
    (y0, y1): (f64, f64),
    (w, h): (f64, f64),
) -> (SeriesLabelPosition, (f64, f64)) {
    let (w, h) = ((w + 0.02).min(0.9), (h + 0.02).min(0.9));
    let (dx, dy) = (w * (x1 - x0), h * (y1 - y0));
    let corners = [
        (SeriesLabelPosition::UpperRight, x1 - dx, x1, y1 - dy, y1),
        (SeriesLabelPosition::UpperLeft, x0, x0 + dx, y1 - dy, y1),
        (SeriesLabelPosition::LowerRight, x1 - dx, x1, y0, y0 + dy),
        (SeriesLabelPosition::LowerLeft, x0, x0 + dx, y0, y0 + dy),
    ];
    for (corner, xa, xb, ya, yb) in corners {
        let inside = |&(x, y): &(f64, f64)| (xa..=xb).contains(&x) && (ya..=yb).contains(&y);
        if !points.iter().any(inside) {
            return (corner, (y0, y1));
        }
    }
    // The box spans the top fraction h of [y0, top]: its bottom y0 + (1 - h)(top - y0)
    // at the old top y1.
    let top = y0 + (y1 - y0) / (1.0 - h);
    (SeriesLabelPosition::UpperRight, (y0, top))
}

fn xy_chart(path: &Path, axes: &Axes, series: &[Series], mark: Mark) -> Result<(), PlotError> {
    let points = || series.iter().flat_map(|s| s.points.iter());
    let (x0, x1) = range(points().map(|p| p.0))?;
    let (y0, y1) = range(points().map(|p| p.1))?;
    let finite: Vec<(f64, f64)> = points()
        .copied()
        .filter(|p| p.0.is_finite() && p.1.is_finite())
        .collect();
    let labels: Vec<&str> = series.iter().map(|s| s.label).collect();
    let (corner, (y0, y1)) = if series.len() > 1 {
        legend_place(&finite, (x0, x1), (y0, y1), legend_size(&labels))
    } else {
        (SeriesLabelPosition::UpperRight, (y0, y1))
    };
    let root = BitMapBackend::new(path, SIZE).into_drawing_area();
    root.fill(&WHITE).map_err(err)?;
    let mut chart = ChartBuilder::on(&root)
        .caption(axes.title, ("sans-serif", 22))
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(Y_LABEL_AREA)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(err)?;
    chart
        .configure_mesh()
        .x_desc(axes.x_label)
        .y_desc(axes.y_label)
        .draw()
        .map_err(err)?;
    for (k, s) in series.iter().enumerate() {
        let color = Palette99::pick(k).to_rgba();
        let finite = s
            .points
            .iter()
            .copied()
            .filter(|p| p.0.is_finite() && p.1.is_finite());
        let drawn = match mark {
            Mark::Line => chart
                .draw_series(LineSeries::new(finite, color.stroke_width(2)))
                .map_err(err)?,
            Mark::Dot => chart
                .draw_series(finite.map(|p| Circle::new(p, 2, color.filled())))
                .map_err(err)?,
        };
        drawn.label(s.label).legend(move |(x, y)| {
            PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(3))
        });
    }
    if series.len() > 1 {
        chart
            .configure_series_labels()
            .position(corner)
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .draw()
            .map_err(err)?;
    }
    root.present().map_err(err)
}

/// Blue (low) to red (high) colour of a value already scaled to [0, 1].
fn heat_color(s: f64) -> RGBColor {
    let s = s.clamp(0.0, 1.0);
    let channel = |v: f64| (255.0 * v.clamp(0.0, 1.0)).round() as u8;
    RGBColor(
        channel(1.5 - (4.0 * s - 3.0).abs()),
        channel(1.5 - (4.0 * s - 2.0).abs()),
        channel(1.5 - (4.0 * s - 1.0).abs()),
    )
}

/// Cell edges around sorted sample positions (midpoints, extended at both ends).
fn edges(xs: &[f64]) -> Vec<f64> {
    let n = xs.len();
    let half = |a: f64, b: f64| 0.5 * (a + b);
    let mut e = Vec::with_capacity(n + 1);
    let first_gap = if n > 1 { xs[1] - xs[0] } else { 1.0 };
    let last_gap = if n > 1 { xs[n - 1] - xs[n - 2] } else { 1.0 };
    e.push(xs[0] - 0.5 * first_gap);
    e.extend(xs.windows(2).map(|w| half(w[0], w[1])));
    e.push(xs[n - 1] + 0.5 * last_gap);
    e
}

/// Writes a heat map of the grid to `path` (PNG), with a colour bar labelled `value_label`.
pub fn heat_map(path: &Path, axes: &Axes, grid: &Grid, value_label: &str) -> Result<(), PlotError> {
    let (nx, ny) = (grid.xs.len(), grid.ys.len());
    if nx == 0 || ny == 0 || grid.values.len() != nx * ny {
        return Err(PlotError(format!(
            "grid of {nx} x {ny} points has {} values",
            grid.values.len()
        )));
    }
    let (v0, v1) = range(grid.values.iter().flatten().copied())?;
    let (ex, ey) = (edges(&grid.xs), edges(&grid.ys));
    let root = BitMapBackend::new(path, SIZE).into_drawing_area();
    root.fill(&WHITE).map_err(err)?;
    let (plot_area, bar_area) = root.split_horizontally(SIZE.0 - 110);
    let mut chart = ChartBuilder::on(&plot_area)
        .caption(axes.title, ("sans-serif", 22))
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(Y_LABEL_AREA)
        .build_cartesian_2d(ex[0]..ex[nx], ey[0]..ey[ny])
        .map_err(err)?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc(axes.x_label)
        .y_desc(axes.y_label)
        .draw()
        .map_err(err)?;
    let cells = (0..ny).flat_map(|iy| (0..nx).map(move |ix| (ix, iy)));
    chart
        .draw_series(cells.filter_map(|(ix, iy)| {
            let v = grid.values[iy * nx + ix]?;
            let color = heat_color((v - v0) / (v1 - v0));
            Some(Rectangle::new(
                [(ex[ix], ey[iy]), (ex[ix + 1], ey[iy + 1])],
                color.filled(),
            ))
        }))
        .map_err(err)?;
    let mut bar = ChartBuilder::on(&bar_area)
        .margin_top(40)
        .margin_bottom(57)
        .margin_right(10)
        .y_label_area_size(60)
        .caption(value_label, ("sans-serif", 16))
        .build_cartesian_2d(0.0..1.0, v0..v1)
        .map_err(err)?;
    bar.configure_mesh()
        .disable_mesh()
        .disable_x_axis()
        .y_label_style(("sans-serif", 14))
        .draw()
        .map_err(err)?;
    let steps = 100;
    bar.draw_series((0..steps).map(|k| {
        let a = v0 + (v1 - v0) * k as f64 / steps as f64;
        let b = v0 + (v1 - v0) * (k + 1) as f64 / steps as f64;
        Rectangle::new(
            [(0.0, a), (1.0, b)],
            heat_color(k as f64 / (steps - 1) as f64).filled(),
        )
    }))
    .map_err(err)?;
    root.present().map_err(err)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn edges_bracket_samples_at_midpoints() {
        // Midpoints of 0, 1, 3 are 0.5 and 2; the ends extend by half the end gaps.
        assert_eq!(edges(&[0.0, 1.0, 3.0]), vec![-0.5, 0.5, 2.0, 4.0]);
    }

    #[test]
    fn range_ignores_non_finite_and_rejects_empty() {
        let (lo, hi) = range([1.0, f64::NAN, 3.0].into_iter()).unwrap();
        assert!((lo - 0.96).abs() < 1e-12 && (hi - 3.04).abs() < 1e-12);
        assert!(range([f64::NAN].into_iter()).is_err());
    }

    #[test]
    fn the_legend_goes_where_no_point_is_or_above_them_all() {
        // Truth by construction: points only in the upper right quarter leave the upper
        // left corner free; points along the whole top edge and bottom edge free no
        // corner, and the y range is raised so that a box of 20 % (+2 % margin) lies
        // above y = 1: top = 0 + 1 / (1 - 0.22).
        let size = (0.2, 0.2);
        let quarter = [(0.8, 0.9), (0.95, 0.95)];
        let (corner, range) = legend_place(&quarter, (0.0, 1.0), (0.0, 1.0), size);
        assert!(matches!(corner, SeriesLabelPosition::UpperLeft));
        assert_eq!(range, (0.0, 1.0));
        let edges: Vec<(f64, f64)> = (0..=10)
            .flat_map(|i| [(i as f64 / 10.0, 1.0), (i as f64 / 10.0, 0.0)])
            .collect();
        let (corner, (low, top)) = legend_place(&edges, (0.0, 1.0), (0.0, 1.0), size);
        assert!(matches!(corner, SeriesLabelPosition::UpperRight));
        assert_eq!(low, 0.0);
        assert!((top - 1.0 / 0.78).abs() < 1e-12, "{top}");
        // The raised box: from top - 0.22 (top - low) = 1.0 up, above every point.
        assert!((top - 0.22 * top - 1.0).abs() < 1e-12);
    }

    #[test]
    fn heat_map_rejects_mismatched_grid() {
        let grid = Grid {
            xs: vec![0.0, 1.0],
            ys: vec![0.0],
            values: vec![Some(1.0)],
        };
        let axes = Axes {
            title: "t",
            x_label: "x",
            y_label: "y",
        };
        let e = heat_map(Path::new("unused.png"), &axes, &grid, "v").unwrap_err();
        assert!(e.0.contains("2 x 1"));
    }

    #[test]
    fn charts_write_png_files() {
        let dir = std::env::temp_dir().join(format!("robofmu-plot-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let axes = Axes {
            title: "test",
            x_label: "x",
            y_label: "y",
        };
        let s = Series {
            label: "sin",
            points: (0..50)
                .map(|i| (i as f64, (i as f64 * 0.1).sin()))
                .collect(),
        };
        line_chart(&dir.join("l.png"), &axes, std::slice::from_ref(&s)).unwrap();
        scatter_chart(&dir.join("s.png"), &axes, &[s]).unwrap();
        let grid = Grid {
            xs: vec![0.0, 1.0, 2.0],
            ys: vec![0.0, 1.0],
            values: vec![Some(0.0), Some(1.0), None, Some(2.0), Some(3.0), Some(4.0)],
        };
        heat_map(&dir.join("h.png"), &axes, &grid, "v").unwrap();
        for f in ["l.png", "s.png", "h.png"] {
            let bytes = std::fs::read(dir.join(f)).unwrap();
            assert_eq!(&bytes[1..4], b"PNG", "{f} is a PNG file");
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
