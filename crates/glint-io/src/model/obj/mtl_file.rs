//! One MTL file as an OBJ's importer loaded it: where its textures are looked for, and the
//! file and line a texture statement's error names.

/// An MTL file as loaded: what a texture statement's error names (its file and line) and
/// where its textures are looked for.
pub struct MtlFile {
    /// As the OBJ names it, relative to the OBJ's folder.
    pub uri: String,
    /// Its folder, relative to the OBJ's (empty beside it).
    pub folder: String,
    /// How many materials it held.
    pub materials: usize,
    /// Its text as decoded, before statements were joined: lines as an editor numbers them.
    pub text: String,
}

impl MtlFile {
    /// The line (from 1) of the first `keyword` statement of the `nth` (from 0) material of
    /// this file named `name` (a file may define one name twice).
    pub fn statement_line(&self, name: &str, nth: usize, keyword: &str) -> Option<usize> {
        let (mut inside, mut seen) = (false, 0);
        for (i, line) in self.text.lines().enumerate() {
            match line.split_whitespace().next() {
                Some("newmtl") => {
                    let named = line.trim_start()["newmtl".len()..].trim() == name;
                    inside = named && seen == nth;
                    seen += usize::from(named);
                }
                Some(k) if inside && k.eq_ignore_ascii_case(keyword) => return Some(i + 1),
                _ => {}
            }
        }
        None
    }
}
