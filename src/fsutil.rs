//! File-system helpers shared by every writer: atomic writes (temp file + rename) that keep
//! the user's permissions.

use std::io::Write;
use std::path::Path;

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

#[cfg(test)]
mod tests;
