//! Files that shapes are made from in the viewer (a mesh's model): the file
//! dialog of "Add ... from file", and the `file` a scene stores for them:
//! relative to the scene file, as docs/scene-format.md (`[[meshes]]`) asks,
//! so that the scene and its files can move together. Which kinds are made
//! from which files the kinds say ([`ShapeKind::for_file`]).

use std::path::{Component, Path, PathBuf};

use crate::scene::ShapeKind;

/// `path` as an absolute path (against the working folder) with `..`
/// steps folded, without resolving links: what the user picked is what the
/// scene names.
fn absolute(path: &Path) -> PathBuf {
    let full = std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf());
    let mut folded = PathBuf::new();
    for part in full.components() {
        match part {
            Component::ParentDir if folded.file_name().is_some() => {
                folded.pop();
            }
            Component::CurDir => {}
            other => folded.push(other),
        }
    }
    folded
}

/// What a scene at `scene_file` writes as a shape's `file` key for the file at `file`:
/// the path from the scene's folder, or the absolute path while the scene
/// has no file yet (a built-in scene; saving it rewrites the path, see
/// [`rebased`]).
pub fn scene_relative(file: &Path, scene_file: Option<&Path>) -> PathBuf {
    let file = absolute(file);
    let Some(dir) = scene_file.map(absolute) else {
        return file;
    };
    let dir = dir.parent().map(Path::to_path_buf).unwrap_or_default();
    pathdiff::diff_paths(&file, &dir).unwrap_or(file)
}

/// A shape's `file` as written by a scene at `from`, rewritten for the
/// same scene saved at `to` (the file stays where it is). An absolute
/// `file` in a scene file is kept as written; in a scene without a file it
/// is the viewer's own (see [`scene_relative`]) and becomes relative.
pub fn rebased(file: &Path, from: Option<&Path>, to: &Path) -> PathBuf {
    match from.and_then(Path::parent) {
        Some(dir) if file.is_relative() => scene_relative(&dir.join(file), Some(to)),
        Some(_) => file.to_path_buf(),
        None => scene_relative(file, Some(to)),
    }
}

/// The kinds made from files ([`ShapeKind::file_extensions`]), by name in
/// lower case: "mesh", for the panel's button and the file dialog.
pub fn kinds_from_files() -> String {
    let names: Vec<String> = ShapeKind::ALL
        .iter()
        .filter(|kind| !kind.file_extensions().is_empty())
        .map(|kind| kind.name().to_ascii_lowercase())
        .collect();
    names.join(" or ")
}

/// Why no shape is made from the file at `path`: which files are.
pub fn not_a_shape_file(path: &Path) -> String {
    let known: Vec<String> = ShapeKind::ALL
        .iter()
        .flat_map(|kind| kind.file_extensions())
        .map(|e| format!(".{e}"))
        .collect();
    format!(
        "{}: no shape is made from this file (the file name must end in {})",
        path.display(),
        known.join(" or ")
    )
}

/// Opens the system's file dialog for a file that a shape is made from, on
/// a thread of its own, so that the window keeps drawing while it is open;
/// `picked` gets the chosen path (nothing if the dialog is cancelled or
/// there is no dialog service).
#[cfg(not(target_arch = "wasm32"))]
pub fn pick_shape_file(start: Option<PathBuf>, picked: impl FnOnce(PathBuf) + Send + 'static) {
    std::thread::spawn(move || {
        let mut dialog =
            rfd::AsyncFileDialog::new().set_title(format!("Add a {}", kinds_from_files()));
        for kind in ShapeKind::ALL {
            let extensions = kind.file_extensions();
            if !extensions.is_empty() {
                let upper: Vec<String> =
                    extensions.iter().map(|e| e.to_ascii_uppercase()).collect();
                dialog = dialog.add_filter(
                    format!("{} ({})", kind.name(), upper.join(", ")),
                    extensions,
                );
            }
        }
        if let Some(dir) = start {
            dialog = dialog.set_directory(dir);
        }
        if let Some(file) = pollster::block_on(dialog.pick_file()) {
            picked(file.path().to_path_buf());
        }
    });
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mesh_files_are_told_by_their_extension() {
        for name in ["bunny.obj", "dragon.PLY", "a/b/teapot.Obj"] {
            assert_eq!(
                ShapeKind::for_file(Path::new(name)),
                Some(ShapeKind::Mesh),
                "{name}"
            );
        }
        for name in ["scene.toml", "obj", "mesh.stl", "noext"] {
            assert_eq!(ShapeKind::for_file(Path::new(name)), None, "{name}");
        }
        assert_eq!(kinds_from_files(), "mesh");
        assert_eq!(
            not_a_shape_file(Path::new("a.stl")),
            "a.stl: no shape is made from this file (the file name must end in .obj or .ply)"
        );
    }

    #[test]
    fn a_mesh_is_named_relative_to_the_scene_file() {
        let scene = Path::new("/class/scenes/demo.toml");
        assert_eq!(
            scene_relative(Path::new("/class/models/bunny.obj"), Some(scene)),
            PathBuf::from("../models/bunny.obj")
        );
        assert_eq!(
            scene_relative(Path::new("/class/scenes/cube.ply"), Some(scene)),
            PathBuf::from("cube.ply")
        );
        assert_eq!(
            scene_relative(Path::new("/class/models/bunny.obj"), None),
            PathBuf::from("/class/models/bunny.obj"),
            "without a scene file the path stays absolute"
        );
        let relative = scene_relative(Path::new("models/bunny.obj"), None);
        assert!(relative.is_absolute(), "{relative:?}");
    }

    #[test]
    fn saving_elsewhere_rewrites_the_path_to_the_same_model() {
        let from = Path::new("/class/scenes/demo.toml");
        let to = Path::new("/home/me/copy/demo.toml");
        assert_eq!(
            rebased(Path::new("../models/bunny.obj"), Some(from), to),
            PathBuf::from("../../../class/models/bunny.obj")
        );
        assert_eq!(
            rebased(
                Path::new("/class/models/bunny.obj"),
                None,
                Path::new("/class/a.toml")
            ),
            PathBuf::from("models/bunny.obj")
        );
        assert_eq!(
            rebased(
                Path::new("bunny.obj"),
                Some(from),
                Path::new("/class/scenes/b.toml")
            ),
            PathBuf::from("bunny.obj"),
            "same folder, same path"
        );
        assert_eq!(
            rebased(Path::new("/models/bunny.obj"), Some(from), to),
            PathBuf::from("/models/bunny.obj"),
            "an absolute path written in a scene file stays"
        );
    }
}
