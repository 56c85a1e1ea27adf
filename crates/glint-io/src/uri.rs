//! The one way a model file's references (glTF buffer and image URIs, OBJ `mtllib`, MTL
//! `map_Kd`) become bytes. URIs are untrusted input: a model may name `../../etc/passwd`, an
//! absolute path or `file:///…`, and the gltf crate's own importer would read any of them.
//! Here only two kinds are read:
//! - `data:` URIs (base64 or percent-encoded), decoded in memory;
//! - relative paths, percent-decoded, that stay inside the model's folder after
//!   canonicalisation (which follows symlinks, so a link out of the folder is refused too).
//!
//! Everything else — absolute paths, other schemes (`file:`, `http:`), escapes, malformed
//! escapes — is an error naming the URI. Sizes are capped before anything is read or decoded.

use std::io::Read;
use std::path::{Path, PathBuf};

use base64::Engine;

/// Largest buffer or image a model may reference (1 GiB): far above any model the tracer can
/// hold in a 128 MiB binding, low enough that a hostile size is refused before it is read.
pub const MAX_RESOURCE_BYTES: u64 = 1 << 30;

/// Why a reference was not read.
#[derive(Debug, thiserror::Error)]
pub enum UriError {
    #[error("URI `{uri}` is an absolute path; a file may only name files inside its own folder (or below it)")]
    Absolute { uri: String },
    #[error("URI `{uri}` uses the scheme `{scheme}:`; only `data:` URIs and relative paths are read")]
    Scheme { uri: String, scheme: String },
    #[error("URI `{uri}` resolves to {path}, outside the folder of the file that names it, {folder}")]
    Escapes { uri: String, path: PathBuf, folder: PathBuf },
    #[error("URI `{uri}` has a malformed percent-escape or is not UTF-8 once decoded")]
    Percent { uri: String },
    #[error("data URI `{uri}`: {reason}")]
    Data { uri: String, reason: String },
    #[error("URI `{uri}` names {size} bytes, more than the {cap} a referenced file may have")]
    TooLarge { uri: String, size: u64, cap: u64 },
    #[error("URI `{uri}` ({path}): {error}")]
    Io { uri: String, path: PathBuf, error: std::io::Error },
}

impl UriError {
    /// Whether the file named does not exist (a reference another place may satisfy, or a
    /// warning rather than an error).
    pub fn is_not_found(&self) -> bool {
        self.missing_path().is_some()
    }

    /// The path of the file named, where it does not exist.
    pub fn missing_path(&self) -> Option<&Path> {
        match self {
            Self::Io { path, error, .. } if error.kind() == std::io::ErrorKind::NotFound => Some(path),
            _ => None,
        }
    }
}

/// At most this many characters of a URI go into a message (data URIs can be megabytes).
const SHOWN: usize = 80;

fn shown(uri: &str) -> String {
    match uri.char_indices().nth(SHOWN) {
        Some((i, _)) => format!("{}…", &uri[..i]),
        None => uri.to_string(),
    }
}

/// The bytes `uri` refers to, for a reference inside the model file `model` (relative paths
/// are relative to its folder), at most `cap` bytes.
pub fn resolve_uri(model: &Path, uri: &str, cap: u64) -> Result<Vec<u8>, UriError> {
    let Some(path) = uri_file(model, uri)? else { return decode_data_uri(uri, cap) };
    let io = |path: &Path, error| UriError::Io { uri: shown(uri), path: path.to_owned(), error };
    // Judged before it is opened: opening a named pipe waits for a writer that may never come.
    let meta = regular_file(&path).map_err(|e| io(&path, e))?;
    let file = std::fs::File::open(&path).map_err(|e| io(&path, e))?;
    if meta.len() > cap {
        return Err(UriError::TooLarge { uri: shown(uri), size: meta.len(), cap });
    }
    let bytes = read_up_to(file, cap, meta.len()).map_err(|e| io(&path, e))?;
    if bytes.len() as u64 > cap {
        return Err(UriError::TooLarge { uri: shown(uri), size: bytes.len() as u64, cap });
    }
    Ok(bytes)
}

/// The existing file `uri` names for a reference inside `model` (percent-decoded, canonical,
/// inside the model's folder), or `None` for a `data:` URI, which names no file.
pub fn uri_file(model: &Path, uri: &str) -> Result<Option<PathBuf>, UriError> {
    if let Some(scheme) = scheme_of(uri) {
        return if scheme.eq_ignore_ascii_case("data") {
            Ok(None)
        } else {
            Err(UriError::Scheme { uri: shown(uri), scheme: scheme.to_string() })
        };
    }
    let decoded = percent_encoding::percent_decode_str(uri)
        .decode_utf8()
        .ok()
        .filter(|d| !d.contains('\0') && well_formed_escapes(uri))
        .ok_or_else(|| UriError::Percent { uri: shown(uri) })?;
    let relative = Path::new(decoded.as_ref());
    if relative.has_root() || decoded.starts_with('\\') || has_drive_prefix(&decoded) {
        return Err(UriError::Absolute { uri: shown(uri) });
    }
    let folder = model.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
    let io = |path: &Path, error| UriError::Io { uri: shown(uri), path: path.to_owned(), error };
    let folder = folder.canonicalize().map_err(|e| io(folder, e))?;
    let joined = folder.join(relative);
    // A `..` that climbs out is refused by its words, before the file is looked for: whether
    // such a file exists is no business of the model's (a missing one was only warned of).
    let mut depth = 0i64;
    for part in relative.components() {
        match part {
            std::path::Component::ParentDir => depth -= 1,
            std::path::Component::Normal(_) => depth += 1,
            std::path::Component::CurDir | std::path::Component::RootDir | std::path::Component::Prefix(_) => {}
        }
        if depth < 0 {
            return Err(UriError::Escapes { uri: shown(uri), path: joined, folder });
        }
    }
    let path = joined.canonicalize().map_err(|e| io(&joined, e))?;
    if !path.starts_with(&folder) {
        return Err(UriError::Escapes { uri: shown(uri), path, folder });
    }
    Ok(Some(path))
}

/// `path`'s metadata, or an error unless it is a regular file (following links): a file a model
/// refers to, or a model file, is read whole, and a named pipe, device or folder is not one
/// (opening a pipe waits for its writer; a device has no end).
pub fn regular_file(path: &Path) -> std::io::Result<std::fs::Metadata> {
    let meta = std::fs::metadata(path)?;
    let kind = meta.file_type();
    let what = if kind.is_file() {
        return Ok(meta);
    } else if kind.is_dir() {
        "a folder"
    } else {
        "a named pipe, socket or device"
    };
    Err(std::io::Error::other(format!("not a regular file ({what})")))
}

/// At most `cap` + 1 bytes of `file` (`len` its size where known, for the buffer): one more than
/// the cap tells the caller that a file which grew after its size was checked, or a pipe that
/// has no size, holds more than it may read.
pub(crate) fn read_up_to(file: impl Read, cap: u64, len: u64) -> std::io::Result<Vec<u8>> {
    let mut bytes = Vec::with_capacity(len.min(cap.saturating_add(1)) as usize);
    file.take(cap.saturating_add(1)).read_to_end(&mut bytes)?;
    Ok(bytes)
}

/// The scheme of an RFC 3986 URI (`ALPHA *( ALPHA / DIGIT / "+" / "-" / "." ) ":"`); one
/// letter is a Windows drive (`C:`), not a scheme.
fn scheme_of(uri: &str) -> Option<&str> {
    let (scheme, _) = uri.split_once(':')?;
    let mut chars = scheme.chars();
    let first = chars.next()?;
    let valid = first.is_ascii_alphabetic() && chars.all(|c| c.is_ascii_alphanumeric() || "+-.".contains(c));
    (valid && scheme.len() > 1).then_some(scheme)
}

fn has_drive_prefix(path: &str) -> bool {
    let b = path.as_bytes();
    b.len() >= 2 && b[0].is_ascii_alphabetic() && b[1] == b':'
}

/// Every `%` starts a two-hex-digit escape (percent_decode passes malformed ones through).
fn well_formed_escapes(uri: &str) -> bool {
    let b = uri.as_bytes();
    (0..b.len())
        .filter(|&i| b[i] == b'%')
        .all(|i| b.len() > i + 2 && b[i + 1].is_ascii_hexdigit() && b[i + 2].is_ascii_hexdigit())
}

/// `data:[<media type>][;base64],<data>`, decoded, at most `cap` bytes.
fn decode_data_uri(uri: &str, cap: u64) -> Result<Vec<u8>, UriError> {
    let data_error = |reason: &str| UriError::Data { uri: shown(uri), reason: reason.to_string() };
    let (header, payload) = uri[5..].split_once(',').ok_or_else(|| data_error("no `,` before the data"))?;
    let base64 = header.split(';').any(|p| p.eq_ignore_ascii_case("base64"));
    // Decoded data is never longer than its text: a size check before decoding.
    let bound = if base64 { payload.len() as u64 / 4 * 3 + 3 } else { payload.len() as u64 };
    if bound > cap {
        return Err(UriError::TooLarge { uri: shown(uri), size: bound, cap });
    }
    let bytes = if base64 {
        base64::engine::general_purpose::STANDARD
            .decode(payload)
            .map_err(|e| data_error(&format!("invalid base64 ({e})")))?
    } else {
        if !well_formed_escapes(payload) {
            return Err(data_error("malformed percent-escape"));
        }
        percent_encoding::percent_decode_str(payload).collect()
    };
    if bytes.len() as u64 > cap {
        return Err(UriError::TooLarge { uri: shown(uri), size: bytes.len() as u64, cap });
    }
    Ok(bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A model folder with `model.gltf`, `a b.bin` and, beside the folder, `secret.bin`.
    fn folder() -> (tempfile::TempDir, PathBuf) {
        let root = tempfile::tempdir().expect("temp dir");
        let models = root.path().join("models");
        std::fs::create_dir(&models).unwrap();
        std::fs::write(models.join("model.gltf"), "{}").unwrap();
        std::fs::write(models.join("a b.bin"), [1u8, 2, 3]).unwrap();
        std::fs::create_dir(models.join("sub")).unwrap();
        std::fs::write(models.join("sub").join("t.png"), [9u8; 10]).unwrap();
        std::fs::write(root.path().join("secret.bin"), [7u8; 4]).unwrap();
        let model = models.join("model.gltf");
        (root, model)
    }

    #[test]
    fn relative_paths_inside_the_folder_are_read_percent_decoded() {
        let (_root, model) = folder();
        assert_eq!(resolve_uri(&model, "a%20b.bin", 100).unwrap(), [1, 2, 3]);
        assert_eq!(resolve_uri(&model, "sub/t.png", 100).unwrap(), [9; 10]);
        assert_eq!(resolve_uri(&model, "sub/../a%20b.bin", 100).unwrap(), [1, 2, 3]);
    }

    #[test]
    fn escapes_absolute_paths_and_other_schemes_are_refused_naming_the_uri() {
        let (root, model) = folder();
        let secret = root.path().join("secret.bin");
        let cases = [
            ("../secret.bin", "outside the folder of the file that names it"),
            ("sub/../../secret.bin", "outside the folder of the file that names it"),
            ("%2E%2E/secret.bin", "outside the folder of the file that names it"),
            // Refused alike whether or not the file outside exists (a missing one was only warned).
            ("../missing-outside.bin", "outside the folder of the file that names it"),
            ("sub/../../missing-outside.bin", "outside the folder of the file that names it"),
            (secret.to_str().unwrap(), "absolute path"),
            ("file:///etc/passwd", "scheme `file:`"),
            ("http://example.com/x.bin", "scheme `http:`"),
            ("C:/Windows/x.bin", "absolute path"),
            ("\\\\server\\share\\x.bin", "absolute path"),
            ("a%zzb.bin", "percent-escape"),
            ("a%2", "percent-escape"),
            ("%FF%FE.bin", "percent-escape"),
            ("a%00.bin", "percent-escape"),
            ("missing.bin", "missing.bin"),
        ];
        for (uri, expected) in cases {
            let message = resolve_uri(&model, uri, 100).expect_err(uri).to_string();
            assert!(message.contains(expected), "{uri}: {message}");
        }
    }

    #[cfg(unix)]
    #[test]
    fn a_symlink_out_of_the_folder_is_refused() {
        let (root, model) = folder();
        let link = model.parent().unwrap().join("link.bin");
        std::os::unix::fs::symlink(root.path().join("secret.bin"), &link).unwrap();
        let message = resolve_uri(&model, "link.bin", 100).unwrap_err().to_string();
        assert!(message.contains("outside the folder of the file that names it"), "{message}");
    }

    #[test]
    fn data_uris_are_decoded_and_malformed_ones_refused() {
        let model = Path::new("model.gltf");
        assert_eq!(resolve_uri(model, "data:application/octet-stream;base64,AQID", 100).unwrap(), [1, 2, 3]);
        assert_eq!(resolve_uri(model, "DATA:,a%20b", 100).unwrap(), b"a b");
        for (uri, expected) in [
            ("data:application/octet-stream;base64,AQ!D", "invalid base64"),
            ("data:application/octet-stream;base64", "no `,`"),
            ("data:,a%zz", "percent-escape"),
        ] {
            let message = resolve_uri(model, uri, 100).expect_err(uri).to_string();
            assert!(message.contains(expected), "{uri}: {message}");
        }
    }

    #[test]
    fn sizes_beyond_the_cap_are_refused_before_reading() {
        let (_root, model) = folder();
        let message = resolve_uri(&model, "sub/t.png", 9).unwrap_err().to_string();
        assert!(message.contains("10 bytes") && message.contains("the 9"), "{message}");
        let big = format!("data:;base64,{}", "A".repeat(4000));
        let message = resolve_uri(&model, &big, 1000).unwrap_err().to_string();
        assert!(message.contains("more than the 1000") && message.chars().count() < 300, "{message}");
    }
}
