//! The WGSL source: files split by concern, joined into one module, validated
//! with naga before any pipeline is built, and errors reported at the line of
//! the file they came from (not of the joined text).
//!
//! The binary embeds the files of `shaders/`, so it runs from any directory;
//! [`ShaderSource::from_dir`] reads the same files from disk for hot reload.

use std::fmt;
use std::path::{Path, PathBuf};

use super::features::MAX_STACK_SIZE;
use super::layout::fixed_arrays;
use super::shapes::glue::{ALL_KINDS_BOUND, DataAccess, shape_glue};
use super::shapes::{KindInfo, generated_parts, kinds};
use crate::scene::KindOptions;

/// The shader files in the order they are joined, before the shape kinds'
/// `shapes/<kind>.wgsl` (see `gpu::shapes`). WGSL resolves names at module
/// scope in any order, so the order only decides line numbering.
pub const SHADER_FILES: [&str; 8] = [
    "scene.wgsl",
    "camera.wgsl",
    "intersect.wgsl",
    "shade.wgsl",
    "main.wgsl",
    "outline.wgsl",
    "views.wgsl",
    "ray_tree.wgsl",
];

const EMBEDDED: [&str; 8] = [
    include_str!("../../shaders/scene.wgsl"),
    include_str!("../../shaders/camera.wgsl"),
    include_str!("../../shaders/intersect.wgsl"),
    include_str!("../../shaders/shade.wgsl"),
    include_str!("../../shaders/main.wgsl"),
    include_str!("../../shaders/outline.wgsl"),
    include_str!("../../shaders/views.wgsl"),
    include_str!("../../shaders/ray_tree.wgsl"),
];

/// One named piece of WGSL: a file of the shader folder.
#[derive(Debug, Clone, PartialEq)]
struct Part {
    /// What error messages call it: the path it was read from, or
    /// `shaders/NAME` for the embedded copy.
    name: String,
    /// Byte offset of this part in the joined source.
    start: usize,
}

/// WGSL joined from several files, with a map back to them.
#[derive(Debug, Clone, PartialEq)]
pub struct ShaderSource {
    joined: String,
    parts: Vec<Part>,
}

/// A WGSL error located in the file it came from.
#[derive(Debug, Clone, PartialEq)]
pub struct ShaderError {
    /// The file, as given to [`ShaderSource`] (e.g. `shaders/shade.wgsl`).
    pub file: String,
    /// 1-based line and column in that file; 0 when naga gave no position.
    pub line: u32,
    pub column: u32,
    /// naga's message, e.g. `expected ';', found 'let'`.
    pub message: String,
    /// The offending line of the file and the labels naga attached to it.
    pub source_line: String,
    pub label: String,
}

impl ShaderError {
    /// A file that could not be read: the error has no position.
    pub fn unreadable(file: String, e: &std::io::Error) -> Self {
        ShaderError {
            file,
            line: 0,
            column: 0,
            message: format!("cannot read the file: {e}"),
            source_line: String::new(),
            label: String::new(),
        }
    }
}

impl fmt::Display for ShaderError {
    /// `FILE:LINE:COLUMN: error: MESSAGE`, then the source line with a caret,
    /// in the style of rustc, so editors and people both recognise it.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.line == 0 {
            return write!(f, "{}: error: {}", self.file, self.message);
        }
        writeln!(
            f,
            "{}:{}:{}: error: {}",
            self.file, self.line, self.column, self.message
        )?;
        let gutter = self.line.to_string().len();
        writeln!(f, "{:gutter$} |", "")?;
        writeln!(f, "{} | {}", self.line, self.source_line)?;
        write!(
            f,
            "{:gutter$} | {}^ {}",
            "",
            " ".repeat(self.column.saturating_sub(1) as usize),
            self.label
        )
    }
}

impl std::error::Error for ShaderError {}

/// Name of the part the program writes in front of the shader files.
const GENERATED: &str = "(generated) specialisation";

/// The generated part: WGSL constants that cannot be pipeline-overridable
/// because they size arrays, the data textures' type for `access`, and the
/// glue of the shape kinds, whose arrays are bound for the kinds in
/// `bound_kinds`.
fn generated_part(stack_size: u32, bound_kinds: u32, access: DataAccess) -> (String, String) {
    let stack_size = stack_size.clamp(1, MAX_STACK_SIZE);
    (
        GENERATED.to_string(),
        format!(
            "// Written by raysandbox for the scene being drawn (src/gpu/shaders.rs).\n\
             const STACK_SIZE: u32 = {stack_size}u;\n\
             // The BVH traversal stack, for trees as deep as src/bvh.rs builds them.\n\
             const BVH_STACK: u32 = {}u;\n{}{}{}",
            crate::bvh::TRAVERSAL_STACK,
            access.wgsl(),
            fixed_arrays(),
            shape_glue(&kinds(), bound_kinds)
        ),
    )
}

/// The generated part of a source not yet specialised for a scene: the
/// largest stack, every kind's arrays, sampled data textures (what
/// `IdRenderer` binds, which compiles such a source as it is).
fn unspecialised_part() -> (String, String) {
    generated_part(MAX_STACK_SIZE, ALL_KINDS_BOUND, DataAccess::Sampled)
}

impl ShaderSource {
    /// The shader files compiled into the binary.
    pub fn embedded() -> Self {
        let files = SHADER_FILES
            .iter()
            .zip(EMBEDDED)
            .map(|(name, text)| (format!("shaders/{name}"), text.to_string()));
        let shapes = kinds()
            .into_iter()
            .map(|k| (format!("shaders/{}", k.file()), k.wgsl.to_string()));
        Self::join(
            std::iter::once(unspecialised_part())
                .chain(files)
                .chain(shapes)
                .chain(generated_parts(&KindOptions::default())),
        )
    }

    /// The same source with the ray-tree stack sized for `stack_size`
    /// entries (a scene's `max_depth + 1`).
    pub fn with_stack_size(&self, stack_size: u32) -> Self {
        self.specialised(stack_size, ALL_KINDS_BOUND, DataAccess::Sampled)
    }

    /// The same source with the ray-tree stack sized for `stack_size`
    /// entries, bindings only for the arrays of `bound_kinds` (see
    /// `shape_glue`), and data textures read as `access` says.
    pub fn specialised(&self, stack_size: u32, bound_kinds: u32, access: DataAccess) -> Self {
        let files = self.parts().filter(|(name, _)| *name != GENERATED);
        Self::join(
            std::iter::once(generated_part(stack_size, bound_kinds, access))
                .chain(files.map(|(name, text)| (name.to_string(), text.to_string()))),
        )
    }

    /// The files of `dir` (`--shaders`) or else the embedded copy,
    /// validated: a broken shader is the user's input, reported before a
    /// GPU is asked for (`raysandbox render`, `raysandbox stress`).
    pub fn checked(dir: Option<&Path>) -> Result<Self, ShaderError> {
        let source = match dir {
            Some(dir) => Self::from_dir(dir)?,
            None => Self::embedded(),
        };
        source.validate()?;
        Ok(source)
    }

    /// Reads the shader files from `dir` (for hot reload and `--shaders`):
    /// [`SHADER_FILES`], then `shapes/<kind>.wgsl` for every shape kind.
    pub fn from_dir(dir: &Path) -> Result<Self, ShaderError> {
        let shape_files = kinds().iter().map(KindInfo::file).collect::<Vec<_>>();
        let names = SHADER_FILES
            .iter()
            .map(|s| s.to_string())
            .chain(shape_files);
        let mut files = Vec::new();
        for name in names {
            let path: PathBuf = dir.join(name);
            let text = std::fs::read_to_string(&path)
                .map_err(|e| ShaderError::unreadable(path.display().to_string(), &e))?;
            files.push((path.display().to_string(), text));
        }
        Ok(Self::join(
            std::iter::once(unspecialised_part())
                .chain(files)
                .chain(generated_parts(&KindOptions::default())),
        ))
    }

    /// The same source with the WGSL the shape kinds write for `kinds`
    /// (an implicit surface's functions, [`generated_parts`]) in
    /// place of the previous.
    pub fn with_generated(&self, kinds: &KindOptions) -> Self {
        let previous: Vec<String> = generated_parts(&KindOptions::default())
            .into_iter()
            .map(|(name, _)| name)
            .collect();
        let files = self
            .parts()
            .filter(|(name, _)| !previous.iter().any(|p| p == name));
        Self::join(
            files
                .map(|(name, text)| (name.to_string(), text.to_string()))
                .chain(generated_parts(kinds)),
        )
    }

    fn join(files: impl IntoIterator<Item = (String, String)>) -> Self {
        let mut joined = String::new();
        let mut parts = Vec::new();
        for (name, text) in files {
            parts.push(Part {
                name,
                start: joined.len(),
            });
            joined.push_str(&text);
            if !text.ends_with('\n') {
                joined.push('\n');
            }
        }
        ShaderSource { joined, parts }
    }

    /// The joined WGSL, as handed to wgpu.
    pub fn text(&self) -> &str {
        &self.joined
    }

    /// Parses and validates the joined source with naga, as wgpu will, so that
    /// a broken shader is reported with its file and line and never reaches
    /// pipeline creation.
    pub fn validate(&self) -> Result<(naga::Module, naga::valid::ModuleInfo), ShaderError> {
        let parsed = self.without_panics(|| naga::front::wgsl::parse_str(&self.joined))?;
        let module = parsed.map_err(|e| {
            let (span, label) = e
                .labels()
                .next()
                .map(|(s, l)| (s, l.to_string()))
                .unwrap_or_default();
            self.locate(span, e.message().to_string(), label)
        })?;
        self.validate_module(module)
    }

    /// Runs naga's validator on a parsed module; its errors are located in
    /// the part they fall in, like parse errors.
    pub fn validate_module(
        &self,
        module: naga::Module,
    ) -> Result<(naga::Module, naga::valid::ModuleInfo), ShaderError> {
        let validated = self.without_panics(|| {
            naga::valid::Validator::new(
                naga::valid::ValidationFlags::all(),
                naga::valid::Capabilities::default(),
            )
            .validate(&module)
            .map_err(Box::new)
        })?;
        let info = validated.map_err(|e| {
            let (span, label) = e.spans().next().cloned().unwrap_or_default();
            // The innermost cause says what is wrong; the outer ones say where.
            let mut message = e.as_inner().to_string();
            let mut source = std::error::Error::source(e.as_inner());
            while let Some(cause) = source {
                message = format!("{message}: {cause}");
                source = cause.source();
            }
            self.locate(span, message, label)
        })?;
        Ok((module, info))
    }

    /// Translates a validated module without `override`s to SPIR-V once, as
    /// wgpu will for the Vulkan driver, so that a module naga's SPIR-V
    /// writer cannot handle (or panics on) is an error here, not a crash
    /// when the pipeline is built.
    pub fn check_translation(
        &self,
        module: &naga::Module,
        info: &naga::valid::ModuleInfo,
    ) -> Result<(), ShaderError> {
        let translated = self.without_panics(|| {
            naga::back::spv::write_vec(module, info, &Default::default(), None)
        })?;
        translated.map(|_| ()).map_err(|e| {
            self.locate(
                naga::Span::default(),
                format!("the SPIR-V translation failed: {e}"),
                String::new(),
            )
        })
    }

    /// Runs a step of naga and turns a panic inside it (a bug of naga's that
    /// some inputs hit) into an error: a shader must never take the program
    /// down. The error has no position; it names the first part.
    pub fn without_panics<T>(&self, step: impl FnOnce() -> T) -> Result<T, ShaderError> {
        catch_panic(step).map_err(|message| {
            self.locate(
                naga::Span::default(),
                format!(
                    "the shader compiler (naga) failed on this shader: {message}; \
                     rewriting the line it trips on usually helps"
                ),
                String::new(),
            )
        })
    }

    /// Joins named parts in order: for example a prelude the program
    /// provides, the user's own file and an epilogue. Errors are reported in
    /// the part they fall in, at that part's own line and column, so a
    /// prelude never shifts the user's line numbers.
    pub fn from_parts(parts: impl IntoIterator<Item = (String, String)>) -> Self {
        Self::join(parts)
    }

    /// The parts as `(name, text)`, in the order they are joined.
    pub fn parts(&self) -> impl Iterator<Item = (&str, &str)> + '_ {
        self.parts.iter().enumerate().map(|(i, part)| {
            let end = self.parts.get(i + 1).map_or(self.joined.len(), |p| p.start);
            (part.name.as_str(), &self.joined[part.start..end])
        })
    }

    /// The file, line and column of a span of the joined source (for errors
    /// found outside naga, e.g. by a check of the source's own).
    pub fn error_at(&self, span: naga::Span, message: String) -> ShaderError {
        self.locate(span, message, String::new())
    }

    /// Turns a span of the joined source into file, line and column.
    fn locate(&self, span: naga::Span, message: String, label: String) -> ShaderError {
        let Some(range) = span.to_range() else {
            let file = self
                .parts
                .first()
                .map(|p| p.name.clone())
                .unwrap_or_default();
            return ShaderError {
                file,
                line: 0,
                column: 0,
                message,
                source_line: String::new(),
                label,
            };
        };
        let part = self
            .parts
            .iter()
            .rev()
            .find(|p| p.start <= range.start)
            .expect("the first part starts at 0");
        let before = &self.joined[part.start..range.start];
        let line_start = before
            .rfind('\n')
            .map_or(part.start, |i| part.start + i + 1);
        let line_end = self.joined[line_start..]
            .find('\n')
            .map_or(self.joined.len(), |i| line_start + i);
        ShaderError {
            file: part.name.clone(),
            line: before.matches('\n').count() as u32 + 1,
            column: (range.start - line_start) as u32 + 1,
            message,
            source_line: self.joined[line_start..line_end].to_string(),
            label,
        }
    }
}

/// Calls `step`, catching a panic: `Err` with the panic's message. The
/// default panic report on stderr is silenced for the panics caught here
/// (the caller reports them as errors), and only for them.
pub fn catch_panic<T>(step: impl FnOnce() -> T) -> Result<T, String> {
    thread_local! {
        static CATCHING: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
    }
    static QUIET_HOOK: std::sync::Once = std::sync::Once::new();
    QUIET_HOOK.call_once(|| {
        let report = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            if !CATCHING.get() {
                report(info);
            }
        }));
    });
    let was_catching = CATCHING.replace(true);
    let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(step));
    CATCHING.set(was_catching);
    result.map_err(|payload| {
        payload
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| payload.downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "a panic without a message".to_string())
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn embedded_shader_validates() {
        ShaderSource::embedded()
            .validate()
            .unwrap_or_else(|e| panic!("{e}"));
    }

    #[test]
    fn parse_error_points_at_the_file_and_line_it_came_from() {
        let files = [
            (
                "a.wgsl".to_string(),
                "fn one() -> f32 {\n    return 1.0;\n}\n".to_string(),
            ),
            (
                "b.wgsl".to_string(),
                "// comment\nfn two() -> f32 {\n    return 2.0\n}\n".to_string(),
            ),
        ];
        let err = ShaderSource::join(files).validate().unwrap_err();
        assert_eq!(err.file, "b.wgsl");
        // naga reports the token after the missing ';', the `}` on line 4.
        assert_eq!((err.line, err.column), (4, 1), "{err}");
        assert_eq!(err.source_line, "}");
        let shown = err.to_string();
        assert!(shown.starts_with("b.wgsl:4:1: error: expected"), "{shown}");
    }

    #[test]
    fn validation_error_is_located_too() {
        let files = [(
            "c.wgsl".to_string(),
            "fn f() -> f32 {\n    let x: f32 = 1u;\n    return x;\n}\n".to_string(),
        )];
        let err = ShaderSource::join(files).validate().unwrap_err();
        assert_eq!(err.file, "c.wgsl");
        assert_eq!(err.line, 2, "{err}");
    }

    #[test]
    fn stack_size_is_generated_in_front_and_keeps_file_lines() {
        let source = ShaderSource::embedded().with_stack_size(4);
        assert!(source.text().contains("const STACK_SIZE: u32 = 4u;"));
        assert_eq!(source.text().matches("const STACK_SIZE").count(), 1);
        source.validate().unwrap_or_else(|e| panic!("{e}"));
        // An error in a file is still reported at the file's own line.
        let broken: Vec<(String, String)> = source
            .parts()
            .map(|(name, text)| {
                let text = if name.ends_with("main.wgsl") {
                    text.replacen("@fragment", "@fragment oops", 1)
                } else {
                    text.to_string()
                };
                (name.to_string(), text)
            })
            .collect();
        let err = ShaderSource::join(broken).validate().unwrap_err();
        assert_eq!(err.file, "shaders/main.wgsl");
        let expected = EMBEDDED[4][..EMBEDDED[4].find("@fragment").unwrap()]
            .lines()
            .count()
            + 1;
        assert_eq!(err.line as usize, expected, "{err}");
    }

    #[test]
    fn the_bvh_stack_is_generated_from_the_tree_depth_limit() {
        let source = ShaderSource::embedded();
        let expected = format!("const BVH_STACK: u32 = {}u;", crate::bvh::TRAVERSAL_STACK);
        assert!(source.text().contains(&expected));
        assert_eq!(source.text().matches("const BVH_STACK").count(), 1);
    }

    #[test]
    fn a_panic_is_caught_with_its_message_and_other_panics_still_unwind() {
        assert_eq!(catch_panic(|| 7), Ok(7));
        let message = catch_panic(|| -> u32 { panic!("Expression [3] is not cached!") });
        assert_eq!(message, Err("Expression [3] is not cached!".to_string()));
        let formatted = catch_panic(|| -> u32 { panic!("{} {}", 1, 2) });
        assert_eq!(formatted, Err("1 2".to_string()));
    }

    #[test]
    fn missing_file_in_a_folder_is_named() {
        let dir = std::env::temp_dir().join(format!("raysandbox-empty-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let err = ShaderSource::from_dir(&dir).unwrap_err();
        assert!(err.file.ends_with("scene.wgsl"), "{err}");
        assert!(err.message.contains("cannot read"), "{err}");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
