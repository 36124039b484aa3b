//! Colours and modifiers for `--color 16|256|truecolor|none`. The 16-colour theme is the default
//! (safe over any SSH link); `none` uses no colour at all, only bold, dim, reversed, underline.

use crate::explorer::display::ColorMode;
use crate::physics::structure::Family;
use ratatui::style::{Color, Modifier, Style};

#[derive(Debug, Clone, Copy)]
pub struct Theme {
    pub mode: ColorMode,
}

/// Series colours: 16-colour name, 256-colour index, RGB.
const SERIES: [(Color, u8, (u8, u8, u8)); 8] = [
    (Color::Cyan, 44, (0, 200, 215)),
    (Color::Yellow, 220, (240, 200, 40)),
    (Color::Green, 77, (90, 200, 90)),
    (Color::Magenta, 170, (210, 90, 210)),
    (Color::LightBlue, 75, (100, 160, 255)),
    (Color::LightRed, 209, (250, 130, 90)),
    (Color::LightCyan, 123, (140, 240, 240)),
    (Color::LightGreen, 157, (170, 240, 170)),
];

impl Theme {
    pub fn new(mode: ColorMode) -> Theme {
        Theme { mode }
    }

    fn pick(&self, c16: Color, c256: u8, rgb: (u8, u8, u8)) -> Color {
        match self.mode {
            ColorMode::Ansi16 => c16,
            ColorMode::Ansi256 => Color::Indexed(c256),
            ColorMode::Truecolor => Color::Rgb(rgb.0, rgb.1, rgb.2),
            ColorMode::None => Color::Reset,
        }
    }

    fn fg(&self, c: Color) -> Style {
        if self.mode == ColorMode::None {
            Style::new()
        } else {
            Style::new().fg(c)
        }
    }

    pub fn colored(&self) -> bool {
        self.mode != ColorMode::None
    }

    pub fn border(&self) -> Style {
        self.fg(self.pick(Color::DarkGray, 242, (110, 110, 110)))
    }

    pub fn title(&self) -> Style {
        Style::new().add_modifier(Modifier::BOLD)
    }

    /// Secondary text: labels, units, hints.
    pub fn dim(&self) -> Style {
        if self.colored() {
            self.fg(self.pick(Color::Gray, 247, (160, 160, 160)))
        } else {
            Style::new().add_modifier(Modifier::DIM)
        }
    }

    /// The selected parameter row.
    pub fn focus(&self) -> Style {
        Style::new().add_modifier(Modifier::REVERSED | Modifier::BOLD)
    }

    pub fn stable(&self) -> Style {
        self.fg(self.pick(Color::Green, 40, (60, 200, 80)))
            .add_modifier(Modifier::BOLD)
    }

    pub fn flutter(&self) -> Style {
        self.fg(self.pick(Color::Red, 196, (240, 60, 60)))
            .add_modifier(Modifier::BOLD)
    }

    pub fn divergence(&self) -> Style {
        self.fg(self.pick(Color::Magenta, 201, (230, 60, 230)))
            .add_modifier(Modifier::BOLD)
    }

    /// Errors from the worker: colour where there is colour, underlined where there is none.
    pub fn error(&self) -> Style {
        let s = self
            .fg(self.pick(Color::LightRed, 203, (255, 95, 95)))
            .add_modifier(Modifier::BOLD);
        if self.colored() {
            s
        } else {
            s.add_modifier(Modifier::UNDERLINED)
        }
    }

    pub fn accent(&self) -> Style {
        self.fg(self.pick(Color::Cyan, 44, (0, 200, 215)))
    }

    /// Colour of plot series `i` (modes, response curves).
    pub fn series(&self, i: usize) -> Color {
        let (c16, c256, rgb) = SERIES[i % SERIES.len()];
        self.pick(c16, c256, rgb)
    }

    /// Colour of a mode family (root-locus markers, the modes table): three of the basic 16
    /// colours, so they survive the 16-colour theme, and none of them the red of flutter or the
    /// green of a stable verdict.
    pub fn family(&self, f: Family) -> Color {
        match f {
            Family::Flap => self.pick(Color::Cyan, 44, (0, 200, 215)),
            Family::Edge => self.pick(Color::Yellow, 220, (240, 200, 40)),
            Family::Torsion => self.pick(Color::Magenta, 170, (210, 90, 210)),
        }
    }

    /// Plain foreground colour for plot lines that are neither series nor warnings.
    pub fn plot(&self) -> Color {
        self.pick(Color::White, 252, (220, 220, 220))
    }

    /// Reference lines (σ = 0, 1P, 3P, current rotor speed).
    pub fn guide(&self) -> Color {
        self.pick(Color::DarkGray, 240, (100, 100, 100))
    }

    /// Colour of a trail `age` steps old out of `len`: fading towards the background.
    pub fn trail(&self, age: usize, len: usize) -> Color {
        let f = (age as f64 + 1.0) / (len.max(1) as f64 + 1.0); // 0 (new) … 1 (old)
        match self.mode {
            ColorMode::Ansi16 => {
                if f < 0.4 {
                    Color::Gray
                } else {
                    Color::DarkGray
                }
            }
            ColorMode::Ansi256 => Color::Indexed(252 - (f * 16.0).round() as u8),
            ColorMode::Truecolor => {
                let g = (210.0 - 150.0 * f).round() as u8;
                Color::Rgb(g, g, g)
            }
            ColorMode::None => Color::Reset,
        }
    }

    /// How many trail steps to draw: without colour they cannot fade, so only the recent few.
    pub fn trail_steps(&self, len: usize) -> usize {
        if self.colored() {
            len
        } else {
            len.min(4)
        }
    }
}
