//! The report's prose, kept as Markdown in methodology.md (so it reads as prose, not as string
//! literals) and filled in here.

use std::fmt::Display;

static METHODOLOGY: &str = include_str!("methodology.md");

/// The blocks of methodology.md, each with the placeholders its text holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Block {
    Setup,
    F32Floor,
    F32FloorDroppedWork,
    F32FloorPaths,
    Bailout,
    Specialisation,
    SpecialisationNotMeasured,
    Epsilon,
    Specular,
    ReferenceNoise,
    EqualTime,
    EqualError,
    AllConfigurations,
}

impl Block {
    #[cfg(test)]
    const ALL: [Self; 13] = [
        Self::Setup,
        Self::F32Floor,
        Self::F32FloorDroppedWork,
        Self::F32FloorPaths,
        Self::Bailout,
        Self::Specialisation,
        Self::SpecialisationNotMeasured,
        Self::Epsilon,
        Self::Specular,
        Self::ReferenceNoise,
        Self::EqualTime,
        Self::EqualError,
        Self::AllConfigurations,
    ];

    fn name(self) -> &'static str {
        match self {
            Self::Setup => "setup",
            Self::F32Floor => "f32-floor",
            Self::F32FloorDroppedWork => "f32-floor-dropped-work",
            Self::F32FloorPaths => "f32-floor-paths",
            Self::Bailout => "bailout",
            Self::Specialisation => "specialisation",
            Self::SpecialisationNotMeasured => "specialisation-not-measured",
            Self::Epsilon => "epsilon",
            Self::Specular => "specular",
            Self::ReferenceNoise => "reference-noise",
            Self::EqualTime => "equal-time",
            Self::EqualError => "equal-error",
            Self::AllConfigurations => "all-configurations",
        }
    }

    fn keys(self) -> &'static [&'static str] {
        match self {
            Self::Setup => &[
                "cpu_model",
                "logical_cores",
                "os",
                "environment",
                "cpu_device",
                "gpu_device",
                "width",
                "height",
                "reference_spp",
                "reference_depth",
                "runs",
                "rel_mse_epsilon",
                "sweep",
            ],
            Self::F32FloorDroppedWork => &["scene", "rays", "camera_rays", "camera_expected", "status"],
            Self::F32FloorPaths => &["scenes"],
            Self::ReferenceNoise => {
                &["renders", "seeds", "seed", "group_spp", "spp", "noise", "mean", "mean_se", "own", "sigmas"]
            }
            Self::Bailout | Self::Specular => &["spp", "depth"],
            Self::F32Floor
            | Self::Specialisation
            | Self::SpecialisationNotMeasured
            | Self::Epsilon
            | Self::EqualTime
            | Self::EqualError
            | Self::AllConfigurations => &[],
        }
    }

    /// The block's lines in methodology.md, from its marker to the next.
    fn source(self) -> &'static str {
        let marker = format!("<!-- block: {} -->\n", self.name());
        let start = METHODOLOGY.find(&marker).unwrap_or_else(|| panic!("methodology.md has no block {}", self.name()))
            + marker.len();
        let end = METHODOLOGY[start..].find("\n<!-- block: ").map_or(METHODOLOGY.len(), |e| start + e);
        &METHODOLOGY[start..end]
    }
}

/// The paragraphs of `source`, each on one line (table rows stay lines of their own) and each
/// followed by a blank line, as report.md has them.
fn paragraphs(source: &str) -> String {
    let mut out = String::new();
    for paragraph in source.split("\n\n").map(str::trim).filter(|p| !p.is_empty()) {
        for (i, line) in paragraph.lines().enumerate() {
            let separator = match (i, line.starts_with('|')) {
                (0, _) => "",
                (_, true) => "\n",
                (_, false) => " ",
            };
            out.push_str(separator);
            out.push_str(line.trim());
        }
        out.push_str("\n\n");
    }
    out
}

/// `block` with `values` in its placeholders. `values` must name exactly the block's keys.
pub fn prose(block: Block, values: &[(&str, &dyn Display)]) -> String {
    let given: Vec<&str> = values.iter().map(|(k, _)| *k).collect();
    assert_eq!(given, block.keys(), "the values given for block {}", block.name());
    // One pass, so that a value holding braces (the sweep's "{1, 4}") is never read as a key.
    let text = paragraphs(block.source());
    let mut out = String::with_capacity(text.len());
    let mut rest = text.as_str();
    while let Some((before, after)) = rest.split_once('{') {
        let (key, tail) = after.split_once('}').expect("a placeholder is closed");
        let (_, value) = values.iter().find(|(k, _)| *k == key).expect("every placeholder has a value");
        out.push_str(before);
        out.push_str(&value.to_string());
        rest = tail;
    }
    out.push_str(rest);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The `{key}` placeholders of a text, in order of first appearance.
    fn placeholders(text: &str) -> Vec<&str> {
        let mut keys = Vec::new();
        for part in text.split('{').skip(1) {
            let key = part.split_once('}').map_or(part, |(k, _)| k);
            if !keys.contains(&key) {
                keys.push(key);
            }
        }
        keys
    }

    #[test]
    fn every_block_exists_and_holds_exactly_its_placeholders() {
        for block in Block::ALL {
            let mut found = placeholders(block.source());
            found.sort_unstable();
            let mut keys = block.keys().to_vec();
            keys.sort_unstable();
            assert_eq!(found, keys, "placeholders of block {}", block.name());
        }
        let markers = METHODOLOGY.lines().filter(|l| l.starts_with("<!-- block: ")).count();
        assert_eq!(markers, Block::ALL.len(), "methodology.md has blocks that no writer prints");
    }

    #[test]
    fn paragraphs_become_lines_and_table_rows_stay_lines() {
        let text = "### Heading\n\nOne paragraph\nwrapped here.\n\n| a |\n| b |\n";
        assert_eq!(paragraphs(text), "### Heading\n\nOne paragraph wrapped here.\n\n| a |\n| b |\n\n");
    }
}
