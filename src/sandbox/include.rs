//! glslViewer's `#include "file"` (docs/sandbox.md, "Includes"): the line
//! is replaced by the file's text, found relative to the including file, so
//! that shader libraries such as LYGIA work from a local copy. Each file is
//! included once (as glslViewer does, so libraries that include each other
//! need no guards); one that includes itself, directly or through others,
//! is an error at the `#include` that closes the cycle. Lines are copied
//! whole, so a map from the joined text's lines to (file, line) puts every
//! error at the included file's own line and column.

use std::path::{Path, PathBuf};

use crate::gpu::ShaderError;

/// Includes nested deeper than this are an error (a runaway chain of
/// generated files, not a library).
pub const MAX_DEPTH: usize = 32;
/// The joined text may not grow beyond this many bytes.
pub const MAX_BYTES: usize = 8 << 20;
/// At most this many files are included.
pub const MAX_FILES: usize = 1024;

/// A file with its includes joined in.
#[derive(Debug, Clone, Default)]
pub struct Expanded {
    /// The joined text.
    pub text: String,
    /// The files read: the including file first, then each included one.
    pub files: Vec<PathBuf>,
    /// For each line of `text` (0-based): the index in `files` and the
    /// 1-based line there.
    lines: Vec<(usize, u32)>,
    /// `files`, canonical: how a file included twice is recognised.
    keys: Vec<PathBuf>,
}

impl Expanded {
    /// The files included (all but the first), to watch for changes.
    pub fn included(&self) -> &[PathBuf] {
        self.files.get(1..).unwrap_or_default()
    }

    /// Moves an error at a line of the joined text called `name` to the file
    /// and line the text came from (the line's text is the same).
    pub fn locate(&self, mut e: ShaderError, name: &str) -> ShaderError {
        if e.file != name || e.line == 0 {
            return e;
        }
        if let Some(&(file, line)) = self.lines.get(e.line as usize - 1) {
            if file > 0 {
                e.file = self.files[file].display().to_string();
            }
            e.line = line;
        }
        e
    }

    /// A text of no file on disk (a pass of a Shadertoy JSON export), named
    /// `name` in errors; `#include` lines stay as they are.
    pub fn of_text(name: &str, text: &str) -> Self {
        Expanded {
            text: text.to_string(),
            files: vec![PathBuf::from(name)],
            lines: (1..=text.split_inclusive('\n').count() as u32)
                .map(|line| (0, line))
                .collect(),
            keys: vec![PathBuf::from(name)],
        }
    }

    /// `first`'s text joined before this one's (Shadertoy's Common code
    /// before each pass), every line still mapped to its own file. This
    /// text's file stays the first of `files`: the one errors are named by.
    pub fn after(mut self, first: &Expanded) -> Self {
        let shift = self.files.len();
        let mut text = first.text.clone();
        if !text.is_empty() && !text.ends_with('\n') {
            text.push('\n');
        }
        let mut lines: Vec<(usize, u32)> =
            first.lines.iter().map(|&(f, l)| (f + shift, l)).collect();
        lines.extend_from_slice(&self.lines);
        text.push_str(&self.text);
        self.text = text;
        self.lines = lines;
        self.files.extend(first.files.iter().cloned());
        self.keys.extend(first.keys.iter().cloned());
        self
    }

    /// The (file, line) a 1-based line of the joined text came from.
    pub fn origin(&self, line: u32) -> Option<(&Path, u32)> {
        let &(file, original) = self.lines.get((line as usize).checked_sub(1)?)?;
        Some((self.files[file].as_path(), original))
    }
}

/// The path of `#include "path"` if `line` is one.
pub(crate) fn include_target(line: &str) -> Option<&str> {
    let rest = line.trim_start().strip_prefix('#')?.trim_start();
    let rest = rest.strip_prefix("include")?.trim_start();
    let rest = rest.strip_prefix('"')?;
    let end = rest.find('"')?;
    Some(&rest[..end])
}

/// Joins the includes of `text`, the content of the file `path`. The files
/// read are in the result also when it is an error (to watch them: fixing
/// one is a reason to reload).
pub fn expand(path: &Path, text: &str) -> (Expanded, Result<(), ShaderError>) {
    let mut out = Expanded {
        files: vec![path.to_path_buf()],
        keys: vec![canonical(path)],
        ..Default::default()
    };
    let mut stack = out.keys.clone();
    let result = expand_into(&mut out, 0, text, &mut stack);
    (out, result)
}

fn canonical(path: &Path) -> PathBuf {
    path.canonicalize().unwrap_or_else(|_| path.to_path_buf())
}

/// Appends the lines of `text` (of `out.files[file]`) to `out`, each
/// include replaced by its file's lines. `stack` holds the files being
/// included, outermost first.
fn expand_into(
    out: &mut Expanded,
    file: usize,
    text: &str,
    stack: &mut Vec<PathBuf>,
) -> Result<(), ShaderError> {
    for (k, line) in text.split_inclusive('\n').enumerate() {
        let number = k as u32 + 1;
        let Some(target) = include_target(line) else {
            out.text.push_str(line);
            out.lines.push((file, number));
            continue;
        };
        let fail = |message: String| ShaderError {
            file: out.files[file].display().to_string(),
            line: number,
            column: (line.len() - line.trim_start().len()) as u32 + 1,
            message,
            source_line: line.trim_end().to_string(),
            label: String::new(),
        };
        let dir = out.files[file].parent().unwrap_or(Path::new(""));
        let included = dir.join(target);
        let key = canonical(&included);
        if stack.contains(&key) {
            return Err(fail(format!(
                "include cycle: \"{target}\" is already being included ({})",
                cycle(stack, &key)
            )));
        }
        // Included once: a second `#include` of a file is left out.
        let seen = out.keys.contains(&key);
        if !seen {
            if stack.len() > MAX_DEPTH {
                return Err(fail(format!("includes nested more than {MAX_DEPTH} deep")));
            }
            if out.files.len() >= MAX_FILES {
                return Err(fail(format!("more than {MAX_FILES} included files")));
            }
            let content = read_included(&included, MAX_BYTES - out.text.len().min(MAX_BYTES))
                .map_err(fail)?;
            out.files.push(included);
            out.keys.push(key.clone());
            stack.push(key);
            expand_into(out, out.files.len() - 1, &content, stack)?;
            stack.pop();
            // The included file's last line ended, unless nothing was
            // joined yet (an empty file first): a newline then would be a
            // line of no file, moving every error below it by one.
            if !out.text.is_empty() && !out.text.ends_with('\n') {
                out.text.push('\n');
            }
        }
        // The `#include` line itself stays, blanked, at its own line.
        out.text.push_str(&" ".repeat(line.trim_end().len()));
        out.text.push_str(&line[line.trim_end().len()..]);
        out.lines.push((file, number));
    }
    Ok(())
}

/// The text of an included file, refused unless it is a regular file (a
/// device such as `/dev/zero` or a named pipe would never end) and at most
/// `budget` bytes long (read no further than that, so that a huge file is
/// never held whole).
fn read_included(path: &Path, budget: usize) -> Result<String, String> {
    let bytes = crate::files::read_regular(path, budget as u64)
        .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    if bytes.len() > budget {
        return Err(format!(
            "the includes make the shader longer than {} MB",
            MAX_BYTES >> 20
        ));
    }
    String::from_utf8(bytes)
        .map_err(|_| format!("cannot read {}: it is not UTF-8 text", path.display()))
}

/// `a.glsl -> b.glsl -> a.glsl`, from where `key` is on the stack.
fn cycle(stack: &[PathBuf], key: &Path) -> String {
    let from = stack.iter().position(|p| p == key).unwrap_or(0);
    let name = |p: &Path| {
        p.file_name()
            .map_or_else(String::new, |n| n.to_string_lossy().into_owned())
    };
    let mut names: Vec<String> = stack[from..].iter().map(|p| name(p)).collect();
    names.push(name(key));
    names.join(" includes ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn include_lines_are_recognised() {
        assert_eq!(include_target("#include \"a/b.glsl\"\n"), Some("a/b.glsl"));
        assert_eq!(include_target("  # include \"x\" // c"), Some("x"));
        assert_eq!(include_target("#include <x>"), None);
        assert_eq!(include_target("// #include \"x\""), None);
        assert_eq!(include_target("#define include \"x\""), None);
    }

    /// An empty file included first adds no line: the error below it is at
    /// its own line (found by the fuzzer).
    #[test]
    fn an_empty_file_included_first_moves_no_line() {
        let dir = std::env::temp_dir().join(format!("raysandbox-include-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(dir.join("empty.glsl"), "").unwrap();
        let main = dir.join("main.frag");
        let (expanded, result) = expand(&main, "#include \"empty.glsl\"\nx\ny\n");
        result.unwrap();
        assert_eq!(expanded.origin(3), Some((main.as_path(), 3)));
        assert_eq!(expanded.text.lines().count(), 3);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    /// A device never ends: reading it whole would fill the memory.
    #[cfg(unix)]
    #[test]
    fn a_device_is_refused_at_the_include_line() {
        let text = "void main() {}\n#include \"/dev/zero\"\n";
        let (_, result) = expand(Path::new("/tmp/main.frag"), text);
        let e = result.unwrap_err();
        assert_eq!((e.file.as_str(), e.line), ("/tmp/main.frag", 2));
        assert!(e.message.contains("/dev/zero: not a file"), "{}", e.message);
    }
}
