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

/// The indices of 0..`count` not in `present` (ascending, each below `count`), as runs, and
/// how many they are. Walks the present indices only: a count of 2^32 costs nothing.
pub fn missing_runs(present: impl IntoIterator<Item = u32>, count: u32) -> (u64, Vec<String>) {
    let mut runs = Vec::new();
    let mut missing = 0u64;
    let mut next = 0u32;
    let mut gap = |from: u32, to: u32, runs: &mut Vec<String>| {
        // [from, to) is missing.
        if from < to {
            missing += u64::from(to - from);
            runs.push(if to - from == 1 { from.to_string() } else { format!("{from}-{}", to - 1) });
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
    (missing, runs)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn missing_indices_are_named_as_runs() {
        let (n, runs) = missing_runs([0, 4, 5, 6, 8, 11], 13);
        assert_eq!((n, runs), (7, vec!["1-3".to_string(), "7".into(), "9-10".into(), "12".into()]));
        assert_eq!(missing_runs([], 3007), (3007, vec!["0-3006".to_string()]));
        assert_eq!(missing_runs(0..5, 5), (0, vec![]));
        assert_eq!(missing_runs([0], u32::MAX), (u64::from(u32::MAX) - 1, vec![format!("1-{}", u32::MAX - 1)]));
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
