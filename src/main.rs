use clap::{CommandFactory, Parser};
use flutterscope::cli::Cli;
use std::io::IsTerminal;
use std::process::ExitCode;

fn main() -> ExitCode {
    restore_default_sigpipe();
    let cli = Cli::parse();
    let result = match cli.command {
        Some(command) => flutterscope::commands::run(command),
        None if std::io::stdout().is_terminal() && std::io::stdin().is_terminal() => {
            flutterscope::commands::run_default_tui(&cli.explorer)
        }
        None => {
            let _ = Cli::command().print_help();
            eprintln!(
                "\nflutterscope: no terminal for the explorer; use a headless command, e.g. \
                 `flutterscope eigen --preset liu2017`"
            );
            return ExitCode::from(2);
        }
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            match e {
                flutterscope::error::Error::Usage(_) => ExitCode::from(2),
                _ => ExitCode::FAILURE,
            }
        }
    }
}

/// Rust ignores SIGPIPE, so writing to a closed pipe (`flutterscope sweep ... | head`) becomes an
/// error that `println!` turns into a panic. A command-line tool should just stop.
fn restore_default_sigpipe() {
    #[cfg(unix)]
    // SAFETY: called first thing in main, before any other thread exists; SIG_DFL is a valid action.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
}
