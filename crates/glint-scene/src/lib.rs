//! Glint's scene description: the plain types a scene is made of (camera, world, materials,
//! lights, objects, and the already-decoded meshes, materials and texels of a model or an
//! image), its validation against the ranges both tracers accept, and the scenes made in code
//! (`bumpy`). Nothing here reads a file: the TOML format, the model importers and image
//! decoding are glint-io's, above this crate.

mod buffered;
pub mod bumpy;
mod camera;
mod desc;
mod error;
mod exact_len;
mod light;
mod limits;
mod material;
mod mesh;
mod model;
mod model_ref;
mod number;
mod overflow;
mod ray_tree;
mod rgb;
mod storage;
mod tables;
mod texture;
mod transform;
mod validate;
mod whole;

pub use camera::{CameraDesc, NARROW_TAN_HALF_FOV, Projection};
pub use desc::{
    GlobalAttenuation, LightSource, ObjectDesc, PlaneDesc, RenderSettings, SceneDesc, SphereDesc, WorldDesc,
    without_imported_materials,
};
pub use error::FieldIssue;
/// The tags a scene file names (light kinds, models, modes), from the shared vocabulary.
pub use glint_types::tags::{
    AttenuationModel, EpsilonMode, Filter, Fresnel, Integrator, LightKind, PathKind, SpecularModel, SpotFalloff, Wrap,
};
pub use light::{Attenuation, DEFAULT_INNER_CONE, DEFAULT_OUTER_CONE, LightDesc, NO_CONE_CUTOFF};
pub use material::{CheckerDesc, DEFAULT_ROUGHNESS, MaterialDesc, material_textures};
pub use mesh::{MeshDesc, has_area};
pub use model::{MaterialSource, Model, ModelCamera};
pub use model_ref::{LoadedModel, ModelDesc, Scale, TransformDesc};
pub use number::{
    f64_spacing, format_number, format_rounded, or_list, serde_words, shorten, shorten_lines, shorten_middle,
};
pub use overflow::overflow_causes;
pub use ray_tree::{
    WARN_RAYS_PER_SAMPLE, bailout_can_cut, ray_tree_bound, reachable_depth, unbounded_ray_tree,
    unbounded_ray_tree_cause,
};
pub use rgb::Rgb;
pub use storage::{bounded_box, far_box_out_of_sight, storage_origin, storage_origin_of_box, storage_origin_within};
pub use texture::{
    ColorSpace, MAX_TEXTURE_SIDE, MAX_TEXTURE_TEXELS, TextureDesc, TextureError, TextureImage, UvTransform, check_size,
    srgb_to_linear,
};
pub use transform::{Mat4, not_unit_quaternion};
pub use validate::{
    EPSILON_SHARE, EPSILON_WARN_SHARE, MAX_ATTENUATION_DIP, MAX_COORD, MAX_DEPTH, MAX_EPSILON, MAX_IMAGE_SIDE,
    MAX_INTENSITY, MAX_IOR, MAX_ROUGHNESS, MAX_SHININESS, MAX_SPOT_EXPONENT, MAX_SPP, MIN_ATTENUATION_DENOMINATOR,
    MIN_DIRECTION_LENGTH, MIN_ROUGHNESS, Range, Report, epsilon_warning, epsilon_warnings_of_objects,
    integrator_warnings, path_gain_warning, ranges, settings_warnings, usable_direction, validate, validate_objects,
    validate_settings, validate_with_objects,
};
