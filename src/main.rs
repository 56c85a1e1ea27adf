//! `glint`: the command-line front end of the Glint ray-tracing lab.

mod cli;

use std::process::ExitCode;

use clap::Parser;

fn main() -> ExitCode {
    quiet_device_select_without_a_session();
    env_logger::Builder::from_env(env_logger::Env::default().default_filter_or("warn"))
        // wgpu's parser of WGPU_BACKEND warns of a name it does not know, and glint's own error
        // says which names are allowed (RUST_LOG=wgpu_types::backend=warn shows it).
        .filter_module("wgpu_types::backend", log::LevelFilter::Error)
        .parse_env(env_logger::Env::default())
        .format_timestamp_millis()
        .init();
    let args = cli::Cli::parse();
    let result = cli::interrupt::install().and_then(|()| cli::run(args));
    match (result, cli::interrupt::exit_code()) {
        (Ok(()), _) => ExitCode::SUCCESS,
        // Whatever failed after a stop was requested failed because of it.
        (Err(_), Some(code)) => {
            cli::console::err_line(format_args!("interrupted"));
            ExitCode::from(code)
        }
        (Err(e), None) => {
            cli::console::err_line(format_args!("error: {e:#}"));
            // A command line that cannot be run exits as the argument parser's refusals do.
            if cli::usage::is_usage(&e) { ExitCode::from(2) } else { ExitCode::FAILURE }
        }
    }
}

/// Mesa's device-select layer (an implicit Vulkan layer) connects to a Wayland display to rank
/// the GPUs. Without `XDG_RUNTIME_DIR` (a headless server, a batch job, a Slurm array task)
/// libwayland then prints "error: XDG_RUNTIME_DIR is invalid or not set" twice for every render,
/// though nothing failed. Glint picks its adapter itself (`--adapter`), so there the layer is
/// turned off, unless the user asks for it (`MESA_VK_DEVICE_SELECT`) or has decided already.
fn quiet_device_select_without_a_session() {
    let set = |name| std::env::var_os(name).is_some_and(|v| !v.is_empty());
    if set("XDG_RUNTIME_DIR") || set("MESA_VK_DEVICE_SELECT") || std::env::var_os("NODEVICE_SELECT").is_some() {
        return;
    }
    #[allow(unsafe_code, reason = "the first statement of main: no other thread reads the environment yet")]
    // SAFETY: single-threaded here (see the allowance's reason).
    unsafe {
        std::env::set_var("NODEVICE_SELECT", "1");
    }
}
