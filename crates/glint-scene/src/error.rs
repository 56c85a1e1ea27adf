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
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.field, self.problem)
    }
}
