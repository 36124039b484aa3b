//! The parameters pane: the parameters offered for this preset with units (the selected one
//! highlighted, the ones that change nothing until another setting changes dimmed) and the live
//! section stiffnesses C22, C23, C33, or for a tabulated blade which blade it is.

use super::{pane, sig, Theme};
use crate::explorer::state::params::{offered_rows, ParamKind, PARAMS};
use crate::explorer::state::AppState;
use crate::preset::{AeroModel, ValidPreset};
use ratatui::layout::Rect;
use ratatui::text::{Line, Span};
use ratatui::widgets::Paragraph;
use ratatui::Frame;

/// Rows for `p` in a column `available` rows high: the offered parameters, a blank, the section
/// header and three stiffnesses (or the blade's source, span, hub and stations, and its beam
/// where the column is tall enough to keep the modes pane's rows: 30 rows and up), plus borders.
pub fn height(p: &ValidPreset, available: u16) -> u16 {
    let beam = u16::from(p.tabulated_blade().is_some() && available >= BEAM_ROW_FROM);
    let layup =
        if p.tabulated_blade().is_some_and(|b| b.layup.is_some()) && available >= BEAM_ROW_FROM {
            LAYUP_ROWS
        } else {
            0
        };
    offered_rows(p).len() as u16 + 5 + beam + layup + 2
}

/// Rows of a WindIO blade's section at `view.section_at`: a header and four stiffnesses.
const LAYUP_ROWS: u16 = 5; // keep in step with the rows `render` pushes

/// Column height from which a tabulated blade's pane also shows its beam.
const BEAM_ROW_FROM: u16 = 30;

/// Whether an offered parameter changes nothing until another setting changes, so the pane dims
/// it: wind and tunnel speed without aerodynamics (`a` turns them on). Knobs that can change
/// nothing for the preset's blade are not offered at all ([`crate::explorer::state::params::offered`]).
fn matters_not(p: &ValidPreset, kind: &ParamKind) -> bool {
    match kind {
        ParamKind::Number { key, .. } => {
            matches!(*key, "operating.wind_speed" | "operating.tunnel_speed")
                && p.aero.model == AeroModel::None
        }
        ParamKind::Aero => false,
    }
}

pub fn render(state: &AppState, theme: &Theme, frame: &mut Frame, area: Rect) {
    let name = &state.presets[state.preset_index].name;
    let title = format!(
        " Parameters · {name} [{}/{}] ",
        state.preset_index + 1,
        state.presets.len()
    );
    let block = pane(title, theme);
    let inner_w = block.inner(area).width as usize;
    let label_w = 12;
    let value_w = inner_w.saturating_sub(label_w + 3);
    let mut lines: Vec<Line> = Vec::new();
    for i in offered_rows(&state.preset) {
        let p = &PARAMS[i];
        let focused = i == state.focus;
        let marker = if focused { "▸ " } else { "  " };
        let value = state.param_text(p);
        let changed = match p.kind {
            ParamKind::Number { key, .. } => {
                // The value asked for counts while its check runs, as the row shows it.
                let shown = state.pending_value(key).or(state.preset.get(key).ok());
                shown != state.opened.get(key).ok()
            }
            ParamKind::Aero => state.preset.aero.model != state.opened.aero.model,
        };
        let text = format!(
            "{marker}{:<label_w$}{}{value:>value_w$}",
            p.label,
            if changed { "*" } else { " " }
        );
        let unused = matters_not(&state.preset, &p.kind);
        let style = match (focused, unused) {
            (true, _) => theme.focus(),
            (false, true) => theme.dim(),
            (false, false) => Default::default(),
        };
        lines.push(Line::styled(text, style));
    }
    lines.push(Line::from(""));
    if let Some(blade) = state.preset.tabulated_blade() {
        // A tabulated blade has no uniform section: show which blade it is instead.
        lines.push(Line::styled(
            format!("blade ({})", blade.format.title()),
            theme.dim(),
        ));
        let row = |name: &str, value: String| {
            Line::from(vec![
                Span::raw(format!("  {name:<9}")),
                Span::raw(format!("{value:>10}")),
            ])
        };
        let b = &state.preset.blade;
        lines.push(row("span", format!("{:.2} m", b.length)));
        lines.push(row("hub", format!("{:.2} m", b.hub_radius)));
        lines.push(row("stations", blade.table.sections.len().to_string()));
        if let Some(beam) = crate::model::blade::beam(&state.preset) {
            lines.push(row("beam", beam.title().to_string()));
        }
        // A WindIO blade's section as its layup gives it, live with the ply angle.
        let room = usize::from(area.height).saturating_sub(2);
        if let Some(layup) = blade.layup.as_ref().filter(|_| room >= lines.len() + 5) {
            let s = layup.nearest(state.preset.view.section_at);
            let p = &s.properties;
            let c = p.bending_torsion;
            lines.push(Line::styled(
                format!("section at {:.0} % span", 100.0 * s.eta),
                theme.dim(),
            ));
            let unit = |name: &str, v: f64| {
                Line::from(vec![
                    Span::raw(format!("  {name:<9}")),
                    Span::raw(format!("{:>10}", sig(v, 4))),
                    Span::styled(" N·m²", theme.dim()),
                ])
            };
            lines.push(unit("EI flap", c[1][1]));
            lines.push(unit("EI edge", c[0][0]));
            lines.push(unit("GJ", p.gj));
            lines.push(row("g/√EI·GJ", format!("{:+.4}", s.flap_twist_ratio())));
        }
        frame.render_widget(Paragraph::new(lines).block(block), area);
        return;
    }
    let source = state.preset.section.source.name();
    lines.push(Line::styled(format!("section ({source})"), theme.dim()));
    let stiff = |name: &str, v: Option<f64>| {
        let value = v.map(|v| sig(v, 4)).unwrap_or_else(|| "—".into());
        Line::from(vec![
            Span::raw(format!("  {name:<5}")),
            Span::raw(format!("{value:>12}")),
            Span::styled(" N·m²", theme.dim()),
        ])
    };
    let sec = state.solved.as_ref().and_then(|s| s.section);
    lines.push(stiff("C22", sec.map(|s| s.c22)));
    lines.push(stiff("C23", sec.map(|s| s.c23)));
    lines.push(stiff("C33", sec.map(|s| s.c33)));
    frame.render_widget(Paragraph::new(lines).block(block), area);
}
