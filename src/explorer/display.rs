//! How the explorer draws: colour depth, plot marker, and the view a headless frame shows. The
//! command line maps its flags onto these (`cli.rs`); the explorer knows nothing of clap.

/// Colour depth of the theme.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ColorMode {
    /// The 16 ANSI colours: safe over any SSH link (the default).
    Ansi16,
    Ansi256,
    Truecolor,
    None,
}

impl ColorMode {
    pub const ALL: [ColorMode; 4] = [
        ColorMode::Ansi16,
        ColorMode::Ansi256,
        ColorMode::Truecolor,
        ColorMode::None,
    ];

    pub fn name(self) -> &'static str {
        match self {
            ColorMode::Ansi16 => "16",
            ColorMode::Ansi256 => "256",
            ColorMode::Truecolor => "truecolor",
            ColorMode::None => "none",
        }
    }
}

/// Plot marker: braille is finest; the others serve terminals or fonts without braille.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MarkerKind {
    Braille,
    Halfblock,
    Block,
    Dot,
}

impl MarkerKind {
    /// In the order the marker key cycles through them.
    pub const ALL: [MarkerKind; 4] = [
        MarkerKind::Braille,
        MarkerKind::Halfblock,
        MarkerKind::Block,
        MarkerKind::Dot,
    ];

    pub fn name(self) -> &'static str {
        match self {
            MarkerKind::Braille => "braille",
            MarkerKind::Halfblock => "halfblock",
            MarkerKind::Block => "block",
            MarkerKind::Dot => "dot",
        }
    }

    /// The next marker in [`MarkerKind::ALL`], wrapping around.
    pub fn next(self) -> MarkerKind {
        let i = Self::ALL.iter().position(|m| *m == self).unwrap_or(0);
        Self::ALL[(i + 1) % Self::ALL.len()]
    }
}

/// What a headless frame (`flutterscope snapshot`) shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ViewKind {
    Main,
    Campbell,
    /// The Campbell view against wind speed along the operating schedule.
    CampbellWind,
    Help,
    /// The main view with the mode-shape pane (the least-damped mode).
    Shape,
}

impl ViewKind {
    pub const ALL: [ViewKind; 5] = [
        ViewKind::Main,
        ViewKind::Campbell,
        ViewKind::CampbellWind,
        ViewKind::Help,
        ViewKind::Shape,
    ];

    pub fn name(self) -> &'static str {
        match self {
            ViewKind::Main => "main",
            ViewKind::Campbell => "campbell",
            ViewKind::CampbellWind => "campbell-wind",
            ViewKind::Help => "help",
            ViewKind::Shape => "shape",
        }
    }
}
