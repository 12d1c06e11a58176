//! Small file-system helpers shared by every layer that reads or writes
//! the user's files (scenes, models, shaders, shader parameters): below
//! everything else, using nothing.

use std::io::{Read, Write};
use std::path::Path;

/// The bytes of the regular file at `path`, at most `limit + 1` of them (a
/// caller that gets more knows the file is over its limit without holding
/// it whole). Anything but a regular file is refused with `InvalidInput`,
/// "not a file": a device such as `/dev/zero` or a named pipe never ends,
/// and reading it would fill the memory or wait for ever.
pub fn read_regular(path: &Path, limit: u64) -> std::io::Result<Vec<u8>> {
    if !std::fs::metadata(path)?.is_file() {
        return Err(std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            "not a file",
        ));
    }
    let mut bytes = Vec::new();
    std::fs::File::open(path)?
        .take(limit.saturating_add(1))
        .read_to_end(&mut bytes)?;
    Ok(bytes)
}

/// Writes `text` to `path` so that a crash or a full disk mid-write never
/// leaves a truncated file: write a temporary file in the same folder, flush
/// it to disk, then rename it over the target (atomic on POSIX and NTFS).
pub fn write_atomically(path: &Path, text: &str) -> std::io::Result<()> {
    let dir = path
        .parent()
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let name = path
        .file_name()
        .ok_or_else(|| std::io::Error::other("not a file name"))?;
    let tmp = dir.join(format!(
        ".{}.tmp-{}",
        name.to_string_lossy(),
        std::process::id()
    ));
    let result = (|| {
        let mut file = std::fs::File::create(&tmp)?;
        file.write_all(text.as_bytes())?;
        file.sync_all()?;
        std::fs::rename(&tmp, path)
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn failed_write_keeps_the_old_file() {
        let dir =
            std::env::temp_dir().join(format!("raysandbox-files-fail-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("keep.toml");
        std::fs::write(&path, "old").unwrap();
        // A folder where the temporary file should go makes the write fail.
        let blocked = dir.join("missing-folder").join("x.toml");
        assert!(write_atomically(&blocked, "new").is_err());
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "old");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
