//! Built-in scenes, embedded in the binary so that they work from any folder.

#[derive(Clone, Copy, Debug)]
pub struct BuiltinScene {
    pub name: &'static str,
    pub text: &'static str,
}

macro_rules! scene {
    ($name:literal) => {
        BuiltinScene { name: $name, text: include_str!(concat!("../../../../assets/scenes/", $name, ".toml")) }
    };
}

pub const BUILTIN_SCENES: &[BuiltinScene] =
    &[scene!("whitted"), scene!("cornell"), scene!("spotlights"), scene!("highlights"), scene!("lights")];

pub fn builtin(name: &str) -> Option<&'static BuiltinScene> {
    BUILTIN_SCENES.iter().find(|b| b.name == name)
}
