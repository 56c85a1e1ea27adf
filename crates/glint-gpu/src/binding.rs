//! The tracer's bindings in one table: the number and WGSL name of every buffer that
//! `shaders/bindings.wgsl` declares (a reflection test checks the table against that file,
//! both ways). A binding outside the table is an error naming it, never a silent fallback.

use crate::error::GpuError;

/// The bind group every binding lives in.
pub const GROUP: u32 = 0;

/// One binding of `shaders/bindings.wgsl`; the discriminant is its `@binding` number.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[repr(u32)]
pub enum Binding {
    Header = 0,
    Camera = 1,
    Tile = 2,
    Materials = 3,
    Lights = 4,
    Spheres = 5,
    Planes = 6,
    Triangles = 7,
    Output = 8,
    Stats = 9,
    Probe = 10,
    BvhNodes = 11,
    /// The BVH leaves' triangle corners and primitive references (`glint_core::flat::
    /// fill_gpu_leaves`), in two arrays.
    BvhLeafAb = 12,
    Vertices = 13,
    Normals = 14,
    Meshes = 15,
    /// Texture coordinates, texels and the texture table (under the TEXTURES shader def).
    Uvs = 16,
    Texels = 17,
    Textures = 18,
    /// The pixel probe's ray tree (under the PROBE shader def).
    ProbeTree = 19,
    BvhLeafC = 20,
    /// Vertex colours (under the VERTEX_COLOURS shader def).
    Colours = 21,
    /// The ray-cast kernel's rays and hits (raycast.wgsl; after the tracer's).
    RaysIn = 22,
    HitsOut = 23,
    /// The path tracer's paths between bounces and its emitters (path.wgsl; after the
    /// ray-cast kernel's).
    PathStates = 24,
    Emitters = 25,
}

impl Binding {
    /// Every binding, ascending.
    pub const ALL: [Self; 26] = [
        Self::Header,
        Self::Camera,
        Self::Tile,
        Self::Materials,
        Self::Lights,
        Self::Spheres,
        Self::Planes,
        Self::Triangles,
        Self::Output,
        Self::Stats,
        Self::Probe,
        Self::BvhNodes,
        Self::BvhLeafAb,
        Self::Vertices,
        Self::Normals,
        Self::Meshes,
        Self::Uvs,
        Self::Texels,
        Self::Textures,
        Self::ProbeTree,
        Self::BvhLeafC,
        Self::Colours,
        Self::RaysIn,
        Self::HitsOut,
        Self::PathStates,
        Self::Emitters,
    ];

    /// The bindings only the ray-cast kernel uses (bound by `raycast::RayCaster`, not by the
    /// scene's buffers).
    pub const RAYCAST: [Self; 2] = [Self::RaysIn, Self::HitsOut];

    /// The bindings only the path tracer uses (`SceneBuffers::with_paths`).
    pub const PATH: [Self; 2] = [Self::PathStates, Self::Emitters];

    /// Whether the Whitted tracer's module may declare it (not the other kernels' own).
    pub fn is_tracers(self) -> bool {
        !Self::RAYCAST.contains(&self) && !Self::PATH.contains(&self)
    }

    /// Its `@binding` number.
    pub const fn number(self) -> u32 {
        self as u32
    }

    /// The name of its variable in `shaders/bindings.wgsl`.
    pub const fn wgsl_name(self) -> &'static str {
        match self {
            Self::Header => "header",
            Self::Camera => "camera",
            Self::Tile => "tile",
            Self::Materials => "materials",
            Self::Lights => "lights",
            Self::Spheres => "spheres",
            Self::Planes => "planes",
            Self::Triangles => "triangles",
            Self::Output => "output",
            Self::Stats => "stats",
            Self::Probe => "probe_out",
            Self::BvhNodes => "bvh_nodes",
            Self::BvhLeafAb => "bvh_leaf_ab",
            Self::Vertices => "vertices",
            Self::Normals => "normals",
            Self::Meshes => "meshes",
            Self::Uvs => "uvs",
            Self::Texels => "texels",
            Self::Textures => "textures",
            Self::ProbeTree => "probe_tree",
            Self::BvhLeafC => "bvh_leaf_c",
            Self::RaysIn => "rays_in",
            Self::HitsOut => "hits_out",
            Self::PathStates => "path_states",
            Self::Emitters => "emitters",
            Self::Colours => "colours",
        }
    }

    /// The table entry of a binding a shader declares: group, number and (undecorated) name
    /// must all match it.
    pub fn of_global(group: u32, number: u32, name: &str) -> Result<Self, GpuError> {
        Self::try_from(number)
            .ok()
            .filter(|b| group == GROUP && b.wgsl_name() == name)
            .ok_or_else(|| GpuError::UnknownBinding { group, binding: number, name: name.to_string() })
    }
}

impl TryFrom<u32> for Binding {
    /// The number no binding has.
    type Error = u32;

    fn try_from(number: u32) -> Result<Self, u32> {
        Self::ALL.into_iter().find(|b| b.number() == number).ok_or(number)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_the_table_order_and_round_trip() {
        // The tracer's bindings are 0, 1, 2, …; the ray-cast kernel's follow them, then the
        // path tracer's.
        let tracer = Binding::ALL.iter().filter(|b| b.is_tracers());
        for (i, b) in tracer.enumerate() {
            assert_eq!(b.number() as usize, i, "{b:?} is out of order in Binding::ALL");
        }
        let tracer_count = Binding::ALL.len() - Binding::RAYCAST.len() - Binding::PATH.len();
        for (i, b) in Binding::RAYCAST.into_iter().chain(Binding::PATH).enumerate() {
            assert_eq!(b.number() as usize, tracer_count + i, "{b:?} is out of order in Binding::RAYCAST/PATH");
        }
        for pair in Binding::ALL.windows(2) {
            assert!(pair[0].number() < pair[1].number(), "{pair:?}: Binding::ALL is not ascending");
        }
        for b in Binding::ALL {
            assert_eq!(Binding::try_from(b.number()), Ok(b));
            assert_eq!(Binding::of_global(GROUP, b.number(), b.wgsl_name()).ok(), Some(b));
        }
        let past_the_last = Binding::Emitters.number() + 1;
        assert_eq!(Binding::try_from(past_the_last), Err(past_the_last));
    }

    #[test]
    fn a_wrong_name_group_or_number_is_an_error_naming_it() {
        for (group, number, name) in [(0, 3, "lights"), (1, 0, "header"), (0, 42, "bogus")] {
            let error = Binding::of_global(group, number, name).expect_err("not in the table");
            let text = error.to_string();
            assert!(
                text.contains(name)
                    && text.contains(&format!("@binding({number})"))
                    && text.contains(&group.to_string()),
                "{text}"
            );
        }
    }
}
