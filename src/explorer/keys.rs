//! The one key table: every binding with its action and help text. [`action_for`] uses it to
//! handle keys and the help overlay lists it, so the two cannot disagree.

use crate::explorer::display::MarkerKind;
use crate::preset::AeroModel;
use crossterm::event::{KeyCode, KeyEvent, KeyEventKind, KeyModifiers};

/// What a key asks for. Pure intent: [`crate::explorer::state::update::update`] decides what it means.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Action {
    FocusPrev,
    FocusNext,
    Decrease,
    Increase,
    DecreaseCoarse,
    IncreaseCoarse,
    PrevPreset,
    NextPreset,
    CycleAero,
    TogglePause,
    Reset,
    /// Rotor speed and pitch follow the preset's operating schedule again.
    FollowSchedule,
    Kick,
    Boundary,
    ToggleCampbell,
    /// The Campbell view's axis: rotor speed ↔ wind speed along the schedule.
    ToggleCampbellAxis,
    /// The mode-shape pane in place of the tip response, or back.
    ToggleShape,
    /// The previous / next mode in the mode-shape pane.
    PrevMode,
    NextMode,
    /// The next part of a rotor's or turbine's mode in the mode-shape pane.
    CyclePart,
    CycleMarker,
    ToggleHelp,
    /// Close the help overlay, else leave the Campbell view.
    Back,
    Quit,
}

/// One key: code plus the modifiers that must be held (Shift is ignored for characters, whose
/// case already carries it).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Key {
    pub code: KeyCode,
    pub mods: KeyModifiers,
}

const fn plain(code: KeyCode) -> Key {
    Key {
        code,
        mods: KeyModifiers::NONE,
    }
}

const fn ch(c: char) -> Key {
    plain(KeyCode::Char(c))
}

const fn shift(code: KeyCode) -> Key {
    Key {
        code,
        mods: KeyModifiers::SHIFT,
    }
}

const fn ctrl(c: char) -> Key {
    Key {
        code: KeyCode::Char(c),
        mods: KeyModifiers::CONTROL,
    }
}

/// One row of the key table.
pub struct Binding {
    pub keys: &'static [Key],
    /// How the keys are shown in the help overlay.
    pub shown: &'static str,
    pub action: Action,
    /// What the keys do; see [`Binding::help_text`].
    pub help: &'static str,
}

impl Binding {
    /// The help line: [`Binding::help`], and for the actions that cycle through a list, the list
    /// in the order the key walks it (taken from the list itself).
    pub fn help_text(&self) -> String {
        let cycle: Vec<String> = match self.action {
            // The key passes by the models that read a station's polar where the blade has none.
            Action::CycleAero => AeroModel::ALL
                .iter()
                .map(|m| match m.needs_polars() {
                    true => format!("{} (real blades)", m.name()),
                    false => m.name().to_string(),
                })
                .collect(),
            Action::CycleMarker => MarkerKind::ALL
                .iter()
                .map(|m| m.name().to_string())
                .collect(),
            _ => return self.help.to_string(),
        };
        format!("{}: {}", self.help, cycle.join(", "))
    }
}

/// Every key the explorer understands, in help-overlay order. `k` kicks the tip (as documented),
/// so "up" is ↑ or Shift-Tab rather than vi's `k`.
pub static BINDINGS: &[Binding] = &[
    Binding {
        keys: &[
            plain(KeyCode::Up),
            plain(KeyCode::BackTab),
            shift(KeyCode::BackTab),
        ],
        shown: "↑  S-Tab",
        action: Action::FocusPrev,
        help: "select the previous parameter",
    },
    Binding {
        keys: &[plain(KeyCode::Down), ch('j'), plain(KeyCode::Tab)],
        shown: "↓  j  Tab",
        action: Action::FocusNext,
        help: "select the next parameter",
    },
    Binding {
        keys: &[plain(KeyCode::Left), ch('h'), ch('-')],
        shown: "←  h  -",
        action: Action::Decrease,
        help: "decrease the selected parameter (fine step)",
    },
    Binding {
        keys: &[plain(KeyCode::Right), ch('l'), ch('+'), ch('=')],
        shown: "→  l  +",
        action: Action::Increase,
        help: "increase the selected parameter (fine step)",
    },
    Binding {
        keys: &[shift(KeyCode::Left), ch('H')],
        shown: "S-←  H",
        action: Action::DecreaseCoarse,
        help: "decrease the selected parameter (coarse step)",
    },
    Binding {
        keys: &[shift(KeyCode::Right), ch('L')],
        shown: "S-→  L",
        action: Action::IncreaseCoarse,
        help: "increase the selected parameter (coarse step)",
    },
    Binding {
        keys: &[ch('[')],
        shown: "[",
        action: Action::PrevPreset,
        help: "previous preset",
    },
    Binding {
        keys: &[ch(']')],
        shown: "]",
        action: Action::NextPreset,
        help: "next preset",
    },
    Binding {
        keys: &[ch('a')],
        shown: "a",
        action: Action::CycleAero,
        help: "cycle the aero model",
    },
    Binding {
        keys: &[ch(' ')],
        shown: "space",
        action: Action::TogglePause,
        help: "pause / resume the streaming tip response",
    },
    Binding {
        keys: &[ch('r')],
        shown: "r",
        action: Action::Reset,
        help: "reset the parameters to the preset and restart the response",
    },
    Binding {
        keys: &[ch('o')],
        shown: "o",
        action: Action::FollowSchedule,
        help: "rotor speed and pitch back on the operating schedule (after overriding them)",
    },
    Binding {
        keys: &[ch('k')],
        shown: "k",
        action: Action::Kick,
        help: "kick the tip (twist and flap) and watch the response",
    },
    Binding {
        keys: &[ch('f')],
        shown: "f",
        action: Action::Boundary,
        help: "recompute the stability boundary along the selected parameter",
    },
    Binding {
        keys: &[ch('c')],
        shown: "c",
        action: Action::ToggleCampbell,
        help: "Campbell diagram (modes against rotor speed or wind speed) / back",
    },
    Binding {
        keys: &[ch('w')],
        shown: "w",
        action: Action::ToggleCampbellAxis,
        help: "Campbell axis: rotor speed ↔ wind speed along the operating schedule",
    },
    Binding {
        keys: &[ch('s')],
        shown: "s",
        action: Action::ToggleShape,
        help: "mode shape along the span (in place of the tip response) / back",
    },
    Binding {
        keys: &[ch(','), ch('<')],
        shown: ",  <",
        action: Action::PrevMode,
        help: "mode shape of the previous mode (by frequency)",
    },
    Binding {
        keys: &[ch('.'), ch('>')],
        shown: ".  >",
        action: Action::NextMode,
        help: "mode shape of the next mode (by frequency)",
    },
    Binding {
        keys: &[ch('p')],
        shown: "p",
        action: Action::CyclePart,
        help: "mode shape on the next part of a rotor or turbine: blade 1, 2, 3, tower",
    },
    Binding {
        keys: &[ch('m')],
        shown: "m",
        action: Action::CycleMarker,
        help: "cycle plot markers",
    },
    Binding {
        keys: &[ch('?')],
        shown: "?",
        action: Action::ToggleHelp,
        help: "this help",
    },
    Binding {
        keys: &[plain(KeyCode::Esc)],
        shown: "Esc",
        action: Action::Back,
        help: "close the help, or go back to the main view",
    },
    Binding {
        keys: &[ch('q'), ctrl('c')],
        shown: "q  C-c",
        action: Action::Quit,
        help: "quit",
    },
];

/// The action bound to a key event, if any. Press and auto-repeat count; releases do not.
pub fn action_for(ev: &KeyEvent) -> Option<Action> {
    if !matches!(ev.kind, KeyEventKind::Press | KeyEventKind::Repeat) {
        return None;
    }
    let relevant = KeyModifiers::SHIFT | KeyModifiers::CONTROL | KeyModifiers::ALT;
    let mut mods = ev.modifiers & relevant;
    if matches!(ev.code, KeyCode::Char(_)) {
        mods.remove(KeyModifiers::SHIFT);
    }
    // Ctrl-letters may arrive upper-case from some terminals.
    let code = match ev.code {
        KeyCode::Char(c) if mods.contains(KeyModifiers::CONTROL) => {
            KeyCode::Char(c.to_ascii_lowercase())
        }
        c => c,
    };
    BINDINGS
        .iter()
        .find(|b| b.keys.iter().any(|k| k.code == code && k.mods == mods))
        .map(|b| b.action)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn press(code: KeyCode, mods: KeyModifiers) -> KeyEvent {
        KeyEvent::new(code, mods)
    }

    #[test]
    fn every_action_but_none_is_bound_once() {
        for (i, a) in BINDINGS.iter().enumerate() {
            for b in &BINDINGS[i + 1..] {
                assert_ne!(a.action, b.action, "action bound in two rows");
                for k in a.keys {
                    assert!(!b.keys.contains(k), "{:?} bound twice", k);
                }
            }
        }
    }

    #[test]
    fn shift_arrows_are_coarse_and_plain_arrows_fine() {
        assert_eq!(
            action_for(&press(KeyCode::Left, KeyModifiers::SHIFT)),
            Some(Action::DecreaseCoarse)
        );
        assert_eq!(
            action_for(&press(KeyCode::Right, KeyModifiers::NONE)),
            Some(Action::Increase)
        );
        assert_eq!(
            action_for(&press(KeyCode::Char('L'), KeyModifiers::SHIFT)),
            Some(Action::IncreaseCoarse)
        );
        assert_eq!(
            action_for(&press(KeyCode::Char('?'), KeyModifiers::SHIFT)),
            Some(Action::ToggleHelp)
        );
        assert_eq!(
            action_for(&press(KeyCode::Char('C'), KeyModifiers::CONTROL)),
            Some(Action::Quit)
        );
        assert_eq!(
            action_for(&press(KeyCode::Char('x'), KeyModifiers::NONE)),
            None
        );
    }

    #[test]
    fn releases_are_ignored() {
        let mut ev = press(KeyCode::Char('q'), KeyModifiers::NONE);
        ev.kind = KeyEventKind::Release;
        assert_eq!(action_for(&ev), None);
    }
}
