//! The example scenes of `assets/scenes/`, embedded in the binary so the
//! viewer runs from any directory.

/// (name, TOML text) of each bundled scene; the first is the default.
const SCENES: [(&str, &str); 6] = [
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_scene_file_is_bundled_and_valid() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/scenes");
        let mut on_disk: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .filter_map(|e| {
                let path = e.unwrap().path();
                (path.extension()? == "toml")
                    .then(|| path.file_stem().unwrap().to_string_lossy().into_owned())
            })
            .collect();
        on_disk.sort();
        let mut bundled: Vec<String> = names().iter().map(|s| s.to_string()).collect();
        bundled.sort();
        assert_eq!(bundled, on_disk, "bundle every scene of assets/scenes");
        for name in names() {
            crate::scene::Scene::from_toml_str(text(name).unwrap(), None)
                .unwrap_or_else(|e| panic!("{name}: {e}"));
        }
    }
}
