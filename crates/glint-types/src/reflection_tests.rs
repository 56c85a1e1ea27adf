//! The one data layout, checked: every `#[repr(C)]` struct of [`crate::layout`] against its
//! WGSL twin in `shaders/layout.wgsl` (member names, offsets, sizes, as naga's layouter sees
//! them), and every shared constant against its Rust value. No "keep in sync" comments.

use crate::layout::*;
use crate::layout_check::{RustLayout, assert_matches_wgsl, assert_members_cover_bytes, literal_value};

fn rust_layouts() -> Vec<RustLayout> {
    vec![
        rust_layout!(SceneHeader {
            width,
            height,
            spp,
            max_depth,
            sphere_count,
            plane_count,
            triangle_count,
            light_count,
            material_count,
            features,
            epsilon_mode,
            seed,
            epsilon,
            bailout,
            vertex_count,
            mesh_count,
            integrator,
            indirect,
            omit_kinds,
            pad_b,
            ambient,
            background,
            global_attenuation,
            frame
        }),
        rust_layout!(GpuCamera { anchor, forward, right, up }),
        rust_layout!(GpuMaterial {
            ka,
            kd,
            ks,
            kr,
            kt,
            emission,
            shininess,
            ior,
            specular_model,
            diffuse_texture,
            emission_texture,
            roughness,
            fresnel,
            pad
        }),
        rust_layout!(GpuTexture {
            offset,
            width,
            height,
            wrap_s,
            wrap_t,
            filter_mode,
            pad_a,
            pad_b,
            transform_u,
            transform_v,
            planar_u,
            planar_v
        }),
        rust_layout!(GpuLight {
            position,
            direction,
            diffuse,
            specular,
            ambient,
            attenuation,
            kind,
            flags,
            spot_exponent,
            spot_versin_cutoff,
            attenuation_model,
            spot_falloff,
            range,
            spot_versin_inner
        }),
        rust_layout!(GpuSphere { center_radius, material, object_id, power, pad }),
        rust_layout!(GpuPlane { normal_offset, material, object_id, pad }),
        rust_layout!(GpuTriangle { va, vb, vc, mesh, order }),
        rust_layout!(GpuMesh { material, object_id, flags, pad }),
        rust_layout!(GpuPathState { origin, dir, beta, radiance, scattered_from, leaving_pixel, sample }),
        rust_layout!(TileParams { origin_x, origin_y, width, height, sample_index, canary_laps, sample_end, pad_b }),
        rust_layout!(ProbeLight {
            f_att,
            spot,
            shadow_ray,
            n_dot_l,
            visibility,
            ambient,
            diffuse,
            specular,
            contribution,
            lobe_cosine,
            lobe,
            lobe_model,
            pad_b
        }),
        rust_layout!(ProbeRecord {
            object_id,
            material,
            light_count,
            flags,
            t,
            pad_a,
            pad_b,
            pad_c,
            point,
            normal,
            emission,
            ambient,
            ka,
            kd,
            kr,
            kt,
            mirror_sum,
            refraction_sum,
            total,
            lights
        }),
        rust_layout!(ProbeNode {
            kind,
            flags,
            parent,
            depth,
            object_id,
            material,
            light,
            light_count,
            t,
            attenuation,
            pad_a,
            pad_b,
            origin,
            dir,
            weight,
            factor,
            point,
            normal,
            emission,
            ambient,
            ka,
            kd,
            lights
        }),
        rust_layout!(ProbeTree { node_count, flags, pad_a, pad_b, nodes }),
        rust_layout!(BvhNode { min, left_first, max, count }),
        rust_layout!(QuantizedPair { origin, exponents, children, planes }),
    ]
}

const LAYOUT_WGSL: &str = include_str!("../../../shaders/layout.wgsl");

/// layout.wgsl as one plain WGSL module: without naga_oil's directives (import path), which
/// only name what the files give each other.
pub fn layout_module() -> naga::Module {
    let source: String =
        LAYOUT_WGSL.lines().filter(|l| !l.trim_start().starts_with('#')).collect::<Vec<_>>().join("\n");
    naga::front::wgsl::parse_str(&source).unwrap_or_else(|e| panic!("{}", e.emit_to_string(&source)))
}

#[test]
fn every_rust_layout_struct_covers_its_bytes() {
    assert_members_cover_bytes(&rust_layouts());
}

#[test]
fn wgsl_structs_match_rust_offsets_and_sizes() {
    let module = layout_module();
    let layouts = rust_layouts();
    assert_matches_wgsl(&module, &layouts);
    let wgsl_structs = module.types.iter().filter(|(_, t)| matches!(t.inner, naga::TypeInner::Struct { .. })).count();
    assert_eq!(wgsl_structs, layouts.len(), "layout.wgsl has a struct without a Rust twin in this test");
}

#[test]
fn wgsl_layout_constants_match_rust() {
    let expected: Vec<(String, u32)> = vec![
        ("LIGHT_POINT".into(), LIGHT_POINT),
        ("LIGHT_DIRECTIONAL".into(), LIGHT_DIRECTIONAL),
        ("LIGHT_SPOT".into(), LIGHT_SPOT),
        ("ATTENUATION_POLYNOMIAL".into(), ATTENUATION_POLYNOMIAL),
        ("ATTENUATION_INVERSE_SQUARE".into(), ATTENUATION_INVERSE_SQUARE),
        ("SPOT_FALLOFF_POWER".into(), SPOT_FALLOFF_POWER),
        ("SPOT_FALLOFF_SMOOTH".into(), SPOT_FALLOFF_SMOOTH),
        ("LIGHT_CASTS_SHADOWS".into(), LIGHT_CASTS_SHADOWS),
        ("SPECULAR_BLINN".into(), SPECULAR_BLINN),
        ("SPECULAR_PHONG".into(), SPECULAR_PHONG),
        ("SPECULAR_COOK_TORRANCE".into(), SPECULAR_COOK_TORRANCE),
        ("FRESNEL_EXACT".into(), FRESNEL_EXACT),
        ("FRESNEL_SCHLICK".into(), FRESNEL_SCHLICK),
        ("MESH_HAS_NORMALS".into(), MESH_HAS_NORMALS),
        ("MESH_HAS_UVS".into(), MESH_HAS_UVS),
        ("MESH_HAS_COLOURS".into(), MESH_HAS_COLOURS),
        ("NO_TEXTURE".into(), NO_TEXTURE),
        ("WRAP_REPEAT".into(), WRAP_REPEAT),
        ("WRAP_CLAMP_TO_EDGE".into(), WRAP_CLAMP_TO_EDGE),
        ("WRAP_MIRRORED_REPEAT".into(), WRAP_MIRRORED_REPEAT),
        ("FILTER_NEAREST".into(), FILTER_NEAREST),
        ("FILTER_BILINEAR".into(), FILTER_BILINEAR),
        ("EPS_TMIN".into(), EPS_TMIN),
        ("EPS_NUDGE_RAY".into(), EPS_NUDGE_RAY),
        ("EPS_NUDGE_NORMAL".into(), EPS_NUDGE_NORMAL),
        ("EPS_ROBUST".into(), EPS_ROBUST),
        ("EPS_SKIP_CONVEX".into(), EPS_SKIP_CONVEX),
        ("INTEGRATOR_WHITTED".into(), INTEGRATOR_WHITTED),
        ("INTEGRATOR_PATH".into(), INTEGRATOR_PATH),
        ("PATH_DIRECT".into(), PATH_DIRECT),
        ("PATH_INDIRECT".into(), PATH_INDIRECT),
        ("PATH_CAUSTIC".into(), PATH_CAUSTIC),
        ("PATH_REST".into(), PATH_REST),
        ("HISTORY_NON_DELTA".into(), HISTORY_NON_DELTA),
        ("HISTORY_DELTA_AFTER".into(), HISTORY_DELTA_AFTER),
        ("UV_MESH".into(), UV_MESH),
        ("UV_ACROSS_X".into(), UV_ACROSS_X),
        ("UV_ACROSS_Y".into(), UV_ACROSS_Y),
        ("UV_ACROSS_Z".into(), UV_ACROSS_Z),
        ("NO_HIT".into(), NO_HIT),
        ("STATUS_LOOP_LIMIT".into(), STATUS_LOOP_LIMIT),
        ("STATUS_STACK_OVERFLOW".into(), STATUS_STACK_OVERFLOW),
        ("STATUS_DRIVER_LOOP_CUTOFF".into(), STATUS_DRIVER_LOOP_CUTOFF),
        ("STATUS_BVH_STACK_OVERFLOW".into(), STATUS_BVH_STACK_OVERFLOW),
        ("PRIM_REF_TRIANGLE".into(), PRIM_REF_TRIANGLE),
        ("PRIM_REF_INDEX".into(), PRIM_REF_INDEX),
        ("NODE_REF_COUNT_BITS".into(), NODE_REF_COUNT_BITS),
        ("PAIR_FIRST_SHIFT".into(), PAIR_FIRST_SHIFT),
        ("STAT_CAMERA".into(), STAT_CAMERA),
        ("STAT_SHADOW".into(), STAT_SHADOW),
        ("STAT_REFLECTION".into(), STAT_REFLECTION),
        ("STAT_REFRACTION".into(), STAT_REFRACTION),
        ("STAT_BAILOUT_SAVED".into(), STAT_BAILOUT_SAVED),
        ("STAT_STATUS".into(), STAT_STATUS),
        ("STAT_PIXELS_DONE".into(), STAT_PIXELS_DONE),
        ("STAT_WORDS".into(), STAT_WORDS),
        ("MAX_PROBE_LIGHTS".into(), MAX_PROBE_LIGHTS),
        ("PROBE_HIT".into(), PROBE_HIT),
        ("PROBE_TIR".into(), PROBE_TIR),
        ("MAX_PROBE_NODES".into(), MAX_PROBE_NODES),
        ("RAY_CAMERA".into(), RAY_CAMERA),
        ("RAY_REFLECTION".into(), RAY_REFLECTION),
        ("RAY_REFRACTION".into(), RAY_REFRACTION),
        ("RAY_SHADOW".into(), RAY_SHADOW),
        ("NODE_HIT".into(), NODE_HIT),
        ("NODE_TIR".into(), NODE_TIR),
        ("NODE_CUT_BAILOUT".into(), NODE_CUT_BAILOUT),
        ("NODE_CUT_DEPTH".into(), NODE_CUT_DEPTH),
        ("NO_PARENT".into(), NO_PARENT),
        ("TREE_OVERFLOW".into(), TREE_OVERFLOW),
        ("TREE_LIGHTS_TRUNCATED".into(), TREE_LIGHTS_TRUNCATED),
    ];
    let module = layout_module();
    let wgsl: Vec<(String, f64)> = module
        .constants
        .iter()
        .map(|(_, c)| (c.name.clone().expect("named constant"), literal_value(&module, c.init)))
        .collect();
    let expected: Vec<(String, f64)> = expected
        .into_iter()
        .map(|(n, v)| (n, f64::from(v)))
        .chain([
            ("NO_CONE_VERSIN".to_string(), f64::from(NO_CONE_VERSIN)),
            ("CAMERA_ORTHOGRAPHIC".to_string(), f64::from(CAMERA_ORTHOGRAPHIC)),
        ])
        .collect();
    for (name, value) in &expected {
        let found = wgsl.iter().find(|(n, _)| n == name).unwrap_or_else(|| panic!("{name} missing from layout.wgsl"));
        assert_eq!(found.1, *value, "{name}: WGSL {} != Rust {value}", found.1);
    }
    for (name, _) in &wgsl {
        assert!(expected.iter().any(|(n, _)| n == name), "layout.wgsl constant {name} has no Rust twin in this test");
    }
}
