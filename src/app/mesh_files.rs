//! Mesh files in the viewer: which dropped files are meshes, the file
//! dialog of "Add mesh from file", and the `file` a scene stores for them:
//! relative to the scene file, as docs/scene-format.md (`[[meshes]]`) asks,
//! so that the scene and its models can move together.

use std::path::{Component, Path, PathBuf};

/// The extensions the mesh loader reads (docs/scene-format.md, `[[meshes]]`).
const MESH_EXTENSIONS: [&str; 2] = ["obj", "ply"];

/// Whether `path` names an OBJ or PLY file (by its extension, in any case).
pub fn is_mesh_file(path: &Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| MESH_EXTENSIONS.contains(&e.to_ascii_lowercase().as_str()))
}

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

/// What a scene at `scene_file` writes as `file` for the mesh at `mesh`:
/// the path from the scene's folder, or the absolute path while the scene
/// has no file yet (a built-in scene; saving it rewrites the path, see
/// [`rebased`]).
pub fn scene_relative(mesh: &Path, scene_file: Option<&Path>) -> PathBuf {
    let mesh = absolute(mesh);
    let Some(dir) = scene_file.map(absolute) else {
        return mesh;
    };
    let dir = dir.parent().map(Path::to_path_buf).unwrap_or_default();
    pathdiff::diff_paths(&mesh, &dir).unwrap_or(mesh)
}

/// A mesh's `file` as written by a scene at `from`, rewritten for the
/// same scene saved at `to` (the model stays where it is). An absolute
/// `file` in a scene file is kept as written; in a scene without a file it
/// is the viewer's own (see [`scene_relative`]) and becomes relative.
pub fn rebased(file: &Path, from: Option<&Path>, to: &Path) -> PathBuf {
    match from.and_then(Path::parent) {
        Some(dir) if file.is_relative() => scene_relative(&dir.join(file), Some(to)),
        Some(_) => file.to_path_buf(),
        None => scene_relative(file, Some(to)),
    }
}

/// Opens the system's file dialog for an OBJ or PLY file on a thread of its
/// own, so that the window keeps drawing while it is open; `picked` gets
/// the chosen path (nothing if the dialog is cancelled or there is no
/// dialog service).
#[cfg(not(target_arch = "wasm32"))]
pub fn pick_mesh_file(start: Option<PathBuf>, picked: impl FnOnce(PathBuf) + Send + 'static) {
    std::thread::spawn(move || {
        let mut dialog = rfd::AsyncFileDialog::new()
            .set_title("Add a mesh (OBJ or PLY)")
            .add_filter("Triangle meshes", &MESH_EXTENSIONS);
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
            assert!(is_mesh_file(Path::new(name)), "{name}");
        }
        for name in ["scene.toml", "obj", "mesh.stl", "noext"] {
            assert!(!is_mesh_file(Path::new(name)), "{name}");
        }
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
