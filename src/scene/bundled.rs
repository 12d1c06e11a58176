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

/// (name, TOML text) of each bundled scene whose shapes read files, from
/// `assets/scenes/meshes/` ([`SCENES_WITH_FILES_FOLDER`]). Only their text is
/// embedded: the models stay files (`file = "../../meshes/bunny.obj"`,
/// relative to that folder), which the web page fetches (docs/web.md,
/// "Scenes with mesh files").
const SCENES_WITH_FILES: [(&str, &str); 3] = [
    (
        "glass_bunny",
        include_str!("../../assets/scenes/meshes/glass_bunny.toml"),
    ),
    (
        "mirror_teapot",
        include_str!("../../assets/scenes/meshes/mirror_teapot.toml"),
    ),
    (
        "cornell_dragon",
        include_str!("../../assets/scenes/meshes/cornell_dragon.toml"),
    ),
];

/// The project's folder of the scenes whose shapes read files: their `file`s are
/// relative to it.
pub const SCENES_WITH_FILES_FOLDER: &str = "assets/scenes/meshes";

/// Names of the bundled scenes that need no file, the default first.
pub fn names() -> Vec<&'static str> {
    SCENES.iter().map(|(name, _)| *name).collect()
}

/// Names of the bundled scenes whose shapes read files.
pub fn names_with_files() -> Vec<&'static str> {
    SCENES_WITH_FILES.iter().map(|(name, _)| *name).collect()
}

/// The TOML text of a bundled scene (with or without files).
pub fn text(name: &str) -> Option<&'static str> {
    SCENES
        .iter()
        .chain(&SCENES_WITH_FILES)
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

    #[test]
    fn every_scene_with_files_is_bundled_and_valid_beside_its_models() {
        let mut bundled: Vec<String> = names_with_files().iter().map(|s| s.to_string()).collect();
        bundled.sort();
        assert_eq!(bundled, toml_stems(SCENES_WITH_FILES_FOLDER));
        let folder =
            std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(SCENES_WITH_FILES_FOLDER);
        for name in names_with_files() {
            let origin = folder.join(format!("{name}.toml"));
            let scene = crate::scene::Scene::from_toml_str(text(name).unwrap(), Some(&origin))
                .unwrap_or_else(|e| panic!("{name}: {e}"));
            assert!(!scene.meshes.is_empty(), "{name} has meshes");
        }
    }
}
