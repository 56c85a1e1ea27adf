//! Where in a scene file an object's field is. Objects are read whole, then by their `type`
//! (`ObjectDesc::from_table`), so the TOML parser's position of an error in one is the first
//! `[[objects]]` header (a tester's `triangles[0][2]` on line 16 was said to be on line 7). The
//! error names the field (`objects[1] (mesh): triangles[0][2]: …`); the file, parsed again with
//! its spans (once, by the caller, for every lookup here), says where that is.

use std::ops::Range;

use toml::Spanned;
use toml::de::{DeTable, DeValue};

/// The span of the value an error raised inside `objects[N]` names (`message` is the parser's,
/// without position): the deepest part of its field path that the file has, else the object.
pub fn object_error_span(root: &DeTable<'_>, message: &str) -> Option<Range<usize>> {
    let rest = message.strip_prefix("objects[")?;
    let (index, rest) = rest.split_once(']')?;
    let index: usize = index.parse().ok()?;
    // ` (mesh): field…`, `.type: …`, `: …`
    let rest = match rest.strip_prefix(" (") {
        Some(kinded) => kinded.split_once(')')?.1,
        None => rest,
    };
    let path = rest.strip_prefix(": ").or_else(|| rest.strip_prefix('.')).unwrap_or("");
    let objects = root.get("objects")?;
    let DeValue::Array(objects) = objects.get_ref() else { return None };
    let object = objects.get(index)?;
    // A key the object's kind has not: the key itself.
    if let Some(key) = path.strip_prefix("unknown field `").and_then(|k| k.split_once('`')).map(|(k, _)| k)
        && let DeValue::Table(table) = object.get_ref()
        && let Some((spanned, _)) = table.get_key_value(key)
    {
        return Some(spanned.span());
    }
    Some(deepest(object, path.split(": ").next().unwrap_or("")).span())
}

/// The span of the field an error names inside a table read whole (a light's `attenuation`),
/// which the parser gives the table's span (`attenuation: l: …` underlined all of
/// `{ c = 1.0, l = "x" }`): the table is found by that span, the field under it by the path
/// after the table's own name. `None` where that finds nothing deeper.
pub fn inner_error_span(root: &DeTable<'_>, span: Range<usize>, message: &str) -> Option<Range<usize>> {
    let (name, rest) = message.split_once(": ")?;
    if name.is_empty() || !name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') {
        return None;
    }
    let table = with_span(root, &span)?;
    let path = rest.split(": ").next().unwrap_or("");
    let field = deepest(table, path);
    (field.span() != span).then(|| field.span())
}

/// The path of the field the parser's error at `span` is about (`lights[0].position`,
/// `materials.red`): the deepest value holding the span's start; a key's own span (an unknown
/// field) names the table holding it. `None` at the top level, or where the file does not
/// parse. The parser's message said what was wrong and the caret where, but not whose field
/// it was (`lights[1]`'s `position` or `lights[4]`'s).
pub fn field_path_at(root: &DeTable<'_>, span: &Range<usize>) -> Option<String> {
    path_in_table(root, span.start, "").filter(|p| !p.is_empty())
}

fn path_in_table(table: &DeTable<'_>, at: usize, path: &str) -> Option<String> {
    table.iter().find_map(|(key, value)| {
        if key.span().contains(&at) {
            return Some(path.to_string());
        }
        let name = key.get_ref();
        let bare = !name.is_empty() && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-');
        let name = if bare { name.to_string() } else { format!("{name:?}") };
        let here = if path.is_empty() { name } else { format!("{path}.{name}") };
        path_in_value(value, at, here)
    })
}

fn path_in_value(value: &Spanned<DeValue<'_>>, at: usize, path: String) -> Option<String> {
    // Children first: an `[[array]]` element's span need not cover its body.
    let inner = match value.get_ref() {
        DeValue::Table(table) => path_in_table(table, at, &path),
        DeValue::Array(items) => {
            items.iter().enumerate().find_map(|(i, item)| path_in_value(item, at, format!("{path}[{i}]")))
        }
        _ => None,
    };
    inner.or_else(|| value.span().contains(&at).then_some(path))
}

/// The value in `table` (at any depth) whose span is `span`.
fn with_span<'a, 'i>(table: &'a DeTable<'i>, span: &Range<usize>) -> Option<&'a Spanned<DeValue<'i>>> {
    fn within<'a, 'i>(value: &'a Spanned<DeValue<'i>>, span: &Range<usize>) -> Option<&'a Spanned<DeValue<'i>>> {
        if value.span() == *span {
            return Some(value);
        }
        match value.get_ref() {
            DeValue::Table(t) => t.values().find_map(|v| within(v, span)),
            DeValue::Array(items) => items.iter().find_map(|v| within(v, span)),
            _ => None,
        }
    }
    table.values().find_map(|v| within(v, span))
}

/// The value at `path` (`transform.scale`, `triangles[0][2]`) under `value`, or the deepest of
/// its parts that there is.
fn deepest<'a, 'i>(value: &'a Spanned<DeValue<'i>>, path: &str) -> &'a Spanned<DeValue<'i>> {
    let mut at = value;
    for step in steps(path) {
        let next = match (step, at.get_ref()) {
            (Step::Key(key), DeValue::Table(table)) => table.get(key),
            (Step::Index(i), DeValue::Array(items)) => items.get(i),
            _ => None,
        };
        match next {
            Some(v) => at = v,
            None => break,
        }
    }
    at
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Step<'a> {
    Key(&'a str),
    Index(usize),
}

/// `transform.scale[1]` as keys and indices; stops at the first character no path has.
fn steps(path: &str) -> Vec<Step<'_>> {
    let mut out = Vec::new();
    let mut rest = path;
    loop {
        let end = rest.find(|c: char| !(c.is_ascii_alphanumeric() || c == '_')).unwrap_or(rest.len());
        if end > 0 {
            out.push(Step::Key(&rest[..end]));
        }
        rest = &rest[end..];
        while let Some(inner) = rest.strip_prefix('[') {
            let Some((n, after)) = inner.split_once(']') else { return out };
            let Ok(n) = n.parse() else { return out };
            out.push(Step::Index(n));
            rest = after;
        }
        match rest.strip_prefix('.') {
            Some(after) => rest = after,
            None => return out,
        }
    }
}

/// `message` at `span` of `text`, laid out as the TOML parser lays out its errors.
pub fn at_position(text: &str, span: Range<usize>, message: &str) -> String {
    let start = span.start.min(text.len());
    let line_start = text[..start].rfind('\n').map_or(0, |i| i + 1);
    let line = text[..line_start].matches('\n').count() + 1;
    let column = text[line_start..start].chars().count();
    let content = text[line_start..].split('\n').next().unwrap_or("").trim_end_matches('\r');
    let width = text[start..span.end.min(text.len())]
        .chars()
        .count()
        .clamp(1, content.chars().count().saturating_sub(column).max(1));
    let gutter = " ".repeat(line.to_string().len() + 1);
    format!(
        "TOML parse error at line {line}, column {}\n{gutter}|\n{line} | {content}\n{gutter}|{}{}\n{message}\n",
        column + 1,
        " ".repeat(column + 1),
        "^".repeat(width)
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paths_read_as_keys_and_indices() {
        assert_eq!(steps("triangles[0][2]"), vec![Step::Key("triangles"), Step::Index(0), Step::Index(2)]);
        assert_eq!(steps("transform.scale"), vec![Step::Key("transform"), Step::Key("scale")]);
        assert_eq!(steps("type"), vec![Step::Key("type")]);
        assert_eq!(steps(""), vec![]);
        assert_eq!(steps("invalid type"), vec![Step::Key("invalid")]);
    }

    #[test]
    fn a_span_is_named_by_the_field_that_holds_it() {
        let text = "[camera]\nfov_y = \"x\"\n[[lights]]\ntype = \"point\"\n[[lights]]\nposition = [0, \"y\"]\n\
                    bogus = 1\n[materials.\"red glass\"]\nkd = { r = 1 }\n";
        let at = |needle: &str| {
            let start = text.find(needle).expect("in the text");
            field_path_at(DeTable::parse(text).expect("parses").get_ref(), &(start..start + needle.len()))
        };
        assert_eq!(at("\"x\"").as_deref(), Some("camera.fov_y"));
        assert_eq!(at("\"y\"").as_deref(), Some("lights[1].position[1]"));
        // An unknown key: the table holding it.
        assert_eq!(at("bogus").as_deref(), Some("lights[1]"));
        assert_eq!(at("{ r").as_deref(), Some("materials.\"red glass\".kd"));
        // A header (a missing field's span): its table.
        assert_eq!(at("[camera]").as_deref(), Some("camera"));
    }
}
