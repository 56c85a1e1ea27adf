//! `glint adapters`: the GPU adapters a render can choose from (`--adapter`, `WGPU_ADAPTER_NAME`,
//! `WGPU_BACKEND`), as the tracer finds them; what `scripts/device-suite` checks first.

use clap::Args;

use super::console::say;

#[derive(Debug, Args)]
pub struct AdaptersArgs {
    /// Print them as JSON (name, backend, device type, driver, software)
    #[arg(long)]
    pub json: bool,
}

pub fn run(args: &AdaptersArgs) -> anyhow::Result<()> {
    let adapters = glint_gpu::list_adapters()?;
    if args.json {
        let list: Vec<serde_json::Value> = adapters
            .iter()
            .map(|a| {
                serde_json::json!({
                    "name": a.name,
                    "backend": a.backend,
                    "device_type": a.device_type,
                    "driver": a.driver,
                    "software": a.is_software(),
                })
            })
            .collect();
        say!("{}", serde_json::to_string_pretty(&list)?)?;
        return Ok(());
    }
    if adapters.is_empty() {
        say!("no GPU adapter (install a Vulkan driver: Mesa's lavapipe is apt-get install mesa-vulkan-drivers)")?;
    }
    for a in &adapters {
        let kind = if a.is_software() { "software, runs on the CPU" } else { "hardware" };
        say!("{a}: driver {} ({kind})", a.driver)?;
    }
    Ok(())
}
