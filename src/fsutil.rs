//! File-system helpers shared by every writer: atomic writes (temp file + rename).

use std::io::Write;
use std::path::Path;

/// Write `bytes` to `path` atomically: the data go to a temporary file in the same
/// directory, are flushed to disk, and the file is renamed over `path`. A crash or an
/// error half-way never leaves a truncated file at `path` nor destroys its old content.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let dir = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    let mut tmp = tempfile::Builder::new().prefix(".tmp-").tempfile_in(dir)?;
    tmp.write_all(bytes)?;
    tmp.as_file().sync_all()?;
    tmp.persist(path).map_err(|e| e.error)?;
    Ok(())
}

#[cfg(test)]
mod tests;
