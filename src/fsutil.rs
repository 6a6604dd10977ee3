//! File-system helpers shared by every writer: atomic writes (temp file + rename) that keep
//! the user's permissions, and the check, before any work, that an output can be written.

use std::io::Write;
use std::path::{Path, PathBuf};

/// Write `bytes` to `path` atomically: the data go to a temporary file in the same
/// directory, are flushed to disk, and the file is renamed over `path`. A crash or an
/// error half-way never leaves a truncated file at `path` nor destroys its old content.
///
/// The file's mode is the one a plain `create` would give: a new file gets `0o666` less the
/// process's umask (0644 under umask 022), and a replaced file keeps its own mode (a model
/// written into a group's shared folder stays readable by the group).
pub fn write_atomic(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let dir = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    let mut builder = tempfile::Builder::new();
    builder.prefix(".tmp-");
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt as _;
        // The mode asked for at creation is reduced by the umask, as for any new file.
        builder.permissions(std::fs::Permissions::from_mode(0o666));
    }
    let mut tmp = builder.tempfile_in(dir)?;
    // A replaced file keeps its mode (and a read-only one stays read-only).
    if let Ok(old) = std::fs::metadata(path) {
        tmp.as_file().set_permissions(old.permissions())?;
    }
    tmp.write_all(bytes)?;
    tmp.as_file().sync_all()?;
    tmp.persist(path).map_err(|e| e.error)?;
    Ok(())
}

/// An output that cannot be written where it was asked ([`check_output`]).
#[derive(Debug, thiserror::Error)]
#[error("{}: cannot write the model there: {reason}", path.display())]
pub struct NotWritable {
    /// The output file.
    pub path: PathBuf,
    /// Why: its directory is missing, not a directory, or not writable.
    pub reason: String,
}

/// Check, before any work, that a file can be written to `path`: its directory exists and a
/// file can be created there (a temporary file is made and removed).
pub fn check_output(path: &Path) -> Result<(), NotWritable> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let err = |reason: String| NotWritable {
        path: path.to_path_buf(),
        reason,
    };
    if !dir.exists() {
        return Err(err(format!(
            "the directory {} does not exist",
            dir.display()
        )));
    }
    if !dir.is_dir() {
        return Err(err(format!("{} is not a directory", dir.display())));
    }
    tempfile::NamedTempFile::new_in(dir).map(drop).map_err(|e| {
        err(format!(
            "the directory {} is not writable ({e})",
            dir.display()
        ))
    })
}

#[cfg(test)]
mod tests;
