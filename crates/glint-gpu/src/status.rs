//! What the status word the shader raises (`STATUS_*` of `glint_types::layout`) means for the
//! user: one message per bit, used by the CLI and the viewer alike.

use glint_types::layout::{
    STATUS_BVH_STACK_OVERFLOW, STATUS_DRIVER_LOOP_CUTOFF, STATUS_LOOP_LIMIT, STATUS_STACK_OVERFLOW, SceneHeader,
    feature,
};

use crate::shaders::{LAVAPIPE_LOOP_BUDGET, ShaderKey};

/// What the remedies of a status word depend on: the scene as built and the variant that
/// traced it. The driver cutoff's remedy listed every cure whatever the scene ("set a
/// bailout" to a scene that had one, "use fewer lights" to a scene of one).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct StatusContext {
    /// The ray stack's levels.
    pub stack_size: u32,
    /// Whitted's child rays are traced in the shader's loops (a mirror or glass, at a depth
    /// above 0).
    pub recurses: bool,
    /// The path tracer's variant (its paths end by Russian roulette, not the bailout).
    pub path: bool,
    /// A Whitted bailout is set.
    pub bailout: bool,
    pub lights: u32,
    /// Every primitive is tested, not through the BVH.
    pub brute_force: bool,
}

impl StatusContext {
    pub fn new(header: &SceneHeader, key: &ShaderKey) -> Self {
        Self {
            stack_size: key.stack_size,
            // The path tracer traces one bounce a dispatch: its depth costs no loop budget.
            recurses: feature::recurses(header.features) && header.max_depth > 0 && !key.path,
            path: key.path,
            bailout: header.bailout > 0.0,
            lights: header.light_count,
            brute_force: !key.bvh,
        }
    }

    /// A variant that traces camera rays alone (the ray caster's): no tree, no shading.
    pub const CAMERA_RAYS: Self =
        Self { stack_size: 1, recurses: false, path: false, bailout: false, lights: 0, brute_force: false };

    /// The cures of a driver cutoff this render can take, the CPU last.
    fn loop_remedies(&self) -> String {
        let mut cures = Vec::new();
        if self.recurses {
            cures.push("lower the depth".to_string());
        }
        if self.recurses && !self.path && !self.bailout {
            cures.push("set a bailout (--bailout, render.bailout)".to_string());
        }
        if self.lights > 1 {
            cures.push(format!("use fewer lights (every shading point loops over each of the {})", self.lights));
        }
        if self.brute_force {
            cures.push(
                "trace through the BVH (--accel auto or bvh: brute force over many primitives spends the budget \
                 first)"
                    .to_string(),
            );
        }
        cures.push("render on the CPU".to_string());
        glint_scene::or_list(&cures)
    }
}

/// One bit of the status word.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u32)]
pub enum StatusBit {
    LoopLimit = STATUS_LOOP_LIMIT,
    DriverLoopCutoff = STATUS_DRIVER_LOOP_CUTOFF,
    StackOverflow = STATUS_STACK_OVERFLOW,
    BvhStackOverflow = STATUS_BVH_STACK_OVERFLOW,
}

impl StatusBit {
    /// Every bit, in the order their messages are reported.
    pub const ALL: [Self; 4] = [Self::LoopLimit, Self::DriverLoopCutoff, Self::StackOverflow, Self::BvhStackOverflow];

    /// The name of its constant in `glint_types::layout` and `shaders/layout.wgsl`.
    pub const fn constant_name(self) -> &'static str {
        match self {
            Self::LoopLimit => "STATUS_LOOP_LIMIT",
            Self::DriverLoopCutoff => "STATUS_DRIVER_LOOP_CUTOFF",
            Self::StackOverflow => "STATUS_STACK_OVERFLOW",
            Self::BvhStackOverflow => "STATUS_BVH_STACK_OVERFLOW",
        }
    }

    /// What it means for a render of `context`.
    pub fn message(self, context: &StatusContext) -> String {
        match self {
            Self::LoopLimit => {
                "the GPU tracer hit its loop bound; some ray trees were cut (see docs/numerics.md)".into()
            }
            Self::DriverLoopCutoff => format!(
                "the GPU driver cut the shader's loops short (lavapipe allows {} loop iterations per invocation \
                 group); this image is missing work: {}",
                with_thousands(LAVAPIPE_LOOP_BUDGET),
                context.loop_remedies()
            ),
            Self::StackOverflow => format!(
                "a ray tree branched deeper than the GPU stack ({} levels); its deepest rays were dropped",
                context.stack_size
            ),
            Self::BvhStackOverflow => format!(
                "a BVH traversal needed more than the GPU's {} stack entries; some subtrees were not visited \
                 (use --accel none or the CPU)",
                crate::shaders::BVH_STACK_SIZE
            ),
        }
    }
}

/// The messages of every bit `status` raises, in `StatusBit::ALL` order; bits no `StatusBit`
/// names are reported too, as unknown, never dropped.
pub fn messages(status: u32, context: &StatusContext) -> Vec<String> {
    let known = StatusBit::ALL.iter().fold(0, |bits, b| bits | *b as u32);
    let mut out: Vec<String> =
        StatusBit::ALL.into_iter().filter(|b| status & *b as u32 != 0).map(|b| b.message(context)).collect();
    let unknown = status & !known;
    if unknown != 0 {
        out.push(format!("the shader raised unknown status bits 0x{unknown:x}; this image may be missing work"));
    }
    out
}

/// 65535 as "65,535".
fn with_thousands(n: u32) -> String {
    let digits = n.to_string();
    let mut out = String::new();
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i).is_multiple_of(3) {
            out.push(',');
        }
        out.push(c);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// (name, value) of every `STATUS_*` constant of `shaders/layout.wgsl`, which the shader
    /// raises from (a reflection test checks them against glint-core's).
    fn wgsl_status_constants() -> Vec<(String, u32)> {
        let module = crate::reflection_tests::layout_module();
        module
            .constants
            .iter()
            .filter_map(|(_, c)| {
                let name = c.name.clone()?;
                let naga::Expression::Literal(naga::Literal::U32(value)) = module.global_expressions[c.init] else {
                    return None;
                };
                name.starts_with("STATUS_").then_some((name, value))
            })
            .collect()
    }

    #[test]
    fn every_status_constant_has_a_message_and_back() {
        let constants = wgsl_status_constants();
        assert!(!constants.is_empty(), "no STATUS_ constants found in layout.wgsl");
        for (name, value) in &constants {
            assert_eq!(value.count_ones(), 1, "{name} = {value} is not one bit");
            let bit = StatusBit::ALL.into_iter().find(|b| *b as u32 == *value);
            let bit = bit.unwrap_or_else(|| panic!("{name} = {value} has no StatusBit (and so no message)"));
            assert_eq!(bit.constant_name(), name, "bit {value}");
            let context = StatusContext { stack_size: 7, ..StatusContext::CAMERA_RAYS };
            let text = messages(*value, &context);
            assert_eq!(text, [bit.message(&context)], "{name}");
            assert!(!text[0].contains("unknown"), "{name}: {text:?}");
        }
        assert_eq!(constants.len(), StatusBit::ALL.len(), "a StatusBit has no constant in layout.wgsl");
    }

    #[test]
    fn unknown_bits_are_reported_not_dropped() {
        let text = messages(STATUS_LOOP_LIMIT | 0x40, &StatusContext::CAMERA_RAYS);
        assert_eq!(text.len(), 2, "{text:?}");
        assert!(text[1].contains("unknown") && text[1].contains("0x40"), "{text:?}");
        assert!(messages(0, &StatusContext::CAMERA_RAYS).is_empty());
    }

    #[test]
    fn messages_print_the_budget_and_the_stack() {
        let context = StatusContext { stack_size: 64, ..StatusContext::CAMERA_RAYS };
        assert!(StatusBit::DriverLoopCutoff.message(&context).contains(&with_thousands(LAVAPIPE_LOOP_BUDGET)));
        assert!(StatusBit::StackOverflow.message(&context).contains("(64 levels)"));
        assert_eq!(with_thousands(1_234_567), "1,234,567");
        assert_eq!(with_thousands(999), "999");
    }

    /// The driver cutoff's cures are the ones the render can take: each where its scene allows it.
    #[test]
    fn the_driver_cutoff_names_only_the_cures_the_render_can_take() {
        let cures = |c: StatusContext| {
            let m = StatusBit::DriverLoopCutoff.message(&c);
            m[m.find("missing work: ").expect("its cures") + "missing work: ".len()..].to_string()
        };
        let mirrors =
            StatusContext { stack_size: 6, recurses: true, path: false, bailout: false, lights: 3, brute_force: true };
        assert_eq!(
            cures(mirrors),
            "lower the depth, set a bailout (--bailout, render.bailout), use fewer lights (every shading point loops \
             over each of the 3), trace through the BVH (--accel auto or bvh: brute force over many primitives \
             spends the budget first), or render on the CPU"
        );
        // One light, a bailout set, through the BVH: the depth and the CPU are left.
        let lean = StatusContext { bailout: true, lights: 1, brute_force: false, ..mirrors };
        assert_eq!(cures(lean), "lower the depth, or render on the CPU");
        // Paths end by Russian roulette, one bounce a dispatch: no bailout to set, and their
        // depth costs no loop budget (`new` leaves `recurses` off for them).
        let paths = StatusContext { path: true, recurses: false, ..mirrors };
        assert!(!cures(paths).contains("bailout") && !cures(paths).contains("depth"), "{}", cures(paths));
        assert_eq!(cures(StatusContext::CAMERA_RAYS), "render on the CPU");
    }
}
