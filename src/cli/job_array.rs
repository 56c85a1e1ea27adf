//! Job-array indices: `I/N` as `--tile` and `--shard` take it, and in messages what of 0..N is
//! missing, as the runs a job array's `--array` takes ("3", "5-9"), so that 3,000 missing tiles
//! or a million missing shards are a line, not megabytes.

/// `I/N`, part I of N (I from 0), or `N` alone where `index_optional` (the index then comes
/// from the scheduler); `part` names a part in messages ("tile", "shard"). Whether I < N is the
/// caller's to judge.
pub fn parse_part(s: &str, part: &str, index_optional: bool) -> Result<(Option<u32>, u32), String> {
    let forms = if index_optional { "I/N or N" } else { "I/N" };
    // An index from 0, a count from 1 (`--tile 0` was refused after "from 0" was offered).
    let number =
        |t: &str, least: u32, what: &str| {
            t.trim().parse::<u32>().ok().filter(|&v| v >= least).ok_or_else(|| {
                format!("'{t}' is not a whole number from {least} to {} ({what}); use {forms}", u32::MAX)
            })
        };
    let index = |t: &str| number(t, 0, &format!("the {part}'s index"));
    let count = |t: &str| number(t, 1, &format!("the {part} count"));
    match s.split_once('/') {
        Some((i, n)) => Ok((Some(index(i)?), count(n)?)),
        None if index_optional => Ok((None, count(s)?)),
        None => Err(format!("'{s}' is not I/N ({part} I of N, I from 0)")),
    }
}

/// Indices `first`, `first + step`, … up to `last` (`step` 1: a run of consecutive ones).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Run {
    pub first: u32,
    pub last: u32,
    pub step: u32,
}

/// The longest `--array` value Slurm's controller takes: 4,097 characters were refused with
/// "Pathname of a file, directory or other parameter too long" (Slurm 22.05, tested), and a
/// tester's 6,967 for 1,503 scattered tiles was.
pub const SLURM_ARRAY_SPEC_MAX: usize = 4096;

/// What of 0..N is missing: how many, and as runs.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Missing {
    pub count: u64,
    pub runs: Vec<Run>,
}

impl Missing {
    /// For a message: "1-3, 7, 9, 11, …, 99" (a progression of four or more is its first two,
    /// an ellipsis and its last; three are as short written out).
    pub fn listing(&self) -> String {
        let run = |r: &Run| match (r.step, (r.last - r.first) / r.step.max(1) + 1) {
            (_, 1) => r.first.to_string(),
            (1, _) => format!("{}-{}", r.first, r.last),
            (s, n) if n <= 3 => (0..n).map(|k| (r.first + k * s).to_string()).collect::<Vec<_>>().join(", "),
            (s, _) => format!("{}, {}, …, {}", r.first, r.first + s, r.last),
        };
        self.runs.iter().map(run).collect::<Vec<_>>().join(", ")
    }

    /// Slurm's `--array` value for the missing indices: "1-3,7-99:2" (its step syntax, so that
    /// every other tile of 3,007 missing is 8 characters, not 6,967).
    pub fn array_spec(&self) -> String {
        let run = |r: &Run| match r.step {
            _ if r.first == r.last => r.first.to_string(),
            1 => format!("{}-{}", r.first, r.last),
            s if (r.last - r.first) / s == 1 => format!("{},{}", r.first, r.last),
            s => format!("{}-{}:{s}", r.first, r.last),
        };
        self.runs.iter().map(run).collect::<Vec<_>>().join(",")
    }

    /// How to run the missing indices as a Slurm array: "as a Slurm array, --array=…", or,
    /// where the indices are too scattered for one value Slurm takes, what to do instead.
    pub fn slurm_array(&self) -> String {
        let spec = self.array_spec();
        if spec.len() <= SLURM_ARRAY_SPEC_MAX {
            return format!("as a Slurm array, --array={spec}");
        }
        format!(
            "too scattered for one Slurm array: its --array value would be {} characters, and Slurm takes at most \
             {SLURM_ARRAY_SPEC_MAX}; submit the whole array again with a script that exits at once where its \
             output exists",
            spec.len()
        )
    }
}

/// The indices of 0..`count` not in `present` (ascending, each below `count`), as runs, and
/// how many they are. Walks the present indices only: a count of 2^32 costs nothing. Lone
/// indices an equal step apart, three or more, are one run with that step (every other tile).
pub fn missing_runs(present: impl IntoIterator<Item = u32>, count: u32) -> Missing {
    let mut runs: Vec<Run> = Vec::new();
    let mut missing = 0u64;
    let mut next = 0u32;
    let mut gap = |from: u32, to: u32, runs: &mut Vec<Run>| {
        // [from, to) is missing.
        if from < to {
            missing += u64::from(to - from);
            let last = to - 1;
            match runs.last_mut() {
                // A lone index that continues a progression of lone ones.
                Some(r) if from == last && r.step > 1 && from - r.last == r.step => r.last = from,
                // A second lone index after a lone one starts a progression.
                Some(r) if from == last && r.first == r.last => {
                    *r = Run { first: r.first, last: from, step: from - r.first }
                }
                // A pair that this index does not continue: its second may start one with it
                // (1, 3, 6, 9 is 1 and 3-9:3).
                Some(r) if from == last && r.step > 1 && r.first + r.step == r.last => {
                    let second = r.last;
                    *r = Run { first: r.first, last: r.first, step: 1 };
                    runs.push(Run { first: second, last: from, step: from - second });
                }
                _ => runs.push(Run { first: from, last, step: 1 }),
            }
        }
    };
    for i in present {
        // Ascending and unique by the callers (map keys); a repeat or an index past `count`
        // adds no gap.
        if i >= next {
            gap(next, i.min(count), &mut runs);
            next = i.saturating_add(1);
        }
    }
    gap(next, count, &mut runs);
    Missing { count: missing, runs }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn missing_indices_are_named_as_runs() {
        let said = |m: Missing| (m.count, m.listing(), m.array_spec());
        assert_eq!(said(missing_runs([0, 4, 5, 6, 8, 11], 13)), (7, "1-3, 7, 9-10, 12".into(), "1-3,7,9-10,12".into()));
        assert_eq!(said(missing_runs([], 3007)), (3007, "0-3006".into(), "0-3006".into()));
        assert_eq!(said(missing_runs(0..5, 5)), (0, String::new(), String::new()));
        let all_but_0 = format!("1-{}", u32::MAX - 1);
        assert_eq!(said(missing_runs([0], u32::MAX)), (u64::from(u32::MAX) - 1, all_but_0.clone(), all_but_0));
    }

    #[test]
    fn lone_indices_an_equal_step_apart_are_one_run_with_slurms_step_syntax() {
        // Every odd tile of 3,007 missing was "--array=1,3,5,…", 6,967 characters, which
        // sbatch refused ("Pathname of a file, directory or other parameter too long").
        let odd = missing_runs((0..3007).step_by(2), 3007);
        assert_eq!((odd.count, odd.listing(), odd.array_spec()), (1503, "1, 3, …, 3005".into(), "1-3005:2".into()));
        assert_eq!(odd.slurm_array(), "as a Slurm array, --array=1-3005:2");
        // Two or three lone ones are written out; a pair the next does not continue gives its
        // second to a progression that it starts.
        let m = missing_runs([0, 2, 4, 6, 8, 9, 10, 12, 13, 14, 15, 16, 17, 18, 19, 21, 22, 24], 26);
        assert_eq!(m.listing(), "1, 3, …, 7, 11, 20, 23, 25");
        let m = missing_runs([0, 2, 4, 5, 7, 8, 10], 11);
        assert_eq!((m.listing(), m.array_spec()), ("1, 3, 6, 9".into(), "1,3-9:3".into()));
        // Runs and progressions together: a grid column missing (every 4th) beside two runs.
        let present = (0..40).filter(|i| i % 4 != 1 && !(20..23).contains(i) && *i != 39);
        let m = missing_runs(present, 40);
        assert_eq!(m.array_spec(), "1-17:4,20-22,25-37:4,39");
        assert_eq!(m.count, 5 + 3 + 4 + 1);
    }

    #[test]
    fn an_array_value_longer_than_slurm_takes_is_not_offered() {
        // Present indices 2 or 3 apart at random: lone missing ones and pairs, few progressions.
        let (mut at, mut state) = (0u32, 0x2545_f491_u32);
        let present: Vec<u32> = (0..2000)
            .map(|_| {
                state ^= state << 13;
                state ^= state >> 17;
                state ^= state << 5;
                at += 2 + state % 2;
                at
            })
            .collect();
        let m = missing_runs(present.iter().copied(), at + 1);
        assert!(m.array_spec().len() > SLURM_ARRAY_SPEC_MAX, "{}", m.array_spec().len());
        let said = m.slurm_array();
        assert!(said.starts_with("too scattered for one Slurm array: its --array value would be "), "{said}");
        assert!(said.contains("Slurm takes at most 4096") && !said.contains("--array="), "{said}");
    }

    #[test]
    fn a_count_of_0_is_refused_with_the_range_as_a_word_is() {
        // `--tile 0` got "a grid needs at least one tile" and exit 1, `--tile x` the range and
        // exit 2 (a tester).
        let said = "is not a whole number from 1 to 4294967295 (the tile count); use I/N or N";
        assert_eq!(parse_part("0", "tile", true), Err(format!("'0' {said}")));
        assert_eq!(parse_part("2/0", "tile", true), Err(format!("'0' {said}")));
        assert_eq!(parse_part("x", "tile", true), Err(format!("'x' {said}")));
        assert_eq!(parse_part("0/1", "shard", false), Ok((Some(0), 1)));
    }
}
