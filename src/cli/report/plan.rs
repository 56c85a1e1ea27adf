//! Which configurations a report measures: the reference, the main grid and the focused sweeps,
//! deduplicated (a configuration that two sweeps share is measured once and tagged with both).

use glint_core::{Backend, FlatScene};
use glint_scene::{EpsilonMode, Integrator, RenderSettings, SceneDesc};
use glint_types::layout::feature;
use serde::{Deserialize, Serialize};

/// The bailout thresholds of the sweep, kept symbolic so that tables can print "1/255".
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub enum Bailout {
    Off,
    Per255,
    Per32,
}

impl Bailout {
    pub fn value(self) -> f64 {
        match self {
            Self::Off => 0.0,
            Self::Per255 => 1.0 / 255.0,
            Self::Per32 => 1.0 / 32.0,
        }
    }

    pub fn label(self) -> &'static str {
        match self {
            Self::Off => "0",
            Self::Per255 => "1/255",
            Self::Per32 => "1/32",
        }
    }
}

/// Why a configuration is in the report (it may be in several sweeps).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub enum Group {
    /// The reference settings: error 0 on the CPU by construction; on the GPU, the f32 floor.
    Reference,
    Grid,
    Bailout,
    Shader,
    Epsilon,
}

impl Group {
    pub fn name(self) -> &'static str {
        match self {
            Self::Reference => "reference",
            Self::Grid => "grid",
            Self::Bailout => "bailout",
            Self::Shader => "shader",
            Self::Epsilon => "epsilon",
        }
    }
}

/// One render configuration. Size, seed and epsilon value are the report's and the scene's.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Config {
    pub backend: Backend,
    pub spp: u32,
    pub depth: u32,
    pub bailout: Bailout,
    pub specialise: bool,
    pub epsilon_mode: EpsilonMode,
}

impl Config {
    /// The same configuration on the other backend: its images differ only in arithmetic.
    pub fn on(self, backend: Backend) -> Self {
        Self { backend, ..self }
    }

    /// A short label for plots: "4spp d5", plus whatever differs from the grid's defaults (a
    /// path row's bailout never does: paths use none).
    pub fn short(&self, integrator: Integrator) -> String {
        let mut s = format!("{}spp d{}", self.spp, self.depth);
        if self.bailout != Bailout::Per255 && integrator == Integrator::Whitted {
            s.push_str(&format!(" b{}", self.bailout.label()));
        }
        if !self.specialise {
            s.push_str(" full");
        }
        if self.epsilon_mode != EpsilonMode::Robust {
            s.push_str(&format!(" {}", self.epsilon_mode.name()));
        }
        s
    }

    /// A row's bailout as a table says it: paths use none (Russian roulette ends them, and
    /// `--integrator path --bailout` is refused), whatever the configuration holds.
    pub fn bailout_label(&self, integrator: Integrator) -> &'static str {
        match integrator {
            Integrator::Path => "none (paths)",
            Integrator::Whitted => self.bailout.label(),
        }
    }

    /// Everything but the backend, for tables: "4 spp, depth 5, bailout 1/255"; a path row's
    /// "4 spp, depth 5, paths (no bailout)".
    pub fn describe(&self, integrator: Integrator) -> String {
        let mut s = match integrator {
            Integrator::Whitted => format!("{} spp, depth {}, bailout {}", self.spp, self.depth, self.bailout.label()),
            Integrator::Path => format!("{} spp, depth {}, paths (no bailout)", self.spp, self.depth),
        };
        if !self.specialise {
            s.push_str(", full shader");
        }
        if self.epsilon_mode != EpsilonMode::Robust {
            s.push_str(&format!(", {}", self.epsilon_mode.name()));
        }
        s
    }
}

#[derive(Clone, Debug, PartialEq)]
pub struct Planned {
    pub config: Config,
    pub groups: Vec<Group>,
}

/// What of a scene decides which planned configurations it needs (`Planned::measured_for`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneNeeds {
    pub integrator: Integrator,
    /// Whether Whitted's trees have child rays (`feature::recurses` of the scene at the
    /// reference's depth): without, every depth renders the depth-0 image and the bailout
    /// prunes nothing.
    pub recurses: bool,
    /// Whether a bailout of the sweep can cut a child ray at the bailout sweep's depths
    /// (`glint_scene::bailout_can_cut`): where none can, every bailout renders one image, ray
    /// for ray (a k_r = 0.9 mirror's three rows differed only in their times' noise).
    pub bailout_cuts: bool,
    /// Whether a specular lobe is evaluated (the scene's `feature::SPECULAR`: some material an
    /// object uses has k_s, lit by a light with a highlight or traced by paths): without, the
    /// specular models render one image with one shader, and their timings are noise.
    pub specular: bool,
}

impl SceneNeeds {
    /// The needs of `desc` rendered with `base` (its integrator) under `plan`: recursion judged
    /// at its reference's depth, the bailout at its bailout sweep's.
    pub fn of(desc: &SceneDesc, base: &RenderSettings, plan: &Plan) -> Self {
        let flat = FlatScene::build(desc, &RenderSettings { max_depth: plan.reference_depth, ..base.clone() });
        let depth = plan.bailout_depth.iter().copied().max().unwrap_or(0);
        let bailout_cuts = plan.bailouts.iter().any(|b| glint_scene::bailout_can_cut(desc, b.value(), depth));
        Self {
            integrator: base.integrator,
            recurses: feature::recurses(flat.header.features),
            bailout_cuts,
            specular: flat.header.features & feature::SPECULAR != 0,
        }
    }

    /// What the sweep leaves out for such a scene, as sentences for the report.
    pub fn left_out(&self) -> Vec<&'static str> {
        let mut out = Vec::new();
        match self.integrator {
            Integrator::Path => out.push(
                "Left out: the rows that only vary the bailout, which the paths do not use (Russian roulette ends \
                 them); each would be the grid's render again.",
            ),
            Integrator::Whitted if !self.recurses => out.push(
                "Left out: the grid's and the bailout sweep's rows deeper than 0. No material an object uses has k_r \
                 or k_t, so no ray goes past the camera's and every depth renders the depth-0 image; the shader and ε \
                 rows keep their depth.",
            ),
            Integrator::Whitted if !self.bailout_cuts => out.push(
                "Left out: the rows that only vary the bailout. Every k_r and k_t an object has keeps a path's weight \
                 above each bailout of the sweep at its depths, so no bailout cuts a ray and each row would be the \
                 grid's render again.",
            ),
            Integrator::Whitted => {}
        }
        if !self.specular {
            out.push(
                "Left out: the specular models' timings. No material an object uses has a specular lobe here (k_s \
                 with a light or paths to weigh it), so Blinn, Phong and Cook–Torrance render one image with one \
                 shader, and their ratio would be noise.",
            );
        }
        out
    }
}

impl Planned {
    /// The sweeps this configuration is in for a scene of `needs`: not those where the row
    /// would time another row's render again. Paths end by Russian roulette, which the bailout
    /// does not change, so a path scene is in no bailout sweep; a Whitted scene without child
    /// rays renders the depth-0 image at every depth, so its grid and bailout sweep stop at
    /// depth 0 (the reference, shader and ε sweeps vary something else and keep their depth).
    pub fn groups_for(&self, needs: SceneNeeds) -> Vec<Group> {
        let deep = self.config.depth > 0;
        let applies = |g: &Group| match (needs.integrator, g) {
            (Integrator::Path, Group::Bailout) => false,
            (Integrator::Whitted, Group::Grid) => needs.recurses || !deep,
            // Without child rays the deep rows render the depth-0 image; where no bailout cuts a
            // ray, every bailout renders the grid's (at 1/255) again.
            (Integrator::Whitted, Group::Bailout) => {
                if needs.recurses {
                    needs.bailout_cuts
                } else {
                    !deep
                }
            }
            (Integrator::Path, Group::Reference | Group::Grid | Group::Shader | Group::Epsilon)
            | (Integrator::Whitted, Group::Reference | Group::Shader | Group::Epsilon) => true,
        };
        self.groups.iter().copied().filter(applies).collect()
    }

    /// Whether a scene of `needs` is measured at this configuration: in some sweep of its own
    /// (`groups_for`).
    pub fn measured_for(&self, needs: SceneNeeds) -> bool {
        !self.groups_for(needs).is_empty()
    }
}

/// The axes of the sweeps.
#[derive(Clone, Debug)]
pub struct Plan {
    pub reference_spp: u32,
    pub reference_depth: u32,
    pub grid_spp: Vec<u32>,
    pub grid_depth: Vec<u32>,
    pub grid_bailout: Bailout,
    pub bailouts: Vec<Bailout>,
    pub bailout_spp: Vec<u32>,
    pub bailout_depth: Vec<u32>,
    pub shader_spp: Vec<u32>,
    pub shader_depth: u32,
    pub epsilon_modes: Vec<EpsilonMode>,
    pub epsilon_spp: u32,
    pub epsilon_depth: u32,
}

impl Plan {
    /// The sweep the issue asks for.
    pub fn full(reference_spp: u32) -> Self {
        Self {
            reference_spp,
            reference_depth: 16,
            grid_spp: vec![1, 4, 16],
            grid_depth: vec![0, 1, 2, 3, 5, 8],
            grid_bailout: Bailout::Per255,
            bailouts: vec![Bailout::Off, Bailout::Per255, Bailout::Per32],
            bailout_spp: vec![1, 4],
            bailout_depth: vec![5, 8],
            shader_spp: vec![1, 4],
            shader_depth: 5,
            epsilon_modes: EpsilonMode::ALL.to_vec(),
            epsilon_spp: 1,
            epsilon_depth: 5,
        }
    }

    /// A reduced sweep for CI (`--quick`), fewer rows of each kind and no full-shader rows:
    /// lavapipe takes most of a minute to compile the full shader.
    pub fn quick(reference_spp: u32) -> Self {
        Self {
            grid_spp: vec![1, 4],
            grid_depth: vec![0, 2, 5],
            bailout_spp: vec![1],
            bailout_depth: vec![5],
            shader_spp: Vec::new(),
            epsilon_modes: vec![EpsilonMode::Tmin, EpsilonMode::Robust, EpsilonMode::SkipConvex],
            ..Self::full(reference_spp)
        }
    }

    /// The reference: CPU f64, many samples, deep, no bailout, robust offsets, specialised.
    pub fn reference(&self) -> Config {
        Config {
            backend: Backend::Cpu,
            spp: self.reference_spp,
            depth: self.reference_depth,
            bailout: Bailout::Off,
            specialise: true,
            epsilon_mode: EpsilonMode::Robust,
        }
    }

    /// The sweeps in one line, for the report's header.
    pub fn describe(&self) -> String {
        let list = |v: &[u32]| v.iter().map(u32::to_string).collect::<Vec<_>>().join(", ");
        let bailouts: Vec<&str> = self.bailouts.iter().map(|b| b.label()).collect();
        let modes: Vec<&str> = self.epsilon_modes.iter().map(|m| m.name()).collect();
        format!(
            "grid: backend × spp {{{}}} × depth {{{}}} at bailout {}; bailout {{{}}} at spp {{{}}} × depth {{{}}}; \
             {}; ε strategy {{{}}} at spp {}, depth {}; the reference settings on each backend; all at robust \
             offsets, specialised and bailout {} unless varied",
            list(&self.grid_spp),
            list(&self.grid_depth),
            self.grid_bailout.label(),
            bailouts.join(", "),
            list(&self.bailout_spp),
            list(&self.bailout_depth),
            if self.shader_spp.is_empty() {
                "no full-shader rows".to_string()
            } else {
                format!("specialised vs full shader at spp {{{}}}, depth {}", list(&self.shader_spp), self.shader_depth)
            },
            modes.join(", "),
            self.epsilon_spp,
            self.epsilon_depth,
            self.grid_bailout.label(),
        )
    }

    /// Every configuration on `backends`, each once, in sweep order (CPU before GPU).
    pub fn configs(&self, backends: &[Backend]) -> Vec<Planned> {
        let mut out: Vec<Planned> = Vec::new();
        let mut add = |config: Config, group: Group| match out.iter_mut().find(|p| p.config == config) {
            Some(p) if !p.groups.contains(&group) => p.groups.push(group),
            Some(_) => {}
            None => out.push(Planned { config, groups: vec![group] }),
        };
        let base = Config {
            backend: Backend::Cpu,
            spp: 1,
            depth: 0,
            bailout: self.grid_bailout,
            specialise: true,
            epsilon_mode: EpsilonMode::Robust,
        };
        for &backend in backends {
            let base = base.on(backend);
            add(self.reference().on(backend), Group::Reference);
            for &spp in &self.grid_spp {
                for &depth in &self.grid_depth {
                    add(Config { spp, depth, ..base }, Group::Grid);
                }
            }
            for &spp in &self.bailout_spp {
                for &depth in &self.bailout_depth {
                    for &bailout in &self.bailouts {
                        add(Config { spp, depth, bailout, ..base }, Group::Bailout);
                    }
                }
            }
            for &spp in &self.shader_spp {
                for specialise in [true, false] {
                    add(Config { spp, depth: self.shader_depth, specialise, ..base }, Group::Shader);
                }
            }
            for &epsilon_mode in &self.epsilon_modes {
                add(Config { spp: self.epsilon_spp, depth: self.epsilon_depth, epsilon_mode, ..base }, Group::Epsilon);
            }
        }
        for p in &mut out {
            p.groups.sort();
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn full_plan_is_deduplicated_and_tags_shared_rows() {
        let plan = Plan::full(64);
        let cpu = plan.configs(&[Backend::Cpu]);
        // 1 reference + 18 grid + 8 bailout (bailout 0 and 1/32; 1/255 is in the grid)
        // + 2 full-shader + 4 epsilon (robust is in the grid).
        assert_eq!(cpu.len(), 1 + 18 + 8 + 2 + 4);
        let both = plan.configs(&[Backend::Cpu, Backend::Gpu]);
        assert_eq!(both.len(), 2 * cpu.len());
        let shared = cpu
            .iter()
            .find(|p| {
                p.config.spp == 4 && p.config.depth == 5 && p.config.specialise && p.config.bailout == Bailout::Per255
            })
            .expect("grid row");
        assert_eq!(shared.groups, vec![Group::Grid, Group::Bailout, Group::Shader]);
        for (i, a) in both.iter().enumerate() {
            assert!(both[i + 1..].iter().all(|b| b.config != a.config), "duplicate {a:?}");
        }
    }

    #[test]
    fn reference_is_a_row_of_its_own_group() {
        let plan = Plan::quick(64);
        let rows = plan.configs(&[Backend::Cpu]);
        let r = rows.iter().find(|p| p.config == plan.reference()).expect("reference row");
        assert_eq!(r.groups, vec![Group::Reference]);
        assert_eq!((r.config.spp, r.config.depth, r.config.bailout), (64, 16, Bailout::Off));
    }

    #[test]
    fn a_path_row_is_described_without_a_bailout() {
        let grid = Plan::quick(64).configs(&[Backend::Cpu]).into_iter().find(|p| p.groups == [Group::Grid]);
        let c = grid.expect("a grid row").config;
        assert!(c.describe(Integrator::Whitted).contains("bailout 1/255"), "{}", c.describe(Integrator::Whitted));
        let paths = c.describe(Integrator::Path);
        assert!(paths.contains("paths (no bailout)") && !paths.contains("1/255"), "{paths}");
        assert_eq!(c.bailout_label(Integrator::Path), "none (paths)");
        let reference = Plan::quick(64).reference();
        assert!(reference.short(Integrator::Whitted).ends_with(" b0"));
        assert!(!reference.short(Integrator::Path).contains(" b"), "{}", reference.short(Integrator::Path));
    }

    #[test]
    fn scenes_leave_out_the_rows_that_would_time_another_rows_render_again() {
        let plan = Plan::full(64);
        let rows = plan.configs(&[Backend::Cpu]);
        let needs = |integrator, recurses| SceneNeeds { integrator, recurses, bailout_cuts: recurses, specular: true };
        let path: Vec<&Planned> = rows.iter().filter(|p| p.measured_for(needs(Integrator::Path, true))).collect();
        assert!(rows.iter().all(|p| p.measured_for(needs(Integrator::Whitted, true))));
        // Without child rays: the reference, the grid's 3 rows at depth 0, the shader rows at
        // depth 5 (spp 1 and 4, specialised and full) and the 4 other ε strategies (robust's is
        // the specialised spp-1 row).
        let flat: Vec<&Planned> = rows.iter().filter(|p| p.measured_for(needs(Integrator::Whitted, false))).collect();
        assert_eq!(flat.len(), 1 + 3 + 4 + 4, "{flat:#?}");
        assert!(flat.iter().all(|p| p.config.depth == 0 || !p.groups.iter().all(|g| *g == Group::Grid)));
        // The rows kept for another sweep are not tagged with the sweeps that left them out.
        let lights = needs(Integrator::Whitted, false);
        for p in &flat {
            let groups = p.groups_for(lights);
            assert!(p.config.depth == 0 || !groups.contains(&Group::Grid) && !groups.contains(&Group::Bailout));
        }
        assert!(path.iter().all(|p| !p.groups_for(needs(Integrator::Path, true)).contains(&Group::Bailout)));
        // bailout 0 and 1/32 at spp {1, 4} × depth {5, 8}; the 1/255 rows are the grid's.
        assert_eq!(rows.len() - path.len(), 8);
        assert!(path.iter().all(|p| p.config.bailout == Bailout::Per255 || p.groups.contains(&Group::Reference)));
        assert!(path.iter().any(|p| p.groups.contains(&Group::Bailout)), "the grid rows of the bailout sweep stay");
        // A Whitted scene whose weights no bailout reaches (a k_r = 0.9 mirror) leaves out the
        // same 8 rows as paths: each would render the grid's image at 1/255 again.
        let uncut = SceneNeeds { bailout_cuts: false, ..needs(Integrator::Whitted, true) };
        let kept: Vec<&Planned> = rows.iter().filter(|p| p.measured_for(uncut)).collect();
        assert_eq!(kept, path, "a scene the bailout cuts nothing in");
        assert!(kept.iter().all(|p| !p.groups_for(uncut).contains(&Group::Bailout)));
    }
}
