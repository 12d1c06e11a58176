//! The folder form of a multipass shader (docs/sandbox.md, "Multipass"),
//! written by hand: `image.glsl`, `buffer_a.glsl` ... `buffer_d.glsl`,
//! `common.glsl`, and `channels.toml`, which binds each pass's channels:
//!
//! ```toml
//! [buffer_a]
//! iChannel0 = "buffer_a"        # its own previous frame
//! iChannel1 = "keyboard"
//! [image]
//! iChannel0 = "buffer_a"
//! iChannel1 = "textures/wood.png" # an image, relative to the folder
//! ```

use std::path::Path;

use super::{BUFFERS, Code, Input, Pass, PassKind, Project};

/// The bindings file of a folder.
pub const CHANNELS_FILE: &str = "channels.toml";
/// The Common code of a folder.
pub const COMMON_FILE: &str = "common.glsl";

/// Reads the folder `dir`. Only `image.glsl` is required; an error names
/// the file and the key.
pub fn load(dir: &Path) -> Result<Project, String> {
    let image = dir.join("image.glsl");
    if !image.is_file() {
        return Err(format!(
            "{}: a multipass folder needs image.glsl (and may have buffer_a.glsl .. \
             buffer_d.glsl, common.glsl, channels.toml; docs/sandbox.md, \"Multipass\")",
            dir.display()
        ));
    }
    let mut passes: Vec<Pass> = PassKind::all()
        .into_iter()
        .map(|kind| (kind, dir.join(format!("{}.glsl", kind.stem()))))
        .filter(|(_, path)| path.is_file())
        .map(|(kind, path)| Pass {
            kind,
            name: path.display().to_string(),
            code: Code::File(path),
            channels: Default::default(),
        })
        .collect();
    let common = dir.join(COMMON_FILE);
    let common = common
        .is_file()
        .then(|| (common.display().to_string(), Code::File(common)));
    let bindings = dir.join(CHANNELS_FILE);
    if bindings.exists() {
        let text = std::fs::read_to_string(&bindings)
            .map_err(|e| format!("{}: cannot read: {e}", bindings.display()))?;
        bind(dir, &bindings.display().to_string(), &text, &mut passes)?;
    }
    let project = Project {
        origin: dir.to_path_buf(),
        common,
        passes,
        warnings: Vec::new(),
    };
    let file = bindings.display().to_string();
    project.check_buffers(|pass, k| format!("{file}: [{}] iChannel{k}", pass.kind.stem()))?;
    Ok(project)
}

/// Applies the tables of `channels.toml` (its text, named `file` in errors)
/// to the passes.
pub fn bind(dir: &Path, file: &str, text: &str, passes: &mut [Pass]) -> Result<(), String> {
    let table: toml::Table = text.parse().map_err(|e| format!("{file}: {e}"))?;
    for (section, value) in &table {
        let kind = PassKind::all()
            .into_iter()
            .find(|k| k.stem() == *section)
            .ok_or_else(|| {
                format!(
                    "{file}: [{section}]: not a pass (image, buffer_a, buffer_b, buffer_c, \
                     buffer_d)"
                )
            })?;
        let pass = passes.iter_mut().find(|p| p.kind == kind).ok_or_else(|| {
            format!(
                "{file}: [{section}]: there is no {section}.glsl in {}",
                dir.display()
            )
        })?;
        let toml::Value::Table(channels) = value else {
            return Err(format!(
                "{file}: `{section}` must be a table: [{section}] then iChannel0 = \"...\""
            ));
        };
        for (key, value) in channels {
            let at = format!("{file}: [{section}] {key}");
            let k = channel_index(key).ok_or_else(|| {
                format!("{at}: not a channel (iChannel0, iChannel1, iChannel2, iChannel3)")
            })?;
            let toml::Value::String(source) = value else {
                return Err(format!("{at}: expected a string: {EXPECTED}"));
            };
            pass.channels[k] = Some(input(dir, source).map_err(|e| format!("{at}: {e}"))?);
        }
    }
    Ok(())
}

/// `iChannel0` .. `iChannel3`.
fn channel_index(key: &str) -> Option<usize> {
    let k: usize = key.strip_prefix("iChannel")?.parse().ok()?;
    (k < 4 && key.len() == "iChannel0".len()).then_some(k)
}

/// What a channel's value may be, for errors.
const EXPECTED: &str = "\"buffer_a\" .. \"buffer_d\", \"keyboard\", \"noise\", \"cube\", \
                        \"volume\" or an image file";

/// A channel's value: a buffer, `keyboard`, `noise`, the built-in `cube`
/// map or noise `volume`, or an image file relative to the folder (which
/// must exist).
fn input(dir: &Path, source: &str) -> Result<Input, String> {
    if let Some(k) = (0..BUFFERS).find(|&k| PassKind::Buffer(k).stem() == source) {
        return Ok(Input::Buffer(k));
    }
    match source {
        "keyboard" => Ok(Input::Keyboard),
        "noise" => Ok(Input::Noise),
        "cube" => Ok(Input::Cube),
        "volume" => Ok(Input::Volume),
        "" => Err(format!("empty: expected {EXPECTED}")),
        _ => {
            let path = dir.join(source);
            if path.is_file() {
                Ok(Input::Texture(path))
            } else {
                Err(format!(
                    "\"{source}\" is neither buffer_a .. buffer_d, keyboard, noise, cube, \
                     volume nor an image file ({} not found)",
                    path.display()
                ))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn channel_keys_are_the_four_channels() {
        assert_eq!(channel_index("iChannel0"), Some(0));
        assert_eq!(channel_index("iChannel3"), Some(3));
        assert_eq!(channel_index("iChannel4"), None);
        assert_eq!(channel_index("iChannel00"), None);
        assert_eq!(channel_index("channel0"), None);
    }
}
