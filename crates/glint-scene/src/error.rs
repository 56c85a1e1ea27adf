//! A problem with one field of a scene description: what validation and the importers report,
//! each naming the field and what is allowed.

use std::fmt;

/// One problem with one field, e.g. `lights[1].cutoff: 120 is outside [0, 90] or 180`.
#[derive(Clone, Debug, PartialEq)]
pub struct FieldIssue {
    /// Dotted path of the field, as written in the scene file (`objects[2].radius`).
    pub field: String,
    /// What is wrong and what is allowed.
    pub problem: String,
}

impl fmt::Display for FieldIssue {
    /// Each part of the field's path cut as an echoed value is (`shorten`): a material named by
    /// 100,000 characters made a line as long, and its `.ks` after it must still show. The
    /// problem is cut in its middle (a path it quotes can be thousands of characters).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let field: Vec<String> = self.field.split('.').map(crate::number::shorten).collect();
        let problem: Vec<String> = self.problem.split('\n').map(crate::number::shorten_middle).collect();
        write!(f, "{}: {}", field.join("."), problem.join("\n"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_long_part_of_a_field_is_cut_and_the_rest_still_shows() {
        let name = "x".repeat(100_000);
        let issue = FieldIssue { field: format!("materials.{name}.ks"), problem: "-1 is outside [0, 1e9]".into() };
        let shown = issue.to_string();
        assert!(shown.len() < 300, "{} bytes", shown.len());
        assert!(shown.ends_with(".ks: -1 is outside [0, 1e9]") && shown.contains("more bytes)"), "{shown}");
        // A problem quoting a 5,000-character path keeps its reason at the end (a 5 KB line before),
        // cut to a line of 1,000 characters.
        let path = format!("/m/{}.obj", "d".repeat(5000));
        let issue = FieldIssue {
            field: "objects[1].path".into(),
            problem: format!("{path}: cannot read the model: File name too long"),
        };
        let shown = issue.to_string();
        assert!(shown.len() < 1_100 && shown.ends_with(".obj: cannot read the model: File name too long"), "{shown}");
    }
}
