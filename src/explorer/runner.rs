//! Carrying out effects through an [`Engine`]: the one place that turns an effect into the
//! messages it produces. The worker threads (real time) and the headless explorer (snapshots,
//! tests, benchmarks) both run effects through these functions; only when they run differs.
//!
//! Every engine call runs under `catch_unwind`: an error or a panic becomes an `Err` that the
//! status line shows, and the caller keeps serving.

use crate::analysis::cancel::Cancel;
use crate::explorer::engine::{Engine, Stream};
use crate::explorer::state::{Check, Effect, Msg};
use crate::preset::ValidPreset;
use std::panic::{catch_unwind, AssertUnwindSafe};

/// The text of a caught panic.
pub fn panic_text(payload: &(dyn std::any::Any + Send)) -> String {
    if let Some(s) = payload.downcast_ref::<&str>() {
        (*s).to_string()
    } else if let Some(s) = payload.downcast_ref::<String>() {
        s.clone()
    } else {
        "unknown panic".to_string()
    }
}

/// Run an engine call; errors and panics become the message shown to the user.
pub fn guarded<T>(what: &str, f: impl FnOnce() -> crate::error::Result<T>) -> Result<T, String> {
    match catch_unwind(AssertUnwindSafe(f)) {
        Ok(Ok(v)) => Ok(v),
        Ok(Err(e)) => Err(format!("{what}: {e}")),
        Err(payload) => Err(format!("{what} panicked: {}", panic_text(&*payload))),
    }
}

/// Solve `preset`: the [`Msg::Solved`] for the state, and the tip simulation started from the
/// same build, or the [`Msg::SimFailed`] saying why there is none.
pub fn solve(
    engine: &dyn Engine,
    gen: u64,
    preset: &ValidPreset,
    cancel: &Cancel,
) -> (Msg, Result<Box<dyn Stream>, Msg>) {
    match guarded("solve", || Ok(engine.solve(preset, cancel))) {
        Ok(s) => (
            Msg::Solved {
                gen,
                result: s.solved.map_err(|e| format!("solve: {e}")),
            },
            s.stream.map_err(|e| Msg::SimFailed {
                gen,
                error: format!("simulation: {e}"),
            }),
        ),
        // A panic: neither the analysis nor the stream exists.
        Err(error) => (
            Msg::Solved {
                gen,
                result: Err(error.clone()),
            },
            Err(Msg::SimFailed { gen, error }),
        ),
    }
}

/// Carry out a check: the preset it gives, or why not, as the [`Msg::Checked`] of `id`.
pub fn check(id: u64, check: &Check) -> Msg {
    let result = match check {
        Check::Edit { base, key, value } => guarded(&format!("{key} = {value}"), || {
            base.with(key, *value).map(Box::new)
        }),
        Check::Open { name, .. } => guarded(&format!("preset {name}"), || {
            crate::preset::Preset::load(name, &[]).map(Box::new)
        }),
    };
    Msg::Checked { id, result }
}

/// The next `samples` samples of a simulation as a [`Msg::Samples`], or the [`Msg::SimFailed`]
/// that ends it.
pub fn advance(stream: &mut dyn Stream, gen: u64, samples: usize) -> Msg {
    match guarded("simulation", || {
        let out = stream.advance(samples)?;
        Ok((out, stream.status()))
    }) {
        Ok((samples, status)) => Msg::Samples {
            gen,
            samples,
            status,
        },
        Err(error) => Msg::SimFailed { gen, error },
    }
}

/// Kick a running simulation; a failure ends it with this message.
pub fn kick(stream: &mut dyn Stream, gen: u64, twist_rad: f64, flap_m: f64) -> Option<Msg> {
    guarded("kick", || {
        stream.kick(twist_rad, flap_m);
        Ok(())
    })
    .err()
    .map(|error| Msg::SimFailed { gen, error })
}

/// Run a background job (a boundary search or a Campbell sweep) to its result message; `None`
/// for effects that are not jobs.
pub fn job(engine: &dyn Engine, effect: &Effect, cancel: &Cancel) -> Option<Msg> {
    match effect {
        Effect::Boundary {
            gen,
            key,
            preset,
            ranges,
        } => Some(Msg::Boundary {
            gen: *gen,
            key: key.to_string(),
            // One search per range (a margin on both sides of the current value has two).
            result: guarded("boundary search", || {
                ranges
                    .iter()
                    .map(|range| engine.boundary(preset, range, cancel))
                    .collect()
            }),
        }),
        Effect::Campbell {
            gen,
            preset,
            key,
            grid,
        } => Some(Msg::Campbell {
            gen: *gen,
            result: guarded("Campbell sweep", || {
                engine.campbell(preset, key, grid, cancel)
            }),
        }),
        _ => None,
    }
}
