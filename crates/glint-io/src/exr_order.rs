//! Glint's text attributes in an EXR header in name order. The `exr` crate keeps them in a
//! `HashMap` with a random hasher and writes them in its order, so one image written twice gave
//! two files (a farm's merge checked with `cmp` or a checksum differed from itself). The header
//! is rewritten in place once the file is written: the attributes keep their bytes and the
//! header its length, so the offsets that follow it stay valid.

use std::io::{Read, Seek, SeekFrom, Write};

/// OpenEXR's magic number, little-endian.
const MAGIC: [u8; 4] = [0x76, 0x2f, 0x31, 0x01];
/// The version field's flag of a multi-part file (its headers differ: Glint never writes one).
const MULTIPART: u32 = 0x1000;
/// A header's attribute names and type names are at most this long (long-name files), plus 0.
const MAX_NAME: usize = 256;

/// One attribute's bytes within the header, and its name.
struct Record {
    start: usize,
    end: usize,
    name: Vec<u8>,
}

/// Puts the attributes named in `names` of the single-part EXR in `file` in name order, in the
/// places those attributes held; every other attribute keeps its place.
pub(crate) fn sort_attributes(file: &mut (impl Read + Write + Seek), names: &[Vec<u8>]) -> std::io::Result<()> {
    let invalid = |what: &str| std::io::Error::new(std::io::ErrorKind::InvalidData, format!("EXR header: {what}"));
    let mut header = Vec::new();
    file.seek(SeekFrom::Start(0))?;
    // The header is small (text attributes of a few hundred bytes, a channel list), but read
    // until its end whatever its size.
    let records = loop {
        let mut chunk = [0u8; 4096];
        let n = file.read(&mut chunk)?;
        header.extend_from_slice(&chunk[..n]);
        if header.len() >= 8 && header[..4] != MAGIC {
            return Err(invalid("not an OpenEXR file"));
        }
        if header.len() >= 8 && u32::from_le_bytes(header[4..8].try_into().expect("4 bytes")) & MULTIPART != 0 {
            return Ok(());
        }
        match parse(&header) {
            Some(records) => break records,
            None if n == 0 => return Err(invalid("ends inside its attributes")),
            None => {}
        }
    };
    let wanted = |r: &Record| names.contains(&r.name);
    let mut moved: Vec<&Record> = records.iter().filter(|r| wanted(r)).collect();
    moved.sort_by(|a, b| a.name.cmp(&b.name));
    let mut moved = moved.into_iter();
    let mut out = Vec::with_capacity(header.len());
    for r in &records {
        let r = if wanted(r) { moved.next().expect("as many as taken") } else { r };
        out.extend_from_slice(&header[r.start..r.end]);
    }
    let (start, end) = (records.first().map_or(8, |r| r.start), records.last().map_or(8, |r| r.end));
    debug_assert_eq!(out.len(), end - start);
    if out != header[start..end] {
        file.seek(SeekFrom::Start(start as u64))?;
        file.write_all(&out)?;
    }
    file.seek(SeekFrom::End(0))?;
    Ok(())
}

/// The attributes of the header at the start of `bytes` (after magic and version), or `None`
/// when `bytes` ends before the header's terminating 0.
fn parse(bytes: &[u8]) -> Option<Vec<Record>> {
    let mut at = 8;
    let mut records = Vec::new();
    loop {
        let start = at;
        let name = zero_terminated(bytes, &mut at)?;
        if name.is_empty() {
            return Some(records);
        }
        zero_terminated(bytes, &mut at)?;
        let size = i32::from_le_bytes(bytes.get(at..at + 4)?.try_into().ok()?);
        at += 4 + usize::try_from(size).ok()?;
        if at > bytes.len() {
            return None;
        }
        records.push(Record { start, end: at, name: name.to_vec() });
    }
}

/// The bytes before the next 0 from `*at`, and `*at` past it.
fn zero_terminated<'a>(bytes: &'a [u8], at: &mut usize) -> Option<&'a [u8]> {
    let rest = bytes.get(*at..)?;
    let len = rest.iter().take(MAX_NAME + 1).position(|&b| b == 0)?;
    *at += len + 1;
    Some(&rest[..len])
}

#[cfg(test)]
mod tests {
    use crate::exr_file::{PIXELS_SHA256, read_exr, write_exr_region};

    #[test]
    fn one_image_written_again_is_the_same_file() {
        // Before: each write drew a new hash order for the attributes (three merges of the same
        // tiles gave three checksums).
        let dir = tempfile::tempdir().expect("temporary folder");
        // Names the file holds as Latin-1 (é), not as their UTF-8, are ordered too.
        let metadata: Vec<(String, String)> =
            (0..12).map(|i| (format!("glint:clé{:02}", 11 - i), format!("value {i}"))).collect();
        let pixel = |x: usize, y: usize| [x as f32, y as f32, 0.5];
        let files: Vec<Vec<u8>> = (0..6)
            .map(|i| {
                let path = dir.path().join(format!("{i}.exr"));
                write_exr_region(&path, (8, 6), (2, 1), (5, 4), pixel, &metadata).expect("write");
                std::fs::read(&path).expect("read back")
            })
            .collect();
        assert!(files.iter().all(|f| *f == files[0]), "the same image gave different files");
        // Still a valid EXR: the exr crate reads its pixels and every attribute back.
        let read = read_exr(&dir.path().join("0.exr")).expect("readable");
        assert_eq!(read.rgb[0], [0.0, 0.0, 0.5]);
        assert_eq!(read.header.origin, (2, 1));
        assert_eq!(read.digest_holds(), Some(true), "and the pixels' digest");
        let mut expected = metadata.clone();
        expected.sort();
        let given: Vec<_> = read.header.attributes.iter().filter(|(k, _)| k != PIXELS_SHA256).cloned().collect();
        assert_eq!(given, expected);
    }
}
