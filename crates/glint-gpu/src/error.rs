//! GPU errors: each says what failed and what the user can do about it.

#[derive(Debug, thiserror::Error)]
pub enum GpuError {
    #[error(
        "no GPU adapter found. On Linux, install Mesa's Vulkan drivers (apt-get install mesa-vulkan-drivers) \
         for the lavapipe CPU adapter; WGPU_BACKEND selects the backend"
    )]
    NoAdapter,
    #[error(
        "a {tile}-pixel tile needs {groups} workgroups a side, more than this GPU dispatches \
         ({limit}, limit max_compute_workgroups_per_dimension)"
    )]
    TileTooLarge { tile: u32, groups: u32, limit: u32 },
    #[error("WGPU_BACKEND='{value}' names no backend; allowed: vulkan, metal, dx12, gl (comma-separated)")]
    UnknownBackend { value: String },
    #[error("no GPU adapter matches '{name}' ({given}); adapters found: {available}")]
    UnknownAdapter { name: String, given: &'static str, available: String },
    #[error("cannot open a device on adapter '{adapter}': {message}")]
    Device { adapter: String, message: String },
    #[error("shader composition failed:\n{0}")]
    Compose(String),
    #[error("shader validation failed:\n{0}")]
    Validation(String),
    #[error(
        "the shader declares `{name}` at @group({group}) @binding({binding}), which is not in the tracer's \
         binding table (glint_gpu::binding::Binding)"
    )]
    UnknownBinding { group: u32, binding: u32, name: String },
    #[error(
        "the shader variant [{variant}] binds {needed} storage buffers, more than this device's \
         max_storage_buffers_per_shader_stage ({limit})"
    )]
    TooManyStorageBuffers { variant: String, needed: u32, limit: u32 },
    #[error(
        "the shader uses `{name}`, which no buffer was given for (glint_gpu::buffers::SceneBuffers::bind_group_with)"
    )]
    Unbound { name: &'static str },
    #[error(
        "the ray-cast kernel raised status bits {status:#x}, so its hits are incomplete and its time means nothing: {messages}"
    )]
    RaycastStatus { status: u32, messages: String },
    #[error(
        "the BVH has {count} {what}, more than the GPU walk indexes ({limit}: a node record holds its \
         children's first record or primitive and their counts in 32 bits, glint_core::bvh::GPU_MAX_TREE_INDEX)"
    )]
    TreeTooLarge { what: &'static str, count: u64, limit: u64 },
    #[error("the scene's BVH has no GPU form: {0}")]
    Tree(#[from] glint_core::bvh::QuantizeError),
    #[error("{what} needs {needed} bytes, more than this GPU allows ({limit} bytes, limit {limit_name})")]
    TooLarge { what: String, needed: u64, limit: u64, limit_name: &'static str },
    #[error(
        "the scene has {count} {what}; without an acceleration structure the GPU tracer walks every \
         primitive and is limited to {limit} of a kind (GPU_PRIMITIVE_LIMIT: lavapipe cuts longer loops \
         silently); `--accel bvh` lifts the limit for spheres and triangles"
    )]
    TooManyPrimitives { what: &'static str, count: u32, limit: u32 },
    #[error(
        "the scene holds a NaN or an infinity in {field}; the GPU tracer never uploads non-finite data \
         (build scenes through validation)"
    )]
    NonFinite { field: String },
    #[error("invalid flat scene: {0}")]
    InvalidScene(#[from] glint_types::layout::UnknownTag),
    #[error("the GPU ran out of memory: {0}")]
    OutOfMemory(String),
    #[error("the GPU reported an error: {0}")]
    Wgpu(String),
    #[error("the GPU device was lost (driver reset or crash); restart to use the GPU again")]
    DeviceLost,
    #[error("the region {region} is not inside the {width}x{height} image, or has no pixel")]
    Region { region: String, width: u32, height: u32 },
    #[error("the render was cancelled")]
    Cancelled,
    #[error("reading the image back from the GPU failed: {0}")]
    Readback(String),
}
