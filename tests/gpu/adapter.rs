//! Adapter selection errors are messages, not wgpu panics.

use glint_gpu::{AdapterRequest, GpuContext, GpuError};

use super::support::gpu_or_skip;

#[test]
fn unknown_adapter_name_lists_the_adapters_found() {
    let tracer = gpu_or_skip!();
    let request = AdapterRequest { name: Some("no-such-gpu-xyz".into()), prefer_cpu: false };
    match GpuContext::new(&request) {
        Err(e @ GpuError::UnknownAdapter { .. }) => {
            let msg = e.to_string();
            assert!(msg.contains("no-such-gpu-xyz"), "{msg}");
            assert!(
                msg.contains(&tracer.context().adapter.name),
                "the message should list '{}': {msg}",
                tracer.context().adapter.name
            );
        }
        other => panic!("expected UnknownAdapter, got {other:?}"),
    }
}

#[test]
fn adapter_is_named_with_backend_and_kind() {
    let tracer = gpu_or_skip!();
    let a = &tracer.context().adapter;
    assert!(!a.name.is_empty() && !a.backend.is_empty() && !a.device_type.is_empty(), "{a:?}");
}
