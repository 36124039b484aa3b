//! The declarative figure model: a [`Figure`] is a grid of [`Panel`]s; each panel holds data
//! [`Series`], reference [`Guide`] lines, labelled [`Marker`]s and notes. Plain data with
//! builders; nothing here draws.

/// Default size of a figure of up to two rows and two columns, in pixels (PNG) or SVG units.
pub const DEFAULT_SIZE: (u32, u32) = (1200, 800);
/// Height given to each row beyond the second, and width to each column beyond the second.
const ROW_HEIGHT: u32 = 420;
const COLUMN_WIDTH: u32 = 640;

/// An sRGB colour.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Rgb(pub u8, pub u8, pub u8);

/// Colour-blind-safe qualitative palette (Okabe–Ito, then Tableau tones); series without a
/// colour take the next one in order.
pub const PALETTE: [Rgb; 12] = [
    Rgb(0, 114, 178),   // blue
    Rgb(213, 94, 0),    // vermillion
    Rgb(0, 158, 115),   // bluish green
    Rgb(204, 121, 167), // reddish purple
    Rgb(230, 159, 0),   // orange
    Rgb(86, 180, 233),  // sky blue
    Rgb(0, 0, 0),       // black
    Rgb(140, 86, 75),   // brown
    Rgb(127, 127, 127), // grey
    Rgb(188, 189, 34),  // olive
    Rgb(148, 103, 189), // purple
    Rgb(23, 190, 207),  // cyan
];

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mark {
    /// A solid line through the points.
    Line,
    /// Unconnected points (e.g. eigenvalues in the complex plane).
    Points,
    /// A solid line with a dot at every point (e.g. a quantity at a few ply angles).
    LinePoints,
}

/// How a line is stroked: a rotor's backward and forward whirls of one blade mode share its
/// colour and differ in stroke.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Dash {
    Solid,
    Dashed,
    Dotted,
}

/// The look of a series.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Style {
    pub mark: Mark,
    pub dash: Dash,
    /// `None`: the next palette colour.
    pub color: Option<Rgb>,
    /// Line width in pixels at the default size.
    pub width: u32,
}

impl Style {
    pub fn new(mark: Mark) -> Self {
        Style {
            mark,
            dash: Dash::Solid,
            color: None,
            width: 2,
        }
    }
}

/// One named data series. Non-finite points are gaps (a line is broken there).
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Legend entry; an empty name keeps the series out of the legend.
    pub name: String,
    pub points: Vec<(f64, f64)>,
    pub style: Style,
}

impl Series {
    pub fn new(name: impl Into<String>, points: Vec<(f64, f64)>, mark: Mark) -> Self {
        Series {
            name: name.into(),
            points,
            style: Style::new(mark),
        }
    }
    pub fn line(name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Self::new(name, points, Mark::Line)
    }
    pub fn points(name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Self::new(name, points, Mark::Points)
    }
    pub fn line_points(name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Self::new(name, points, Mark::LinePoints)
    }
    /// Pair `xs` with `ys` (the shorter length wins).
    pub fn from_xy(name: impl Into<String>, xs: &[f64], ys: &[f64], mark: Mark) -> Self {
        Self::new(
            name,
            xs.iter().copied().zip(ys.iter().copied()).collect(),
            mark,
        )
    }
    pub fn with_color(mut self, color: Rgb) -> Self {
        self.style.color = Some(color);
        self
    }
    pub fn with_dash(mut self, dash: Dash) -> Self {
        self.style.dash = dash;
        self
    }
    /// Line width in pixels at the default size (at least 1).
    pub fn with_width(mut self, width: u32) -> Self {
        self.style.width = width.max(1);
        self
    }
}

/// Where a reference line runs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum GuideKind {
    /// x = const over the whole panel height; its x is kept inside the panel's range.
    Vertical(f64),
    /// y = const over the whole panel width; its y is kept inside the panel's range.
    Horizontal(f64),
    /// A straight segment in data coordinates, clipped to the panel; does not widen the range
    /// (e.g. a 3P line on a Campbell diagram).
    Segment { from: (f64, f64), to: (f64, f64) },
}

/// A dashed reference line with its label written beside it (not in the legend).
#[derive(Debug, Clone, PartialEq)]
pub struct Guide {
    pub kind: GuideKind,
    pub label: String,
    /// `None`: dark grey.
    pub color: Option<Rgb>,
}

/// A guide's colour when it has none of its own: dark grey, quieter than the data.
pub(super) const GUIDE_GREY: Rgb = Rgb(90, 90, 90);

impl Guide {
    pub fn vertical(x: f64, label: impl Into<String>) -> Self {
        Guide {
            kind: GuideKind::Vertical(x),
            label: label.into(),
            color: None,
        }
    }
    pub fn horizontal(y: f64, label: impl Into<String>) -> Self {
        Guide {
            kind: GuideKind::Horizontal(y),
            label: label.into(),
            color: None,
        }
    }
    pub fn segment(from: (f64, f64), to: (f64, f64), label: impl Into<String>) -> Self {
        Guide {
            kind: GuideKind::Segment { from, to },
            label: label.into(),
            color: None,
        }
    }
    pub fn with_color(mut self, color: Rgb) -> Self {
        self.color = Some(color);
        self
    }
}

/// A highlighted point with a label (e.g. the flutter boundary on the σ = 0 line).
#[derive(Debug, Clone, PartialEq)]
pub struct Marker {
    pub x: f64,
    pub y: f64,
    pub label: String,
}

impl Marker {
    pub fn new(x: f64, y: f64, label: impl Into<String>) -> Self {
        Marker {
            x,
            y,
            label: label.into(),
        }
    }
}

/// One set of axes.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Panel {
    /// Caption above the axes, e.g. "(a) classical flutter"; empty for none.
    pub title: String,
    /// Axis descriptions with their units, e.g. "rotor speed (rpm)".
    pub x_label: String,
    pub y_label: String,
    pub series: Vec<Series>,
    pub guides: Vec<Guide>,
    pub markers: Vec<Marker>,
    /// Free text lines written in a corner of the axes.
    pub notes: Vec<String>,
    /// Fixed axis ranges; `None`: fitted to the series, markers and vertical/horizontal guides.
    pub x_range: Option<(f64, f64)>,
    pub y_range: Option<(f64, f64)>,
    /// Draw the legend (when at least one series has a name).
    pub legend: bool,
}

impl Panel {
    pub fn new(x_label: impl Into<String>, y_label: impl Into<String>) -> Self {
        Panel {
            x_label: x_label.into(),
            y_label: y_label.into(),
            legend: true,
            ..Panel::default()
        }
    }
    pub fn titled(mut self, title: impl Into<String>) -> Self {
        self.title = title.into();
        self
    }
    pub fn with_series(mut self, series: Series) -> Self {
        self.series.push(series);
        self
    }
    pub fn with_guide(mut self, guide: Guide) -> Self {
        self.guides.push(guide);
        self
    }
    pub fn with_marker(mut self, marker: Marker) -> Self {
        self.markers.push(marker);
        self
    }
    pub fn with_note(mut self, note: impl Into<String>) -> Self {
        self.notes.push(note.into());
        self
    }
    pub fn with_x_range(mut self, lo: f64, hi: f64) -> Self {
        self.x_range = Some((lo, hi));
        self
    }
    pub fn with_y_range(mut self, lo: f64, hi: f64) -> Self {
        self.y_range = Some((lo, hi));
        self
    }
}

/// A titled grid of panels, filled row by row.
#[derive(Debug, Clone, PartialEq)]
pub struct Figure {
    pub title: String,
    pub panels: Vec<Panel>,
    /// Panels per row (1: stacked).
    pub columns: usize,
    /// Pixel size; `None`: 1200×800, grown by 420 px per row beyond two and 640 px per column
    /// beyond two.
    pub size: Option<(u32, u32)>,
}

impl Figure {
    pub fn new(title: impl Into<String>) -> Self {
        Figure {
            title: title.into(),
            panels: Vec::new(),
            columns: 1,
            size: None,
        }
    }
    pub fn with_panel(mut self, panel: Panel) -> Self {
        self.panels.push(panel);
        self
    }
    pub fn with_columns(mut self, columns: usize) -> Self {
        self.columns = columns;
        self
    }
    pub fn with_size(mut self, width: u32, height: u32) -> Self {
        self.size = Some((width, height));
        self
    }

    /// Rows of the panel grid.
    pub fn rows(&self) -> usize {
        self.panels.len().div_ceil(self.columns.max(1))
    }

    /// The pixel size the figure is drawn at.
    pub fn pixel_size(&self) -> (u32, u32) {
        if let Some(size) = self.size {
            return size;
        }
        let rows = self.rows() as u32;
        let cols = self.columns.max(1) as u32;
        (
            DEFAULT_SIZE.0 + COLUMN_WIDTH * cols.saturating_sub(2),
            DEFAULT_SIZE.1 + ROW_HEIGHT * rows.saturating_sub(2),
        )
    }
}
