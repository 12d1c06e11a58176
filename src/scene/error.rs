//! [`SceneError`]: why a scene file was rejected, and where.

use std::fmt;
use std::path::{Path, PathBuf};

/// A scene that failed to load: unreadable file, TOML syntax, wrong type,
/// unknown key or a value that breaks a rule of the rendering model.
///
/// The parts are kept apart so that a UI can show them separately (jump to
/// `line`, highlight `key`); `Display` joins them into the single line that
/// compilers use and editors recognise:
///
/// - `FILE:LINE: KEY: MESSAGE`, e.g.
///   `scenes/a.toml:12: spheres[2].radius: must be > 0, got -1`;
/// - `FILE:LINE:COLUMN: MESSAGE` for TOML syntax errors, which have no key but
///   where the column matters;
/// - parts that are unknown are left out, and `<scene>` stands for the file
///   when the text did not come from one.
///
/// Only the first problem of a scene is reported.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SceneError {
    /// The file the scene came from, if it came from one.
    pub file: Option<PathBuf>,
    /// 1-based line of the offending text, when it could be located.
    pub line: Option<usize>,
    /// 1-based column (in characters) of the offending text, when located.
    pub column: Option<usize>,
    /// The key path of the offending value, e.g. `spheres[2].radius` (array
    /// indices count from 0), or `None` for syntax and I/O errors.
    pub key: Option<String>,
    /// What is wrong, e.g. `must be > 0, got -1`.
    pub message: String,
}

impl SceneError {
    /// The file at `path` could not be read.
    pub fn io(path: &Path, e: &std::io::Error) -> Self {
        Self::new(format!("cannot read the file: {e}")).in_file(Some(path))
    }

    /// An error with only a message; the builders below add the rest.
    pub(super) fn new(message: impl Into<String>) -> Self {
        Self {
            file: None,
            line: None,
            column: None,
            key: None,
            message: message.into(),
        }
    }

    /// Names the file the scene came from.
    pub(super) fn in_file(mut self, file: Option<&Path>) -> Self {
        self.file = file.map(Path::to_path_buf);
        self
    }

    /// Names the offending value.
    pub(super) fn with_key(mut self, key: impl fmt::Display) -> Self {
        self.key = Some(key.to_string());
        self
    }

    /// Places the error at a 1-based line and column.
    pub(super) fn at(mut self, (line, column): (usize, usize)) -> Self {
        self.line = Some(line);
        self.column = Some(column);
        self
    }
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match (&self.file, self.line) {
            (Some(file), _) => write!(f, "{}", file.display())?,
            (None, Some(_)) => f.write_str("<scene>")?,
            (None, None) => {}
        }
        if let Some(line) = self.line {
            write!(f, ":{line}")?;
            // Without a key, the column is the only pointer into the line.
            if let (None, Some(column)) = (&self.key, self.column) {
                write!(f, ":{column}")?;
            }
        }
        if self.file.is_some() || self.line.is_some() {
            f.write_str(": ")?;
        }
        if let Some(key) = &self.key {
            write!(f, "{key}: ")?;
        }
        f.write_str(&self.message)
    }
}

impl std::error::Error for SceneError {}
