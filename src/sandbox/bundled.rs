//! The example shaders of `assets/shaders/`, embedded so the page can offer
//! them in its menu (docs/web.md) without files.

/// (file name, text) of each example shader; the file's extension tells
/// its language (docs/sandbox.md, "Which kind of file").
pub const SHADERS: [(&str, &str); 4] = [
    (
        "whitted.frag",
        include_str!("../../assets/shaders/whitted.frag"),
    ),
    (
        "whitted.wgsl",
        include_str!("../../assets/shaders/whitted.wgsl"),
    ),
    (
        "mirror_cube.frag",
        include_str!("../../assets/shaders/mirror_cube.frag"),
    ),
    (
        "blobs.glsl",
        include_str!("../../assets/shaders/blobs.glsl"),
    ),
];

/// The text of an example shader, by file name.
pub fn text(name: &str) -> Option<&'static str> {
    SHADERS.iter().find(|(n, _)| *n == name).map(|(_, t)| *t)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sandbox::compile;

    /// Every file of the folder is embedded, and compiles under its name
    /// and also without it (as from a link, where only the text travels).
    /// Its subfolders are multipass shaders, which the menu does not offer.
    #[test]
    fn every_example_shader_is_embedded_and_compiles_from_its_text_alone() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/shaders");
        let mut files: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap())
            .filter(|e| e.file_type().unwrap().is_file())
            .map(|e| e.file_name().to_string_lossy().into_owned())
            .collect();
        files.sort();
        let mut embedded: Vec<String> = SHADERS.iter().map(|(n, _)| n.to_string()).collect();
        embedded.sort();
        assert_eq!(embedded, files);
        for (name, text) in SHADERS {
            let named = compile(name, text).unwrap_or_else(|e| panic!("{e}"));
            let unnamed = compile("shader", text).unwrap_or_else(|e| panic!("{e}"));
            assert_eq!(named.style, unnamed.style, "{name}");
        }
    }
}
