//! The TOML parser's error, said in a scene author's words. serde's derive sees a TOML
//! date-time as a map with one private key, and an integer beyond i64 as an i128 of the wrong
//! type; the author wrote neither.

use glint_scene::{serde_words, shorten_lines};

/// The key under which the `toml` crate hands a date-time to serde.
const DATETIME_KEY: &str = "$__toml_private_datetime";

/// `error`, raised parsing `text`, as a message: what the file holds named as the file says it,
/// every line cut to a readable length.
pub fn parse_message(error: &toml::de::Error, text: &str) -> String {
    if error.span().is_none() && error.message().contains("recursion limit") {
        return too_deep(text);
    }
    // An object's error at the field it names, not at the first `[[objects]]` header.
    // And a field's error inside a table read whole (an attenuation) at the field.
    // The file parsed again with its spans, once for every lookup (on the error path alone).
    let parsed = toml::de::DeTable::parse(text).ok();
    let root = parsed.as_ref().map(|r| r.get_ref());
    // The one required table, absent: the parser put the error at the first table of the file
    // and named it (`world: missing field `camera``, line 1), as if `[world]` lacked a field.
    if error.message() == "missing field `camera`" && root.is_some_and(|root| !root.contains_key("camera")) {
        return CAMERA_REQUIRED.to_string();
    }
    let refined = root.and_then(|root| {
        crate::toml_position::object_error_span(root, error.message()).or_else(|| {
            error.span().and_then(|span| crate::toml_position::inner_error_span(root, span, error.message()))
        })
    });
    let (span, located) = match refined {
        Some(span) => (Some(span.clone()), crate::toml_position::at_position(text, span, error.message())),
        None => (error.span(), error.to_string()),
    };
    let path = root.zip(span.as_ref()).and_then(|(root, span)| crate::toml_position::field_path_at(root, span));
    let spanned = span.and_then(|span| text.get(span)).unwrap_or("");
    let located = window_about_caret(&located);
    let clarified = serde_words(&clarify_datetime(&clarify_integer_overflow(&located), spanned));
    shorten_lines(&match path {
        Some(path) => with_field_path(&clarified, &path),
        None => clarified,
    })
}

/// A scene without its `[camera]` table, said of the table, not of the file's first one.
const CAMERA_REQUIRED: &str =
    "camera: the [camera] table is required (position, look_at; docs/scene-format.md#camera); the file has none";

/// `located`'s message line led by the path of the field it is about (`lights[2].position:
/// invalid length 2, …`), unless it names the field already: the parts of the path the message
/// begins with (`attenuation: l: …`) are left to it, and an object's message names its index.
fn with_field_path(located: &str, path: &str) -> String {
    let mut lines: Vec<&str> = located.split('\n').collect();
    if !located.starts_with("TOML parse error at line ") || lines.len() < 5 || lines[4].starts_with("objects[") {
        return located.to_string();
    }
    let said = lines[4];
    // The path cut before each of its parts, the whole path first: where the message begins
    // with the part after the cut, only the part before it is added.
    let mut cuts = std::iter::once(0).chain(path.match_indices(['.', '[']).map(|(i, _)| i));
    let named = cuts.find_map(|cut| {
        let rest = path[cut..].trim_start_matches('.');
        let part = rest.split(['.', '[']).next().unwrap_or(rest);
        let begins =
            !part.is_empty() && said.strip_prefix(part).is_some_and(|after| after.starts_with([':', ' ', '.', '[']));
        begins.then_some(&path[..cut])
    });
    let led = match named {
        Some("") => return located.to_string(),
        Some(head) => format!("{head}.{said}"),
        None => format!("{path}: {said}"),
    };
    lines[4] = &led;
    lines.join("\n")
}

/// The parser's source line and caret line cut to a window about the caret where the line is
/// long: cut at the end of a message line, the value and its caret fell past the cut (a
/// tester's 300 triangles on one line put the bad index at column 3681).
fn window_about_caret(message: &str) -> String {
    /// Characters of the source line kept before the caret, and in all.
    const BEFORE: usize = 60;
    const WIDTH: usize = 200;
    let mut lines: Vec<String> = message.split('\n').map(str::to_string).collect();
    if lines.len() < 4 || !lines[0].starts_with("TOML parse error at line ") {
        return message.to_string();
    }
    let (Some((gutter, content)), Some(bar)) = (lines[2].split_once(" | "), lines[3].find('|')) else {
        return message.to_string();
    };
    let chars: Vec<char> = content.chars().collect();
    let after_bar = &lines[3][bar + 1..];
    // The caret line is the gutter, `|`, then column + 1 spaces and the carets.
    let column = after_bar.chars().take_while(|&c| c == ' ').count().saturating_sub(1);
    let carets = after_bar.chars().filter(|&c| c == '^').count().max(1);
    // Tabs drawn as spaces to the next stop of 4, the caret moved with them: a tab before the
    // value left the caret short of it (a tester).
    let tabs = chars.contains(&'\t');
    let (chars, column) = if tabs { expand_tabs(&chars, column) } else { (chars, column) };
    if (!tabs && chars.len() <= WIDTH) || column > chars.len() {
        return message.to_string();
    }
    let (start, end) = if chars.len() <= WIDTH {
        (0, chars.len())
    } else {
        let start = column.saturating_sub(BEFORE);
        (start, (start + WIDTH).min(chars.len()))
    };
    let (head, tail) = (if start > 0 { "…" } else { "" }, if end < chars.len() { "…" } else { "" });
    let window: String = chars[start..end].iter().collect();
    let caret_at = column - start + head.chars().count();
    let carets = carets.min(end.saturating_sub(column)).max(1);
    lines[2] = format!("{gutter} | {head}{window}{tail}");
    lines[3] = format!("{}|{}{}", &lines[3][..bar], " ".repeat(caret_at + 1), "^".repeat(carets));
    lines.join("\n")
}

/// `line` with each tab as the spaces to the next multiple of 4, and where character `column`
/// of it then stands.
fn expand_tabs(line: &[char], column: usize) -> (Vec<char>, usize) {
    let mut out = Vec::with_capacity(line.len() + 16);
    let mut at = None;
    for (i, &c) in line.iter().enumerate() {
        if i == column {
            at = Some(out.len());
        }
        if c == '\t' {
            out.extend(std::iter::repeat_n(' ', 4 - out.len() % 4));
        } else {
            out.push(c);
        }
    }
    let at = at.unwrap_or(out.len() + column.saturating_sub(line.len()));
    (out, at)
}

/// Tables nested past what serde's reader recurses into: the parser said only "recursion
/// limit", with no line. The first header that nests that deep, found here.
fn too_deep(text: &str) -> String {
    /// A scene's deepest table is a few levels down (`[objects.transform]`, a texture's
    /// `uv_transform`); serde's reader stops near a hundred.
    const DEEP: usize = 16;
    let deepest = text.lines().enumerate().find_map(|(i, line)| {
        let header = line.trim_start().strip_prefix('[')?;
        let depth = header.split(']').next()?.matches('.').count() + 1;
        (depth > DEEP).then_some((i + 1, depth))
    });
    match deepest {
        Some((line, depth)) => format!(
            "line {line}: a table header nests {depth} tables, more than the TOML reader recurses into (a scene \
             nests a few)"
        ),
        None => "tables or arrays nested more deeply than the TOML reader recurses into (a scene nests a few)".into(),
    }
}

/// A date-time where another type belongs is called one, not a map or a table with a private
/// field (`unknown field `$__toml_private_datetime``).
fn clarify_datetime(message: &str, spanned: &str) -> String {
    let is_datetime = spanned.trim().parse::<toml::value::Datetime>().is_ok();
    message
        .lines()
        .map(|line| {
            if line.starts_with(&format!("unknown field `{DATETIME_KEY}`")) {
                "invalid type: date-time, expected a table ([section] or { key = value, … })".to_string()
            } else if line == "floating-point number overflowed" {
                // The parser's words alone named neither the number's bound nor the fields'.
                let fields = "and so outside every field's allowed range (docs/scene-format.md gives each field's)";
                format!("{}: beyond f64's range (±{:e}), {fields}", spanned.trim(), f64::MAX)
            } else if is_datetime && line.starts_with("invalid type: map, expected ") {
                line.replacen("map", "date-time", 1)
            } else if let Some(at) = line.find(&format!("unknown field `{DATETIME_KEY}`")) {
                // Inside Glint's own table readers' messages (`objects[0] (model): transform: …`).
                format!("{}invalid type: date-time, expected a table ([section] or {{ key = value, … }})", &line[..at])
            } else if line.contains(DATETIME_KEY) {
                // Glint's own table readers see the private key too: `attenuation.KEY is not a
                // field` and `got { KEY = "1979-05-27" }`.
                line.replace(&format!(".{DATETIME_KEY} is not a field"), " is a date-time, not a table")
                    .replace(&format!("{{ {DATETIME_KEY} = \""), "the date-time ")
                    .replace("\" }", "")
            } else {
                line.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// serde's words for an integer TOML cannot hold (beyond i64; "as i128, expected any valid
/// TOML value" read as if the value had the wrong type) said plainly.
fn clarify_integer_overflow(message: &str) -> String {
    const LIMIT: &str = "beyond the 64-bit integers TOML allows (at most 9223372036854775807)";
    let mut out = message.to_string();
    for wide in ["i128", "u128"] {
        out = out
            .replace(&format!(" as {wide}, expected any valid TOML value"), &format!(" is {LIMIT}"))
            .replace(&format!(" as {wide}, expected "), &format!(" is {LIMIT}; expected "));
    }
    if out != message {
        out = out.replace("invalid type: integer", "invalid value: integer");
    }
    out.replace("u64 value was too large", &format!("an integer {LIMIT}"))
}

#[cfg(test)]
mod tests {
    use super::{clarify_integer_overflow, parse_message};

    fn message(text: &str) -> String {
        let error = toml::from_str::<glint_scene::SceneDesc>(text).expect_err("the scene is refused");
        parse_message(&error, text)
    }

    #[test]
    fn a_date_time_is_called_one_wherever_it_stands() {
        let number = message("[camera]\nposition = [0, 0, -5]\nlook_at = [0, 0, 0]\nfov_y = 07:32:00\n");
        assert!(
            message_line(&number).starts_with("camera.fov_y: invalid type: date-time, expected a number"),
            "{number}"
        );
        let colour = message("[world]\nambient = 1979-05-27T07:32:00Z\n");
        assert!(
            message_line(&colour).starts_with("world.ambient: invalid type: date-time, expected a number (grey)"),
            "{colour}"
        );
        let table = message("[materials]\nglass = 1979-05-27\n");
        assert!(!table.contains("$__toml"), "{table}");
        assert!(table.contains("invalid type: date-time, expected a table"), "{table}");
        // The parser's position stays.
        assert!(table.contains("line 2"), "{table}");
    }

    #[test]
    fn a_date_time_read_by_glint_s_own_table_readers_is_called_one_too() {
        let light = "[camera]\nposition = [0, 0, -4]\nlook_at = [0, 0, 0]\n[[lights]]\ntype = \"point\"\n\
                     position = [0, 1, -4]\nattenuation = 07:32:00\n";
        let said = message(light);
        assert!(said.contains("attenuation is a date-time, not a table; model = "), "{said}");
        let object = "[camera]\nposition = [0, 0, -4]\nlook_at = [0, 0, 0]\n[[objects]]\ntype = 1979-05-27\n";
        let said = message(object);
        assert!(
            said.contains("must be a string, one of: sphere, plane, mesh, model; got the date-time 1979-05-27"),
            "{said}"
        );
        assert!(!said.contains("$__toml"), "{said}");
        let model = "[camera]\nposition = [0, 0, -4]\nlook_at = [0, 0, 0]\n[[objects]]\ntype = \"model\"\n\
                     path = \"x.obj\"\ntransform = 1979-05-27\n";
        let said = message(model);
        assert!(said.contains("transform: invalid type: date-time, expected a table"), "{said}");
        assert!(!said.contains("$__toml"), "{said}");
    }

    #[test]
    fn an_object_s_error_is_at_the_field_it_names_not_the_first_objects_header() {
        // Objects are read whole, then by their type: the parser put every error of one at the
        // first `[[objects]]` header (a tester's line 16 said line 7).
        let scene = "[camera]\nposition = [0, 0, -5]\nlook_at = [0, 0, 0]\n[materials.m]\n\
                     [[objects]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"m\"\n\
                     [[objects]]\ntype = \"mesh\"\nmaterial = \"m\"\nEXTRA\n\
                     vertices = [[0, 0, 0], [1, 0, 0], [0, 1, 0]]\ntriangles = [[0, 1, 2.0]]\n";
        let said = message(&scene.replace("EXTRA\n", ""));
        assert!(said.starts_with("TOML parse error at line 14, column 21\n"), "{said}");
        assert!(said.contains("14 | triangles = [[0, 1, 2.0]]\n   |                     ^^^\n"), "{said}");
        assert!(said.ends_with("objects[1] (mesh): triangles[0][2]: invalid type: floating point `2`, expected a whole number from 0 to 4294967295"), "{said}");
        let said = message(&scene.replace("EXTRA", "bogus = 1"));
        assert!(said.starts_with("TOML parse error at line 13, column 1\n"), "{said}");
        assert!(said.contains("13 | bogus = 1\n   | ^^^^^\n"), "{said}");
        // A field the object lacks: at its table.
        let lacking = scene.replace("EXTRA\n", "").replace("2.0]", "2]");
        let said = message(&lacking.replace("type = \"mesh\"\nmaterial = \"m\"", "type = \"mesh\""));
        assert!(said.starts_with("TOML parse error at line 10, column 1\n"), "{said}");
        assert!(said.contains("objects[1] (mesh): missing field `material`"), "{said}");
        // Objects written inline, one line each.
        let inline = "objects = [\n  { type = \"sphere\", center = [0, 0, 0], radius = 1, material = \"m\" },\n\
                      { type = \"sphere\", center = [0, 0, \"x\"], radius = 1, material = \"m\" },\n]\n\
                      [camera]\nposition = [0, 0, -5]\nlook_at = [0, 0, 0]\n[materials.m]\n";
        let said = message(inline);
        assert!(said.starts_with("TOML parse error at line 3, column 36\n"), "{said}");
    }

    #[test]
    fn tables_nested_past_the_reader_s_limit_name_their_line() {
        let deep = format!("[camera]\nposition = [0, 0, -4]\nlook_at = [0, 0, 0]\n[{}]\nx = 1\n", ["a"; 100].join("."));
        assert_eq!(
            message(&deep),
            "line 4: a table header nests 100 tables, more than the TOML reader recurses into (a scene nests a few)"
        );
    }

    #[test]
    fn a_field_of_a_table_read_whole_is_shown_at_the_field() {
        // A light's attenuation is read whole, then by its model: the parser underlined the
        // whole table (a tester).
        let head = "[camera]\nposition = [0, 0, -5]\nlook_at = [0, 0, 0]\n[[lights]]\ntype = \"point\"\nposition = [0, 2, 0]\n";
        let inline = message(&format!("{head}attenuation = {{ c = 1.0,\n  l = \"x\" }}\n"));
        assert!(inline.starts_with("TOML parse error at line 8, column 7\n"), "{inline}");
        assert!(inline.ends_with("attenuation: l: invalid type: string \"x\", expected a number"), "{inline}");
        let table = message(&format!("{head}[lights.attenuation]\nc = 1.0\nl = \"x\"\n"));
        assert!(table.starts_with("TOML parse error at line 9, column 5\n"), "{table}");
    }

    #[test]
    fn on_a_long_line_the_value_and_its_caret_stay_in_view() {
        let triangles: Vec<String> = (0..300).map(|i| format!("[0, {}, {}]", i + 1, i + 2)).collect();
        let text = format!(
            "[camera]\nposition = [0, 0, -5]\nlook_at = [0, 0, 0]\n[materials.m]\n[[objects]]\ntype = \"mesh\"\n\
             material = \"m\"\nvertices = [[0, 0, 0], [1, 0, 0], [0, 1, 0]]\ntriangles = [{}, [0, 1, 2.5]]\n",
            triangles.join(", ")
        );
        let said = message(&text);
        let lines: Vec<&str> = said.lines().collect();
        assert!(lines[0].starts_with("TOML parse error at line 9, column "), "{said}");
        let (source, caret) = (lines[2], lines[3]);
        assert!(source.chars().count() < 220 && source.starts_with("9 | …") && source.ends_with("2.5]]"), "{said}");
        let value = source.find("2.5").expect("the value is in view");
        let at = caret.find('^').expect("a caret");
        assert_eq!(source[..value].chars().count(), caret[..at].chars().count(), "{said}");
        // A short line is left as the parser laid it out.
        let short = message("[camera]\nposition = [0, 0, -5]\nlook_at = [0, 0, 0]\nfov_y = \"x\"\n");
        assert!(short.contains("4 | fov_y = \"x\"\n  |         ^^^\n"), "{short}");
    }

    #[test]
    fn a_tab_before_the_value_moves_the_caret_with_it() {
        let said = message("[camera]\nposition = [0, 0, -5]\nlook_at = [0, 0, 0]\n\tfov_y\t=\t\"x\"\n");
        assert!(said.contains("4 |     fov_y   =   \"x\"\n  |                 ^^^\n"), "{said}");
    }

    #[test]
    fn a_number_beyond_f64_says_so_and_where_the_ranges_are() {
        let said = message("[camera]\nposition = [0, 0, -5]\nlook_at = [0, 0, 0]\nfov_y = 1e400\n");
        assert!(said.contains("line 4, column 9"), "{said}");
        assert_eq!(
            message_line(&said),
            "camera.fov_y: 1e400: beyond f64's range (±1.7976931348623157e308), and so outside every field's allowed range \
             (docs/scene-format.md gives each field's)"
        );
    }

    #[test]
    fn the_message_names_the_field_it_is_about() {
        // The caret showed the line, but not whose field it was: with twenty lights, `position`
        // is any light's (a tester).
        let head = "[camera]\nposition = [0, 0, -5]\nlook_at = [0, 0, 0]\n[[lights]]\ntype = \"point\"\n\
                    position = [0, 2, 0]\n[[lights]]\ntype = \"point\"\n";
        let said = message(&format!("{head}position = [0, 2]\n"));
        assert!(message_line(&said).starts_with("lights[1].position: invalid length 2"), "{said}");
        let said = message(&format!("{head}intensity = 1\n"));
        assert!(message_line(&said).starts_with("lights[1]: unknown field `intensity`, expected one of"), "{said}");
        // What the message names already is not said twice.
        let said = message(&format!("{head}attenuation = {{ l = \"x\" }}\n"));
        assert!(message_line(&said).starts_with("lights[1].attenuation: l: invalid type: string"), "{said}");
        let said =
            message("[camera]\nposition = [0, 0, -5]\nlook_at = [0, 0, 0]\n[materials.red]\nkd = [1, \"x\", 0]\n");
        assert!(message_line(&said).starts_with("materials.red.kd"), "{said}");
        let said = message("[camera]\nposition = [0, 0, -5]\n");
        assert_eq!(message_line(&said), "camera: missing field `look_at`", "{said}");
        let said = message("[render]\nmax_depth = -1\n[camera]\nposition = [0, 0, -5]\nlook_at = [0, 0, 0]\n");
        assert!(message_line(&said).starts_with("render.max_depth: invalid value: integer `-1`"), "{said}");
    }

    #[test]
    fn a_scene_without_its_camera_table_is_told_the_table_is_required_not_blamed_on_its_first_table() {
        // A tester: `[world] ambient = 0.1` alone was "world: missing field `camera`" at line 1.
        for text in ["[world]\nambient = 0.1\n", "[render]\nwidth = 8\n[materials.m]\nkd = 1\n", "", "# nothing\n"] {
            assert_eq!(
                message(text),
                "camera: the [camera] table is required (position, look_at; docs/scene-format.md#camera); the file \
                 has none",
                "{text:?}"
            );
        }
        // A camera table lacking a field is still said of that field.
        assert_eq!(
            message_line(&message("[world]\nambient = 0.1\n[camera]\nposition = [0, 0, -5]\n")),
            "camera: missing field `look_at`"
        );
    }

    #[test]
    fn a_map_that_is_a_map_stays_one() {
        let text = "[world]\nambient = { r = 1 }\n";
        assert!(message(text).contains("invalid type: map, expected a number (grey)"), "{}", message(text));
    }

    fn message_line(message: &str) -> &str {
        message.lines().last().unwrap_or("")
    }

    #[test]
    fn integers_beyond_64_bits_are_said_to_be_too_large_not_of_the_wrong_type() {
        assert_eq!(
            clarify_integer_overflow(
                "invalid type: integer `99999999999999999999` as i128, expected any valid TOML value"
            ),
            "invalid value: integer `99999999999999999999` is beyond the 64-bit integers TOML allows (at most \
             9223372036854775807)"
        );
        assert_eq!(clarify_integer_overflow("expected f64"), "expected f64");
    }
}
