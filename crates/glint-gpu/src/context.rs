//! The wgpu device: chosen by name or kind like wgpu's own examples (`--adapter`,
//! `WGPU_ADAPTER_NAME`, `WGPU_BACKEND`), or injected by a host that owns one (the viewer).

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use crate::error::GpuError;

/// How to pick an adapter.
#[derive(Clone, Debug, Default)]
pub struct AdapterRequest {
    /// Case-insensitive substring of the adapter name; `None` reads `WGPU_ADAPTER_NAME`.
    pub name: Option<String>,
    /// Prefer a CPU adapter (lavapipe) when no name is given: its arithmetic is the same on
    /// every machine, which tests and reports want.
    pub prefer_cpu: bool,
}

/// Adapter facts shown to users and stored in image metadata.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct AdapterSummary {
    pub name: String,
    pub backend: String,
    pub device_type: String,
    pub driver: String,
}

impl AdapterSummary {
    pub fn from_info(info: &wgpu::AdapterInfo) -> Self {
        Self {
            name: info.name.clone(),
            backend: format!("{:?}", info.backend),
            device_type: format!("{:?}", info.device_type),
            driver: format!("{} {}", info.driver, info.driver_info).trim().to_string(),
        }
    }
}

impl AdapterSummary {
    /// A software adapter (Mesa's lavapipe/llvmpipe, WARP, SwiftShader: wgpu's `Cpu` device
    /// type): its "GPU" work runs on the CPU cores.
    pub fn is_software(&self) -> bool {
        self.device_type == format!("{:?}", wgpu::DeviceType::Cpu)
    }

    /// The adapter and its driver, as an image's metadata and a report name the device: two
    /// drivers of one GPU can render other bits.
    pub fn with_driver(&self) -> String {
        if self.driver.is_empty() { self.to_string() } else { format!("{self}, driver {}", self.driver) }
    }
}

impl std::fmt::Display for AdapterSummary {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} ({}, {})", self.name, self.backend, self.device_type)
    }
}

/// A device and queue with what the tracer needs to know about them.
#[derive(Clone, Debug)]
pub struct GpuContext {
    pub device: wgpu::Device,
    pub queue: wgpu::Queue,
    pub adapter: AdapterSummary,
    pub limits: wgpu::Limits,
    lost: Arc<AtomicBool>,
}

/// The adapters a render can choose from, as `GpuContext::new` finds them (`WGPU_BACKEND`, else
/// the primary backends, else OpenGL).
pub fn list_adapters() -> Result<Vec<AdapterSummary>, GpuError> {
    Ok(find_adapters()?.iter().map(|a| AdapterSummary::from_info(&a.get_info())).collect())
}

fn find_adapters() -> Result<Vec<wgpu::Adapter>, GpuError> {
    let requested = requested_backends()?;
    let mut adapters = enumerate(requested.unwrap_or(wgpu::Backends::PRIMARY));
    if adapters.is_empty() && requested.is_none() {
        // OpenGL only when nothing else is there: initialising it probes the display
        // server (and prints errors of its own where there is none).
        adapters = enumerate(wgpu::Backends::GL);
    }
    Ok(adapters)
}

impl GpuContext {
    /// Opens an adapter as `request` says and creates a device with its default limits.
    pub fn new(request: &AdapterRequest) -> Result<Self, GpuError> {
        let adapter = choose_adapter(find_adapters()?, request)?;
        let info = adapter.get_info();
        let limits = adapter.limits();
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("glint"),
            required_features: wgpu::Features::empty(),
            required_limits: limits.clone(),
            ..Default::default()
        }))
        .map_err(|e| GpuError::Device { adapter: info.name.clone(), message: e.to_string() })?;
        log::info!("GPU adapter: {} ({:?}, {:?})", info.name, info.backend, info.device_type);
        Ok(Self::from_device(device, queue, &info))
    }

    /// Wraps a device someone else created (eframe's, in the viewer).
    pub fn from_device(device: wgpu::Device, queue: wgpu::Queue, info: &wgpu::AdapterInfo) -> Self {
        let lost = Arc::new(AtomicBool::new(false));
        let flag = lost.clone();
        device.set_device_lost_callback(move |reason, message| {
            log::error!("GPU device lost ({reason:?}): {message}");
            flag.store(true, Ordering::SeqCst);
        });
        let limits = device.limits();
        Self { device, queue, adapter: AdapterSummary::from_info(info), limits, lost }
    }

    pub fn is_lost(&self) -> bool {
        self.lost.load(Ordering::SeqCst)
    }
}

/// The backends `WGPU_BACKEND` asks for; an error when it names none.
fn requested_backends() -> Result<Option<wgpu::Backends>, GpuError> {
    let Some(value) = std::env::var("WGPU_BACKEND").ok().filter(|v| !v.trim().is_empty()) else {
        return Ok(None);
    };
    let backends = wgpu::Backends::from_comma_list(&value);
    if backends.is_empty() { Err(GpuError::UnknownBackend { value }) } else { Ok(Some(backends)) }
}

fn enumerate(backends: wgpu::Backends) -> Vec<wgpu::Adapter> {
    let mut descriptor = wgpu::InstanceDescriptor::new_without_display_handle_from_env();
    descriptor.backends = backends;
    pollster::block_on(wgpu::Instance::new(descriptor).enumerate_adapters(backends))
}

fn choose_adapter(adapters: Vec<wgpu::Adapter>, request: &AdapterRequest) -> Result<wgpu::Adapter, GpuError> {
    let listing = |adapters: &[wgpu::Adapter]| {
        adapters.iter().map(|a| AdapterSummary::from_info(&a.get_info()).to_string()).collect::<Vec<_>>().join("; ")
    };
    if adapters.is_empty() {
        return Err(GpuError::NoAdapter);
    }
    // Where the name came from, for the message: a variable set in a shell profile is easily
    // forgotten.
    let (name, given) = match request.name.clone() {
        Some(name) => (Some(name), "the adapter asked for"),
        None => (std::env::var("WGPU_ADAPTER_NAME").ok(), "from WGPU_ADAPTER_NAME"),
    };
    let name = name.filter(|n| !n.is_empty());
    if let Some(name) = name {
        let wanted = name.to_lowercase();
        let found = adapters.iter().position(|a| a.get_info().name.to_lowercase().contains(&wanted));
        return match found {
            Some(i) => Ok(adapters.into_iter().nth(i).expect("index from position")),
            None => Err(GpuError::UnknownAdapter { name, given, available: listing(&adapters) }),
        };
    }
    let rank = |a: &wgpu::Adapter| {
        use wgpu::DeviceType as D;
        let t = a.get_info().device_type;
        match (request.prefer_cpu, t) {
            (true, D::Cpu) => 0,
            (false, D::DiscreteGpu) => 0,
            (false, D::IntegratedGpu) => 1,
            (_, D::DiscreteGpu | D::IntegratedGpu | D::VirtualGpu) => 2,
            (_, D::Cpu) => 3,
            (_, D::Other) => 4,
        }
    };
    let best = adapters.iter().enumerate().min_by_key(|(_, a)| rank(a)).map(|(i, _)| i).unwrap_or(0);
    Ok(adapters.into_iter().nth(best).expect("index from enumerate"))
}
