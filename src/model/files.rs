//! The files a preset names, as read when it is checked (docs/model.md §11–§12): a tabulated
//! blade's (`blade.file`, `blade.twist_file`, `blade.htc_file` …), the rotor's aerodynamic
//! description (`aero.blade_file` … or `aero.ae_file` …, with its prebend), its operating table
//! (`operating.schedule_file`), and the Gauss stations built on that description, per count.
//!
//! [`ReadFiles`] holds them with the keys they were read from. A checked preset
//! ([`crate::preset::ValidPreset`]) carries one beside its TOML, so the files are read once per
//! preset, not per solve; a preset checked again after an edit ([`read_tabulated`],
//! [`read_rotor`]) reads again only the files whose keys the edit changed and shares the rest
//! (the explorer edits its preset on every key press, a sweep at every point). File errors keep
//! the file's own path and line, after the preset and the keys that led to the file.
//!
//! This file reads the preset's schema and file bases only, never the rest of `preset/`, which
//! calls it when it checks a preset.

use super::htc::htc_files;
use super::kept::Kept;
use super::turbine_htc::{hawc2_turbine, Hawc2Turbine};
use crate::error::{Error, Result};
use crate::formats::elastodyn_tower::{parse_tower, ElastoDynTower};
use crate::formats::elastodyn_turbine::{parse_turbine, ElastoDynTurbine};
use crate::formats::hawc2_st::parse_st;
use crate::formats::htc::{parse_htc, TimoshenkoInput};
use crate::formats::htc_turbine;
use crate::formats::text_file::{ModelRoot, TextFile};
use crate::formats::windio::{self, WindIo};
use crate::physics::blade::source::{
    read_twist, BeamDynFiles, BladeFiles, Hawc2Files, LayupRequest, TabulatedBlade, TurnRequest,
    WindIoFiles,
};
use crate::physics::blade::windio::TrailingEdgeFill;
use crate::physics::rotor::bem::AeroStation;
use crate::physics::rotor::files::{
    read_aerodyn, read_hawc2, read_htc_aero, read_prebend, windio_aero, AePc,
};
use crate::physics::rotor::schedule::Table as ScheduleTable;
use crate::physics::rotor::AeroBlade;
use crate::preset::files::BladeFile;
use crate::preset::schema::{Blade, BladeSource, Preset, Schedule, TurbineModel, TurbineSource};
use std::path::Path;
use std::sync::Arc;

/// Everything a checked preset's files gave, with the keys each was read from.
///
/// Two are equal when they were read from the same keys: what the files give follows from the
/// keys (and the preset's directory, which an edit never changes), and the stations built on
/// the aerodynamic description are a cache of it, no part of what was read. Keys rather than
/// the identity of the read set, so that two presets loaded apart from the same text are equal.
#[derive(Debug)]
pub struct ReadFiles {
    /// The tabulated blade (`None` for the uniform blade).
    tabulated: Option<Tabulated>,
    /// The aerodynamic description and the stations built on it.
    aero: AeroFiles,
    /// The operating table.
    table: TableFile,
    /// The turbine around the blades (`turbine.file`).
    turbine: TurbineFile,
}

impl PartialEq for ReadFiles {
    fn eq(&self, other: &ReadFiles) -> bool {
        let tabulated = match (&self.tabulated, &other.tabulated) {
            (Some(a), Some(b)) => a.keys == b.keys,
            (a, b) => a.is_none() && b.is_none(),
        };
        tabulated
            && self.aero.keys == other.aero.keys
            && self.table.key == other.table.key
            && self.turbine.key == other.turbine.key
    }
}

impl ReadFiles {
    /// The tabulated blade (`None` for the uniform blade).
    pub fn tabulated_blade(&self) -> Option<&Arc<TabulatedBlade>> {
        self.tabulated.as_ref().map(|t| &t.blade)
    }

    /// Whether checking `p` against these files reads (or analyses) its tabulated blade again:
    /// a key it was read from changed.
    pub fn reads_blade_again(&self, p: &Preset) -> bool {
        match &self.tabulated {
            Some(t) => !t.read_from(&p.blade, &layup_request(p)),
            None => p.blade.source.is_tabulated(),
        }
    }

    /// The tabulated blade with the keys it was read from, for the rules that check a preset
    /// against its files.
    pub fn tabulated(&self) -> Option<&Tabulated> {
        self.tabulated.as_ref()
    }

    /// The aerodynamic description (`None` when the preset names no aerodynamic files).
    pub fn aero_blade(&self) -> Option<&Arc<AeroBlade>> {
        self.aero.blade.as_ref()
    }

    /// The `count` Gauss stations on [`Self::aero_blade`] ([`AeroStation::gauss`]), built on
    /// first use and shared by every preset that holds this description (`None` without one).
    pub fn aero_stations(&self, count: usize) -> Option<Result<Arc<Vec<AeroStation>>>> {
        let blade = self.aero.blade.as_ref()?;
        Some(
            self.aero
                .stations
                .get_or_build(count, KEPT_COUNTS, || AeroStation::gauss(blade, count)),
        )
    }

    /// The operating table (`None` unless `operating.schedule = "table"`).
    pub fn schedule_table(&self) -> Option<&Arc<ScheduleTable>> {
        self.table.table.as_ref()
    }

    /// The ElastoDyn main file `turbine.file` names (`None` without one), and its display name.
    pub fn turbine(&self) -> Option<&(Arc<ElastoDynTurbine>, String)> {
        self.turbine.turbine.as_ref()
    }

    /// The HAWC2 model's turbine `turbine.htc_file` names (`None` without one), and its
    /// display name.
    pub fn hawc2_turbine(&self) -> Option<&(Arc<Hawc2Turbine>, String)> {
        self.turbine.hawc2.as_ref()
    }

    /// The tower file the turbine file names, read for `turbine.model = "turbine"` (`None`
    /// otherwise), and its display name.
    pub fn tower(&self) -> Option<&(Arc<ElastoDynTower>, String)> {
        self.turbine.tower.as_ref()
    }
}

/// The tabulated blade a preset was checked with, and the keys it was read from: a change of
/// any of them reads the files again.
#[derive(Debug, Clone)]
pub struct Tabulated {
    keys: BladeKeys,
    blade: Arc<TabulatedBlade>,
}

/// What a tabulated blade is read from.
#[derive(Debug, Clone, PartialEq)]
struct BladeKeys {
    source: BladeSource,
    file: String,
    twist_file: String,
    st_set: usize,
    st_subset: usize,
    /// `htc_file`, `htc_body`, `htc_root`.
    htc: [String; 3],
    /// A WindIO blade's ply turn and trailing-edge fill (`section.ply_angle`,
    /// `section.rotate_layers`, `section.rotate_span`, `section.trailing_edge_fill*`).
    layup: LayupRequest,
}

impl Tabulated {
    /// The blade as read.
    pub fn blade(&self) -> &Arc<TabulatedBlade> {
        &self.blade
    }

    /// The `blade.source` it was read for.
    pub fn source(&self) -> BladeSource {
        self.keys.source
    }

    /// The `blade.file` it was read from.
    pub fn file(&self) -> &str {
        &self.keys.file
    }

    /// Whether this was read from what `blade` now names, its layup as `layup` asks.
    fn read_from(&self, blade: &Blade, layup: &LayupRequest) -> bool {
        let k = &self.keys;
        k.source == blade.source
            && k.file == blade.file
            && k.htc == blade.htc_keys()
            && (k.source != BladeSource::Hawc2
                || (k.st_set, k.st_subset, &k.twist_file)
                    == (blade.st_set, blade.st_subset, &blade.twist_file))
            && &k.layup == layup
    }
}

/// The aerodynamic description as read, with its keys: (the aero keys, `blade.twist_file`).
struct AeroFiles {
    keys: (Vec<String>, String),
    blade: Option<Arc<AeroBlade>>,
    /// The stations built on `blade`, by count, shared by the read sets that share `blade`
    /// (new whenever the blade is read again, so stations never outlive their blade).
    stations: Arc<Kept<usize, Vec<AeroStation>>>,
}

impl std::fmt::Debug for AeroFiles {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("AeroFiles")
            .field("keys", &self.keys)
            .field("blade", &self.blade)
            .finish_non_exhaustive()
    }
}

/// The operating table as read, with its key (`operating.schedule_file` for a table schedule,
/// else empty).
#[derive(Debug)]
struct TableFile {
    key: String,
    table: Option<Arc<ScheduleTable>>,
}

/// The turbine file and the keys it was read from (`turbine.source`, `turbine.file` or
/// `turbine.htc_file`, and whether the model holds the tower).
#[derive(Debug)]
struct TurbineFile {
    key: (String, String, bool),
    turbine: Option<(Arc<ElastoDynTurbine>, String)>,
    /// The tower file the main file names, read for `turbine.model = "turbine"` only.
    tower: Option<(Arc<ElastoDynTower>, String)>,
    /// A HAWC2 model's turbine, its tower built for `turbine.model = "turbine"` only.
    hawc2: Option<(Arc<Hawc2Turbine>, String)>,
}

/// How many station counts are kept (the most recently built): an operating point and a
/// convergence study's neighbours. A station's section is a blend of the neighbouring airfoils'
/// polars (docs/model.md §12.1): building the 30 stations of the IEA 15MW is about 0.5 ms, more
/// than a third of its steady operating point once they are kept; they depend only on the blade
/// and the count, so a sweep along the schedule or a key press that moves the wind speed reuses
/// them.
const KEPT_COUNTS: usize = 4;

/// The tabulated blade `blade.source` and `blade.file` name (`None` for the uniform blade):
/// `held`'s when it was read from the same keys, else read now.
pub fn read_tabulated(p: &Preset, held: Option<&Tabulated>) -> Result<Option<Tabulated>> {
    let (b, base) = (&p.blade, &p.base);
    if !b.source.is_tabulated() {
        return Ok(None);
    }
    let request = layup_request(p);
    if let Some(t) = held.filter(|t| t.read_from(b, &request)) {
        return Ok(Some(t.clone()));
    }
    let file = base.resolve(&b.file);
    let twist = match b.source {
        BladeSource::Hawc2 if !b.from_htc() => {
            Some(read_twist(&base.resolve(&b.twist_file)).map_err(|e| {
                file_error(p, &format!("blade.twist_file = \"{}\"", b.twist_file), e)
            })?)
        }
        _ => None,
    };
    let subset = match b.source {
        BladeSource::Hawc2 => format!(
            " (blade.st_set = {}, blade.st_subset = {})",
            b.st_set, b.st_subset
        ),
        _ => String::new(),
    };
    if b.source == BladeSource::Windio {
        let keys = format!("blade.file = \"{}\"", b.file);
        let blade = windio_blade(&file, &request, held).map_err(|e| file_error(p, &keys, e))?;
        return Ok(Some(Tabulated {
            keys: blade_keys(b, request),
            blade,
        }));
    }
    let files: Box<dyn BladeFiles> = match twist {
        _ if b.from_htc() => Box::new(htc_files(b, base)),
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
    let blade = files.read().map_err(|e| file_error(p, &keys, e))?;
    Ok(Some(Tabulated {
        keys: blade_keys(b, request),
        blade: Arc::new(blade),
    }))
}

fn blade_keys(b: &Blade, layup: LayupRequest) -> BladeKeys {
    BladeKeys {
        source: b.source,
        file: b.file.clone(),
        twist_file: b.twist_file.clone(),
        st_set: b.st_set,
        st_subset: b.st_subset,
        htc: b.htc_keys(),
        layup,
    }
}

/// WindIO files as parsed, by name and a hash of their text: a preset loaded again (a sweep's
/// points, a `--set`, the explorer's presets) parses its file once.
static WINDIO_FILES: Kept<(String, u64), WindIo> = Kept::new();

/// WindIO blades as analysed, by file name, text hash and layup request: the analysis of 50 layup
/// sections is the cost of loading such a blade (docs/model.md §11.12), and the same blade is
/// asked for again by every preset that names it.
static LAYUP_BLADES: Kept<(String, u64, LayupRequest), TabulatedBlade> = Kept::new();

/// The WindIO file as parsed: kept from before (by its name and text), or parsed now. The
/// structure and the aerodynamic description of a WindIO blade share one parse.
fn windio_file(file: &BladeFile) -> Result<Arc<WindIo>> {
    let (name, hash, text) = windio_text(file)?;
    parsed(&name, hash, &text)
}

/// A WindIO file's name, the hash of its text, and the text.
fn windio_text(file: &BladeFile) -> Result<(String, u64, String)> {
    use std::hash::{Hash, Hasher};
    let text = file.read()?;
    let mut hasher = std::collections::hash_map::DefaultHasher::new();
    text.hash(&mut hasher);
    Ok((file.display(), hasher.finish(), text))
}

fn parsed(name: &str, hash: u64, text: &str) -> Result<Arc<WindIo>> {
    WINDIO_FILES.get_or_build((name.to_string(), hash), 2, || windio::parse(text, name))
}

/// The WindIO blade of `file` as `request` asks: kept from before, or analysed now, its
/// unturned stations lent by `held` (the blade the preset had) or by the newest kept blade of
/// the same file.
fn windio_blade(
    file: &BladeFile,
    request: &LayupRequest,
    held: Option<&Tabulated>,
) -> Result<Arc<TabulatedBlade>> {
    let (name, hash, text) = windio_text(file)?;
    LAYUP_BLADES.get_or_build((name.clone(), hash, request.clone()), 8, || {
        let windio = parsed(&name, hash, &text)?;
        let kept = LAYUP_BLADES.newest(|k| k.0 == name && k.1 == hash);
        let lender = held
            .map(|t| Arc::clone(&t.blade))
            .into_iter()
            .chain(kept)
            .find(|b| {
                b.layup
                    .as_ref()
                    .is_some_and(|l| Arc::ptr_eq(&l.windio, &windio))
            });
        WindIoFiles {
            windio,
            layup: request.clone(),
            held: lender.as_ref().and_then(|b| b.layup.as_deref()),
        }
        .read()
    })
}

/// What the preset asks of a WindIO blade's layup beyond its file: the ply turn when
/// `section.ply_angle` is set (unset, the ontology's angles stand) and the trailing-edge fill
/// when `section.trailing_edge_fill` names a material.
fn layup_request(p: &Preset) -> LayupRequest {
    let s = &p.section;
    if p.blade.source != BladeSource::Windio {
        return LayupRequest::default();
    }
    LayupRequest {
        turn: s.ply_angle.map(|angle_deg| TurnRequest {
            angle_deg,
            layers: s.rotate_layers.clone(),
            span: s.rotate_span,
        }),
        fill: (!s.trailing_edge_fill.trim().is_empty()).then(|| TrailingEdgeFill {
            material: s.trailing_edge_fill.trim().to_string(),
            length: s.trailing_edge_fill_length,
            span: s.trailing_edge_fill_span,
        }),
    }
}

/// The preset's read files: `tabulated` ([`read_tabulated`]) with the aerodynamic description
/// and the operating table, each `held`'s where it was read from the same keys, else read now.
/// `held` itself when nothing was read again.
///
/// The aerodynamic description and the table are kept apart: an operating point on its
/// schedule sets `operating.schedule = "none"` (docs/model.md §12.6), which must not read the
/// blade's aerodynamic files again (a third of a point's cost on the IEA 15MW).
pub fn read_rotor(
    p: &Preset,
    tabulated: Option<Tabulated>,
    held: Option<&Arc<ReadFiles>>,
) -> Result<Arc<ReadFiles>> {
    let (aero_keys, table_key) = rotor_keys(p);
    let turbine_key = (
        format!("{:?}", p.turbine.source),
        format!("{}|{}", p.turbine.file.trim(), p.turbine.htc_file.trim()),
        p.turbine.model == TurbineModel::Turbine,
    );
    if let Some(h) = held {
        let same_blade = match (&h.tabulated, &tabulated) {
            (Some(a), Some(b)) => a.keys == b.keys,
            (a, b) => a.is_none() && b.is_none(),
        };
        if same_blade
            && h.aero.keys == aero_keys
            && h.table.key == table_key
            && h.turbine.key == turbine_key
        {
            return Ok(Arc::clone(h));
        }
    }
    let (turbine, tower, hawc2) = match held.filter(|h| h.turbine.key == turbine_key) {
        Some(h) => (
            h.turbine.turbine.clone(),
            h.turbine.tower.clone(),
            h.turbine.hawc2.clone(),
        ),
        None => {
            let (turbine, tower) = read_turbine_files(p)?;
            (turbine, tower, read_hawc2_turbine(p)?)
        }
    };
    let aero = match held.filter(|h| h.aero.keys == aero_keys) {
        Some(h) => AeroFiles {
            keys: aero_keys,
            blade: h.aero.blade.clone(),
            stations: Arc::clone(&h.aero.stations),
        },
        None => AeroFiles {
            keys: aero_keys,
            blade: read_aero_blade(p)?.map(Arc::new),
            stations: Arc::default(),
        },
    };
    let table = match held.filter(|h| h.table.key == table_key) {
        Some(h) => h.table.table.clone(),
        None => match p.operating.schedule {
            Schedule::Table => {
                let name = &p.operating.schedule_file;
                Some(Arc::new(
                    read_schedule_table(&p.base.resolve(name)).map_err(|e| {
                        file_error(p, &format!("operating.schedule_file = \"{name}\""), e)
                    })?,
                ))
            }
            _ => None,
        },
    };
    Ok(Arc::new(ReadFiles {
        tabulated,
        aero,
        table: TableFile {
            key: table_key,
            table,
        },
        turbine: TurbineFile {
            key: turbine_key,
            turbine,
            tower,
            hawc2,
        },
    }))
}

/// The turbine of the HAWC2 model `turbine.htc_file` names, with its display name; none
/// unless `turbine.source = "hawc2"`. Its st files resolve from the folder above the htc
/// file's, as its `continue_in_file`s do.
fn read_hawc2_turbine(p: &Preset) -> Result<Named<Hawc2Turbine>> {
    let name = p.turbine.htc_file.trim();
    if p.turbine.source != TurbineSource::Hawc2 || name.is_empty() {
        return Ok(None);
    }
    let keys = format!("turbine.htc_file = \"{name}\"");
    let htc = p.base.resolve(name);
    let root = ModelRoot::above_folder_of(&htc);
    let display = htc.display();
    let read = || -> Result<Hawc2Turbine> {
        let text = htc.read()?;
        let mut include = |path: &str| {
            let file = root.file(path);
            Ok((file.display(), file.read()?))
        };
        let model = parse_htc(&text, &display, &mut include)?;
        let described = htc_turbine::turbine(&model)?;
        let mut st = |input: &TimoshenkoInput| {
            let file = root.file(&input.filename);
            let st_name = file.display();
            parse_st(&file.read()?, &st_name)
        };
        hawc2_turbine(
            &described,
            &mut st,
            p.turbine.model == TurbineModel::Turbine,
        )
    };
    let turbine = read().map_err(|e| file_error(p, &keys, e))?;
    Ok(Some((Arc::new(turbine), display)))
}

/// A file read with its display name.
type Named<T> = Option<(Arc<T>, String)>;

/// The ElastoDyn main file `turbine.file` names, with its display name, and for the whole
/// turbine the tower file it names (`TwrFile`, relative to the main file's directory as
/// OpenFAST resolves it); none without one.
fn read_turbine_files(p: &Preset) -> Result<(Named<ElastoDynTurbine>, Named<ElastoDynTower>)> {
    let name = p.turbine.file.trim();
    if p.turbine.source != TurbineSource::Elastodyn || name.is_empty() {
        return Ok((None, None));
    }
    let keys = format!("turbine.file = \"{name}\"");
    let file = p.base.resolve(name);
    let display = file.display();
    let turbine = file
        .read()
        .and_then(|text| parse_turbine(&text, &display))
        .map_err(|e| file_error(p, &keys, e))?;
    let tower = if p.turbine.model == TurbineModel::Turbine {
        let tower_name = turbine.tower_file_path(Path::new(name));
        let tower_name = tower_name.to_string_lossy();
        let tower_file = p.base.resolve(&tower_name);
        let tower_display = tower_file.display();
        let tower = tower_file
            .read()
            .and_then(|text| parse_tower(&text, &tower_display))
            .map_err(|e| file_error(p, &format!("{keys} (its TwrFile)"), e))?;
        Some((Arc::new(tower), tower_display))
    } else {
        None
    };
    Ok((Some((Arc::new(turbine), display)), tower))
}

/// The keys that decide what the rotor's files are: (the aerodynamic description's: the aero
/// keys and `blade.twist_file`) and the table's (`operating.schedule_file` for a table
/// schedule, else empty).
fn rotor_keys(p: &Preset) -> ((Vec<String>, String), String) {
    let a = &p.aero;
    let mut aero = vec![
        a.blade_file.clone(),
        a.pitch_axis_file.clone(),
        a.ae_file.clone(),
        a.ae_set.to_string(),
        a.pc_file.clone(),
        a.prebend_file.clone(),
    ];
    aero.extend(a.airfoils.iter().cloned());
    aero.extend(p.blade.htc_keys());
    // A WindIO blade's file is its aerodynamic description too.
    if p.blade.source == BladeSource::Windio {
        aero.push(p.blade.file.clone());
    }
    let table = match p.operating.schedule {
        Schedule::Table => p.operating.schedule_file.clone(),
        _ => String::new(),
    };
    ((aero, p.blade.twist_file.clone()), table)
}

/// A file's error named after the preset and the keys that name the file.
fn file_error(p: &Preset, keys: &str, e: Error) -> Error {
    Error::Invalid {
        origin: p.origin.clone(),
        message: format!("{keys}: {e}"),
    }
}

/// The aerodynamic description (`aero.blade_file` … or `aero.ae_file` …) with its prebend;
/// `None` when the preset names no aerodynamic files.
fn read_aero_blade(p: &Preset) -> Result<Option<AeroBlade>> {
    let (a, base) = (&p.aero, &p.base);
    let blade = if p.blade.from_htc() {
        read_htc_blade_aero(p)?
    } else if p.blade.source == BladeSource::Windio {
        Some(
            windio_file(&base.resolve(&p.blade.file))
                .and_then(|w| windio_aero(&w))
                .map_err(|e| file_error(p, &format!("blade.file = \"{}\"", p.blade.file), e))?,
        )
    } else if !a.blade_file.is_empty() {
        let airfoils: Vec<BladeFile> = a.airfoils.iter().map(|f| base.resolve(f)).collect();
        Some(
            read_aerodyn(
                &base.resolve(&a.blade_file),
                &airfoils,
                &base.resolve(&a.pitch_axis_file),
            )
            .map_err(|e| {
                file_error(
                    p,
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
                &base.resolve(&p.blade.twist_file),
            )
            .map_err(|e| {
                file_error(
                    p,
                    &format!(
                        "aero.ae_file = \"{}\" (aero.ae_set = {}, aero.pc_file = \"{}\", \
                         twist from blade.twist_file = \"{}\")",
                        a.ae_file, a.ae_set, a.pc_file, p.blade.twist_file
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
                file_error(p, &format!("aero.prebend_file = \"{}\"", a.prebend_file), e)
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
fn read_htc_blade_aero(p: &Preset) -> Result<Option<AeroBlade>> {
    let (a, b, base) = (&p.aero, &p.blade, &p.base);
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
    read_htc_aero(&htc_files(b, base), given).map_err(|e| file_error(p, &keys, e))
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
