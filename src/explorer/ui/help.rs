//! The help overlay, generated from the key table that handles the keys.

use super::{centered, pane, Theme};
use crate::explorer::keys::BINDINGS;
use ratatui::layout::Rect;
use ratatui::text::{Line, Span};
use ratatui::widgets::{Clear, Paragraph, Wrap};
use ratatui::Frame;

pub fn render(theme: &Theme, frame: &mut Frame, area: Rect) {
    let key_w = BINDINGS
        .iter()
        .map(|b| b.shown.chars().count())
        .max()
        .unwrap_or(0);
    let mut lines: Vec<Line> = BINDINGS
        .iter()
        .map(|b| {
            Line::from(vec![
                Span::styled(format!(" {:<key_w$}  ", b.shown), theme.title()),
                Span::raw(b.help_text()),
            ])
        })
        .collect();
    for note in [
        " * marks parameters changed from the preset.",
        " The margin comes from a background search along the selected parameter",
        " (ply angle or bend–twist α, wind, tunnel or rotor speed, pitch); presets",
        " choose the first.",
        " Root locus: σ on an asinh axis (linear near 0), ω on a log axis.",
    ] {
        lines.push(Line::styled(note, theme.dim()));
    }
    let width = lines.iter().map(|l| l.width() as u16).max().unwrap_or(40) + 3;
    let height = lines.len() as u16 + 2;
    let popup = centered(area, width, height);
    frame.render_widget(Clear, popup);
    frame.render_widget(
        Paragraph::new(lines)
            .wrap(Wrap { trim: false })
            .block(pane(" Keys (? or Esc closes) ", theme)),
        popup,
    );
}
