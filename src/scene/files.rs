//! Where the files a scene's shapes read (a mesh's model, docs/scene-format.md)
//! come from while the scene is validated: natively the file system
//! ([`Folder`]); in the web page, which has no file system, bytes its caller
//! fetched first ([`GivenFiles`]). The kind that reads a file parses the
//! bytes itself, so this knows no kind.

use std::borrow::Cow;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// A source of the files a scene names, by `file` as the scene writes it.
pub trait SceneFiles {
    /// The name of `file` for messages and its bytes; the error names the
    /// file and says why it cannot be read.
    fn read(&self, file: &Path) -> Result<(String, Cow<'_, [u8]>), String>;
}

/// Files on disk, relative to a folder (the scene file's) unless
/// absolute; `Folder(None)`: relative to the working directory.
pub struct Folder<'a>(pub Option<&'a Path>);

impl Folder<'_> {
    /// Where `file`, as the scene writes it, is on disk.
    pub fn path(&self, file: &Path) -> PathBuf {
        match self.0 {
            Some(dir) => dir.join(file),
            None => file.to_path_buf(),
        }
    }
}

impl SceneFiles for Folder<'_> {
    fn read(&self, file: &Path) -> Result<(String, Cow<'_, [u8]>), String> {
        read_file(&self.path(file)).map(|(name, bytes)| (name, Cow::Owned(bytes)))
    }
}

/// The bytes of the regular file at `path` (`crate::files::read_regular`:
/// a device is refused, not read), with its name for messages; the error
/// starts with the name.
pub fn read_file(path: &Path) -> Result<(String, Vec<u8>), String> {
    let name = path.display().to_string();
    match crate::files::read_regular(path, u64::MAX) {
        Ok(bytes) => Ok((name, bytes)),
        Err(e) => Err(format!("{name}: cannot read the file: {e}")),
    }
}

/// Files given as bytes, by `file` as the scene writes it (the web page
/// fetches them over http before it parses the scene). Nothing is read
/// from disk: a file not given is an error that names it and says why.
pub struct GivenFiles {
    files: HashMap<PathBuf, Vec<u8>>,
    /// What an error about a file that was not given says after its name.
    missing: String,
}

impl GivenFiles {
    /// No file yet; `missing` explains, after a file's name, why a file
    /// the scene names is not there.
    pub fn new(missing: &str) -> Self {
        GivenFiles {
            files: HashMap::new(),
            missing: missing.to_owned(),
        }
    }

    /// Gives the `bytes` of `file` (as the scene writes it).
    pub fn insert(&mut self, file: PathBuf, bytes: Vec<u8>) {
        self.files.insert(file, bytes);
    }

    /// Whether `file` was given.
    pub fn has(&self, file: &Path) -> bool {
        self.files.contains_key(file)
    }
}

impl SceneFiles for GivenFiles {
    fn read(&self, file: &Path) -> Result<(String, Cow<'_, [u8]>), String> {
        let name = file.display().to_string();
        match self.files.get(file) {
            Some(bytes) => Ok((name, Cow::Borrowed(bytes))),
            None => Err(format!("{name}: {}", self.missing)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A device never ends: refused by name, not read.
    #[cfg(unix)]
    #[test]
    fn a_device_is_refused_not_read() {
        let e = read_file(Path::new("/dev/zero")).unwrap_err();
        assert_eq!(e, "/dev/zero: cannot read the file: not a file");
        let e = read_file(Path::new("/no/such/model.obj")).unwrap_err();
        assert!(
            e.starts_with("/no/such/model.obj: cannot read the file: "),
            "{e}"
        );
    }
}
