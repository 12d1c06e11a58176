//! The example scenes of `assets/scenes/`, embedded in the binary so the
//! viewer runs from any directory.

/// (name, TOML text) of each bundled scene; the first is the default.
const SCENES: [(&str, &str); 10] = [
    ("whitted", include_str!("../../assets/scenes/whitted.toml")),
    ("cornell", include_str!("../../assets/scenes/cornell.toml")),
    (
        "mirror_cube",
        include_str!("../../assets/scenes/mirror_cube.toml"),
    ),
    (
        "refraction",
        include_str!("../../assets/scenes/refraction.toml"),
    ),
    (
        "rotated_cubes",
        include_str!("../../assets/scenes/rotated_cubes.toml"),
    ),
    (
        "many_spheres",
        include_str!("../../assets/scenes/many_spheres.toml"),
    ),
    (
        "thin_lens",
        include_str!("../../assets/scenes/thin_lens.toml"),
    ),
    ("torus", include_str!("../../assets/scenes/torus.toml")),
    ("julia", include_str!("../../assets/scenes/julia.toml")),
    (
        "implicits",
        include_str!("../../assets/scenes/implicits.toml"),
    ),
];

/// Names of the bundled scenes, the default first.
pub fn names() -> Vec<&'static str> {
    SCENES.iter().map(|(name, _)| *name).collect()
}

/// The TOML text of a bundled scene.
pub fn text(name: &str) -> Option<&'static str> {
    SCENES
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(_, text)| *text)
}

/// The sorted names (without `.toml`) of the scene files in a folder of the
/// project: tests check that every file there is embedded.
#[cfg(test)]
pub(crate) fn toml_stems(folder: &str) -> Vec<String> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(folder);
    let mut stems: Vec<String> = std::fs::read_dir(dir)
        .expect("the folder exists")
        .filter_map(|e| {
            let path = e.expect("a directory entry").path();
            (path.extension()? == "toml").then(|| {
                path.file_stem()
                    .unwrap_or_default()
                    .to_string_lossy()
                    .into_owned()
            })
        })
        .collect();
    stems.sort();
    stems
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_scene_file_is_bundled_and_valid() {
        let on_disk = toml_stems("assets/scenes");
        let mut bundled: Vec<String> = names().iter().map(|s| s.to_string()).collect();
        bundled.sort();
        assert_eq!(bundled, on_disk, "bundle every scene of assets/scenes");
        for name in names() {
            crate::scene::Scene::from_toml_str(text(name).unwrap(), None)
                .unwrap_or_else(|e| panic!("{name}: {e}"));
        }
    }
}
