//! A scene carried in a link: its TOML text, deflated and written in
//! URL-safe base64 after `#scene=` in the page's address (docs/web.md,
//! "Sharing a scene"). The fragment never reaches the server, so any static
//! host serves shared scenes.

use base64::Engine;
use base64::engine::general_purpose::URL_SAFE_NO_PAD;

/// What precedes the encoded scene in the address's fragment.
const SCENE_KEY: &str = "scene=";

/// Deflate level: the best compression; scenes are a few kilobytes.
const LEVEL: u8 = 10;

/// The fragment (without `#`) that carries `toml`.
pub fn scene_hash(toml: &str) -> String {
    let deflated = miniz_oxide::deflate::compress_to_vec(toml.as_bytes(), LEVEL);
    format!("{SCENE_KEY}{}", URL_SAFE_NO_PAD.encode(deflated))
}

/// The scene text in a fragment: `None` when it carries no scene, an error
/// saying what is wrong with a damaged one (cut short when copied, edited).
pub fn scene_in_hash(hash: &str) -> Option<Result<String, String>> {
    let encoded = hash.trim_start_matches('#').strip_prefix(SCENE_KEY)?;
    Some(decode(encoded))
}

fn decode(encoded: &str) -> Result<String, String> {
    let deflated = URL_SAFE_NO_PAD
        .decode(encoded.trim())
        .map_err(|e| format!("the link is damaged (not base64: {e})"))?;
    let bytes = miniz_oxide::inflate::decompress_to_vec(&deflated)
        .map_err(|e| format!("the link is damaged or cut short ({e:?})"))?;
    String::from_utf8(bytes).map_err(|_| "the link's scene is not UTF-8 text".to_string())
}

#[cfg(test)]
mod tests {
    use super::*;
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
        }
    }

    #[test]
    fn a_damaged_link_is_an_error_and_no_link_is_none() {
        let hash = scene_hash(bundled::text("whitted").unwrap());
        let cut = &hash[..hash.len() / 2];
        assert!(scene_in_hash(cut).unwrap().unwrap_err().contains("damaged"));
        assert!(scene_in_hash("scene=%%%").unwrap().is_err());
        assert_eq!(scene_in_hash(""), None);
        assert_eq!(scene_in_hash("other=1"), None);
    }
}
