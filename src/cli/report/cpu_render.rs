//! A CPU render of the report's, stopped by SIGINT or SIGTERM (the rows', the reference's and
//! the probes' alike).

use glint_core::{CpuOptions, FlatScene, RenderControl, render_cpu};

/// A CPU render of the report, which SIGINT/SIGTERM stop at the next pixel (`cli::interrupt`).
pub fn cpu_render(flat: &FlatScene, options: &CpuOptions) -> anyhow::Result<glint_core::CpuRender> {
    let cancel = glint_io::interrupt::flag();
    Ok(render_cpu(flat, options, RenderControl { cancel: Some(&cancel), ..RenderControl::default() })?)
}
