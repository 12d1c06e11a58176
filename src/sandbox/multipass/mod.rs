//! Multipass Shadertoy shaders (docs/sandbox.md, "Multipass"): Buffer A to
//! D, Common and Image, each pass's `iChannel0..3` bound to a buffer, an
//! image, the keyboard or noise. Two forms come in: a folder written by hand
//! (`folder`) and the JSON of Shadertoy's API and export tools (`json`);
//! both become one [`Project`], which `compile` turns into validated passes
//! and `gpu` draws.
//!
//! | module | what |
//! | --- | --- |
//! | `folder` | `image.glsl`, `buffer_a.glsl` ..., `common.glsl` and `channels.toml` |
//! | `json` | Shadertoy's JSON (`renderpass`, `inputs`, `outputs`) |
//! | `compile` | the Common code joined before each pass, each pass compiled |
//! | `keyboard` | Shadertoy's 256x3 keyboard texture |
//! | `gpu` | the buffers (ping-pong textures), the passes drawn in order |
//! | `session` | the window's reloads: each pass's last good pipeline |
//! | `headless` | `--render`, `--frames` and `--check-all` of multipass shaders |

pub mod compile;
pub mod folder;
pub mod gpu;
pub mod headless;
pub mod json;
pub mod keyboard;
pub mod session;

use std::path::{Path, PathBuf};

pub use compile::{CompiledProject, compile_project};

use crate::sandbox::channels_3d::{ChannelKind, ChannelKinds};

/// Shadertoy has four buffers, A to D.
pub const BUFFERS: usize = 4;

/// A pass: one of the buffers (0 = A .. 3 = D) or the Image pass, which is
/// drawn last and shown.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum PassKind {
    Buffer(usize),
    Image,
}

impl PassKind {
    /// "Buffer A", ..., "Image": Shadertoy's tab names.
    pub fn title(&self) -> String {
        match self {
            PassKind::Buffer(k) => format!("Buffer {}", buffer_letter(*k)),
            PassKind::Image => "Image".into(),
        }
    }

    /// "buffer_a", ..., "image": the folder form's file stems and tables.
    pub fn stem(&self) -> String {
        match self {
            PassKind::Buffer(k) => format!("buffer_{}", buffer_letter(*k).to_ascii_lowercase()),
            PassKind::Image => "image".into(),
        }
    }

    /// The kinds in the order Shadertoy draws them: A, B, C, D, Image.
    pub fn all() -> [PassKind; BUFFERS + 1] {
        [
            PassKind::Buffer(0),
            PassKind::Buffer(1),
            PassKind::Buffer(2),
            PassKind::Buffer(3),
            PassKind::Image,
        ]
    }
}

fn buffer_letter(k: usize) -> char {
    (b'A' + k.min(BUFFERS - 1) as u8) as char
}

/// What a channel reads.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Input {
    /// A buffer (0 = A): its content as the passes before this one left it
    /// this frame, or of the previous frame for the pass itself and those
    /// after it (Shadertoy's order).
    Buffer(usize),
    /// An image file.
    Texture(PathBuf),
    /// Shadertoy's keyboard texture ([`keyboard`]).
    Keyboard,
    /// The built-in noise image (docs/sandbox.md, "Textures").
    Noise,
    /// The built-in cube map, read as a `samplerCube` (docs/sandbox.md,
    /// "Cube maps and volumes").
    Cube,
    /// The built-in noise volume, read as a `sampler3D`.
    Volume,
}

impl Input {
    /// The sampler type the channel has in the pass.
    pub fn kind(&self) -> ChannelKind {
        match self {
            Input::Cube => ChannelKind::Cube,
            Input::Volume => ChannelKind::Volume,
            _ => ChannelKind::Flat,
        }
    }
}

/// Where a pass's code is: a file of its own (the folder form, reloaded
/// when saved) or text inside the JSON file.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Code {
    File(PathBuf),
    Text(String),
}

/// One pass: its code and its four channels (None: black, as an empty
/// channel on Shadertoy).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Pass {
    pub kind: PassKind,
    /// The name errors use: the pass's file, or `FILE.json [Buffer A]`.
    pub name: String,
    pub code: Code,
    pub channels: [Option<Input>; 4],
}

/// A multipass shader: the passes (buffers in order, then Image) and the
/// Common code joined before each.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Project {
    /// The folder or JSON file it was read from.
    pub origin: PathBuf,
    pub common: Option<(String, Code)>,
    pub passes: Vec<Pass>,
    /// What was read but left out (a sound pass, a texture not found):
    /// each names the file and the key.
    pub warnings: Vec<String>,
}

impl Project {
    /// Reads a folder (`image.glsl` ...) or a Shadertoy JSON file; the error
    /// names the file and the key or line.
    pub fn load(path: &Path) -> Result<Project, String> {
        if path.is_dir() {
            folder::load(path)
        } else {
            let text = std::fs::read_to_string(path)
                .map_err(|e| format!("{}: cannot read: {e}", path.display()))?;
            json::parse(path, &text)
        }
    }

    /// The files a change of which is a reload: the JSON file, or the
    /// folder's pass files, `common.glsl` and `channels.toml`.
    pub fn files(&self) -> Vec<PathBuf> {
        let mut files = Vec::new();
        if self.origin.is_dir() {
            files.push(self.origin.join(folder::CHANNELS_FILE));
        } else {
            files.push(self.origin.clone());
        }
        let codes = self.common.iter().map(|(_, c)| c);
        for code in codes.chain(self.passes.iter().map(|p| &p.code)) {
            if let Code::File(path) = code {
                files.push(path.clone());
            }
        }
        files
    }

    /// The pass of `kind`, if the shader has it.
    pub fn pass(&self, kind: PassKind) -> Option<&Pass> {
        self.passes.iter().find(|p| p.kind == kind)
    }

    /// Every buffer a channel reads must be a pass of the shader; the error
    /// names the reading pass and channel.
    fn check_buffers(&self, at: impl Fn(&Pass, usize) -> String) -> Result<(), String> {
        for pass in &self.passes {
            for (k, input) in pass.channels.iter().enumerate() {
                if let Some(Input::Buffer(b)) = input
                    && self.pass(PassKind::Buffer(*b)).is_none()
                {
                    return Err(format!(
                        "{}: reads {}, which this shader does not have",
                        at(pass, k),
                        PassKind::Buffer(*b).title()
                    ));
                }
            }
        }
        Ok(())
    }
}

/// The kinds of a pass's channels (an empty one is flat, black).
pub fn kinds(channels: &[Option<Input>; 4]) -> ChannelKinds {
    channels
        .each_ref()
        .map(|c| c.as_ref().map_or(ChannelKind::Flat, Input::kind))
}

/// Whether `path` is a multipass shader: a folder, or a `.json` file.
pub fn is_multipass(path: &Path) -> bool {
    path.is_dir()
        || path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("json"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pass_names_follow_shadertoy() {
        assert_eq!(PassKind::Buffer(2).title(), "Buffer C");
        assert_eq!(PassKind::Buffer(3).stem(), "buffer_d");
        assert_eq!(PassKind::Image.stem(), "image");
        assert!(PassKind::Buffer(3) < PassKind::Image);
    }
}
