//! The background threads that own the solver. The event loop sends [`Effect`]s; results come back
//! as [`Msg`]s on the loop's channel.
//!
//! Two threads, so a slow boundary search or Campbell sweep never delays the next solve:
//! - the **solver** solves the latest parameters (pending requests are drained and only the newest
//!   is solved), then restarts the tip simulation from them and streams sample batches in real
//!   time, at most one batch per frame interval; paused, or after the response diverged, it blocks
//!   on its channel (no polling). It also runs the latest check of a preset whose blade is
//!   analysed again (a WindIO ply angle) or that is opened for the first time, so the event loop
//!   never waits for one;
//! - the **jobs** thread runs the latest boundary search and the latest Campbell sweep, once the
//!   requests have settled for a moment, on its own thread pool.
//!
//! Effects become messages through [`crate::explorer::runner`] (errors and panics included), as
//! in the headless explorer. If a thread dies anyway, the next send spawns it again and the state
//! is told.

use crate::analysis::cancel::Cancel;
use crate::analysis::simulate::RunStatus;
use crate::explorer::engine::{Engine, Stream};
use crate::explorer::runner;
use crate::explorer::state::{Check, Effect, Msg};
use crate::preset::ValidPreset;
use crossbeam_channel::{unbounded, Receiver, RecvTimeoutError, Sender};
use std::sync::Arc;
use std::time::{Duration, Instant};

/// Thread names (the jobs' pool threads take the jobs thread's with a number), as a debugger or
/// `top -H` shows them.
pub const SOLVER_THREAD: &str = "flutterscope-solver";
pub const JOBS_THREAD: &str = "flutterscope-jobs";

/// Longest stretch of simulated time caught up in one batch (after a stall or a slow frame), so a
/// hiccup never turns into a burst of work.
const MAX_CATCH_UP_S: f64 = 0.25;

/// Quiet time before a background job starts: requests arriving within it replace the pending
/// one (a held key sends one per solve).
const JOB_SETTLE: Duration = Duration::from_millis(120);

enum SolverReq {
    Solve {
        gen: u64,
        preset: Arc<ValidPreset>,
        cancel: Cancel,
    },
    Kick {
        gen: u64,
        twist: f64,
        flap: f64,
    },
    Check {
        id: u64,
        check: Check,
    },
    Pause(bool),
    Quit,
}

/// Handle to the worker threads.
pub struct Worker {
    engine: Arc<dyn Engine>,
    out: Sender<Msg>,
    batch_interval: Duration,
    solver: Sender<SolverReq>,
    jobs: Sender<(Effect, Cancel)>,
    /// The last solve and pause requests, re-sent to a restarted solver.
    last_solve: Option<(u64, Arc<ValidPreset>)>,
    paused: bool,
    /// Flags of the requests in flight: a newer request of the same kind raises the older one's,
    /// so the thread on it moves on at its next check instead of finishing stale work.
    solve_cancel: Cancel,
    boundary_cancel: Cancel,
    campbell_cancel: Cancel,
}

impl Worker {
    /// Start the threads. Results go to `out`; sample batches are at most one per
    /// `batch_interval` (the frame interval).
    pub fn spawn(engine: Arc<dyn Engine>, out: Sender<Msg>, batch_interval: Duration) -> Worker {
        let solver = spawn_solver(engine.clone(), out.clone(), batch_interval, false);
        let jobs = spawn_jobs(engine.clone(), out.clone());
        Worker {
            engine,
            out,
            batch_interval,
            solver,
            jobs,
            last_solve: None,
            paused: false,
            solve_cancel: Cancel::never(),
            boundary_cancel: Cancel::never(),
            campbell_cancel: Cancel::never(),
        }
    }

    /// Carry out one effect.
    pub fn send(&mut self, effect: Effect) {
        match effect {
            Effect::Solve { gen, preset } => {
                self.last_solve = Some((gen, preset.clone()));
                // New parameters: the solve and the boundary search of the old ones are stale
                // (the Campbell diagram may not be: it is kept while only the rotor speed moves).
                self.solve_cancel.cancel();
                self.boundary_cancel.cancel();
                self.solve_cancel = Cancel::new();
                let cancel = self.solve_cancel.clone();
                self.send_solver(SolverReq::Solve {
                    gen,
                    preset,
                    cancel,
                });
            }
            Effect::Kick {
                gen,
                twist_rad,
                flap_m,
            } => self.send_solver(SolverReq::Kick {
                gen,
                twist: twist_rad,
                flap: flap_m,
            }),
            Effect::Check { id, check } => self.send_solver(SolverReq::Check { id, check }),
            Effect::Pause(p) => {
                self.paused = p;
                self.send_solver(SolverReq::Pause(p));
            }
            // Background jobs travel as the effects themselves.
            job @ Effect::Boundary { .. } => {
                self.boundary_cancel.cancel();
                self.boundary_cancel = Cancel::new();
                let cancel = self.boundary_cancel.clone();
                self.send_jobs(job, cancel);
            }
            job @ Effect::Campbell { .. } => {
                self.campbell_cancel.cancel();
                self.campbell_cancel = Cancel::new();
                let cancel = self.campbell_cancel.clone();
                self.send_jobs(job, cancel);
            }
            Effect::Quit => {
                for c in [
                    &self.solve_cancel,
                    &self.boundary_cancel,
                    &self.campbell_cancel,
                ] {
                    c.cancel();
                }
                let _ = self.solver.send(SolverReq::Quit);
                let _ = self.jobs.send((Effect::Quit, Cancel::never()));
            }
        }
    }

    fn send_solver(&mut self, req: SolverReq) {
        if let Err(failed) = self.solver.send(req) {
            let _ = self.out.send(Msg::WorkerFailed(
                "the solver thread stopped; restarted it".into(),
            ));
            self.solver = spawn_solver(
                self.engine.clone(),
                self.out.clone(),
                self.batch_interval,
                self.paused,
            );
            let req = failed.into_inner();
            if !matches!(req, SolverReq::Solve { .. }) {
                if let Some((gen, preset)) = self.last_solve.clone() {
                    self.solve_cancel = Cancel::new();
                    let cancel = self.solve_cancel.clone();
                    let _ = self.solver.send(SolverReq::Solve {
                        gen,
                        preset,
                        cancel,
                    });
                }
            }
            let _ = self.solver.send(req);
        }
    }

    fn send_jobs(&mut self, req: Effect, cancel: Cancel) {
        if let Err(failed) = self.jobs.send((req, cancel)) {
            let _ = self.out.send(Msg::WorkerFailed(
                "the background-job thread stopped; restarted it".into(),
            ));
            self.jobs = spawn_jobs(self.engine.clone(), self.out.clone());
            let _ = self.jobs.send(failed.into_inner());
        }
    }
}

fn spawn_solver(
    engine: Arc<dyn Engine>,
    out: Sender<Msg>,
    batch_interval: Duration,
    paused: bool,
) -> Sender<SolverReq> {
    let (tx, rx) = unbounded();
    let spawned = std::thread::Builder::new()
        .name(SOLVER_THREAD.into())
        .spawn(move || {
            let mut solver = Solver {
                engine,
                out,
                batch_interval,
                paused,
                sim: None,
            };
            solver.run(&rx);
        });
    if let Err(e) = spawned {
        // The receiver is gone with the closure: the next send fails and retries the spawn.
        eprintln!("flutterscope: cannot start the solver thread: {e}");
    }
    tx
}

fn spawn_jobs(engine: Arc<dyn Engine>, out: Sender<Msg>) -> Sender<Job> {
    let (tx, rx) = unbounded();
    let spawned = std::thread::Builder::new()
        .name(JOBS_THREAD.into())
        .spawn(move || {
            // The jobs' parallel loops get their own threads: in the shared pool a search's
            // long tasks would queue ahead of the solver's, and a key would wait for them.
            match rayon::ThreadPoolBuilder::new()
                .thread_name(|i| format!("{JOBS_THREAD}-{i}"))
                .build()
            {
                Ok(pool) => pool.install(|| run_jobs(&*engine, &out, &rx)),
                Err(_) => run_jobs(&*engine, &out, &rx),
            }
        });
    if let Err(e) = spawned {
        eprintln!("flutterscope: cannot start the background-job thread: {e}");
    }
    tx
}

/// The running tip simulation.
struct Sim {
    gen: u64,
    stream: Box<dyn Stream>,
    sample_rate: f64,
    /// Samples owed but not yet produced (fractional part carried).
    owed: f64,
    last_tick: Instant,
    done: bool,
}

struct Solver {
    engine: Arc<dyn Engine>,
    out: Sender<Msg>,
    batch_interval: Duration,
    paused: bool,
    sim: Option<Sim>,
}

impl Solver {
    fn streaming(&self) -> bool {
        !self.paused && self.sim.as_ref().is_some_and(|s| !s.done)
    }

    fn run(&mut self, rx: &Receiver<SolverReq>) {
        loop {
            // Wait: for a request, or for the next batch when streaming.
            let first = if self.streaming() {
                match rx.recv_timeout(self.batch_interval) {
                    Ok(r) => Some(r),
                    Err(RecvTimeoutError::Timeout) => None,
                    Err(RecvTimeoutError::Disconnected) => return,
                }
            } else {
                match rx.recv() {
                    Ok(r) => Some(r),
                    Err(_) => return,
                }
            };
            let mut reqs: Vec<SolverReq> = first.into_iter().collect();
            reqs.extend(rx.try_iter());
            // Latest wins: only the newest solve and the newest check run; kicks meant for a
            // replaced simulation go.
            let newest = reqs
                .iter()
                .rposition(|r| matches!(r, SolverReq::Solve { .. }));
            let newest_check = reqs
                .iter()
                .rposition(|r| matches!(r, SolverReq::Check { .. }));
            for (i, req) in reqs.into_iter().enumerate() {
                match req {
                    SolverReq::Quit => return,
                    SolverReq::Pause(p) => {
                        self.paused = p;
                        if let Some(sim) = self.sim.as_mut() {
                            sim.last_tick = Instant::now();
                        }
                    }
                    SolverReq::Solve {
                        gen,
                        preset,
                        cancel,
                    } if Some(i) == newest => self.solve(gen, &preset, &cancel),
                    SolverReq::Solve { .. } => {}
                    SolverReq::Check { id, check } if Some(i) == newest_check => {
                        if self.out.send(runner::check(id, &check)).is_err() {
                            return;
                        }
                    }
                    SolverReq::Check { .. } => {}
                    SolverReq::Kick { gen, twist, flap } => {
                        if newest.is_some_and(|n| i < n) {
                            continue;
                        }
                        if let Some(sim) = self.sim.as_mut().filter(|s| s.gen == gen) {
                            if let Some(failed) = runner::kick(&mut *sim.stream, gen, twist, flap) {
                                let _ = self.out.send(failed);
                                self.sim = None;
                            }
                        }
                    }
                }
            }
            self.stream_batch();
        }
    }

    fn solve(&mut self, gen: u64, preset: &ValidPreset, cancel: &Cancel) {
        let (solved, stream) = runner::solve(&*self.engine, gen, preset, cancel);
        if cancel.is_cancelled() {
            // A newer request is already in the channel; this result is stale.
            return;
        }
        if self.out.send(solved).is_err() {
            return;
        }
        self.sim = match stream {
            Ok(stream) => Some(Sim {
                gen,
                stream,
                sample_rate: preset.simulation.sample_rate,
                owed: 0.0,
                last_tick: Instant::now(),
                done: false,
            }),
            Err(failed) => {
                let _ = self.out.send(failed);
                None
            }
        };
    }

    /// Produce the samples owed since the last batch (real time), if streaming.
    fn stream_batch(&mut self) {
        if !self.streaming() {
            return;
        }
        let Some(sim) = self.sim.as_mut() else {
            return;
        };
        let now = Instant::now();
        let elapsed = now.duration_since(sim.last_tick).as_secs_f64();
        if elapsed < self.batch_interval.as_secs_f64() * 0.5 {
            return;
        }
        sim.last_tick = now;
        sim.owed += elapsed.min(MAX_CATCH_UP_S) * sim.sample_rate;
        let n = sim.owed.floor() as usize;
        if n == 0 {
            return;
        }
        sim.owed -= n as f64;
        let msg = runner::advance(&mut *sim.stream, sim.gen, n);
        match &msg {
            Msg::Samples { status, .. } => sim.done = *status == RunStatus::Diverging,
            _ => self.sim = None,
        }
        let _ = self.out.send(msg);
    }
}

type Job = (Effect, Cancel);

fn run_jobs(engine: &dyn Engine, out: &Sender<Msg>, rx: &Receiver<Job>) {
    let mut boundary: Option<Job> = None;
    let mut campbell: Option<Job> = None;
    loop {
        if boundary.is_none() && campbell.is_none() {
            match rx.recv() {
                Ok(r) => {
                    if !take(r, &mut boundary, &mut campbell) {
                        return;
                    }
                }
                Err(_) => return,
            }
        }
        // Wait until the requests settle: while a slider is held, every solve asks for a new
        // search, and only the last one is worth running (it also leaves the cores to the solver).
        loop {
            match rx.recv_timeout(JOB_SETTLE) {
                Ok(r) => {
                    if !take(r, &mut boundary, &mut campbell) {
                        return;
                    }
                }
                Err(RecvTimeoutError::Timeout) => break,
                Err(RecvTimeoutError::Disconnected) => return,
            }
        }
        // One job, then look at the channel again: a newer request may have replaced the other.
        let Some((job, cancel)) = boundary.take().or_else(|| campbell.take()) else {
            continue;
        };
        let Some(msg) = runner::job(engine, &job, &cancel) else {
            continue;
        };
        if cancel.is_cancelled() {
            // Replaced while it ran: the newer request is in the channel.
            continue;
        }
        if out.send(msg).is_err() {
            return;
        }
    }
}

/// File a job request (latest wins); false on quit.
fn take(r: Job, boundary: &mut Option<Job>, campbell: &mut Option<Job>) -> bool {
    match r.0 {
        Effect::Quit => return false,
        Effect::Boundary { .. } => *boundary = Some(r),
        Effect::Campbell { .. } => *campbell = Some(r),
        // Only jobs and Quit are sent to this thread.
        _ => {}
    }
    true
}
