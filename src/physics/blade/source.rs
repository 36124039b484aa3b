//! A tabulated blade from its files, and its structure (docs/model.md §11): the files are read
//! and mapped to a [`BladeTable`] with the damping they state ([`read_beamdyn`],
//! [`read_hawc2`], a HAWC2 model's htc file through [`HtcFiles`]); [`pitch_range_basis`] builds
//! the finite elements and the modal basis over a pitch range, and [`BladeStructure`] is the
//! blade at one pitch with each mode's damping.
//!
//! Damping (docs/model.md §11.4): a modal damping ratio set per family (a preset's
//! `structure.damping_flap`, `…_edge`, `…_torsion`) damps every mode of that family; a family
//! left unset takes what the files state: BeamDyn's stiffness-proportional `mu` or an htc body's
//! `damping_aniso` projected on each mode, or a ratio per family ([`SourceDamping::PerFamily`]); a
//! file that states none leaves the mode undamped.

use super::axis::CurvedAxis;
use super::beamdyn::from_beamdyn;
use super::coupling::with_bend_twist_coupling;
use super::fem::Mesh;
use super::hawc2::{from_hawc2_st, C2Line, ChordTwist};
use super::modal::{BladeMode, ModalBlade, StiffnessFactors};
use super::pitch_range::{snapshot_pitches, PitchRangeBlade};
use super::windio::{LayupBlade, PlyTurn, TrailingEdgeFill};
use super::BladeTable;
use crate::error::{Error, Result};
use crate::formats::htc::{self, HtcBlade, HtcDamping, Named};
use crate::formats::text_file::{ModelRoot, TextFile};
use crate::formats::windio::WindIo;
use crate::formats::{aerodyn, beamdyn, elastodyn, hawc2_st};
use std::sync::Arc;

/// The format of a tabulated blade's structural files.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BladeFormat {
    /// A BeamDyn primary file and the blade file it names.
    Beamdyn,
    /// A HAWC2 st file.
    Hawc2,
    /// A WindIO ontology file: the sections analysed from its layup.
    Windio,
}

impl BladeFormat {
    /// The name as the format's program spells it, for reports.
    pub fn title(self) -> &'static str {
        match self {
            BladeFormat::Beamdyn => "BeamDyn",
            BladeFormat::Hawc2 => "HAWC2",
            BladeFormat::Windio => "WindIO",
        }
    }
}

/// Damping as a blade's files state it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SourceDamping {
    /// The files state none.
    None,
    /// Stiffness-proportional damping (BeamDyn `damp_type = 1`), projected on each mode.
    StiffnessProportional(StiffnessFactors),
    /// A damping ratio per family, in [`Family::ALL`](super::modal::Family::ALL) order (a
    /// source that states its damping per mode family, e.g. tuned HAWC2 log decrements).
    PerFamily([f64; 3]),
}

/// A blade as its files describe it: the sections (root at the hub radius 0: the preset's
/// `blade.hub_radius` places it) and the damping they state.
#[derive(Debug, Clone, PartialEq)]
pub struct TabulatedBlade {
    pub format: BladeFormat,
    pub table: BladeTable,
    pub damping: SourceDamping,
    /// The files read, as errors name them (a BeamDyn blade: the primary file, then its blade
    /// file).
    pub files: Vec<String>,
    /// A WindIO blade's layup and the sections analysed from it (`None` for a blade read from
    /// section tables).
    pub layup: Option<Arc<LayupBlade>>,
}

impl TabulatedBlade {
    /// Blade length (m): the span of the last station.
    pub fn length(&self) -> f64 {
        self.table.length()
    }
}

/// The files a tabulated blade is read from, in one of the formats the program reads: each format
/// is one implementation (a BeamDyn blade, a HAWC2 st file with its twist), and a new one (a
/// layup ontology, say) is one more.
pub trait BladeFiles {
    /// The blade as its files describe it: sections and the damping they state. Errors name the
    /// file and line; a file of another known kind says which kind it is.
    fn read(&self) -> Result<TabulatedBlade>;
}

/// A BeamDyn blade: its primary file ([`read_beamdyn`]).
pub struct BeamDynFiles<F> {
    pub primary: F,
}

impl<F: TextFile> BladeFiles for BeamDynFiles<F> {
    fn read(&self) -> Result<TabulatedBlade> {
        read_beamdyn(&self.primary)
    }
}

/// A HAWC2 blade: subset `subset` of set `set` of its st file, turned by the chord's `twist`
/// ([`read_hawc2`]).
pub struct Hawc2Files<F> {
    pub st: F,
    pub twist: ChordTwist,
    pub set: usize,
    pub subset: usize,
}

impl<F: TextFile> BladeFiles for Hawc2Files<F> {
    fn read(&self) -> Result<TabulatedBlade> {
        read_hawc2(&self.st, &self.twist, self.set, self.subset)
    }
}

/// A HAWC2 blade from its model's htc file (docs/model.md §11.6): main body `body`'s `c2_def`
/// (the twist), its `timoschenko_input` (st file, set, subset, FPM flag) and its damping
/// statement; the files it names, included htc files too, resolve against `root`, as HAWC2
/// resolves them against the folder it is run from.
pub struct HtcFiles<F> {
    pub htc: F,
    pub root: ModelRoot<F>,
    pub body: String,
}

impl<F: TextFile> HtcFiles<F> {
    /// The blade as the htc describes it, its `continue_in_file`s read from the root.
    pub fn model(&self) -> Result<HtcBlade> {
        let name = self.htc.display();
        let text = self.htc.read()?;
        let mut include = |path: &str| {
            let file = self.root.file(path);
            Ok((file.display(), file.read()?))
        };
        let model = htc::parse_htc(&text, &name, &mut include)?;
        htc::blade(&model, &self.body)
    }

    /// The file a statement of the htc names, relative to the root.
    pub fn named(&self, n: &Named) -> F {
        self.root.file(&n.value)
    }
}

/// The half-chord line of a blade's `c2_def`.
pub fn c2_line(blade: &HtcBlade) -> Result<C2Line> {
    C2Line::new(&blade.body.c2_def, &blade.body.c2_file)
}

impl<F: TextFile> BladeFiles for HtcFiles<F> {
    fn read(&self) -> Result<TabulatedBlade> {
        let model = self.model()?;
        let t = &model.body.timoshenko;
        let at_input = |e: Error| {
            Error::format(
                &t.file,
                t.line,
                format!(
                    "timoschenko_input of {}: filename {}: {e}",
                    model.body.name, t.filename
                ),
            )
        };
        let twist = ChordTwist::from_c2_def(&c2_line(&model)?);
        let st = self.root.file(&t.filename);
        let mut blade = read_hawc2(&st, &twist, t.set, t.subset).map_err(at_input)?;
        let fpm_rows = !blade.table.matrices.is_empty();
        if fpm_rows != t.fpm {
            return Err(at_input(Error::format(
                st.display(),
                0,
                format!(
                    "the timoshenko_input says FPM {}, but set {} subset {} holds {} rows",
                    u8::from(t.fpm),
                    t.set,
                    t.subset,
                    if fpm_rows {
                        "fully populated (30-column)"
                    } else {
                        "classic (19-column)"
                    }
                ),
            )));
        }
        if let Some(d) = &model.body.damping {
            blade.damping = htc_damping(d)?;
        }
        blade.files = vec![self.htc.display(), st.display()];
        Ok(blade)
    }
}

/// docs/model.md §11.6: a body's `damping_aniso` or `damping_posdef` as stiffness-proportional
/// damping, `kx` on the bending about `x_c2` (flap, as `E I_x`) and the flapwise shear, `ky` on
/// the edge bending and shear, `kz` on torsion. Mass-proportional terms are not modelled: a body that states them is refused
/// rather than damped otherwise than its file says.
pub fn htc_damping(d: &HtcDamping) -> Result<SourceDamping> {
    if d.mass.iter().any(|&m| m != 0.0) {
        return Err(Error::format(
            &d.file,
            d.line,
            format!(
                "{}: mass-proportional damping (mx my mz = {} {} {}) is not modelled; only the \
                 stiffness-proportional kx ky kz are",
                d.keyword, d.mass[0], d.mass[1], d.mass[2]
            ),
        ));
    }
    if let Some(k) = d.stiffness.iter().find(|&&k| k.is_nan() || k < 0.0) {
        return Err(Error::format(
            &d.file,
            d.line,
            format!(
                "{}: expected stiffness factors kx ky kz ≥ 0, found {k}",
                d.keyword
            ),
        ));
    }
    let [kx, ky, kz] = d.stiffness;
    // The flap bending's factor also damps the flap-direction shear strain that goes with it,
    // the edge's the edgewise shear.
    Ok(SourceDamping::StiffnessProportional(StiffnessFactors {
        shear: [kx, ky],
        flap: kx,
        edge: ky,
        torsion: kz,
    }))
}

/// The BeamDyn primary file, then the blade file its `BldFile` names (relative to it, as
/// BeamDyn resolves it). Errors name the file and line; a file of another known kind says which
/// kind it is and what to do instead.
pub fn read_beamdyn(file: &impl TextFile) -> Result<TabulatedBlade> {
    let name = file.display();
    let text = file.read()?;
    let primary = beamdyn::parse_primary(&text, &name)
        .map_err(|e| misread(&text, &name, BladeFormat::Beamdyn).unwrap_or(e))?;
    let blade_file = file.sibling(&primary.blade_file);
    let blade_name = blade_file.display();
    let blade_text = blade_file.read()?;
    let blade = beamdyn::parse_blade(&blade_text, &blade_name)?;
    let table = from_beamdyn(&primary, &blade, &name, 0.0)?;
    // BeamDyn's mu follow its strain order (shear along x1 = ξ, shear along x2 = η, extension,
    // bending about x1 = edge, bending about x2 = flap, torsion); the beam here has no axial
    // dof, so mu3 has nothing to damp.
    let damping = match blade.damp_type {
        1 => SourceDamping::StiffnessProportional(StiffnessFactors {
            shear: [blade.mu[0], blade.mu[1]],
            flap: blade.mu[4],
            edge: blade.mu[3],
            torsion: blade.mu[5],
        }),
        _ => SourceDamping::None,
    };
    Ok(TabulatedBlade {
        format: BladeFormat::Beamdyn,
        table,
        damping,
        files: vec![name, blade_name],
        layup: None,
    })
}

/// Subset `st_subset` of set `st_set` of a HAWC2 st file, its sections turned by `twist`
/// (docs/model.md §11.6). The st file states no damping: a HAWC2 blade is damped as the preset
/// sets `structure.damping_*`. Errors as [`read_beamdyn`]'s.
pub fn read_hawc2(
    file: &impl TextFile,
    twist: &ChordTwist,
    st_set: usize,
    st_subset: usize,
) -> Result<TabulatedBlade> {
    let name = file.display();
    let text = file.read()?;
    let st = hawc2_st::parse_st(&text, &name)
        .map_err(|e| misread(&text, &name, BladeFormat::Hawc2).unwrap_or(e))?;
    let table = from_hawc2_st(&st, st_set, st_subset, twist, 0.0)?;
    Ok(TabulatedBlade {
        format: BladeFormat::Hawc2,
        table,
        damping: SourceDamping::None,
        files: vec![name],
        layup: None,
    })
}

/// A WindIO blade (docs/model.md §11.12): its parsed file's layup with the ply turn, each
/// station's section analysed; `held`, a blade of the same parsed file analysed before, lends
/// the stations the turn leaves as they were. The file states no damping.
pub struct WindIoFiles<'a> {
    pub windio: Arc<WindIo>,
    pub layup: LayupRequest,
    pub held: Option<&'a LayupBlade>,
}

/// What a preset asks of a WindIO blade's layup beyond its file: a ply turn and a
/// trailing-edge fill.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct LayupRequest {
    pub turn: Option<TurnRequest>,
    pub fill: Option<TrailingEdgeFill>,
}

/// A preset's ply turn: the angle (deg) for the layers named (empty: the spar caps) over the span
/// fractions.
#[derive(Debug, Clone, PartialEq)]
pub struct TurnRequest {
    pub angle_deg: f64,
    pub layers: Vec<String>,
    pub span: [f64; 2],
}

impl BladeFiles for WindIoFiles<'_> {
    fn read(&self) -> Result<TabulatedBlade> {
        let windio = self.windio.clone();
        let name = windio.path.clone();
        let turn = self.layup.turn.as_ref().map(|t| PlyTurn {
            angle: t.angle_deg.to_radians(),
            layers: if t.layers.is_empty() {
                PlyTurn::spar_caps(&windio)
            } else {
                t.layers.clone()
            },
            span: t.span,
        });
        let layup = LayupBlade::new(windio, turn, self.layup.fill.clone(), self.held)?;
        Ok(TabulatedBlade {
            format: BladeFormat::Windio,
            table: layup.table()?,
            damping: SourceDamping::None,
            files: vec![name],
            layup: Some(Arc::new(layup)),
        })
    }
}

/// The chord twist a HAWC2 blade takes from an AeroDyn 15 blade file's `BlTwist`.
pub fn read_twist(file: &impl TextFile) -> Result<ChordTwist> {
    let name = file.display();
    let text = file.read()?;
    let blade = aerodyn::parse_blade(&text, &name)?;
    Ok(ChordTwist::from_aerodyn(&blade))
}

/// When a file does not parse as what `expected` needs, whether it is another kind of blade
/// file this program knows, as an error that says so: an ElastoDyn blade file above all, which
/// has no torsional stiffness and so cannot describe a blade for flutter.
fn misread(text: &str, name: &str, expected: BladeFormat) -> Option<Error> {
    let is = |message: String| Some(Error::format(name, 0, message));
    if elastodyn::parse_blade(text, name).is_ok() {
        return is(
            "this is an ElastoDyn blade file (NBlInpSt, FlpStff, EdgStff): ElastoDyn blade files \
             carry no torsional stiffness, which flutter needs; use the blade's BeamDyn files \
             (blade.source = \"beamdyn\", blade.file = the primary file) or a HAWC2 st file \
             (blade.source = \"hawc2\"), which do"
                .into(),
        );
    }
    match expected {
        BladeFormat::Beamdyn if beamdyn::parse_blade(text, name).is_ok() => is(
            "this is a BeamDyn blade file; blade.file names the BeamDyn primary file, which \
             names this one in its BldFile line"
                .into(),
        ),
        BladeFormat::Beamdyn
            if hawc2_st::parse_st(text, name).is_ok_and(|s| !s.sets.is_empty()) =>
        {
            is("this is a HAWC2 st file: set blade.source = \"hawc2\"".into())
        }
        BladeFormat::Hawc2 if beamdyn::parse_primary(text, name).is_ok() => {
            is("this is a BeamDyn primary file: set blade.source = \"beamdyn\"".into())
        }
        _ => None,
    }
}

/// A tabulated blade's structure at a preset's pitch: the modal basis the analyses work on, and
/// how its modes are damped.
#[derive(Debug, Clone)]
pub struct BladeStructure {
    pub blade: Arc<TabulatedBlade>,
    /// The blade as the elements see it: the file's sections at the preset's hub radius, with
    /// the preset's `blade.bend_twist_coupling` added (docs/model.md §11.7).
    pub table: BladeTable,
    pub modal: Arc<ModalBlade>,
    /// K, the modes retained (`structure.modes`).
    pub count: usize,
    /// Per family, the damping ratio the preset sets (`structure.damping_*`) or the source
    /// states per family ([`family_ratios`]); `None`: the projected ratio of each mode (0
    /// without damping).
    pub ratios: [Option<f64>; 3],
}

/// What a tabulated blade's pitch-range basis is built with besides its files (docs/model.md
/// §11.7–§11.8).
#[derive(Debug, Clone, PartialEq)]
pub struct BasisSettings {
    /// `blade.bend_twist_coupling` α: another α is another blade.
    pub coupling: f64,
    /// r_hub (m): where the files' root sits.
    pub hub_radius: f64,
    /// Fewest finite elements along the span.
    pub min_elements: usize,
    /// Shear-deformable elements where the files give a shear stiffness; `false`: the
    /// Euler–Bernoulli beam, rigid in shear.
    pub shear: bool,
    /// The reference axis the beam is curved along (straight: the pitch axis).
    pub axis: CurvedAxis,
    /// K, the modes retained.
    pub count: usize,
    /// Rotor speeds (rad/s) the basis holds the modes at.
    pub speeds: Vec<f64>,
    /// The pitch range (rad) the basis spans.
    pub pitches: (f64, f64),
}

/// A blade's pitch-range basis: the elements of its table (coupling added, at its hub radius) and
/// the reduced basis over the pitch range and rotor speeds.
pub fn pitch_range_basis(
    blade: &TabulatedBlade,
    s: &BasisSettings,
) -> Result<(BladeTable, PitchRangeBlade)> {
    let coupled = with_bend_twist_coupling(&blade.table, s.coupling);
    let table = BladeTable::new(&coupled.origin, s.hub_radius, coupled.sections)?
        .with_matrices(coupled.matrices)?;
    let table = if s.shear {
        table
    } else {
        table.rigid_in_shear()
    }
    .with_axis(s.axis.clone());
    let mesh = Mesh::following(&table, s.min_elements);
    let (low, high) = s.pitches;
    let damping = match blade.damping {
        SourceDamping::StiffnessProportional(f) => Some(f),
        _ => None,
    };
    let modal = PitchRangeBlade::new(
        &table,
        &mesh,
        &snapshot_pitches(low, high),
        &s.speeds,
        s.count,
        damping,
    )?;
    Ok((table, modal))
}

/// Per family, the ratio that replaces a mode's projected damping: the one `set` gives (a
/// preset's `structure.damping_*`), else the source's per-family ratio if it states one.
pub fn family_ratios(set: [Option<f64>; 3], damping: SourceDamping) -> [Option<f64>; 3] {
    let stated = match damping {
        SourceDamping::PerFamily(r) => r.map(Some),
        _ => [None; 3],
    };
    [0, 1, 2].map(|k| set[k].or(stated[k]))
}

impl BladeStructure {
    /// The first K modes at rotor speed `omega` (rad/s), ascending, each with its damping
    /// ratio: the family's when the preset or the source sets one, else its projection.
    pub fn modes(&self, omega: f64) -> Result<Vec<BladeMode>> {
        let mut modes = self.modal.modes(omega, self.count)?;
        self.damp(&mut modes);
        Ok(modes)
    }

    /// The first K modes at rotor speed `omega` (rad/s), as [`BladeStructure::modes`], and the
    /// rest of the reduced basis's modes there, ascending: the modes the K coordinates leave
    /// out, whose static response corrects the truncated basis (docs/model.md §12.6).
    pub fn retained_and_left_out(&self, omega: f64) -> Result<(Vec<BladeMode>, Vec<BladeMode>)> {
        let mut modes = self.modal.modes(omega, self.modal.basis_size())?;
        let left_out = modes.split_off(self.count.min(modes.len()));
        self.damp(&mut modes);
        Ok((modes, left_out))
    }

    fn damp(&self, modes: &mut [BladeMode]) {
        for m in modes {
            if let Some(ratio) = self.ratios[m.family().index()] {
                m.damping_ratio = ratio;
            }
        }
    }

    /// Finite elements along the span.
    pub fn elements(&self) -> usize {
        self.modal.geometry.mesh.elements()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A preset's `structure.damping_*` wins over a source's per-family ratio, family by family;
    /// without either a family keeps each mode's projection (`None`).
    #[test]
    fn family_ratios_take_the_preset_then_the_source() {
        let set = [None, Some(0.05), None];
        let stated = SourceDamping::PerFamily([0.01, 0.02, 0.03]);
        assert_eq!(
            family_ratios(set, stated),
            [Some(0.01), Some(0.05), Some(0.03)]
        );
        let mu = SourceDamping::StiffnessProportional(StiffnessFactors {
            shear: [1e-3, 1e-3],
            flap: 1e-3,
            edge: 1e-3,
            torsion: 1e-3,
        });
        assert_eq!(family_ratios(set, mu), [None, Some(0.05), None]);
        assert_eq!(
            family_ratios(set, SourceDamping::None),
            [None, Some(0.05), None]
        );
    }
}
