//! Numbers and values in messages: as short as the value allows, never a 300-digit decimal or
//! a 200 kB value echoed back in full.

/// `v` in `%g` style with the shortest digits that read back to it: plain where that is short
/// (0.5, 120, 1e-4 as 0.0001), scientific outside [1e-4, 1e15) (5e-324, 1e300, 1e16).
pub fn format_number(v: f64) -> String {
    let magnitude = v.abs();
    if v == 0.0 || !v.is_finite() || (1e-4..1e15).contains(&magnitude) { v.to_string() } else { format!("{v:e}") }
}

/// A range's bound in a message: a power of ten from 1e4 up or 1e-4 down as `1e9`, `-1e9`,
/// `1e-9` (as the docs' tables write them; 1000000000 beside 1e-9 read as two styles), any
/// other number as `format_number` writes it.
pub fn format_bound(v: f64) -> String {
    let exponent = v.abs().log10().round();
    let power_of_ten = v != 0.0 && v.is_finite() && 10f64.powf(exponent) == v.abs();
    if power_of_ten && exponent.abs() >= 4.0 { format!("{v:e}") } else { format_number(v) }
}

/// A computed value (not one the user wrote) for a message: rounded to `digits` significant
/// digits, then written as `format_number` writes it (8e-5, not 7.999999797903001e-5).
pub fn format_rounded(v: f64, digits: usize) -> String {
    let rounded = format!("{v:.*e}", digits.saturating_sub(1)).parse().unwrap_or(v);
    format_number(rounded)
}

/// The distance between adjacent f64 values at |x| (at least the smallest normal's): how finely
/// a scene's own numbers hold a coordinate or an angle of that size (f32's, as the tracers
/// store them, is `glint_types::layout::f32_spacing`).
pub fn f64_spacing(x: f64) -> f64 {
    let exponent = (x.abs().max(f64::MIN_POSITIVE).to_bits() >> 52) as i32 - 1023;
    2f64.powi(exponent - 52)
}

/// A computed value beyond a `bound` it is said to exceed: `format_rounded` to the fewest digits,
/// from 3, that still read beyond it (a reach of 1e9 + 0.5 printed as "1000000000" seemed to
/// meet the bound 1e9 it was refused by).
pub fn format_beyond(v: f64, bound: f64) -> String {
    (3..=17)
        .map(|digits| format_rounded(v, digits))
        .find(|text| text.parse::<f64>().is_ok_and(|r| r.abs() > bound.abs()))
        .unwrap_or_else(|| format_number(v))
}

/// Choices as a sentence lists them: "a", "a, or b", "a, b, or c" (remedies of one message).
pub fn or_list(items: &[impl AsRef<str>]) -> String {
    match items.split_last() {
        Some((last, [])) => last.as_ref().to_string(),
        Some((last, rest)) => {
            let rest: Vec<&str> = rest.iter().map(AsRef::as_ref).collect();
            format!("{}, or {}", rest.join(", "), last.as_ref())
        }
        None => String::new(),
    }
}

/// serde's words in a scene author's: Rust's type names (`expected f64`, `expected u32`) as
/// what a scene file holds, and a float as `tidy_floats` writes it.
pub fn serde_words(message: &str) -> String {
    tidy_floats(message)
        .replace("expected f64", "expected a number")
        .replace("expected f32", "expected a number")
        .replace("expected u32", "expected a whole number from 0 to 4294967295")
}

/// serde's `floating point \`…\`` written as `format_number` writes it: serde prints every
/// digit, 309 of them for 1e308 and 320 zeros for 1e-320.
pub fn tidy_floats(message: &str) -> String {
    const MARK: &str = "floating point `";
    let mut out = String::with_capacity(message.len());
    let mut rest = message;
    while let Some(at) = rest.find(MARK) {
        let (head, tail) = rest.split_at(at + MARK.len());
        out.push_str(head);
        match tail.find('`') {
            Some(end) => {
                let (number, after) = tail.split_at(end);
                match number.parse::<f64>() {
                    Ok(v) => out.push_str(&format_number(v)),
                    Err(_) => out.push_str(number),
                }
                rest = after;
            }
            None => {
                rest = tail;
                break;
            }
        }
    }
    out.push_str(rest);
    out
}

/// Characters of an echoed value kept before it is cut.
pub const ECHO_CHARS: usize = 120;

/// Characters of one line of a message kept before it is cut: room for the message itself (a
/// ray-tree warning with its bound and remedies runs to 460), not for a value echoed whole.
pub const LINE_CHARS: usize = 1000;

/// `text` cut to `ECHO_CHARS` characters, saying how much was left out.
pub fn shorten(text: &str) -> String {
    cut(text, ECHO_CHARS)
}

fn cut(text: &str, chars: usize) -> String {
    match text.char_indices().nth(chars) {
        Some((at, _)) => format!("{}… ({} more bytes)", &text[..at], text.len() - at),
        None => text.to_string(),
    }
}

/// A line cut to `LINE_CHARS` characters in its middle, so that its start (what is wrong) and
/// its end (the reason a system call gives, after a path) both show: a 5,000-character texture
/// path made a 5 KB error line.
pub fn shorten_middle(text: &str) -> String {
    let chars = text.chars().count();
    if chars <= LINE_CHARS {
        return text.to_string();
    }
    let (head, tail) = (LINE_CHARS * 5 / 8, LINE_CHARS * 3 / 8);
    let start: String = text.chars().take(head).collect();
    let end: String = text.chars().skip(chars - tail).collect();
    format!("{start}…({} characters)…{end}", chars - head - tail)
}

/// Every line of a multi-line message cut to `LINE_CHARS` (the TOML parser shows the offending
/// line and a caret line under it, as long as the line is).
pub fn shorten_lines(text: &str) -> String {
    text.split('\n').map(|line| cut(line, LINE_CHARS)).collect::<Vec<_>>().join("\n")
}

#[cfg(test)]
mod tests {
    use super::{
        LINE_CHARS, format_beyond, format_number, serde_words, shorten, shorten_lines, shorten_middle, tidy_floats,
    };

    #[test]
    fn f64_spacing_is_the_step_to_the_next_f64() {
        for x in [1.0, 5e5, 1e6, 9e8, 1e30, -3.0] {
            assert_eq!(super::f64_spacing(x), f64::from_bits(x.abs().to_bits() + 1) - x.abs(), "{x}");
        }
    }

    #[test]
    fn a_value_beyond_its_bound_reads_beyond_it() {
        assert_eq!(format_beyond(1e9 + 0.5, 1e9), "1000000000.5");
        assert_eq!(format_beyond(1.234e10, 1e9), "12300000000");
        assert_eq!(format_beyond(-2e9, 1e9), "-2000000000");
    }

    #[test]
    fn rust_type_names_are_said_as_what_a_scene_holds() {
        assert_eq!(
            serde_words("invalid type: string \"x\", expected f64"),
            "invalid type: string \"x\", expected a number"
        );
        assert!(serde_words("integer `-1`, expected u32").ends_with("expected a whole number from 0 to 4294967295"));
    }

    #[test]
    fn serde_s_long_floats_are_written_short() {
        let long = format!("invalid type: floating point `1{}.0`, expected an array of length 3", "0".repeat(308));
        assert_eq!(tidy_floats(&long), "invalid type: floating point `1e308`, expected an array of length 3");
        assert_eq!(
            tidy_floats("floating point `0.5` and floating point `x`"),
            "floating point `0.5` and floating point `x`"
        );
        assert_eq!(tidy_floats("unclosed floating point `1"), "unclosed floating point `1");
    }

    #[test]
    fn a_long_line_keeps_its_start_and_its_end() {
        let line = format!("URI `{}.png`: File name too long (os error 36)", "a".repeat(5000));
        let cut = shorten_middle(&line);
        assert!(cut.starts_with("URI `aaa") && cut.ends_with("a.png`: File name too long (os error 36)"), "{cut}");
        assert!(cut.contains("…(4044 characters)…"), "{cut}");
        assert!(cut.chars().count() < LINE_CHARS + 30, "{}", cut.len());
        assert_eq!(shorten_middle("short"), "short");
    }

    #[test]
    fn long_values_are_cut_and_say_so() {
        assert_eq!(shorten("short"), "short");
        let long = "é".repeat(200);
        let cut = shorten(&long);
        assert!(cut.starts_with(&"é".repeat(120)) && cut.ends_with("… (160 more bytes)"), "{cut}");
        assert_eq!(
            shorten_lines(&format!("a\n{}\nb", "x".repeat(1600))),
            format!("a\n{}… (600 more bytes)\nb", "x".repeat(1000))
        );
    }

    #[test]
    fn extremes_are_scientific_and_everyday_numbers_plain() {
        assert_eq!(format_number(5e-324), "5e-324");
        assert_eq!(format_number(1e300), "1e300");
        assert_eq!(format_number(-1.5e20), "-1.5e20");
        assert_eq!(format_number(1e15), "1e15");
        assert_eq!(format_number(0.5), "0.5");
        assert_eq!(format_number(-120.0), "-120");
        assert_eq!(format_number(1e-4), "0.0001");
        assert_eq!(format_number(0.0), "0");
        assert_eq!(format_number(f64::INFINITY), "inf");
        assert_eq!(format_number(f64::NAN), "NaN");
    }
}
