//! A scene or a sandbox shader carried in a link: its text, deflated and
//! written in URL-safe base64 after `#scene=` or `#shader=` in the page's
//! address (docs/web.md, "Sharing a scene or a shader"). The fragment never
//! reaches the server, so any static host serves shared work.

use base64::Engine;
use base64::engine::general_purpose::URL_SAFE_NO_PAD;
use miniz_oxide::inflate::TINFLStatus;

/// What precedes the encoded scene in the address's fragment.
const SCENE_KEY: &str = "scene=";

/// What precedes the encoded sandbox shader in the address's fragment.
const SHADER_KEY: &str = "shader=";

/// The most text a link may carry once inflated: far more than any scene
/// or shader (the bundled ones are a few kilobytes), far less than a
/// deflate bomb, whose few kilobytes of link inflate 1000-fold
/// (docs/reliability.md, "Fuzzing").
pub const MAX_TEXT: usize = 4 << 20;

/// What a damaged link is, in words for its reader (who did not damage it
/// on purpose); what the decoder found follows in brackets.
pub const DAMAGED: &str = "this link is damaged: it was cut short or changed";

/// Deflate level: the best compression; scenes and shaders are a few kilobytes.
const LEVEL: u8 = 10;

/// The fragment (without `#`) that carries the scene `toml`.
pub fn scene_hash(toml: &str) -> String {
    encode(SCENE_KEY, toml)
}

/// The scene text in a fragment: `None` when it carries no scene, an error
/// saying what is wrong with a damaged one (cut short when copied, edited).
pub fn scene_in_hash(hash: &str) -> Option<Result<String, String>> {
    decode_after(SCENE_KEY, hash)
}

/// The fragment (without `#`) that carries a sandbox shader's text. The
/// text alone tells its language and style (docs/sandbox.md, "Which kind
/// of file"), so no file name travels with it.
pub fn shader_hash(text: &str) -> String {
    encode(SHADER_KEY, text)
}

/// The shader text in a fragment, as [`scene_in_hash`] for scenes.
pub fn shader_in_hash(hash: &str) -> Option<Result<String, String>> {
    decode_after(SHADER_KEY, hash)
}

fn encode(key: &str, text: &str) -> String {
    let deflated = miniz_oxide::deflate::compress_to_vec(text.as_bytes(), LEVEL);
    format!("{key}{}", URL_SAFE_NO_PAD.encode(deflated))
}

fn decode_after(key: &str, hash: &str) -> Option<Result<String, String>> {
    let encoded = hash.trim_start_matches('#').strip_prefix(key)?;
    Some(decode(encoded))
}

fn decode(encoded: &str) -> Result<String, String> {
    let deflated = URL_SAFE_NO_PAD
        .decode(encoded.trim())
        .map_err(|e| format!("{DAMAGED} (not base64: {e})"))?;
    let bytes = miniz_oxide::inflate::decompress_to_vec_with_limit(&deflated, MAX_TEXT).map_err(
        |e| match e.status {
            TINFLStatus::HasMoreOutput => {
                format!("the link's text is longer than {} MiB", MAX_TEXT >> 20)
            }
            status => format!("{DAMAGED} (deflate: {status:?})"),
        },
    )?;
    String::from_utf8(bytes).map_err(|_| format!("{DAMAGED} (not UTF-8 text)"))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sandbox::bundled as shaders;
    use crate::scene::bundled;

    #[test]
    fn every_bundled_scene_survives_a_link() {
        for name in bundled::names() {
            let text = bundled::text(name).unwrap();
            let hash = scene_hash(text);
            assert!(hash.len() < text.len(), "{name}: the link is not shorter");
            assert_eq!(scene_in_hash(&hash), Some(Ok(text.to_string())), "{name}");
            assert_eq!(
                scene_in_hash(&format!("#{hash}")),
                Some(Ok(text.to_string()))
            );
            assert_eq!(shader_in_hash(&hash), None, "a scene is not a shader");
        }
    }

    #[test]
    fn every_bundled_shader_survives_a_link() {
        for (name, text) in shaders::SHADERS {
            let hash = shader_hash(text);
            assert!(hash.starts_with("shader="), "{name}");
            assert!(hash.len() < text.len(), "{name}: the link is not shorter");
            assert_eq!(shader_in_hash(&hash), Some(Ok(text.to_string())), "{name}");
            assert_eq!(
                shader_in_hash(&format!("#{hash}")),
                Some(Ok(text.to_string()))
            );
            assert_eq!(scene_in_hash(&hash), None, "a shader is not a scene");
        }
    }

    #[test]
    fn a_damaged_link_is_an_error_and_no_link_is_none() {
        let hash = scene_hash(bundled::text("whitted").unwrap());
        let cut = &hash[..hash.len() / 2];
        assert!(
            scene_in_hash(cut)
                .unwrap()
                .unwrap_err()
                .starts_with(DAMAGED)
        );
        assert!(scene_in_hash("scene=%%%").unwrap().is_err());
        assert_eq!(scene_in_hash(""), None);
        assert_eq!(scene_in_hash("other=1"), None);
        let shader = shader_hash(shaders::SHADERS[0].1);
        let cut = &shader[..shader.len() / 2];
        assert!(
            shader_in_hash(cut)
                .unwrap()
                .unwrap_err()
                .contains("damaged")
        );
        assert!(shader_in_hash("shader=").unwrap().is_err());
        assert_eq!(shader_in_hash(""), None);
    }

    #[test]
    fn a_link_that_inflates_past_the_limit_is_refused() {
        let bomb = scene_hash(&"a".repeat(MAX_TEXT + 1));
        assert!(bomb.len() < 10_000, "{} bytes", bomb.len());
        let error = scene_in_hash(&bomb).unwrap().unwrap_err();
        assert!(error.contains("longer than 4 MiB"), "{error}");
        let largest = "a".repeat(MAX_TEXT);
        assert_eq!(scene_in_hash(&scene_hash(&largest)), Some(Ok(largest)));
    }
}
