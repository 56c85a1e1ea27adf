//! `glint`: the command-line front end of the Glint ray-tracing lab.

mod cli;

use std::process::ExitCode;

use clap::Parser;

fn main() -> ExitCode {
    env_logger::Builder::from_env(env_logger::Env::default().default_filter_or("warn"))
        .format_timestamp_millis()
        .init();
    let args = cli::Cli::parse();
    let result = cli::interrupt::install().and_then(|()| cli::run(args));
    match (result, cli::interrupt::exit_code()) {
        (Ok(()), _) => ExitCode::SUCCESS,
        // Whatever failed after a stop was requested failed because of it.
        (Err(_), Some(code)) => {
            eprintln!("interrupted");
            ExitCode::from(code)
        }
        (Err(e), None) => {
            eprintln!("error: {e:#}");
            ExitCode::FAILURE
        }
    }
}
