//! Reading the files the FMU opens — the profiles a parameter names, the exact_table model's
//! table in the resources — so that no file can hang the master or size its memory: only
//! regular files (not a device, FIFO, socket or directory, whatever their name: `/dev/zero`, a
//! FIFO or a link to `/dev/stdin` would never end or would read the master's input), opened
//! without waiting for a writer, and at most a given size.

use std::fs::File;
use std::io::Read;
use std::path::Path;

/// The bytes of the regular file at `path`, of at most `limit` bytes, or why not.
pub fn read_regular_file(path: &Path, limit: u64) -> Result<Vec<u8>, String> {
    let file = open_without_blocking(path).map_err(|e| e.to_string())?;
    let metadata = file.metadata().map_err(|e| e.to_string())?;
    if !metadata.is_file() {
        return Err("it is not a regular file (a device, FIFO, socket or directory)".to_owned());
    }
    let too_large = |size: u64| format!("it has {size} bytes; this file may have at most {limit}");
    if metadata.len() > limit {
        return Err(too_large(metadata.len()));
    }
    let mut bytes = Vec::new();
    // At most one byte beyond the limit, should the file grow while it is read.
    file.take(limit + 1).read_to_end(&mut bytes).map_err(|e| e.to_string())?;
    if bytes.len() as u64 > limit {
        return Err(too_large(bytes.len() as u64));
    }
    Ok(bytes)
}

/// Opens `path` for reading without waiting for a writer: opening a FIFO blocks until one
/// comes, so the kind of file is asked of the opened file, not of the path (no race between
/// the two).
#[cfg(unix)]
fn open_without_blocking(path: &Path) -> std::io::Result<File> {
    use std::os::unix::fs::OpenOptionsExt;
    std::fs::OpenOptions::new().read(true).custom_flags(libc::O_NONBLOCK).open(path)
}

/// (Windows has no FIFOs in its file system; its named pipes live under `\\.\pipe\`, which
/// `metadata` reports as not a regular file.)
#[cfg(not(unix))]
fn open_without_blocking(path: &Path) -> std::io::Result<File> {
    File::open(path)
}

#[cfg(test)]
mod tests {
    use super::read_regular_file;

    /// A file of exactly the limit is read whole; one byte more is refused, naming both sizes.
    #[test]
    fn a_file_of_the_limit_is_read_whole_and_one_byte_more_is_refused() {
        let path = std::env::temp_dir().join(format!("wrc-files-limit-{}", std::process::id()));
        std::fs::write(&path, b"0123456789").unwrap();
        assert_eq!(read_regular_file(&path, 10).unwrap(), b"0123456789");
        assert_eq!(read_regular_file(&path, 9).unwrap_err(), "it has 10 bytes; this file may have at most 9");
        std::fs::remove_file(&path).unwrap();
    }
}
