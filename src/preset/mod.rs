//! Presets: the TOML description of a blade, its section, its operating point and the analysis
//! settings. [`schema`] holds the tables and their defaults, [`keys`] the numeric keys with their
//! ranges (they also serve `--set key=value` and the parameters that sweeps, flutter searches and
//! the explorer vary), [`rules`] the rules across keys.
//!
//! A preset is checked once, when it is loaded or changed, into a [`ValidPreset`]; the physics
//! and analysis layers take only that type, so they never re-check an input. Checking a preset
//! reads the files it names too ([`files`] says where they resolve; [`crate::model::files`]
//! reads them and holds what they gave), so a checked preset carries its blade, its aerodynamic
//! description and its operating table beside the TOML, and a missing or broken file fails at
//! load, naming the preset, the key and the file's line. The [`Preset`] itself is only what its
//! TOML says.
//!
//! Units at this edge: degrees for angles, rpm for rotor speed, SI otherwise. The physics layers
//! receive SI through the accessors at the bottom of this file.

pub mod files;
pub mod keys;
pub mod rules;
pub mod schema;

pub use files::{BladeFile, FileBase, BUILTIN_FILES};
pub use keys::{key_spec, KeySpec, KEYS};
pub use rules::MAX_SAMPLES;
pub use schema::*;

use crate::error::{Error, Result};
use crate::model::files::{read_rotor, read_tabulated, ReadFiles, Tabulated};
use crate::physics::blade::source::TabulatedBlade;
use crate::physics::rotor::bem::AeroStation;
use crate::physics::rotor::schedule::Table as ScheduleTable;
use crate::physics::rotor::AeroBlade;
use serde::Deserialize;
use std::path::Path;
use std::sync::Arc;

/// Presets shipped in `presets/` and embedded so the binary runs from anywhere.
pub static BUILTIN: &[(&str, &str)] = &[
    ("liu2017", include_str!("../../presets/liu2017.toml")),
    (
        "liu2017-stall",
        include_str!("../../presets/liu2017-stall.toml"),
    ),
    ("goland", include_str!("../../presets/goland.toml")),
    ("demo-blade", include_str!("../../presets/demo-blade.toml")),
    ("nrel5mw", include_str!("../../presets/nrel5mw.toml")),
    ("iea15mw", include_str!("../../presets/iea15mw.toml")),
    (
        "iea15mw-btc",
        include_str!("../../presets/iea15mw-btc.toml"),
    ),
    (
        "iea15mw-btc-st2019",
        include_str!("../../presets/iea15mw-btc-st2019.toml"),
    ),
    (
        "iea15mw-htc",
        include_str!("../../presets/iea15mw-htc.toml"),
    ),
    (
        "iea15mw-windio",
        include_str!("../../presets/iea15mw-windio.toml"),
    ),
];

/// The preset the explorer opens with no arguments.
pub const DEFAULT_PRESET: &str = "liu2017";

/// Names of the built-in presets, in display order.
pub fn builtin_names() -> Vec<&'static str> {
    BUILTIN.iter().map(|(n, _)| *n).collect()
}

/// A preset that passed every key range and every rule across keys, with the files it names read
/// ([`Preset::validate`]): the preset as its TOML says (what it derefs to) and, beside it, what
/// its files gave ([`ReadFiles`], shared by the presets edited from this one in other keys). The
/// only way to make one is to validate, so whatever takes a `&ValidPreset` can rely on it.
#[derive(Debug, Clone, PartialEq)]
pub struct ValidPreset {
    preset: Preset,
    files: Arc<ReadFiles>,
}

impl std::ops::Deref for ValidPreset {
    type Target = Preset;
    fn deref(&self) -> &Preset {
        &self.preset
    }
}

impl ValidPreset {
    /// The preset, to edit and validate again.
    pub fn into_preset(self) -> Preset {
        self.preset
    }

    /// This preset with `key` set to `value`, validated again (cross-key rules included).
    pub fn with(&self, key: &str, value: f64) -> Result<ValidPreset> {
        self.with_all(&[(key, value)])
    }

    /// This preset with every `(key, value)` set, validated again; a key that cannot change
    /// what the model computes for this blade is an error ([`Preset::acts`]). The files are
    /// read again only if a key they were read from changed.
    pub fn with_all(&self, values: &[(&str, f64)]) -> Result<ValidPreset> {
        let mut p = self.preset.clone();
        for (key, value) in values {
            p.acts(key)?;
            p.set(key, *value)?;
        }
        p.validated(Some(&self.files), None)
    }

    /// Whether [`Self::with`] would read or analyse the blade again (a WindIO blade's ply angle,
    /// say): an edit worth checking off the thread that waits for it. A value that cannot be set
    /// is not: its error comes at once.
    pub fn with_reads_blade(&self, key: &str, value: f64) -> bool {
        let mut p = self.preset.clone();
        p.acts(key).is_ok() && p.set(key, value).is_ok() && self.files.reads_blade_again(&p)
    }

    /// This preset changed by `edit` (for the keys that are not numbers), validated again; the
    /// files are read again only if a key they were read from changed.
    pub fn edited(&self, edit: impl FnOnce(&mut Preset)) -> Result<ValidPreset> {
        let mut p = self.preset.clone();
        edit(&mut p);
        p.validated(Some(&self.files), None)
    }

    /// What the preset's files gave when it was checked.
    pub fn files(&self) -> &ReadFiles {
        &self.files
    }

    /// The tabulated blade this checked preset holds (`None` for the uniform blade).
    pub fn tabulated_blade(&self) -> Option<&Arc<TabulatedBlade>> {
        self.files.tabulated_blade()
    }

    /// The aerodynamic description this checked preset holds (`None` when it names no
    /// aerodynamic files).
    pub fn aero_blade(&self) -> Option<&Arc<AeroBlade>> {
        self.files.aero_blade()
    }

    /// The `aero.stations` Gauss stations on [`Self::aero_blade`], built once and shared by
    /// the presets edited from this one in other keys (`None` without an aerodynamic
    /// description).
    pub fn aero_stations(&self) -> Option<Result<Arc<Vec<AeroStation>>>> {
        self.files.aero_stations(self.aero.stations)
    }

    /// The operating table this checked preset holds (`operating.schedule = "table"`).
    pub fn schedule_table(&self) -> Option<&Arc<ScheduleTable>> {
        self.files.schedule_table()
    }
}

impl Preset {
    /// Load a built-in preset by name, or a file by path (anything containing a path separator
    /// or ending in `.toml`), then apply `--set` overrides and validate.
    pub fn load(name_or_path: &str, overrides: &[String]) -> Result<ValidPreset> {
        if let Some((name, text)) = BUILTIN.iter().find(|(n, _)| *n == name_or_path) {
            let origin = format!("built-in preset '{name}'");
            return Preset::from_toml_in(text, &origin, FileBase::Builtin, overrides);
        }
        let path = Path::new(name_or_path);
        let looks_like_path = name_or_path.ends_with(".toml")
            || name_or_path.contains(std::path::MAIN_SEPARATOR)
            || name_or_path.contains('/');
        if looks_like_path || path.exists() {
            // The capped reader: a wrong path (a device, a FIFO, a huge file) fails at once.
            let text = crate::formats::text::read_text(path).map_err(|e| Error::Preset {
                origin: name_or_path.to_string(),
                message: match e {
                    Error::Format { message, .. } => format!(
                        "cannot read preset file: {}",
                        message.strip_prefix("cannot read: ").unwrap_or(&message)
                    ),
                    other => other.to_string(),
                },
            })?;
            let dir = path.parent().unwrap_or_else(|| Path::new("")).to_path_buf();
            return Preset::from_toml_in(&text, name_or_path, FileBase::Dir(dir), overrides);
        }
        Err(Error::usage(format!(
            "no preset named '{name_or_path}'; built-in presets: {} (or give a path to a .toml file)",
            builtin_names().join(", ")
        )))
    }

    /// Parse TOML text, apply overrides (`key=value`, value in TOML syntax or a bare word) and
    /// validate. `origin` names the source in every error; a relative `blade.file` resolves
    /// against the working directory.
    pub fn from_toml(text: &str, origin: &str, overrides: &[String]) -> Result<ValidPreset> {
        Preset::from_toml_in(text, origin, FileBase::WorkingDir, overrides)
    }

    /// [`Preset::from_toml`] with relative file names resolved against `base`.
    pub fn from_toml_in(
        text: &str,
        origin: &str,
        base: FileBase,
        overrides: &[String],
    ) -> Result<ValidPreset> {
        let preset_err = |message: String| Error::Preset {
            origin: origin.to_string(),
            message,
        };
        let file_err = |e: toml::de::Error| preset_err(e.to_string().trim_end().to_string());
        // The file alone, deserialized from its text so that every error in it (syntax, unknown
        // field, wrong type) carries the line and a caret.
        let mut preset: Preset = toml::from_str(text).map_err(file_err)?;
        // The keys as written (after the overrides): which ones the text leaves to defaults.
        let mut table: toml::Table = text.parse().map_err(file_err)?;
        let mut notes = Vec::new();
        if !overrides.is_empty() {
            // Overrides edit the parsed table; its errors have no spans and read "…\nin
            // `table`", kept on one line and blamed on the --set.
            for ov in overrides {
                apply_override(&mut table, ov)?;
            }
            notes.extend(set_aside_schedule_file(&mut table, overrides));
            preset = Preset::deserialize(table.clone()).map_err(|e| {
                let msg = e.to_string().trim_end().replace('\n', " ");
                preset_err(format!("{msg} (after --set {})", overrides.join(" --set ")))
            })?;
        }
        preset.origin = origin.to_string();
        preset.base = base;
        preset.notes = notes;
        // A rotor speed or pitch set on the command line holds against the schedule, as an
        // edit does ([`Preset::set`]).
        for ov in overrides {
            if let Some(key) = ov.split('=').next() {
                preset.hold_against_schedule(key.trim());
            }
        }
        preset.check_ranges()?;
        rules::check_blade_keys(&preset)?;
        let tabulated = read_tabulated(&preset, None)?;
        if let Some(t) = &tabulated {
            preset.source_defaults(&table, t.blade());
        }
        preset.validated(None, tabulated)
    }

    /// Range-check every numeric key, read the files the preset names, then the rules across
    /// keys ([`rules`]).
    pub fn validate(self) -> Result<ValidPreset> {
        self.validated(None, None)
    }

    /// [`Preset::validate`], keeping of `held` (the files of the preset this one was edited
    /// from) and of `tabulated` (its tabulated blade, read already) what was read from the keys
    /// this preset names ([`crate::model::files`]).
    fn validated(
        self,
        held: Option<&Arc<ReadFiles>>,
        tabulated: Option<Tabulated>,
    ) -> Result<ValidPreset> {
        self.check_ranges()?;
        rules::check_blade_keys(&self)?;
        let held_blade = tabulated.as_ref().or(held.and_then(|f| f.tabulated()));
        let tabulated = read_tabulated(&self, held_blade)?;
        rules::check_rotor_keys(&self)?;
        let files = read_rotor(&self, tabulated, held)?;
        rules::check(&self, &files)?;
        Ok(ValidPreset {
            preset: self,
            files,
        })
    }

    fn check_ranges(&self) -> Result<()> {
        KEYS.iter()
            .filter(|spec| !(spec.unset)(self))
            .try_for_each(|spec| spec.check(&self.origin, (spec.get)(self)))
    }

    /// Defaults that depend on `blade.source`, for the keys `written` (the preset's keys as
    /// written, overrides applied) leaves out: a tabulated blade is as long as its file says,
    /// keeps [`TABULATED_MODES`] modes and, until its aerodynamics can be described, has none.
    fn source_defaults(&mut self, written: &toml::Table, blade: &TabulatedBlade) {
        let given = |table: &str, key: &str| {
            written
                .get(table)
                .and_then(|t| t.as_table())
                .is_some_and(|t| t.contains_key(key))
        };
        if !given("blade", "length") {
            self.blade.length = blade.length();
        }
        if !given("structure", "modes") {
            self.structure.modes = TABULATED_MODES;
        }
        if !given("aero", "model") {
            self.aero.model = AeroModel::None;
        }
    }

    /// `Ok` when setting `key` can change what the model computes for this preset's blade, else
    /// the error naming the key and what acts instead ([`rules::not_acting`]).
    pub fn acts(&self, key: &str) -> Result<()> {
        match rules::not_acting(self, key) {
            None => Ok(()),
            Some(reason) => Err(Error::usage(format!("{}: {key} {reason}", self.origin))),
        }
    }

    /// `Ok` when every numeric key `overrides` (`key=value`) sets acts for this blade
    /// ([`Preset::acts`]).
    pub fn overrides_act(&self, overrides: &[String]) -> Result<()> {
        overrides
            .iter()
            .filter_map(|ov| ov.split_once('='))
            .try_for_each(|(key, _)| self.acts(key.trim()))
    }

    /// Value of a numeric key.
    pub fn get(&self, key: &str) -> Result<f64> {
        Ok((key_spec(key)?.get)(self))
    }

    /// Set a numeric key, checking its range (the rules across keys wait for
    /// [`Preset::validate`]).
    ///
    /// Setting `operating.rotor_speed` or `operating.pitch` overrides the schedule for that key
    /// ([`ScheduleOverrides`]); [`Preset::follow_schedule`] returns to it.
    pub fn set(&mut self, key: &str, value: f64) -> Result<()> {
        let spec = key_spec(key)?;
        spec.check(&self.origin, value)?;
        (spec.set)(self, value);
        self.hold_against_schedule(key);
        Ok(())
    }

    /// A rotor speed or pitch set by hand holds against the schedule ([`ScheduleOverrides`]).
    fn hold_against_schedule(&mut self, key: &str) {
        match key {
            "operating.rotor_speed" => self.schedule_overrides.rotor_speed = true,
            "operating.pitch" => self.schedule_overrides.pitch = true,
            _ => {}
        }
    }

    /// Rotor speed and pitch follow `operating.schedule` again.
    pub fn follow_schedule(&mut self) {
        self.schedule_overrides = ScheduleOverrides::default();
    }

    /// The preset as TOML text (round-trips through [`Preset::from_toml`]).
    pub fn to_toml(&self) -> String {
        toml::to_string(self).unwrap_or_default()
    }

    /// True when the time response steps the linearisation of a model whose stall is
    /// nonlinear: a rotor or turbine in the ground frame (docs/model.md §13.8).
    pub fn stall_linearised_in_time(&self) -> bool {
        self.turbine.model != TurbineModel::Blade && self.aero.model.stalls()
    }

    /// A display name: `meta.name`, else the origin.
    pub fn display_name(&self) -> &str {
        if self.meta.name.is_empty() {
            &self.origin
        } else {
            &self.meta.name
        }
    }

    /// Where one solve of this preset runs, in words, for numerical errors: the preset, its
    /// aerodynamic model and its operating point.
    pub fn operating_point(&self) -> String {
        let o = &self.operating;
        format!(
            "{} ({} aerodynamics) at operating.rotor_speed = {} rpm, operating.wind_speed = {} \
             m/s, operating.tunnel_speed = {} m/s, operating.pitch = {} deg",
            self.display_name(),
            self.aero.model.name(),
            o.rotor_speed,
            o.wind_speed,
            o.tunnel_speed,
            o.pitch
        )
    }

    // ---- SI accessors for the physics layers ----

    /// Rotor speed Ω (rad/s).
    pub fn omega(&self) -> f64 {
        self.operating.rotor_speed * std::f64::consts::PI / 30.0
    }
    /// Pitch β (rad).
    pub fn pitch_rad(&self) -> f64 {
        self.operating.pitch.to_radians()
    }
}

/// A `--set operating.schedule` away from "table" on a preset that runs along a table file: the
/// file is then unused, so it is set aside (the rule that a schedule file belongs to a table
/// schedule, [`rules::check_rotor_keys`], holds for what a preset file says) and the note that
/// says so is returned. A `--set operating.schedule_file` as well keeps what it sets.
fn set_aside_schedule_file(table: &mut toml::Table, overrides: &[String]) -> Option<String> {
    let sets = |key: &str| {
        overrides
            .iter()
            .any(|ov| ov.split_once('=').is_some_and(|(k, _)| k.trim() == key))
    };
    if !sets("operating.schedule") || sets("operating.schedule_file") {
        return None;
    }
    let operating = table.get_mut("operating")?.as_table_mut()?;
    let schedule = operating.get("schedule")?.as_str()?.to_string();
    if schedule == Schedule::Table.name() {
        return None;
    }
    let file = operating.get("schedule_file")?.as_str()?.to_string();
    if file.trim().is_empty() {
        return None;
    }
    operating.remove("schedule_file");
    Some(format!(
        "operating.schedule = \"{schedule}\" (--set): the preset's operating.schedule_file = \
         \"{file}\" is not used"
    ))
}

/// Apply one `key=value` override to the raw TOML table, creating intermediate tables. The value
/// is parsed as TOML (numbers, booleans, quoted strings); a bare word becomes a string, so
/// `--set aero.model=theodorsen` works without quotes.
fn apply_override(table: &mut toml::Table, ov: &str) -> Result<()> {
    let (key, raw) = ov.split_once('=').ok_or_else(|| {
        Error::usage(format!(
            "--set expects key=value (e.g. --set section.ply_angle=30), got '{ov}'"
        ))
    })?;
    let key = key.trim();
    let raw = raw.trim();
    let bare = |part: &str| {
        !part.is_empty()
            && part
                .bytes()
                .all(|b| b.is_ascii_alphanumeric() || b == b'_' || b == b'-')
    };
    if !key.split('.').all(bare) {
        return Err(Error::usage(format!(
            "--set: malformed key '{}' in '{}'; a key is dotted words, e.g. section.ply_angle",
            key.escape_debug(),
            ov.escape_debug()
        )));
    }
    // One --set sets one key: a line break would smuggle a second assignment into the TOML
    // parsed below (and be silently dropped), a table or an array would replace several keys.
    let one_key = |what: &str| {
        Error::usage(format!(
            "--set {key}: the value '{}' {what}; --set sets one key to one value: give each key \
             its own --set (e.g. --set blade.length=5 --set structure.modes=3)",
            raw.escape_debug()
        ))
    };
    if raw.contains(['\n', '\r']) {
        return Err(one_key("spans several lines"));
    }
    let value: toml::Value = match format!("v = {raw}").parse::<toml::Table>() {
        Ok(mut t) => t
            .remove("v")
            .unwrap_or(toml::Value::String(raw.to_string())),
        Err(_) => toml::Value::String(raw.to_string()),
    };
    if value.is_table() || value.is_array() {
        return Err(one_key("is a TOML table or array"));
    }
    let parts: Vec<&str> = key.split('.').collect();
    let mut cur = table;
    for part in &parts[..parts.len() - 1] {
        let entry = cur
            .entry(part.to_string())
            .or_insert_with(|| toml::Value::Table(toml::Table::new()));
        cur = entry.as_table_mut().ok_or_else(|| {
            Error::usage(format!("--set {key}: '{part}' is a value, not a section"))
        })?;
    }
    cur.insert(parts[parts.len() - 1].to_string(), value);
    Ok(())
}
