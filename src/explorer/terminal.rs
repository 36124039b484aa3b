//! The only code that touches the terminal: raw mode and the alternate screen (restored on every
//! exit path, panics included), the input thread, and the event loop that feeds [`update`] from
//! the keyboard and the worker and draws at most `fps` frames a second, only when something
//! changed. Idle (paused, no input), the loop blocks on its channel: no redraws, no polling.
//!
//! Nothing here queries the terminal (no cursor-position or capability requests that could stall
//! a slow link); the window size comes from the ioctl that `Terminal::draw` already does.

use crate::error::{Error, Result};
use crate::explorer::engine::Engine;
use crate::explorer::keys::action_for;
use crate::explorer::state::update::update;
use crate::explorer::state::{AppState, Effect, Msg};
use crate::explorer::worker::Worker;
use crossbeam_channel::{unbounded, Receiver, RecvTimeoutError, Sender};
use crossterm::cursor::{Hide, Show};
use crossterm::event::{self, Event};
use crossterm::terminal::{
    disable_raw_mode, enable_raw_mode, BeginSynchronizedUpdate, EndSynchronizedUpdate,
    EnterAlternateScreen, LeaveAlternateScreen,
};
use crossterm::{execute, queue};
use ratatui::backend::CrosstermBackend;
use ratatui::Terminal;
use std::io::{stdout, Stdout, Write};
use std::sync::Arc;
use std::time::{Duration, Instant};

/// Messages handled before a frame is considered again, so a flood of events cannot starve the
/// screen.
const MAX_BATCH: usize = 256;

/// Leave raw mode and the alternate screen, show the cursor. Safe to call more than once.
pub fn restore() {
    let _ = disable_raw_mode();
    let _ = execute!(stdout(), LeaveAlternateScreen, Show);
}

/// Restores the terminal when dropped (normal return, `?` errors, unwinding panics).
struct Guard;

impl Drop for Guard {
    fn drop(&mut self) {
        restore();
    }
}

impl Guard {
    fn enter() -> std::io::Result<Guard> {
        install_panic_hook();
        // Created first, so a failure half-way still restores what was changed.
        let guard = Guard;
        enable_raw_mode()?;
        execute!(stdout(), EnterAlternateScreen, Hide)?;
        Ok(guard)
    }
}

/// A panic on the UI thread (the one installing the hook) restores the terminal before the
/// message is printed (so it is readable). Panics anywhere else (the worker threads and the
/// thread pools their parallel loops run on) are caught by the worker and shown in the status
/// line; they must not print over the screen or restore the terminal under the running explorer.
fn install_panic_hook() {
    let previous = std::panic::take_hook();
    let ui = std::thread::current().id();
    std::panic::set_hook(Box::new(move |info| {
        if std::thread::current().id() != ui {
            return;
        }
        restore();
        previous(info);
    }));
}

/// Read terminal events and forward the ones the explorer uses.
fn spawn_input(tx: Sender<Msg>) -> std::io::Result<()> {
    std::thread::Builder::new()
        .name("flutterscope-input".into())
        .spawn(move || loop {
            let msg = match event::read() {
                Ok(Event::Key(key)) => match action_for(&key) {
                    Some(a) => Msg::Action(a),
                    None => continue,
                },
                Ok(Event::Resize(..)) => Msg::Resize,
                Ok(_) => continue,
                Err(e) => {
                    let _ = tx.send(Msg::InputClosed(e.to_string()));
                    return;
                }
            };
            if tx.send(msg).is_err() {
                return;
            }
        })
        .map(|_| ())
}

fn draw(
    terminal: &mut Terminal<CrosstermBackend<Stdout>>,
    state: &AppState,
) -> std::io::Result<()> {
    queue!(terminal.backend_mut(), BeginSynchronizedUpdate)?;
    terminal.draw(|f| crate::explorer::ui::render(state, f))?;
    execute!(terminal.backend_mut(), EndSynchronizedUpdate)?;
    terminal.backend_mut().flush()
}

/// How often a running solve's time is told to the state once it is over its budget.
const SOLVE_CLOCK: Duration = Duration::from_millis(250);

/// Handle one message: update the state, hand its effects to the worker, and note when the
/// newest solve was asked for (`solve_sent`), to report a slow one.
fn handle(state: &mut AppState, worker: &mut Worker, solve_sent: &mut (u64, Instant), msg: Msg) {
    for effect in update(state, msg) {
        dispatch(worker, solve_sent, effect);
    }
}

/// Hand one effect to the worker, noting when a solve was asked for.
fn dispatch(worker: &mut Worker, solve_sent: &mut (u64, Instant), effect: Effect) {
    if let Effect::Solve { gen, .. } = &effect {
        *solve_sent = (*gen, Instant::now());
    }
    worker.send(effect);
}

/// Run the explorer until the user quits. The caller has checked that stdin and stdout are
/// terminals.
pub fn run(mut state: AppState, engine: Arc<dyn Engine>, fps: u32) -> Result<()> {
    let io = |what: &str, e: std::io::Error| Error::Io(format!("terminal: {what}: {e}"));
    let frame_interval = Duration::from_secs_f64(1.0 / f64::from(fps.max(1)));
    let (tx, rx): (Sender<Msg>, Receiver<Msg>) = unbounded();
    let guard = Guard::enter().map_err(|e| io("cannot enter raw mode", e))?;
    let mut terminal =
        Terminal::new(CrosstermBackend::new(stdout())).map_err(|e| io("cannot start", e))?;
    spawn_input(tx.clone()).map_err(|e| io("cannot start the input thread", e))?;
    let mut worker = Worker::spawn(engine, tx, frame_interval);
    let mut solve_sent = (0, Instant::now());
    for effect in state.start() {
        dispatch(&mut worker, &mut solve_sent, effect);
    }
    let mut last_draw: Option<Instant> = None;
    let outcome = loop {
        if state.quit {
            break Ok(());
        }
        // Wait for a message; when a frame is due, no longer than until it is.
        let first = if state.dirty {
            let wait = last_draw
                .map(|t| frame_interval.saturating_sub(t.elapsed()))
                .unwrap_or(Duration::ZERO);
            if wait.is_zero() {
                if let Err(e) = draw(&mut terminal, &state) {
                    break Err(io("cannot draw", e));
                }
                state.dirty = false;
                last_draw = Some(Instant::now());
                continue;
            }
            match rx.recv_timeout(wait) {
                Ok(m) => m,
                Err(RecvTimeoutError::Timeout) => continue,
                Err(RecvTimeoutError::Disconnected) => break Ok(()),
            }
        } else if state.solving() {
            // Idle but for a solve in flight: wake up to report its time if it runs long.
            match rx.recv_timeout(SOLVE_CLOCK) {
                Ok(m) => m,
                Err(RecvTimeoutError::Timeout) => Msg::SolveTime {
                    gen: solve_sent.0,
                    seconds: solve_sent.1.elapsed().as_secs_f64(),
                },
                Err(RecvTimeoutError::Disconnected) => break Ok(()),
            }
        } else {
            match rx.recv() {
                Ok(m) => m,
                Err(_) => break Ok(()),
            }
        };
        handle(&mut state, &mut worker, &mut solve_sent, first);
        for m in rx.try_iter().take(MAX_BATCH) {
            handle(&mut state, &mut worker, &mut solve_sent, m);
            if state.quit {
                break;
            }
        }
    };
    worker.send(Effect::Quit);
    drop(terminal);
    drop(guard);
    outcome?;
    match state.exit_error.take() {
        Some(e) => Err(Error::Io(format!("terminal input failed: {e}"))),
        None => Ok(()),
    }
}
