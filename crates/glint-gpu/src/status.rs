//! What the status word the shader raises (`STATUS_*` of `glint_types::layout`) means for the
//! user: one message per bit, used by the CLI and the viewer alike.

use glint_types::layout::{
    STATUS_BVH_STACK_OVERFLOW, STATUS_DRIVER_LOOP_CUTOFF, STATUS_LOOP_LIMIT, STATUS_STACK_OVERFLOW,
};

use crate::shaders::LAVAPIPE_LOOP_BUDGET;

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

    /// What it means, for a render whose shader had a stack of `stack_size` levels.
    pub fn message(self, stack_size: u32) -> String {
        match self {
            Self::LoopLimit => {
                "the GPU tracer hit its loop bound; some ray trees were cut (see docs/numerics.md)".into()
            }
            Self::DriverLoopCutoff => format!(
                "the GPU driver cut the shader's loops short (lavapipe allows {} loop iterations per invocation \
                 group); this image is missing work: lower the depth, set a bailout, use fewer lights (every shading \
                 point loops over each), trace through the BVH (--accel auto or bvh: brute force over many primitives \
                 spends the budget first) or use the CPU",
                with_thousands(LAVAPIPE_LOOP_BUDGET)
            ),
            Self::StackOverflow => format!(
                "a ray tree branched deeper than the GPU stack ({stack_size} levels); its deepest rays were dropped"
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
pub fn messages(status: u32, stack_size: u32) -> Vec<String> {
    let known = StatusBit::ALL.iter().fold(0, |bits, b| bits | *b as u32);
    let mut out: Vec<String> =
        StatusBit::ALL.into_iter().filter(|b| status & *b as u32 != 0).map(|b| b.message(stack_size)).collect();
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
            let text = messages(*value, 7);
            assert_eq!(text, [bit.message(7)], "{name}");
            assert!(!text[0].contains("unknown"), "{name}: {text:?}");
        }
        assert_eq!(constants.len(), StatusBit::ALL.len(), "a StatusBit has no constant in layout.wgsl");
    }

    #[test]
    fn unknown_bits_are_reported_not_dropped() {
        let text = messages(STATUS_LOOP_LIMIT | 0x40, 1);
        assert_eq!(text.len(), 2, "{text:?}");
        assert!(text[1].contains("unknown") && text[1].contains("0x40"), "{text:?}");
        assert!(messages(0, 1).is_empty());
    }

    #[test]
    fn messages_print_the_budget_and_the_stack() {
        assert!(StatusBit::DriverLoopCutoff.message(1).contains(&with_thousands(LAVAPIPE_LOOP_BUDGET)));
        assert!(StatusBit::StackOverflow.message(64).contains("(64 levels)"));
        assert_eq!(with_thousands(1_234_567), "1,234,567");
        assert_eq!(with_thousands(999), "999");
    }
}
