//! How large a ray tree can grow (issue 13, point 8): a hit on a material with both k_r and k_t
//! spawns two rays, so a tree can double at every level up to `max_depth`, unless the bailout
//! stops it first. The path weight of a child is its parent's times k_r or k_t (k_r + k_t under
//! total internal reflection), so each branch ends where its own product of k falls below the
//! bailout b: a glass of k_r = 0.06 spawns a reflection only while 0.06 stays above b, so its
//! trees stay small however deep the transmission goes. `ray_tree_bound` counts the largest tree
//! any sequence of hits can make; a scene whose bound passes `WARN_RAYS_PER_SAMPLE` is warned
//! about at load, with the bound and the remedy.

use super::desc::{GlobalAttenuation, RenderSettings, SceneDesc};
use super::material::MaterialDesc;
use super::number::{format_number, format_rounded};

/// Rays of one camera sample's tree beyond which a scene is warned about: the GPU's walk bound
/// is about as many (65,000 nodes), and on the CPU a 640×480 image of such pixels is 2e10 rays.
pub const WARN_RAYS_PER_SAMPLE: f64 = 65_536.0;

/// The levels of the deepest ray a tree can reach: `max_depth`, or fewer where the bailout
/// stops every path first.
pub fn reachable_depth(desc: &SceneDesc, settings: &RenderSettings) -> u32 {
    let gain = largest_gain(desc);
    if settings.bailout > 0.0 && gain < 1.0 {
        if gain <= 0.0 {
            return 0;
        }
        // The largest k with gain^k ≥ bailout.
        let levels = (settings.bailout.ln() / gain.ln()).floor();
        return settings.max_depth.min(levels as u32);
    }
    settings.max_depth
}

/// Whether a bailout of `bailout` can cut a child ray within `depth` levels: `false` only where
/// every child's path weight provably stays at or above it, so that the render is the one
/// without a bailout, ray for ray (`glint report` then leaves out the rows that vary only the
/// bailout: a k_r = 0.9 mirror's 0.9^8 = 0.43 is above every bailout of its sweep). Each level
/// multiplies every channel of the weight by at least the least channel of some nonzero k_r or
/// k_t (under total internal reflection by k_r + k_t, no less), and a constant global
/// attenuation by 1/c; one that falls with distance (l or q > 0) can make any weight small.
pub fn bailout_can_cut(desc: &SceneDesc, bailout: f64, depth: u32) -> bool {
    if bailout <= 0.0 || depth == 0 {
        return false;
    }
    let g = &desc.world.global_attenuation;
    if g.l != 0.0 || g.q != 0.0 {
        return true;
    }
    let a = (1.0 / g.c).min(1.0);
    let factors = used_materials(desc).flat_map(|(_, m)| [m.kr, m.kt]).filter(|k| k.max_channel() > 0.0);
    let Some(least) = factors.map(|k| k.min_channel()).reduce(f64::min) else {
        // No child rays at all.
        return false;
    };
    // Level k's weight is at least (least·a)^k: the least at the deepest level where a level
    // shrinks it, at the first where it grows. One more factor a (the camera ray is not
    // attenuated: a bound, not the weight) and the margin keep it below every weight, the f32
    // weights the bailout judges included.
    let f = least * a;
    let worst = if f < 1.0 { f.powi(depth.min(i32::MAX as u32) as i32) } else { f };
    worst * a < bailout * (1.0 + 1e-4)
}

/// g: the largest max-channel k_r + k_t of any material an object uses, times the most the
/// world's global attenuation can multiply by: the most a level multiplies a path's weight by.
fn largest_gain(desc: &SceneDesc) -> f64 {
    let most = used_materials(desc).map(|(_, m)| m.gain(glint_types::Integrator::Whitted)).fold(0.0, f64::max);
    most * largest_attenuation(&desc.world.global_attenuation)
}

/// The largest global attenuation 1 / (c + l·t + q·t²) over t ≥ 0, at least 1: with c < 1 a
/// near hit's weight grows. Validation keeps the denominator positive; a scene it refuses is
/// bounded as if unattenuated.
pub(crate) fn largest_attenuation(g: &GlobalAttenuation) -> f64 {
    let vertex = if g.q > 0.0 && g.l < 0.0 { g.c - g.l * g.l / (4.0 * g.q) } else { g.c };
    let least = vertex.min(g.c);
    if least > 0.0 && least.is_finite() { (1.0 / least).max(1.0) } else { 1.0 }
}

/// The materials some object uses, in the scene's order: a material no ray can hit shapes no
/// tree (a scene file may define materials it does not use).
fn used_materials(desc: &SceneDesc) -> impl Iterator<Item = (&String, &MaterialDesc)> {
    let used: std::collections::HashSet<&str> = desc.objects.iter().flat_map(|o| o.materials()).collect();
    desc.materials.iter().filter(move |(name, _)| used.contains(name.as_str()))
}

/// What one hit can spawn, as steps of a path weight's quantized logarithm (`Quantized`): a
/// reflected and a refracted child, or under total internal reflection one child of k_r + k_t.
/// `None` where the factor is 0 (no child).
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
struct Branching {
    reflect: Option<i64>,
    refract: Option<i64>,
    internal: Option<i64>,
}

/// Path weights w ≥ b as i = ⌈ln(w/b) / step⌉, rounded up so that a quantized tree is never
/// smaller than a real one: a child's index is its parent's plus its factor's (each rounded up).
struct Quantized {
    step: f64,
    root: i64,
}

/// Weight levels between the bailout and 1 at most: the rounding up adds at most one step per
/// level, 0.1 % of the weight at b = 1/255.
const LEVELS: f64 = 4096.0;
/// Work (levels × weights × kinds of hit) the recursion may take: a coarser grid beyond it
/// (a scene of thousands of materials, or weights that grow by total internal reflection).
const MAX_WORK: f64 = 5e7;

impl Quantized {
    /// The grid for `bailout`, no finer than `LEVELS` steps from it to 1, and coarse enough that
    /// the recursion's work (levels × weights × `kinds` of hit, weights growing by `rise`, the
    /// largest ln k ≥ 0, a level) stays within `MAX_WORK`: a coarser grid rounds up more.
    fn new(bailout: f64, depth: usize, kinds: usize, rise: f64) -> Self {
        let span = -bailout.ln();
        let levels = depth as f64;
        let step = (span / LEVELS).max(1e-3).max(levels * kinds as f64 * (span + rise * levels) / MAX_WORK);
        Self { step, root: (span / step).ceil() as i64 }
    }

    fn factor(&self, k: f64) -> Option<i64> {
        (k > 0.0).then(|| (k.ln() / self.step).ceil() as i64)
    }
}

/// The largest tree (rays, the camera ray included) of one camera sample under `settings`, over
/// every sequence of hits on the materials objects use, each level of it: `[d]` is the bound
/// with `max_depth = d`. Channels are taken at their largest (the product of max-channel
/// factors bounds the max channel of the product), and each level may multiply by the world's
/// largest global attenuation too.
fn bounds_by_depth(desc: &SceneDesc, settings: &RenderSettings) -> Vec<f64> {
    let g = largest_attenuation(&desc.world.global_attenuation);
    let factors: Vec<[f64; 3]> = used_materials(desc)
        .map(|(_, m)| {
            let kr = m.kr.max_channel() * g;
            let kt = m.kt.max_channel() * g;
            let internal = if kt > 0.0 { m.gain(glint_types::Integrator::Whitted) * g } else { 0.0 };
            [kr, kt, internal]
        })
        .collect();
    // Within the allowed depth: a refused max_depth (u32::MAX) is warned of in the same pass.
    let depth = settings.max_depth.min(crate::limits::MAX_DEPTH) as usize;
    let full = |both: bool, one: bool| -> Vec<f64> {
        (0..=depth)
            .map(|d| match (both, one) {
                (true, _) => 2f64.powi(d as i32 + 1) - 1.0,
                (false, true) => d as f64 + 1.0,
                (false, false) => 1.0,
            })
            .collect()
    };
    let both = factors.iter().any(|f| f[0] > 0.0 && f[1] > 0.0);
    let one = factors.iter().any(|f| f.iter().any(|&k| k > 0.0));
    // NaN (refused, but warned of in the same pass) as no bailout.
    if settings.bailout.is_nan() || settings.bailout <= 0.0 {
        return full(both, one);
    }
    let rise = factors.iter().flatten().filter(|&&k| k > 0.0).map(|k| k.ln()).fold(0.0, f64::max);
    let q = Quantized::new(settings.bailout.min(1.0), depth, factors.len(), rise);
    let mut kinds: Vec<Branching> = factors
        .iter()
        .map(|f| Branching { reflect: q.factor(f[0]), refract: q.factor(f[1]), internal: q.factor(f[2]) })
        .collect();
    kinds.sort_unstable();
    kinds.dedup();
    // Indices beyond the root only where a factor is ≥ 1: a weight that grows.
    let rise = kinds.iter().flat_map(|k| [k.reflect, k.refract, k.internal]).flatten().fold(0, i64::max);
    let top = q.root + rise * depth as i64;
    let width = top as usize + 1;
    // rays[i]: the largest tree below a ray of weight index i with the levels left so far.
    let mut rays = vec![1.0_f64; width];
    let mut out = vec![1.0];
    for _ in 0..depth {
        // Clamped at the top: only weights no tree reaches go beyond it.
        let child = |rays: &[f64], i: usize, step: Option<i64>| match step {
            Some(s) if i as i64 + s >= 0 => rays[((i as i64 + s) as usize).min(width - 1)],
            Some(_) | None => 0.0,
        };
        let next: Vec<f64> = (0..width)
            .map(|i| {
                let spawned = kinds
                    .iter()
                    .map(|k| {
                        let split = child(&rays, i, k.reflect) + child(&rays, i, k.refract);
                        split.max(child(&rays, i, k.internal))
                    })
                    .fold(0.0, f64::max);
                1.0 + spawned
            })
            .collect();
        let settled = next == rays;
        rays = next;
        out.push(rays[q.root as usize]);
        if settled {
            // No deeper level adds a ray: every branch has fallen below the bailout.
            out.resize(depth + 1, rays[q.root as usize]);
            break;
        }
    }
    out
}

/// The largest number of rays one camera sample's Whitted tree can trace under `settings`
/// (see `bounds_by_depth`): what `--max-rays-per-sample` must allow.
pub fn ray_tree_bound(desc: &SceneDesc, settings: &RenderSettings) -> f64 {
    bounds_by_depth(desc, settings).last().copied().unwrap_or(1.0)
}

/// The warning for a scene whose ray tree can grow past `WARN_RAYS_PER_SAMPLE` rays a camera
/// sample, naming a branching material, the bound and the remedy; `None` for the others.
pub fn unbounded_ray_tree(desc: &SceneDesc, settings: &RenderSettings) -> Option<String> {
    let (cause, remedy) = ray_tree_problem(desc, settings)?;
    Some(format!("{cause}; {remedy}"))
}

/// `unbounded_ray_tree`'s finding without its remedy (a branching material, what stops it and the
/// bound), for a caller whose settings are not the user's to change: `glint report`'s fixed
/// reference, which has no --depth or --bailout.
pub fn unbounded_ray_tree_cause(desc: &SceneDesc, settings: &RenderSettings) -> Option<String> {
    ray_tree_problem(desc, settings).map(|(cause, _)| cause)
}

/// The finding and the remedy of `unbounded_ray_tree`.
fn ray_tree_problem(desc: &SceneDesc, settings: &RenderSettings) -> Option<(String, String)> {
    // A path follows one lobe a bounce: it never branches.
    if settings.integrator == glint_types::Integrator::Path {
        return None;
    }
    let (name, m) = used_materials(desc).find(|(_, m)| m.kr.max_channel() > 0.0 && m.kt.max_channel() > 0.0)?;
    let by_depth = bounds_by_depth(desc, settings);
    let rays = by_depth.last().copied().unwrap_or(1.0);
    if rays <= WARN_RAYS_PER_SAMPLE {
        return None;
    }
    let depth = reachable_depth(desc, settings);
    let stop = if depth < settings.max_depth {
        format!("the bailout ({}) stops every branch only after {depth} levels", format_number(settings.bailout))
    } else {
        format!(
            "the bailout ({}) cannot stop it before max_depth = {}",
            format_number(settings.bailout),
            settings.max_depth
        )
    };
    // The deepest tree within the threshold.
    let shallower = by_depth.iter().rposition(|&r| r <= WARN_RAYS_PER_SAMPLE).unwrap_or(0);
    let lower = format!("lower render.max_depth (--depth) to {shallower}");
    let gain = largest_gain(desc);
    let remedy = if settings.bailout > 0.0 && gain < 1.0 {
        match least_bailout(desc, settings) {
            Some(b) => format!("raise render.bailout to {} or more, or {lower}", format_number(b)),
            None => lower,
        }
    } else if settings.bailout > 0.0 {
        // The bailout is set: asking for one (as before) read as if it were not (a glTF glass,
        // k_r + k_t = 0.04 + 0.96, under the default 1/255).
        let attenuation = largest_attenuation(&desc.world.global_attenuation);
        if attenuation > 1.0 {
            // The material's own sum is below 1: the world's global attenuation lifts it.
            format!(
                "world.global_attenuation reaches {} near a hit (c = {} < 1), which lifts k_r + k_t to {}, so no \
                 bailout stops it: {lower}, or raise global_attenuation's c (and l, q) so that 1 / (c + l·d + q·d²) \
                 stays ≤ 1",
                format_rounded(attenuation, 3),
                format_number(desc.world.global_attenuation.c),
                format_rounded(gain, 3)
            )
        } else {
            format!(
                "k_r + k_t = {} keeps a path's weight from level to level, so no bailout stops it: {lower}, or make \
                 k_r + k_t < 1",
                format_number(gain)
            )
        }
    } else {
        format!("set render.bailout (--bailout; e.g. 1/255, with k_r + k_t < 1) or {lower}")
    };
    let full = 2f64.powf(f64::from(settings.max_depth) + 1.0) - 1.0;
    let count = if rays == full {
        // Widened: max_depth = u32::MAX (refused, but warned of in the same pass) overflowed.
        let exponent = u64::from(settings.max_depth) + 1;
        if rays.is_finite() { format!("2^{exponent} − 1 ≈ {rays:.1e}") } else { format!("2^{exponent} − 1") }
    } else {
        format!("≈ {rays:.1e}")
    };
    let cause = format!(
        "materials.{name} reflects and refracts (k_r = {}, k_t = {}), so a ray tree can branch at every level, and \
         {stop}: up to {count} rays per camera sample",
        format_number(m.kr.max_channel()),
        format_number(m.kt.max_channel()),
    );
    Some((cause, remedy))
}

/// The least bailout, rounded up to 3 digits, under which the tree stays within
/// `WARN_RAYS_PER_SAMPLE`; `None` where even a bailout of 1 does not.
fn least_bailout(desc: &SceneDesc, settings: &RenderSettings) -> Option<f64> {
    let fits = |b: f64| {
        let s = RenderSettings { bailout: b, ..settings.clone() };
        ray_tree_bound(desc, &s) <= WARN_RAYS_PER_SAMPLE
    };
    if !fits(1.0) {
        return None;
    }
    // The bound only falls as the bailout rises: bisect its logarithm.
    let (mut lo, mut hi) = (settings.bailout.ln(), 0.0_f64);
    for _ in 0..24 {
        let mid = 0.5 * (lo + hi);
        if fits(mid.exp()) { hi = mid } else { lo = mid }
    }
    let rounded = format_rounded(hi.exp(), 3).parse::<f64>().unwrap_or(hi.exp());
    // Rounding may have gone below: the next 3-digit value up.
    Some(if fits(rounded) { rounded } else { next_three_digits(rounded) })
}

fn next_three_digits(v: f64) -> f64 {
    let unit = 10f64.powf(v.log10().floor() - 2.0);
    ((v / unit).floor() + 1.0) * unit
}

#[cfg(test)]
mod tests {
    use super::*;

    const SPHERE: &str = "[[objects]]\ntype = \"sphere\"\ncenter = [0.0, 0.0, 0.0]\nradius = 1.0\n";

    /// A sphere of `material` (named glass).
    fn scene(material: &str) -> SceneDesc {
        let head = "[camera]\nposition = [0.0, 0.0, -4.0]\nlook_at = [0.0, 0.0, 0.0]\n";
        toml::from_str(&format!("{head}[materials.glass]\n{material}\n{SPHERE}material = \"glass\"\n"))
            .expect("scene parses")
    }

    fn settings(max_depth: u32, bailout: f64) -> RenderSettings {
        RenderSettings { max_depth, bailout, ..RenderSettings::default() }
    }

    #[test]
    fn a_bailout_cuts_nothing_where_every_weight_stays_above_it() {
        // A k_r = 0.9 mirror: 0.9^8 = 0.43 is above 1/32; 0.9^40 = 0.015 is not.
        let mirror = scene("kr = 0.9");
        assert!(!bailout_can_cut(&mirror, 1.0 / 32.0, 8));
        assert!(bailout_can_cut(&mirror, 1.0 / 32.0, 40));
        // whitted's glass: 0.08^2 = 0.0064 > 1/255, 0.08^3 is not.
        let glass = scene("kr = 0.08\nkt = 0.9");
        assert!(!bailout_can_cut(&glass, 1.0 / 255.0, 2));
        assert!(bailout_can_cut(&glass, 1.0 / 255.0, 3));
        // The bound takes the least channel: a red mirror (0.9, 0, 0) is judged by its 0, so the
        // rows are kept (its red channel alone would stay above the bailout: conservative).
        assert!(bailout_can_cut(&scene("kr = [0.9, 0.0, 0.0]"), 1.0 / 255.0, 2));
        // No child rays, no bailout, no depth: nothing to cut.
        assert!(!bailout_can_cut(&scene("kd = 0.7"), 1.0 / 32.0, 8));
        assert!(!bailout_can_cut(&mirror, 0.0, 8) && !bailout_can_cut(&mirror, 1.0, 0));
        // An attenuation that falls with distance can make any weight small.
        let mut far = mirror.clone();
        far.world.global_attenuation.l = 0.1;
        assert!(bailout_can_cut(&far, 1.0 / 32.0, 1));
    }

    #[test]
    fn a_bailout_already_set_is_not_asked_for_again() {
        // glTF's clear glass: k_r + k_t = 1 keeps the weight under total internal reflection, so
        // no bailout ends that chain; its reflections end after 56 levels (0.04·0.96^k < 1/255).
        let glass = scene("kr = 0.04\nkt = 0.96");
        assert!(unbounded_ray_tree(&glass, &settings(40, 1.0 / 255.0)).is_none(), "861 rays at most");
        // A stronger reflection branches again (0.1² ≥ 1/255), and its trees pass the threshold.
        let glass = scene("kr = 0.1\nkt = 0.9");
        let text = unbounded_ray_tree(&glass, &settings(1024, 1.0 / 255.0)).expect("a warning");
        assert!(text.contains("k_r + k_t = 1 keeps a path's weight"), "{text}");
        assert!(
            text.contains("up to ≈ 7.9e4 rays per camera sample")
                && text.contains("lower render.max_depth (--depth) to 850")
                && !text.contains("set render.bailout"),
            "{text}"
        );
    }

    /// The bound of a sphere of `material` under `max_depth` and `bailout`.
    fn bound(material: &str, max_depth: u32, bailout: f64) -> f64 {
        ray_tree_bound(&scene(material), &settings(max_depth, bailout))
    }

    #[test]
    fn the_bound_counts_each_branch_until_its_own_weight_falls_below_the_bailout() {
        // Cornell-gi's glass (a teacher's count): a reflection (0.06) spawns no second one
        // (0.06² < 1/255), so a tree is the transmitted chain and one reflected chain from each
        // of its levels, Σ_{k=0}^{16} (1 + k) = 153 rays, not 2^17 − 1.
        assert_eq!(bound("kr = 0.06\nkt = 0.92", 16, 1.0 / 255.0), 153.0);
        // Without a bailout every branch goes on: a full binary tree, or a chain.
        assert_eq!(bound("kr = 0.06\nkt = 0.92", 16, 0.0), 2f64.powi(17) - 1.0);
        assert_eq!(bound("kr = 0.9", 16, 0.0), 17.0);
        // Against the recursion itself (every hit on every material, unquantized): never
        // below it, and close (87, 195, 224 and 91 rays against 87, 195, 218 and 91).
        for (materials, depth, bailout) in [
            (&[[0.5, 0.5]][..], 12, 0.125),
            (&[[0.3, 0.6], [0.9, 0.0]][..], 12, 0.01),
            (&[[0.7, 0.2], [0.0, 0.8]][..], 10, 1.0 / 255.0),
            (&[[0.06, 0.92]][..], 12, 1.0 / 255.0),
        ] {
            let text: String = materials
                .iter()
                .enumerate()
                .map(|(i, [kr, kt])| format!("[materials.m{i}]\nkr = {kr}\nkt = {kt}\n{SPHERE}material = \"m{i}\"\n"))
                .collect();
            let desc: SceneDesc =
                toml::from_str(&format!("[camera]\nposition = [0.0, 0.0, -4.0]\nlook_at = [0.0, 0.0, 0.0]\n{text}"))
                    .expect("scene parses");
            let exact = recursion(1.0, depth, materials, bailout);
            let bound = ray_tree_bound(&desc, &settings(depth, bailout));
            assert!(bound >= exact && bound <= exact * 1.05, "{materials:?}: {bound} against {exact}");
        }
    }

    /// The largest tree below a ray of weight `w` with `depth` levels left: a split into k_r and
    /// k_t, or total internal reflection into k_r + k_t, on whichever material grows it most.
    fn recursion(w: f64, depth: u32, materials: &[[f64; 2]], bailout: f64) -> f64 {
        let child = |k: f64| {
            if k > 0.0 && w * k >= bailout { recursion(w * k, depth - 1, materials, bailout) } else { 0.0 }
        };
        let spawned = if depth == 0 {
            0.0
        } else {
            materials
                .iter()
                .map(|&[kr, kt]| {
                    let internal = if kt > 0.0 { child(kr + kt) } else { 0.0 };
                    (child(kr) + child(kt)).max(internal)
                })
                .fold(0.0, f64::max)
        };
        1.0 + spawned
    }

    #[test]
    fn glass_between_mirrors_without_a_bailout_is_warned_about_with_its_bound() {
        let glass = scene("kr = 0.5\nkt = 0.4");
        let text = unbounded_ray_tree(&glass, &settings(1024, 0.0)).expect("a warning");
        assert!(text.starts_with("materials.glass reflects and refracts (k_r = 0.5, k_t = 0.4)"), "{text}");
        assert!(
            text.contains("cannot stop it before max_depth = 1024: up to 2^1025 − 1 rays per camera sample"),
            "{text}"
        );
        assert!(unbounded_ray_tree(&glass, &settings(20, 0.0)).unwrap().contains("up to 2^21 − 1 ≈ 2.1e6 rays"));
        assert!(text.ends_with("set render.bailout (--bailout; e.g. 1/255, with k_r + k_t < 1) or lower render.max_depth (--depth) to 15"), "{text}");
        // The default bailout bounds it: 563 rays, however deep.
        assert_eq!(reachable_depth(&glass, &settings(1024, 1.0 / 255.0)), 52);
        assert!(unbounded_ray_tree(&glass, &settings(1024, 1.0 / 255.0)).is_none());
        // A bailout too small to bound it in time is raised to the least that does.
        let small = unbounded_ray_tree(&glass, &settings(1024, 1e-6)).expect("a warning");
        assert!(small.contains("the bailout (1e-6) stops every branch only after"), "{small}");
        let least: f64 = small
            .split("raise render.bailout to ")
            .nth(1)
            .and_then(|rest| rest.split(' ').next())
            .and_then(|v| v.parse().ok())
            .unwrap_or_else(|| panic!("{small}"));
        assert!(bound("kr = 0.5\nkt = 0.4", 1024, least) <= WARN_RAYS_PER_SAMPLE, "{small}");
        assert!(bound("kr = 0.5\nkt = 0.4", 1024, least * 0.99) > WARN_RAYS_PER_SAMPLE, "{small}");
        // 15 levels (65,535 rays) is the largest full tree not warned about.
        assert!(unbounded_ray_tree(&glass, &settings(15, 0.0)).is_none());
        assert!(unbounded_ray_tree(&glass, &settings(16, 0.0)).is_some());
    }

    #[test]
    fn a_gain_of_one_or_more_defeats_the_bailout_and_a_tree_without_branches_is_not_warned_about() {
        let gain = scene("kr = 0.6\nkt = 0.6");
        assert_eq!(reachable_depth(&gain, &settings(40, 0.5)), 40);
        // Total internal reflection (1.2) raises the weight until both branches pass 0.5.
        assert!(unbounded_ray_tree(&gain, &settings(60, 0.5)).is_some());
        let mirror = scene("kr = 1.0");
        assert!(unbounded_ray_tree(&mirror, &settings(1024, 0.0)).is_none(), "a chain, not a tree");
    }

    #[test]
    fn a_global_attenuation_that_lifts_the_weight_is_named_as_the_cause() {
        let mut glass = scene("kr = 0.5\nkt = 0.4");
        glass.world.global_attenuation = GlobalAttenuation { c: 0.5, l: 0.0, q: 0.0 };
        let text = unbounded_ray_tree(&glass, &settings(20, 1.0 / 255.0)).expect("a warning");
        assert!(
            text.contains("world.global_attenuation reaches 2 near a hit (c = 0.5 < 1), which lifts k_r + k_t to 1.8"),
            "{text}"
        );
        assert!(!text.contains("make k_r + k_t < 1"), "{text}");
    }

    #[test]
    fn a_global_attenuation_that_can_exceed_one_counts_in_the_bound() {
        // f_att = 1 / (0.5 + t) reaches 2 at t = 0: a mirror of 0.5 can keep its weight.
        let mut mirror = scene("kr = 0.5");
        assert_eq!(ray_tree_bound(&mirror, &settings(40, 0.125)), 4.0);
        mirror.world.global_attenuation = GlobalAttenuation { c: 0.5, l: 1.0, q: 0.0 };
        assert_eq!(ray_tree_bound(&mirror, &settings(40, 0.125)), 41.0);
    }

    #[test]
    fn a_branching_material_no_object_uses_is_not_warned_about() {
        let head = "[camera]\nposition = [0.0, 0.0, -4.0]\nlook_at = [0.0, 0.0, 0.0]\n";
        let text = format!(
            "{head}[materials.glass]\nkr = 0.3\nkt = 0.9\n[materials.mirror]\nkr = 0.5\n{SPHERE}material = \"mirror\"\n"
        );
        let mirrors: SceneDesc = toml::from_str(&text).expect("scene parses");
        assert!(unbounded_ray_tree(&mirrors, &settings(1024, 0.0)).is_none(), "glass is on nothing");
        // 0.5^3 ≥ 0.1 > 0.5^4; counting glass's gain of 1.2, the bailout could stop nothing.
        assert_eq!(reachable_depth(&mirrors, &settings(1024, 0.1)), 3);
    }
}
