//! The JSON of Shadertoy's API (`{"Shader": {"info": ..., "renderpass":
//! [...]}}`) and of the tools that export shaders from shadertoy.com (the
//! same object, or a list of them, or the shader object alone). Each
//! `renderpass` has `type` (`image`, `buffer`, `common`, ...), `name`,
//! `code`, `inputs` (`channel`, `ctype` or, in older exports, `type`, `id`,
//! `src` or `filepath`, `sampler`) and `outputs` (`id`); a buffer input names
//! the `id` of the pass that draws it. Errors name the file and the key
//! (`renderpass[2].inputs[0].channel`).

use std::path::{Path, PathBuf};

use serde_json::Value;

use super::{BUFFERS, Code, Input, Pass, PassKind, Project};

/// The output ids Shadertoy gives buffers A to D: the numbers of its
/// current API and the strings of older exports.
const BUFFER_IDS: [[&str; 2]; BUFFERS] = [
    ["257", "4dXGR8"],
    ["258", "XsXGR8"],
    ["259", "4sXGR8"],
    ["260", "XdfGR8"],
];

/// Whether `text` is JSON rather than a shader (the page's shader document
/// holds either): no GLSL or WGSL file starts with `{` or `[`.
pub fn is_json(text: &str) -> bool {
    text.trim_start().starts_with(['{', '['])
}

/// The line a [`parse`] error names, when the JSON is malformed
/// (serde_json's `... at line 3 column 7`).
pub fn error_line(message: &str) -> Option<usize> {
    let (_, rest) = message.rsplit_once(" at line ")?;
    rest.split_whitespace().next()?.parse().ok()
}

/// What a JSON file holds, read from `text` (the content of `path`); a
/// texture input reads the image found next to the file.
pub fn parse(path: &Path, text: &str) -> Result<Project, String> {
    let dir = path.parent().unwrap_or(Path::new(""));
    parse_finding(path, text, &|src| next_to(dir, src))
}

/// As [`parse`], each texture input's `src` found by `find`: the image's
/// path, or `None` for the built-in noise with a warning. The page, which
/// has no files, keeps every `src` and binds the images dropped on it
/// (docs/web.md, "Multipass shaders").
pub fn parse_finding(
    path: &Path,
    text: &str,
    find: &dyn Fn(&str) -> Option<PathBuf>,
) -> Result<Project, String> {
    let file = path.display().to_string();
    let value: Value = serde_json::from_str(text).map_err(|e| format!("{file}: {e}"))?;
    let shader = shader_object(&value).ok_or_else(|| {
        format!(
            "{file}: no \"renderpass\" list: not a Shadertoy shader (expected \
             {{\"Shader\": {{\"renderpass\": [...]}}}} as Shadertoy's API gives it)"
        )
    })?;
    let Some(Value::Array(list)) = shader.get("renderpass") else {
        return Err(format!("{file}: renderpass: expected a list of passes"));
    };
    let mut project = Project {
        origin: path.to_path_buf(),
        common: None,
        passes: Vec::new(),
        warnings: Vec::new(),
    };
    // (pass index in `project.passes`, its JSON) to bind the inputs after
    // every pass's outputs are known.
    let mut outputs: Vec<(String, PassKind)> = Vec::new();
    let mut read: Vec<(usize, usize)> = Vec::new();
    let mut buffers_seen = 0;
    for (i, pass) in list.iter().enumerate() {
        let at = format!("{file}: renderpass[{i}]");
        let kind_text = string(pass, "type").unwrap_or_default();
        let name = string(pass, "name").unwrap_or_default();
        let code = match pass.get("code") {
            Some(Value::String(code)) => code.clone(),
            _ => return Err(format!("{at}.code: missing (the pass's GLSL as a string)")),
        };
        let kind = match kind_text.as_str() {
            "common" => {
                if project.common.is_some() {
                    return Err(format!("{at}: a second common pass"));
                }
                project.common = Some((format!("{file} [Common]"), Code::Text(code)));
                continue;
            }
            "image" => PassKind::Image,
            "buffer" => {
                let k = buffer_of(&name, pass).unwrap_or(buffers_seen);
                buffers_seen += 1;
                if k >= BUFFERS {
                    return Err(format!(
                        "{at}: more than {BUFFERS} buffers (Shadertoy has A to D)"
                    ));
                }
                PassKind::Buffer(k)
            }
            "sound" => {
                project.warnings.push(format!(
                    "{at} ({name}): a sound pass, left out (raysandbox plays no sound)"
                ));
                continue;
            }
            other => {
                return Err(format!(
                    "{at}.type: `{other}` ({name}) is not supported: only image, buffer, \
                     common (and sound, left out)"
                ));
            }
        };
        if project.pass(kind).is_some() {
            return Err(format!("{at}: a second {} pass", kind.title()));
        }
        for id in ids(pass.get("outputs")) {
            outputs.push((id, kind));
        }
        read.push((i, project.passes.len()));
        project.passes.push(Pass {
            kind,
            name: format!("{file} [{}]", kind.title()),
            code: Code::Text(code),
            channels: Default::default(),
        });
    }
    if project.pass(PassKind::Image).is_none() {
        return Err(format!(
            "{file}: renderpass: no pass of type \"image\" (the one shown)"
        ));
    }
    let kinds: Vec<PassKind> = project.passes.iter().map(|p| p.kind).collect();
    for (i, p) in read {
        let mut channels: [Option<Input>; 4] = Default::default();
        let inputs = match list[i].get("inputs") {
            None | Some(Value::Null) => &Vec::new(),
            Some(Value::Array(inputs)) => inputs,
            Some(_) => return Err(format!("{file}: renderpass[{i}].inputs: expected a list")),
        };
        for (j, input) in inputs.iter().enumerate() {
            let at = format!("{file}: renderpass[{i}].inputs[{j}]");
            let channel = match input.get("channel").and_then(Value::as_u64) {
                Some(k) if k < 4 => k as usize,
                _ => return Err(format!("{at}.channel: expected a number 0 to 3")),
            };
            let reader = format!("{} iChannel{channel}", project.passes[p].kind.title());
            let bound = bind(find, (&at, &reader), input, &outputs, &mut project.warnings)?;
            if let Some(Input::Buffer(k)) = bound
                && !kinds.contains(&PassKind::Buffer(k))
            {
                return Err(format!(
                    "{at}: reads {}, which this shader does not have",
                    PassKind::Buffer(k).title()
                ));
            }
            channels[channel] = bound;
        }
        project.passes[p].channels = channels;
    }
    project.passes.sort_by_key(|p| p.kind);
    Ok(project)
}

/// The object with the `renderpass` list: the API's `{"Shader": ...}`, a
/// list of shaders (its first), or the shader itself.
fn shader_object(value: &Value) -> Option<&Value> {
    match value {
        Value::Array(list) => list.first().and_then(shader_object),
        Value::Object(map) if map.contains_key("renderpass") => Some(value),
        Value::Object(map) => map.get("Shader").and_then(shader_object),
        _ => None,
    }
}

fn string(value: &Value, key: &str) -> Option<String> {
    value.get(key).and_then(Value::as_str).map(str::to_string)
}

/// An id as text, whether the export wrote it as a number or a string.
fn id_text(value: &Value) -> Option<String> {
    match value {
        Value::Number(n) => Some(n.to_string()),
        Value::String(s) => Some(s.clone()),
        _ => None,
    }
}

/// The ids of a pass's `outputs`.
fn ids(outputs: Option<&Value>) -> Vec<String> {
    match outputs {
        Some(Value::Array(list)) => list
            .iter()
            .filter_map(|o| o.get("id").and_then(id_text))
            .collect(),
        _ => Vec::new(),
    }
}

/// Which buffer a buffer pass is: by its name ("Buffer A", "Buf A"), else
/// by Shadertoy's id of its output.
fn buffer_of(name: &str, pass: &Value) -> Option<usize> {
    let compact: String = name
        .chars()
        .filter(|c| !c.is_whitespace())
        .collect::<String>()
        .to_ascii_lowercase();
    let letter = compact
        .strip_prefix("buffer")
        .or_else(|| compact.strip_prefix("buf"));
    if let Some(k) = letter.and_then(|l| ["a", "b", "c", "d"].iter().position(|x| *x == l)) {
        return Some(k);
    }
    ids(pass.get("outputs"))
        .iter()
        .find_map(|id| BUFFER_IDS.iter().position(|ids| ids.contains(&id.as_str())))
}

/// What one input binds: a buffer (by the id of the pass drawing it), the
/// keyboard, or an image found next to the JSON file. What cannot be shown
/// (a texture not found, a video, sound) reads noise or black, with a
/// warning naming the key and the pass's channel (`reader`, `Image
/// iChannel0`).
fn bind(
    find: &dyn Fn(&str) -> Option<PathBuf>,
    (at, reader): (&str, &str),
    input: &Value,
    outputs: &[(String, PassKind)],
    warnings: &mut Vec<String>,
) -> Result<Option<Input>, String> {
    let ctype = string(input, "ctype")
        .or_else(|| string(input, "type"))
        .ok_or_else(|| format!("{at}.ctype: missing (buffer, texture, keyboard, ...)"))?;
    let src = string(input, "src")
        .or_else(|| string(input, "filepath"))
        .unwrap_or_default();
    match ctype.as_str() {
        "buffer" => {
            let id = input.get("id").and_then(id_text).unwrap_or_default();
            let by_output = outputs
                .iter()
                .find(|(out, _)| *out == id)
                .and_then(|(_, kind)| match kind {
                    PassKind::Buffer(k) => Some(*k),
                    PassKind::Image => None,
                });
            let by_id = || BUFFER_IDS.iter().position(|ids| ids.contains(&id.as_str()));
            // "/media/previz/buffer00.png" is Buffer A's picture on the site.
            let by_src = || {
                let stem = Path::new(&src).file_stem()?.to_str()?.to_string();
                let k: usize = stem.strip_prefix("buffer")?.parse().ok()?;
                (k < BUFFERS).then_some(k)
            };
            let k = by_output.or_else(by_id).or_else(by_src).ok_or_else(|| {
                format!("{at}.id: `{id}` is the output of no buffer pass of this file")
            })?;
            Ok(Some(Input::Buffer(k)))
        }
        "keyboard" => Ok(Some(Input::Keyboard)),
        "texture" => match find(&src) {
            Some(path) => Ok(Some(Input::Texture(path))),
            None => {
                warnings.push(format!(
                    "{at}.src ({reader}): the texture `{src}` is not next to the file: the \
                     built-in noise instead (put the image there to use it)"
                ));
                Ok(Some(Input::Noise))
            }
        },
        // Shadertoy's own cube maps and volumes are not part of an export:
        // the built-in ones stand in (docs/sandbox.md, "Cube maps and volumes").
        "cubemap" => {
            warnings.push(format!(
                "{at}.src ({reader}): the cube map `{src}` is Shadertoy's own: the built-in \
                 cube map instead"
            ));
            Ok(Some(Input::Cube))
        }
        "volume" => Ok(Some(Input::Volume)),
        other => {
            warnings.push(format!(
                "{at}.ctype ({reader}): `{other}` inputs are not supported: the channel reads \
                 black"
            ));
            Ok(None)
        }
    }
}

/// The image a texture's `src` names next to the JSON file in `dir`: at
/// `src` relative to it, or by its file name.
fn next_to(dir: &Path, src: &str) -> Option<PathBuf> {
    let name = Path::new(src).file_name().map(Path::new);
    let candidates = [
        Some(dir.join(src.trim_start_matches('/'))),
        name.map(|n| dir.join(n)),
    ];
    candidates.into_iter().flatten().find(|p| p.is_file())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn json_texts_are_told_from_shaders_and_their_errors_have_a_line() {
        assert!(is_json("  \n{\"Shader\": {}}"));
        assert!(is_json("[{}]"));
        assert!(!is_json(
            "void mainImage(out vec4 c, in vec2 p) { c = vec4(1.0); }"
        ));
        assert!(!is_json("// {\nfn main() {}"));
        let text = "{\n  \"Shader\": {\n    \"renderpass\": [,]\n  }\n}";
        let message = parse(Path::new("shader.json"), text).expect_err("malformed");
        assert!(message.starts_with("shader.json: "), "{message}");
        assert_eq!(error_line(&message), Some(3), "{message}");
        let missing = parse(Path::new("shader.json"), "{}").expect_err("no passes");
        assert_eq!(error_line(&missing), None, "{missing}");
    }

    #[test]
    fn buffers_are_known_by_name_or_output_id() {
        let none = Value::Null;
        assert_eq!(buffer_of("Buffer A", &none), Some(0));
        assert_eq!(buffer_of("Buf C", &none), Some(2));
        assert_eq!(buffer_of("bufferD", &none), Some(3));
        let pass: Value = serde_json::from_str(r#"{"outputs": [{"id": "XsXGR8"}]}"#).unwrap();
        assert_eq!(buffer_of("", &pass), Some(1));
        let pass: Value = serde_json::from_str(r#"{"outputs": [{"id": 260}]}"#).unwrap();
        assert_eq!(buffer_of("x", &pass), Some(3));
    }
}
