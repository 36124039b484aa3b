//! The command line: one clap definition for every subcommand. Parsing only; each command's
//! work lives in `commands/`.

use crate::explorer::display::{ColorMode, MarkerKind, ViewKind};
use clap::builder::PossibleValue;
use clap::{Args, Parser, Subcommand, ValueEnum};

#[derive(Debug, Parser)]
#[command(
    name = "flutterscope",
    version,
    about = "Aeroelastic stability of rotating composite wind-turbine blades: classical and stall flutter",
    long_about = "Aeroelastic stability of rotating composite wind-turbine blades with bending–torsion \
coupling. With no subcommand in a terminal, opens the interactive explorer (the options below are \
the explorer's, as for `flutterscope tui`); the headless subcommands run the same engine for scripts.",
    args_conflicts_with_subcommands = true
)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Option<Command>,
    /// The explorer's options when no subcommand is given.
    #[command(flatten)]
    pub explorer: TuiArgs,
}

/// What the explorer opens on and how it draws (`flutterscope tui`, or no subcommand).
#[derive(Debug, Clone, Args)]
pub struct TuiArgs {
    #[command(flatten)]
    pub preset: PresetArgs,
    #[command(flatten)]
    pub display: DisplayArgs,
    /// Frame-rate cap (frames per second); frames are drawn only when something changed.
    #[arg(long, default_value_t = 20, value_parser = clap::value_parser!(u32).range(1..=120))]
    pub fps: u32,
}

/// Which preset to start from and what to change in it.
#[derive(Debug, Clone, Args)]
pub struct PresetArgs {
    /// Built-in preset name (see `flutterscope presets`) or path to a .toml file.
    #[arg(long, short = 'p', default_value = crate::preset::DEFAULT_PRESET, value_name = "NAME|PATH")]
    pub preset: String,
    /// Override a preset key, e.g. --set section.ply_angle=30 (repeatable).
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub set: Vec<String>,
}

impl PresetArgs {
    /// The preset after `--set`, every key set one the model uses for this blade
    /// ([`crate::preset::Preset::acts`]).
    pub fn load(&self) -> crate::error::Result<crate::preset::ValidPreset> {
        let p = self.load_for_layup()?;
        p.overrides_act(&self.set)?;
        Ok(p)
    }

    /// The preset after `--set`, any key allowed: for `section`, which evaluates the layup
    /// whatever the blade uses.
    pub fn load_for_layup(&self) -> crate::error::Result<crate::preset::ValidPreset> {
        load_preset(&self.preset, &self.set)
    }
}

/// A preset by name or path after `--set` overrides, its notes (what the overrides left unused)
/// on stderr.
pub fn load_preset(
    name: &str,
    overrides: &[String],
) -> crate::error::Result<crate::preset::ValidPreset> {
    let p = crate::preset::Preset::load(name, overrides)?;
    for note in &p.notes {
        eprintln!("note: {note}");
    }
    Ok(p)
}

/// The explorer's display settings as command-line values, named as the explorer names them.
macro_rules! value_enum {
    ($($ty:ty),+) => {$(
        impl ValueEnum for $ty {
            fn value_variants<'a>() -> &'a [Self] {
                &<$ty>::ALL
            }
            fn to_possible_value(&self) -> Option<PossibleValue> {
                Some(PossibleValue::new(self.name()))
            }
        }
    )+};
}

value_enum!(ColorMode, MarkerKind, ViewKind);

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum Reproduction {
    Table1,
    Table2,
    Fig2,
    Fig3,
    Fig4,
    Fig5,
}

#[derive(Debug, Clone, Args)]
pub struct DisplayArgs {
    /// Colour depth; 16 colours is safe over any SSH link.
    #[arg(long, value_enum, default_value = "16")]
    pub color: ColorMode,
    /// Plot marker: braille (finest), or halfblock/block/dot for terminals or fonts without braille.
    #[arg(long, value_enum, default_value = "braille")]
    pub marker: MarkerKind,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Open the interactive explorer (the default in a terminal).
    Tui(TuiArgs),
    /// Natural modes of the blade structure (no aerodynamics): frequency, family, shares,
    /// damping ratio.
    Modes {
        #[command(flatten)]
        preset: PresetArgs,
        /// Machine-readable output.
        #[arg(long)]
        json: bool,
        /// Also give each mode's shape along the span (flap, edge, twist).
        #[arg(long)]
        shapes: bool,
        /// Plot the mode shapes (SVG or PNG by extension).
        #[arg(long, value_name = "FILE")]
        plot: Option<std::path::PathBuf>,
    },
    /// Eigenvalues of the linearised aeroelastic system and the stability verdict.
    Eigen {
        #[command(flatten)]
        preset: PresetArgs,
        #[arg(long)]
        json: bool,
    },
    /// Steady operating point of the rotor (BEM on the blade in its static aeroelastic
    /// equilibrium): power, thrust, torque, tip speed ratio, tip deflection and the flow at every
    /// station; with --vary, power and thrust curves.
    Operating {
        #[command(flatten)]
        preset: PresetArgs,
        /// KEY=FROM:TO:STEP, e.g. operating.wind_speed=3:25:1 (along operating.schedule).
        #[arg(long, value_name = "KEY=A:B:STEP")]
        vary: Option<String>,
        #[arg(long, conflicts_with = "csv")]
        json: bool,
        /// CSV: the stations (one point) or the curve (with --vary, the default then).
        #[arg(long)]
        csv: bool,
        /// Plot the power and thrust curves (needs --vary; SVG or PNG by extension).
        #[arg(long, value_name = "FILE")]
        plot: Option<std::path::PathBuf>,
    },
    /// Flutter (or divergence) boundary along one numeric preset key.
    Flutter {
        #[command(flatten)]
        preset: PresetArgs,
        /// The key to vary, e.g. operating.rotor_speed.
        #[arg(long, value_name = "KEY")]
        vary: String,
        /// Start of the search range [default: the preset's value of KEY, the schedule's for a
        /// scheduled rotor speed or pitch].
        #[arg(long, allow_negative_numbers = true)]
        from: Option<f64>,
        /// End of the search range [default: the top of KEY's range, as the explorer's slider
        /// has it: `view.rotor_speed_max` for the rotor speed, cut-out for the wind on a
        /// schedule, the key table's maximum otherwise].
        #[arg(long, allow_negative_numbers = true)]
        to: Option<f64>,
        /// Grid points used to bracket the crossing before refinement (2 to 10000).
        #[arg(long, default_value_t = 41, value_parser = clap::value_parser!(u32).range(2..=10_000))]
        points: u32,
        #[arg(long)]
        json: bool,
        /// Write a plot (SVG or PNG by extension).
        #[arg(long, value_name = "FILE")]
        plot: Option<std::path::PathBuf>,
    },
    /// Tracked modes' frequency and damping over a grid of one or more keys.
    Sweep {
        #[command(flatten)]
        preset: PresetArgs,
        /// KEY=FROM:TO:STEP, repeatable (the grid is their product).
        #[arg(long, value_name = "KEY=A:B:STEP", required = true)]
        vary: Vec<String>,
        /// CSV output (the default).
        #[arg(long, conflicts_with = "json")]
        csv: bool,
        #[arg(long)]
        json: bool,
        /// Compute slice I of N (1-based) of the grid, for batch schedulers; `auto` takes it
        /// from a Slurm array job: task k of SLURM_ARRAY_TASK_COUNT in index order computes
        /// slice k, counted from SLURM_ARRAY_TASK_MIN (default 0) in steps of
        /// SLURM_ARRAY_TASK_STEP (default 1; 0 is refused) to SLURM_ARRAY_TASK_ID.
        #[arg(long, value_name = "I/N|auto")]
        shard: Option<String>,
        /// Write a plot (SVG or PNG by extension).
        #[arg(long, value_name = "FILE")]
        plot: Option<std::path::PathBuf>,
    },
    /// Time response of the blade tip (twist and flap).
    Simulate {
        #[command(flatten)]
        preset: PresetArgs,
        #[arg(long, conflicts_with = "csv")]
        json: bool,
        #[arg(long)]
        csv: bool,
        #[arg(long, value_name = "FILE")]
        plot: Option<std::path::PathBuf>,
    },
    /// Cross-section stiffness and mass properties (laminate, contour).
    Section {
        #[command(flatten)]
        preset: PresetArgs,
        /// Tabulate over a key, e.g. section.ply_angle=0:90:15.
        #[arg(long, value_name = "KEY=A:B:STEP", conflicts_with = "at")]
        vary: Option<String>,
        /// A WindIO blade's section at this span fraction, from its layup (e.g. 0.7).
        #[arg(long, value_name = "ETA")]
        at: Option<f64>,
        #[arg(long)]
        json: bool,
        #[arg(long, value_name = "FILE")]
        plot: Option<std::path::PathBuf>,
    },
    /// Reproduce the source paper's tables and figures beside our numbers.
    Reproduce {
        #[arg(value_enum)]
        what: Reproduction,
        #[arg(long)]
        json: bool,
        #[arg(long, value_name = "FILE")]
        plot: Option<std::path::PathBuf>,
    },
    /// Render one explorer frame as text, after the worker has finished (deterministic).
    Snapshot {
        #[command(flatten)]
        preset: PresetArgs,
        /// Frame size COLSxROWS.
        #[arg(long, default_value = "120x40")]
        size: String,
        #[arg(long, value_enum, default_value = "main")]
        view: ViewKind,
        #[arg(long, value_enum, default_value = "braille")]
        marker: MarkerKind,
    },
    /// List the built-in presets, or print one in full.
    Presets {
        #[arg(long)]
        json: bool,
        /// The preset to print in full, as --show does (`flutterscope presets iea15mw`).
        #[arg(value_name = "NAME|PATH", group = "shown", conflicts_with = "json")]
        preset: Option<String>,
        /// Print this preset (built-in name or path) as TOML with every key, defaults included,
        /// after --set overrides: what the engine actually uses.
        #[arg(
            long,
            value_name = "NAME|PATH",
            group = "shown",
            conflicts_with = "json"
        )]
        show: Option<String>,
        /// Override a key of the shown preset (repeatable; needs a preset to show).
        #[arg(long = "set", value_name = "KEY=VALUE", requires = "shown")]
        set: Vec<String>,
    },
}
