//! `raysandbox shader --check-all DIR` (docs/sandbox.md, "Checking a
//! folder of shaders"): every shader file of a folder compiled and drawn
//! once, a verdict per file with a warning column (a picture of one flat
//! colour or all NaN, uniforms nothing sets), and the totals.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use super::multipass::{
    self,
    headless::{MultipassOffscreen, Unbuilt},
};
use super::render::NanColor;
use super::render::{BuildFailed, FRAME_LIMIT, build_too_slow};
use super::{
    CanvasStats, FrameUniforms, Offscreen, SandboxError, ShaderArgs, Warning, WarningKind,
    compile_file,
};
use crate::gpu::Gpu;

/// The extensions of shader files (docs/sandbox.md, "Which kind of file").
const SHADER_EXTENSIONS: [&str; 6] = ["wgsl", "glsl", "frag", "fs", "fsh", "fragment"];

/// `--check-all DIR`: every shader file of DIR compiled and drawn once.
pub(super) fn check_all(args: &ShaderArgs) -> Result<(), SandboxError> {
    let dir = &args.file;
    let entries = std::fs::read_dir(dir)
        .map_err(|e| SandboxError::Input(format!("{}: {e}", dir.display())))?;
    let mut files: Vec<PathBuf> = entries
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| {
            p.extension()
                .is_some_and(|e| SHADER_EXTENSIONS.contains(&e.to_string_lossy().as_ref()))
                || is_multipass_entry(p)
        })
        .collect();
    files.sort();
    if files.is_empty() {
        return Err(SandboxError::Input(format!(
            "{}: no shader files (.{}), Shadertoy JSON files or multipass folders in this folder",
            dir.display(),
            SHADER_EXTENSIONS.join(", .")
        )));
    }
    let size = args.size.unwrap_or((64, 36));
    let mut gpu = Gpu::headless().map_err(|e| SandboxError::Runtime(e.to_string()))?;
    let mut failed = 0;
    let mut totals = Totals::default();
    for path in &files {
        let checked = if is_multipass_entry(path) {
            check_multipass(&gpu, path, size, args.time)
        } else {
            check_file(&gpu, path, size, args.time)
        };
        match checked {
            Ok(report) => {
                println!("pass  {}{}", path.display(), report.column());
                totals.count(&report);
            }
            Err(e) => {
                failed += 1;
                let first = e.message().lines().next().unwrap_or_default().to_string();
                println!("FAIL  {first}");
                if let Checked::Stopped(_) = e {
                    // That device is still busy with the frame: a new one.
                    std::mem::forget(gpu);
                    gpu = Gpu::headless().map_err(|e| SandboxError::Runtime(e.to_string()))?;
                }
            }
        }
    }
    let total = files.len();
    println!(
        "{} of {total} pass ({:.1}%), {failed} fail; {totals}",
        total - failed,
        100.0 * (total - failed) as f64 / total as f64
    );
    match failed {
        0 => Ok(()),
        _ => Err(SandboxError::Input(format!(
            "{failed} of {total} shaders in {} failed",
            dir.display()
        ))),
    }
}

/// A multipass shader among the files of a folder: a `.json` file, or a
/// folder with an `image.glsl` (docs/sandbox.md, "Multipass").
fn is_multipass_entry(path: &Path) -> bool {
    multipass::is_multipass(path) && (path.is_file() || path.join("image.glsl").is_file())
}

/// Why a shader did not pass [`check_file`].
#[derive(Debug, Clone, PartialEq)]
pub enum Checked {
    /// It does not compile, or wgpu refused it: the error, at the file.
    Failed(String),
    /// Its frame was stopped by the watchdog: the device is still busy.
    Stopped(String),
}

impl Checked {
    pub fn message(&self) -> &str {
        match self {
            Checked::Failed(m) | Checked::Stopped(m) => m,
        }
    }
}

/// Compiles `path` and draws one frame of it at `time` (what "it runs"
/// means for `--check-all` and the compatibility suite).
pub fn check_file(gpu: &Gpu, path: &Path, size: (u32, u32), time: f64) -> Result<Report, Checked> {
    let compiled = compile_file(path).map_err(|e| Checked::Failed(e.to_string()))?;
    let mut offscreen = Offscreen::new(gpu);
    let pipeline = match offscreen.builder(gpu).build_within(&compiled, FRAME_LIMIT) {
        Ok(pipeline) => pipeline,
        Err(BuildFailed::Refused(m)) => return Err(Checked::Failed(m)),
        Err(BuildFailed::TooSlow) => {
            std::mem::forget(offscreen);
            return Err(Checked::Stopped(build_too_slow(&compiled.file)));
        }
    };
    let frame = FrameUniforms::at(time, 0, size);
    if let Err(stopped) = offscreen.draw(gpu, &pipeline, &compiled.params, &frame) {
        std::mem::forget((offscreen, pipeline));
        return Err(Checked::Stopped(format!("{}: {stopped}", path.display())));
    }
    let stats = offscreen
        .stats(gpu)
        .map_err(|e| Checked::Failed(format!("{}: {e}", path.display())))?;
    Ok(Report {
        warnings: compiled.warnings,
        stats,
    })
}

/// What a shader that passed drew, and the warnings of its source.
#[derive(Debug, Clone, Default)]
pub struct Report {
    /// Uniforms nothing sets (docs/sandbox.md, "Uniforms nobody sets").
    pub warnings: Vec<Warning>,
    pub stats: CanvasStats,
}

/// What a picture is, when it is not a picture: every pixel NaN, or one
/// flat colour.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Flat {
    Nan,
    Colour([u8; 3]),
}

impl Report {
    /// The picture as `--check-all` judges it: `None` for a picture that
    /// is not one flat colour.
    pub fn flat(&self) -> Option<Flat> {
        if self.stats.pixels > 0 && self.stats.non_finite == self.stats.pixels {
            return Some(Flat::Nan);
        }
        self.stats.flat.map(Flat::Colour)
    }

    /// The warning column of a line of `--check-all`: empty, or
    /// `  | one flat colour (r, g, b)  | FILE:LINE: warning: ...`.
    pub fn column(&self) -> String {
        let mut text = String::new();
        match self.flat() {
            Some(Flat::Nan) => text.push_str("  | every pixel is NaN"),
            Some(Flat::Colour([r, g, b])) => {
                let _ = write!(text, "  | one flat colour ({r}, {g}, {b})");
            }
            None => {}
        }
        if let Some(first) = self.warnings.first() {
            let _ = write!(text, "  | {first}");
            if self.warnings.len() > 1 {
                let _ = write!(text, " (and {} more)", self.warnings.len() - 1);
            }
        }
        text
    }
}

/// The counts of the totals line of `--check-all`.
#[derive(Debug, Default)]
struct Totals {
    picture: usize,
    flat: usize,
    nan: usize,
    silent: usize,
    no_return: usize,
}

impl Totals {
    fn count(&mut self, report: &Report) {
        match report.flat() {
            None => self.picture += 1,
            Some(Flat::Colour(_)) => self.flat += 1,
            Some(Flat::Nan) => self.nan += 1,
        }
        let has = |kind| report.warnings.iter().any(|w| w.kind == kind);
        self.silent += usize::from(has(WarningKind::SilentZero));
        self.no_return += usize::from(has(WarningKind::MissingReturn));
    }
}

impl std::fmt::Display for Totals {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "of those {} drew a picture, {} one flat colour, {} every pixel NaN; \
             {} with uniforms nothing sets (silent zeros)",
            self.picture, self.flat, self.nan, self.silent
        )?;
        if self.no_return > 0 {
            write!(
                f,
                "; {} with a function that returns 0 where it ends without a return",
                self.no_return
            )?;
        }
        Ok(())
    }
}

/// Frames `--check-all` draws of a multipass shader: two, so that each
/// buffer is read back once after it was written.
const CHECK_FRAMES: u32 = 2;

/// `--check-all`'s verdict on a folder or JSON file: it compiles and its
/// first frames draw.
pub fn check_multipass(
    gpu: &Gpu,
    path: &Path,
    size: (u32, u32),
    time: f64,
) -> Result<Report, Checked> {
    let (_, compiled) = multipass::headless::load(path).map_err(Checked::Failed)?;
    let warnings = compiled
        .passes
        .iter()
        .flat_map(|p| p.compiled.warnings.iter().cloned())
        .collect();
    let mut offscreen = match MultipassOffscreen::new(gpu, compiled, size, NanColor::Black) {
        Ok(o) => o,
        Err(Unbuilt::Refused(m)) => return Err(Checked::Failed(m)),
        Err(Unbuilt::TooSlow(m)) => return Err(Checked::Stopped(m)),
    };
    for k in 0..CHECK_FRAMES {
        let frame = FrameUniforms::at(time + f64::from(k) / 60.0, k, size);
        if let Err(stopped) = offscreen.draw(gpu, &frame) {
            std::mem::forget(offscreen);
            return Err(Checked::Stopped(format!("{}: {stopped}", path.display())));
        }
    }
    let stats = offscreen
        .stats(gpu)
        .map_err(|e| Checked::Failed(format!("{}: {e}", path.display())))?;
    Ok(Report { warnings, stats })
}
