//! Every file rollbeam reads back or writes goes through here. Nothing read from disk is
//! trusted: a read takes regular files only (a FIFO would hang it, a device feed it forever),
//! and no more bytes than the caller allows, whatever the file's metadata says. Every write
//! is whole or absent: a reader, or a run killed or out of disk midway, never finds half a
//! file under the final name.

use std::io::{Read, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

use crate::error::Error;

/// The text of the regular file at `path` (a link to one is followed), refused when it is
/// anything else, holds more than `limit` bytes, or is not UTF-8. `what` names the file in
/// messages ("scene file", "case record").
pub fn read_text(path: &Path, limit: u64, what: &str) -> Result<String, Error> {
    let cannot = |e: &dyn std::fmt::Display| {
        Error::Input(format!("cannot read {what} {}: {e}", path.display()))
    };
    let meta = std::fs::metadata(path).map_err(|e| cannot(&e))?;
    if !meta.is_file() {
        return Err(Error::Input(format!(
            "{} is not a regular file but {}; a {what} is read from a regular file only",
            path.display(),
            kind(&meta.file_type())
        )));
    }
    let file = std::fs::File::open(path).map_err(|e| cannot(&e))?;
    let mut bytes = Vec::new();
    file.take(limit.saturating_add(1))
        .read_to_end(&mut bytes)
        .map_err(|e| cannot(&e))?;
    if bytes.len() as u64 > limit {
        return Err(Error::Input(format!(
            "{} holds more than {limit} bytes, more than a {what} can be",
            path.display()
        )));
    }
    String::from_utf8(bytes).map_err(|e| {
        Error::Input(format!(
            "{} is not UTF-8 text (byte {} is not), so it is not a {what}",
            path.display(),
            e.utf8_error().valid_up_to() + 1
        ))
    })
}

fn kind(t: &std::fs::FileType) -> &'static str {
    use std::os::unix::fs::FileTypeExt;
    if t.is_dir() {
        "a folder"
    } else if t.is_fifo() {
        "a FIFO"
    } else if t.is_char_device() || t.is_block_device() {
        "a device"
    } else if t.is_socket() {
        "a socket"
    } else {
        "not a file"
    }
}

/// Whether `path` is a folder itself, not a link to one: a folder that a plan or an output
/// writes into stays where its parent is.
pub fn is_real_dir(path: &Path) -> bool {
    std::fs::symlink_metadata(path).is_ok_and(|m| m.is_dir())
}

/// Write `text` to `path` whole or not at all: into a temporary file beside it that no other
/// writer (process or thread) shares, then renamed over the path. A link left at the path is
/// replaced, not written through; on failure the temporary file is removed and the path keeps
/// what it held.
pub fn write_whole(path: &Path, text: &str) -> Result<(), Error> {
    let partial = partial_path(path);
    let written = std::fs::File::create(&partial).and_then(|mut f| {
        f.write_all(text.as_bytes())?;
        f.flush()
    });
    let renamed = written.and_then(|()| std::fs::rename(&partial, path));
    renamed.map_err(|e| {
        let _ = std::fs::remove_file(&partial);
        Error::Output(format!("cannot write {}: {e}", path.display()))
    })
}

/// `.NAME.PID-N.partial` beside `path`: hidden, and one per write in flight.
fn partial_path(path: &Path) -> PathBuf {
    static WRITES: AtomicU64 = AtomicU64::new(0);
    let n = WRITES.fetch_add(1, Ordering::Relaxed);
    let name = path
        .file_name()
        .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
    path.with_file_name(format!(".{name}.{}-{n}.partial", std::process::id()))
}

/// FNV-1a (64 bit) of a file's text (a scene, a case, a stored history) with carriage returns left out, so that a checkout with
/// either line ending gives the same hash.
pub fn content_hash(text: &str) -> String {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in text.bytes().filter(|&b| b != b'\r') {
        h ^= u64::from(b);
        h = h.wrapping_mul(0x0000_0100_0000_01b3);
    }
    format!("fnv1a64:{h:016x}")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A folder of the test's own: tests run in parallel, and one that counts the files
    /// in its folder must not see another's write in flight.
    fn temp(test: &str, name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("rollbeam-files-{}-{test}", std::process::id()));
        std::fs::create_dir_all(&d).unwrap();
        d.join(name)
    }

    /// A device reports length 0 and would feed bytes forever; it is refused before a byte
    /// is read.
    #[test]
    fn devices_and_folders_are_not_read() {
        let e = read_text(Path::new("/dev/zero"), 10, "scene file").unwrap_err();
        assert!(e.to_string().contains("a device"), "{e}");
        let e = read_text(&std::env::temp_dir(), 10, "scene file").unwrap_err();
        assert!(e.to_string().contains("a folder"), "{e}");
    }

    /// The limit holds on the bytes read, and exactly `limit` bytes are allowed.
    #[test]
    fn the_limit_is_on_the_bytes() {
        let p = temp("limit", "eleven.txt");
        write_whole(&p, "hello world").unwrap();
        assert_eq!(read_text(&p, 11, "record").unwrap(), "hello world");
        assert!(read_text(&p, 10, "record").is_err());
    }

    /// A write replaces a link at the path instead of writing through it, and leaves no
    /// temporary file behind.
    #[test]
    fn a_link_is_replaced_not_followed() {
        let target = temp("link", "target.txt");
        let link = temp("link", "link.txt");
        std::fs::write(&target, "kept").unwrap();
        let _ = std::fs::remove_file(&link);
        std::os::unix::fs::symlink(&target, &link).unwrap();
        write_whole(&link, "new").unwrap();
        assert_eq!(std::fs::read_to_string(&target).unwrap(), "kept");
        assert_eq!(std::fs::read_to_string(&link).unwrap(), "new");
        let left = std::fs::read_dir(link.parent().unwrap())
            .unwrap()
            .filter(|e| {
                e.as_ref()
                    .unwrap()
                    .file_name()
                    .to_string_lossy()
                    .ends_with(".partial")
            })
            .count();
        assert_eq!(left, 0);
    }

    /// The reference FNV-1a 64 values of the empty string and "a".
    #[test]
    fn fnv1a_matches_its_definition() {
        assert_eq!(content_hash(""), "fnv1a64:cbf29ce484222325");
        assert_eq!(content_hash("a"), "fnv1a64:af63dc4c8601ec8c");
        assert_eq!(content_hash("a\r\nb"), content_hash("a\nb"));
    }
}
