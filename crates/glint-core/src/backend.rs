//! The two tracers, as the CLI, the report and the test suites name them: the CPU f64
//! reference (this crate) and its GPU f32 mirror (glint-gpu).

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, serde::Serialize, serde::Deserialize)]
pub enum Backend {
    Cpu,
    Gpu,
}

impl Backend {
    /// `cpu` or `gpu`: the name in file names, metadata, CSV cells and messages.
    pub fn name(self) -> &'static str {
        match self {
            Self::Cpu => "cpu",
            Self::Gpu => "gpu",
        }
    }

    /// `cpu` on the CPU, `gpu` on the GPU (per-backend tolerances, colours, devices).
    pub fn pick<T>(self, cpu: T, gpu: T) -> T {
        match self {
            Self::Cpu => cpu,
            Self::Gpu => gpu,
        }
    }
}
