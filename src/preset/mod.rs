//! Presets: the TOML description of a blade, its section, its operating point and the analysis
//! settings. [`schema`] holds the tables and their defaults, [`keys`] the numeric keys with their
//! ranges (they also serve `--set key=value` and the parameters that sweeps, flutter searches and
//! the explorer vary), [`rules`] the rules across keys.
//!
//! A preset is checked once, when it is loaded or changed, into a [`ValidPreset`]; the physics
//! and analysis layers take only that type, so they never re-check an input. Checking a preset
//! whose `blade.source` is a tabulated blade reads the blade's files too ([`files`] says where
//! they resolve; `physics::blade::source` reads them), so a checked preset holds its blade and
//! a missing or broken file fails at load, naming the preset, the key and the file's line.
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
use crate::formats::text_file::TextFile;
use crate::physics::blade::source::{
    read_twist, BeamDynFiles, BladeFiles, Hawc2Files, TabulatedBlade,
};
use crate::physics::rotor::bem::AeroStation;
use crate::physics::rotor::files::{read_aerodyn, read_hawc2, read_htc_aero, read_prebend, AePc};
use crate::physics::rotor::schedule::Table as ScheduleTable;
use crate::physics::rotor::stations::GaussStations;
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
        "iea15mw-htc",
        include_str!("../../presets/iea15mw-htc.toml"),
    ),
];

/// The preset the explorer opens with no arguments.
pub const DEFAULT_PRESET: &str = "liu2017";

/// Names of the built-in presets, in display order.
pub fn builtin_names() -> Vec<&'static str> {
    BUILTIN.iter().map(|(n, _)| *n).collect()
}

/// A preset that passed every key range and every rule across keys, its blade files read
/// ([`Preset::validate`]). The only way to make one is to validate, so whatever takes a
/// `&ValidPreset` can rely on it.
#[derive(Debug, Clone, PartialEq)]
pub struct ValidPreset(Preset);

impl std::ops::Deref for ValidPreset {
    type Target = Preset;
    fn deref(&self) -> &Preset {
        &self.0
    }
}

impl ValidPreset {
    /// The preset, to edit and validate again.
    pub fn into_preset(self) -> Preset {
        self.0
    }

    /// This preset with `key` set to `value`, validated again (cross-key rules included).
    pub fn with(&self, key: &str, value: f64) -> Result<ValidPreset> {
        self.with_all(&[(key, value)])
    }

    /// This preset with every `(key, value)` set, validated again; a key that cannot change
    /// what the model computes for this blade is an error ([`Preset::acts`]).
    pub fn with_all(&self, values: &[(&str, f64)]) -> Result<ValidPreset> {
        let mut p = self.0.clone();
        for (key, value) in values {
            p.acts(key)?;
            p.set(key, *value)?;
        }
        p.validate()
    }

    /// This preset changed by `edit` (for the keys that are not numbers), validated again.
    pub fn edited(&self, edit: impl FnOnce(&mut Preset)) -> Result<ValidPreset> {
        let mut p = self.0.clone();
        edit(&mut p);
        p.validate()
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
        preset.read_tabulated()?;
        preset.source_defaults(&table);
        preset.validate()
    }

    /// Range-check every numeric key, read a tabulated blade's files (unless this preset already
    /// holds what they say), then the rules across keys ([`rules`]).
    pub fn validate(mut self) -> Result<ValidPreset> {
        self.check_ranges()?;
        rules::check_blade_keys(&self)?;
        self.read_tabulated()?;
        rules::check_rotor_keys(&self)?;
        self.read_rotor_files()?;
        rules::check(&self)?;
        Ok(ValidPreset(self))
    }

    fn check_ranges(&self) -> Result<()> {
        KEYS.iter()
            .filter(|spec| !(spec.unset)(self))
            .try_for_each(|spec| spec.check(&self.origin, (spec.get)(self)))
    }

    /// Read the blade `blade.source` and `blade.file` name, once: a preset edited in other keys
    /// keeps the blade it holds. File errors keep the file's own path and line, after the
    /// preset and the key that led to the file.
    fn read_tabulated(&mut self) -> Result<()> {
        let b = &self.blade;
        if !b.source.is_tabulated() {
            self.tabulated = None;
            return Ok(());
        }
        if self.tabulated.as_ref().is_some_and(|t| t.read_from(b)) {
            return Ok(());
        }
        let file = self.base.resolve(&b.file);
        let twist = match b.source {
            BladeSource::Hawc2 if !b.from_htc() => Some(
                read_twist(&self.base.resolve(&b.twist_file)).map_err(|e| Error::Invalid {
                    origin: self.origin.clone(),
                    message: format!("blade.twist_file = \"{}\": {e}", b.twist_file),
                })?,
            ),
            _ => None,
        };
        let subset = match b.source {
            BladeSource::Hawc2 => format!(
                " (blade.st_set = {}, blade.st_subset = {})",
                b.st_set, b.st_subset
            ),
            _ => String::new(),
        };
        let files: Box<dyn BladeFiles> = match twist {
            _ if b.from_htc() => Box::new(crate::model::htc::htc_files(b, &self.base)),
            Some(twist) => Box::new(Hawc2Files {
                st: file,
                twist,
                set: b.st_set,
                subset: b.st_subset,
            }),
            None => Box::new(BeamDynFiles { primary: file }),
        };
        let keys = if b.from_htc() {
            format!(
                "blade.htc_file = \"{}\" (blade.htc_body = \"{}\")",
                b.htc_file, b.htc_body
            )
        } else {
            format!("blade.file = \"{}\"{subset}", b.file)
        };
        let blade = files.read().map_err(|e| Error::Invalid {
            origin: self.origin.clone(),
            message: format!("{keys}: {e}"),
        })?;
        self.tabulated = Some(Tabulated {
            source: b.source,
            file: b.file.clone(),
            twist_file: b.twist_file.clone(),
            st_set: b.st_set,
            st_subset: b.st_subset,
            htc: b.htc_keys(),
            blade: Arc::new(blade),
        });
        Ok(())
    }

    /// Read the aerodynamic description (`aero.blade_file` … or `aero.ae_file` …) and the
    /// operating table (`operating.schedule_file`), once: a preset edited in other keys keeps
    /// what it holds. File errors keep the file's own path and line, after the preset and keys.
    fn read_rotor_files(&mut self) -> Result<()> {
        let keys = RotorFiles::keys_of(self);
        let held = self.rotor_files.as_ref();
        if held.is_some_and(|r| r.keys == keys) {
            return Ok(());
        }
        // The aerodynamic description and the table are kept apart: an operating point on its
        // schedule sets `operating.schedule = "none"` (docs/model.md §12.6), which must not read
        // the blade's aerodynamic files again (a third of a point's cost on the IEA 15MW).
        let held_blade = held
            .filter(|r| (&r.keys.0, &r.keys.1) == (&keys.0, &keys.1))
            .map(|r| (r.blade.clone(), r.stations.clone()));
        let held_table = held.filter(|r| r.keys.2 == keys.2).map(|r| r.table.clone());
        let base = &self.base;
        let (blade, stations) = match held_blade {
            Some(held) => held,
            None => (
                self.read_aero_blade()?.map(Arc::new),
                GaussStations::default(),
            ),
        };
        let table = if let Some(table) = held_table {
            table
        } else {
            match self.operating.schedule {
                Schedule::Table => {
                    let name = &self.operating.schedule_file;
                    Some(Arc::new(read_schedule_table(&base.resolve(name)).map_err(
                        |e| self.file_error(&format!("operating.schedule_file = \"{name}\""), e),
                    )?))
                }
                _ => None,
            }
        };
        self.rotor_files = Some(RotorFiles {
            keys,
            blade,
            table,
            stations,
        });
        Ok(())
    }

    /// A file's error named after the preset and the keys that name the file.
    fn file_error(&self, keys: &str, e: Error) -> Error {
        Error::Invalid {
            origin: self.origin.clone(),
            message: format!("{keys}: {e}"),
        }
    }

    /// Read the aerodynamic description (`aero.blade_file` … or `aero.ae_file` …) with its
    /// prebend; `None` when the preset names no aerodynamic files.
    fn read_aero_blade(&self) -> Result<Option<AeroBlade>> {
        let (a, base) = (&self.aero, &self.base);
        let blade = if self.blade.from_htc() {
            self.read_htc_aero()?
        } else if !a.blade_file.is_empty() {
            let airfoils: Vec<BladeFile> = a.airfoils.iter().map(|f| base.resolve(f)).collect();
            Some(
                read_aerodyn(
                    &base.resolve(&a.blade_file),
                    &airfoils,
                    &base.resolve(&a.pitch_axis_file),
                )
                .map_err(|e| {
                    self.file_error(
                        &format!(
                            "aero.blade_file = \"{}\" (with aero.airfoils, aero.pitch_axis_file = \"{}\")",
                            a.blade_file, a.pitch_axis_file
                        ),
                        e,
                    )
                })?,
            )
        } else if !a.ae_file.is_empty() {
            Some(
                read_hawc2(
                    &base.resolve(&a.ae_file),
                    a.ae_set,
                    &base.resolve(&a.pc_file),
                    &base.resolve(&self.blade.twist_file),
                )
                .map_err(|e| {
                    self.file_error(
                        &format!(
                            "aero.ae_file = \"{}\" (aero.ae_set = {}, aero.pc_file = \"{}\", \
                             twist from blade.twist_file = \"{}\")",
                            a.ae_file, a.ae_set, a.pc_file, self.blade.twist_file
                        ),
                        e,
                    )
                })?,
            )
        } else {
            None
        };
        let blade = match (blade, a.prebend_file.is_empty()) {
            (Some(mut b), false) => {
                b.prebend = read_prebend(&base.resolve(&a.prebend_file)).map_err(|e| {
                    self.file_error(&format!("aero.prebend_file = \"{}\"", a.prebend_file), e)
                })?;
                Some(b)
            }
            (blade, _) => blade,
        };
        Ok(blade)
    }

    /// The aerodynamic description of an htc blade: the ae and pc files the htc's `aero` block
    /// names, or `aero.ae_file`, `aero.ae_set` and `aero.pc_file` where the preset names them;
    /// twist and prebend from the body's `c2_def`.
    fn read_htc_aero(&self) -> Result<Option<AeroBlade>> {
        let (a, b, base) = (&self.aero, &self.blade, &self.base);
        let named = |s: &str| !s.trim().is_empty();
        let given = AePc {
            ae: named(&a.ae_file).then(|| (base.resolve(&a.ae_file), a.ae_set)),
            pc: named(&a.pc_file).then(|| base.resolve(&a.pc_file)),
        };
        let keys = match (named(&a.ae_file), named(&a.pc_file)) {
            (false, false) => format!(
                "blade.htc_file = \"{}\" (blade.htc_body = \"{}\", its aero block)",
                b.htc_file, b.htc_body
            ),
            _ => format!(
                "aero.ae_file = \"{}\" (aero.ae_set = {}), aero.pc_file = \"{}\" (either empty: \
                 the aero block's; twist and prebend from blade.htc_file = \"{}\")",
                a.ae_file, a.ae_set, a.pc_file, b.htc_file
            ),
        };
        read_htc_aero(&crate::model::htc::htc_files(b, base), given)
            .map_err(|e| self.file_error(&keys, e))
    }

    /// The aerodynamic description this checked preset holds (`None` when it names no
    /// aerodynamic files).
    pub fn aero_blade(&self) -> Option<&Arc<AeroBlade>> {
        self.rotor_files.as_ref().and_then(|r| r.blade.as_ref())
    }

    /// The `aero.stations` Gauss stations on [`Self::aero_blade`], built once and shared by
    /// the presets edited from this one in other keys (`None` without an aerodynamic
    /// description).
    pub fn aero_stations(&self) -> Option<Result<Arc<Vec<AeroStation>>>> {
        let files = self.rotor_files.as_ref()?;
        let blade = files.blade.as_ref()?;
        Some(files.stations.of(blade, self.aero.stations))
    }

    /// The operating table this checked preset holds (`operating.schedule = "table"`).
    pub fn schedule_table(&self) -> Option<&Arc<ScheduleTable>> {
        self.rotor_files.as_ref().and_then(|r| r.table.as_ref())
    }

    /// Defaults that depend on `blade.source`, for the keys `written` (the preset's keys as
    /// written, overrides applied) leaves out: a tabulated blade is as long as its file says,
    /// keeps [`TABULATED_MODES`] modes and, until its aerodynamics can be described, has none.
    fn source_defaults(&mut self, written: &toml::Table) {
        let Some(t) = &self.tabulated else { return };
        let given = |table: &str, key: &str| {
            written
                .get(table)
                .and_then(|t| t.as_table())
                .is_some_and(|t| t.contains_key(key))
        };
        if !given("blade", "length") {
            self.blade.length = t.blade.length();
        }
        if !given("structure", "modes") {
            self.structure.modes = TABULATED_MODES;
        }
        if !given("aero", "model") {
            self.aero.model = AeroModel::None;
        }
    }

    /// The tabulated blade this checked preset holds (`None` for the uniform blade).
    pub fn tabulated_blade(&self) -> Option<&Arc<TabulatedBlade>> {
        self.tabulated.as_ref().map(|t| &t.blade)
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

/// An operating table from a HAWC2 `.opt` file, in SI.
fn read_schedule_table(file: &BladeFile) -> Result<ScheduleTable> {
    let name = file.display();
    let opt = crate::formats::hawc2_aero::parse_opt(&file.read()?, &name)?;
    Ok(ScheduleTable {
        wind_speed: opt.wind_speed,
        pitch: opt.pitch_deg.iter().map(|d| d.to_radians()).collect(),
        rotor_speed: opt
            .rotor_speed_rpm
            .iter()
            .map(|r| r * std::f64::consts::PI / 30.0)
            .collect(),
        origin: name,
    })
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
