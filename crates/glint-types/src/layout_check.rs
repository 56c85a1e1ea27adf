//! The checks of a `#[repr(C)]` struct against its WGSL twin, shared by the two reflection
//! tests that own such structs (glint-types' layout, glint-core's BVH records in glint-gpu's
//! tests, which include this file by path): one harness, not two copies of it.

/// A Rust struct as (name, size, [(member, offset, size)]).
pub type RustLayout = (&'static str, usize, Vec<(&'static str, usize, usize)>);

/// The `RustLayout` of a `Pod` struct from its listed fields.
macro_rules! rust_layout {
    ($ty:ident { $($field:ident),* $(,)? }) => {{
        let zero: $ty = bytemuck::Zeroable::zeroed();
        let members =
            vec![$((stringify!($field), std::mem::offset_of!($ty, $field), size_of_val(&zero.$field))),*];
        (stringify!($ty), size_of::<$ty>(), members)
    }};
}

/// Each struct's listed members follow one another and end at its size: a field added in Rust
/// but not listed breaks the chain, so the lists stay complete.
pub fn assert_members_cover_bytes(layouts: &[RustLayout]) {
    for (name, size, members) in layouts {
        let mut end = 0;
        for (field, offset, field_size) in members {
            assert_eq!(*offset, end, "{name}.{field} does not follow the previous member (unlisted field or padding?)");
            end = offset + field_size;
        }
        assert_eq!(end, *size, "{name}: listed members end at {end}, the struct has {size} bytes");
    }
}

/// Each struct has a WGSL twin in `module` with the same size, member names, order and offsets
/// as naga's layouter sees them.
pub fn assert_matches_wgsl(module: &naga::Module, layouts: &[RustLayout]) {
    let mut layouter = naga::proc::Layouter::default();
    layouter.update(module.to_ctx()).expect("layout.wgsl lays out");
    for (name, size, members) in layouts {
        let (handle, ty) = module
            .types
            .iter()
            .find(|(_, t)| t.name.as_deref() == Some(*name))
            .unwrap_or_else(|| panic!("struct {name} is missing from shaders/layout.wgsl"));
        let naga::TypeInner::Struct { members: wgsl, span } = &ty.inner else { panic!("{name} is not a struct") };
        assert_eq!(*span as usize, *size, "{name}: WGSL size {span} != Rust size {size}");
        assert_eq!(layouter[handle].size as usize, *size, "{name}: naga layouter size");
        assert_eq!(wgsl.len(), members.len(), "{name}: member count differs");
        for (w, (field, offset, _)) in wgsl.iter().zip(members) {
            assert_eq!(w.name.as_deref(), Some(*field), "{name}: member order/name differs");
            assert_eq!(w.offset as usize, *offset, "{name}.{field}: WGSL offset {} != Rust {offset}", w.offset);
        }
    }
}

/// A constant's literal value, widened to f64.
pub fn literal_value(module: &naga::Module, init: naga::Handle<naga::Expression>) -> f64 {
    match module.global_expressions[init] {
        naga::Expression::Literal(naga::Literal::U32(v)) => f64::from(v),
        naga::Expression::Literal(naga::Literal::I32(v)) => f64::from(v),
        naga::Expression::Literal(naga::Literal::F32(v)) => f64::from(v),
        ref other => panic!("constant initialiser {other:?} is not a literal"),
    }
}
