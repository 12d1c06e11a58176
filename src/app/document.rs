//! The open scene and its file: what is unsaved, saving without ever leaving
//! a broken file behind, and telling our own writes from external edits.

use std::path::{Path, PathBuf};

use super::shape_files;
use crate::files::write_atomically;
use crate::scene::{Camera, Folder, NewShape, Scene, SceneError, SceneFiles, ShapeKind, bundled};

/// A scene being edited, and where it came from.
pub struct Document {
    pub scene: Scene,
    /// The file it is saved to; `None` for a built-in scene not saved yet.
    path: Option<PathBuf>,
    /// What the scene was when last loaded or saved: unsaved = differs.
    saved: Scene,
    /// The file's text as last read or written, so that a change event for
    /// our own save is not mistaken for an external edit.
    disk_text: Option<String>,
    /// Name of the built-in scene, for the title when there is no file.
    builtin_name: Option<&'static str>,
}

impl Document {
    /// A bundled example scene, embedded in the binary, that names no
    /// file (`bundled::names`); a mesh scene's files are not beside the
    /// binary: see [`Document::bundled_with_files`].
    pub fn bundled(name: &'static str) -> Result<Self, SceneError> {
        Document::bundled_with_files(name, &Folder(None))
    }

    /// A bundled example scene whose shapes' files (a mesh's model, if it
    /// names any) are read from `files` (the web page gives the files it
    /// fetched).
    pub fn bundled_with_files(
        name: &'static str,
        files: &dyn SceneFiles,
    ) -> Result<Self, SceneError> {
        let text = bundled::text(name).unwrap_or_default();
        let origin = format!("(built-in) {name}.toml");
        let scene = Scene::from_toml_with_files(text, Some(Path::new(&origin)), files)?;
        Ok(Document {
            saved: scene.clone(),
            scene,
            path: None,
            disk_text: None,
            builtin_name: Some(name),
        })
    }

    /// A scene that has no file (one carried in a link, in the web page).
    pub fn untitled(scene: Scene) -> Self {
        Document {
            saved: scene.clone(),
            scene,
            path: None,
            disk_text: None,
            builtin_name: None,
        }
    }

    /// Reads a scene file.
    pub fn open(path: &Path) -> Result<Self, SceneError> {
        let text = std::fs::read_to_string(path).map_err(|e| SceneError::io(path, &e))?;
        let scene = Scene::from_toml_str(&text, Some(path))?;
        Ok(Document {
            saved: scene.clone(),
            scene,
            path: Some(path.to_path_buf()),
            disk_text: Some(text),
            builtin_name: None,
        })
    }

    pub fn path(&self) -> Option<&Path> {
        self.path.as_deref()
    }

    /// The folder that shapes' `file`s are relative to: the scene file's.
    fn base(&self) -> Option<&Path> {
        self.path.as_deref().and_then(Path::parent)
    }

    /// Reads a new shape of `kind` from `file` (as picked or dropped:
    /// absolute, or relative to the working folder) when called, on any
    /// thread (a large model takes seconds), naming it relative to the
    /// scene file. The error names the file and its line or element.
    pub fn shape_reader(
        &self,
        kind: ShapeKind,
        file: &Path,
    ) -> impl FnOnce() -> Result<NewShape, String> + Send + 'static {
        let named = shape_files::scene_relative(file, self.path());
        let base = self.base().map(Path::to_path_buf);
        move || NewShape::from_file(kind, named, base.as_deref())
    }

    /// Every file the scene's shapes read (a mesh's model), as
    /// [`Document::reload_file`] expects it, each once.
    pub fn files_read(&self) -> Vec<PathBuf> {
        self.scene.files_read(self.base())
    }

    /// Reads `file` (one of [`Document::files_read`]) again after it
    /// changed on disk, for every shape that reads it, in the scene and in
    /// its saved state (a reload is not an edit). Returns how many shapes
    /// of the scene read it. On an error (file and line) nothing changes:
    /// the last good geometry stays.
    pub fn reload_file(&mut self, file: &Path) -> Result<usize, String> {
        let base = self.base().map(Path::to_path_buf);
        Scene::read_again(
            &mut [&mut self.scene, &mut self.saved],
            file,
            base.as_deref(),
        )
    }

    pub fn is_dirty(&self) -> bool {
        self.scene != self.saved
    }

    /// The camera as last loaded or saved (what "reset camera" returns to).
    pub fn saved_camera(&self) -> &Camera {
        &self.saved.camera
    }

    /// The scene's file as given (a path), or "(built-in whitted scene)",
    /// with " *" when unsaved: the window's title and the panel title's
    /// hover text.
    pub fn label(&self) -> String {
        self.marked(self.path.as_ref().map(|p| p.display().to_string()))
    }

    /// As [`Document::label`], with the file's name alone: the panel's
    /// title, which a deep folder's path would otherwise wrap onto several
    /// lines, pushing the whole panel down.
    pub fn short_label(&self) -> String {
        self.marked(self.path.as_ref().map(|p| {
            p.file_name().map_or_else(
                || p.display().to_string(),
                |n| n.to_string_lossy().into_owned(),
            )
        }))
    }

    /// `file`, or the built-in scene's name, with " *" when unsaved.
    fn marked(&self, file: Option<String>) -> String {
        let name = match (file, self.builtin_name) {
            (Some(file), _) => file,
            (None, Some(n)) => format!("(built-in {n} scene)"),
            (None, None) => "(untitled)".to_string(),
        };
        if self.is_dirty() {
            format!("{name} *")
        } else {
            name
        }
    }

    /// Writes the scene to its file. A built-in scene has none yet: the
    /// caller must ask for a path (`save_as`).
    pub fn save(&mut self) -> Result<PathBuf, String> {
        let path = self
            .path
            .clone()
            .ok_or("this scene has no file yet: use \"Save as\" to choose one")?;
        self.save_as(&path)
    }

    /// Writes the scene to `path` and makes it the document's file. The
    /// files shapes read stay where they are: in another folder the scene
    /// names them by new relative paths.
    pub fn save_as(&mut self, path: &Path) -> Result<PathBuf, String> {
        let mut scene = self.scene.clone();
        if self.base() != path.parent() {
            scene.rename_files(|file| shape_files::rebased(file, self.path(), path));
        }
        let text = scene.to_toml_string();
        write_atomically(path, &text).map_err(|e| format!("{}: {e}", path.display()))?;
        self.scene = scene;
        self.path = Some(path.to_path_buf());
        self.saved = self.scene.clone();
        self.disk_text = Some(text);
        Ok(path.to_path_buf())
    }

    /// Reads the file again after a change event. `Ok(None)`: the content is
    /// what we last read or wrote (e.g. our own save), nothing to do.
    pub fn read_external_change(&self) -> Result<Option<(Scene, String)>, SceneError> {
        let Some(path) = &self.path else {
            return Ok(None);
        };
        let text = std::fs::read_to_string(path).map_err(|e| SceneError::io(path, &e))?;
        if self.disk_text.as_deref() == Some(text.as_str()) {
            return Ok(None);
        }
        let scene = Scene::from_toml_str(&text, Some(path))?;
        Ok(Some((scene, text)))
    }

    /// Takes an externally edited version of the file as the new saved state.
    pub fn accept_external(&mut self, scene: Scene, text: String) {
        self.saved = scene.clone();
        self.scene = scene;
        self.disk_text = Some(text);
    }

    /// Remembers the disk text without taking the scene (the user kept their
    /// edits): the same external version is not offered again.
    pub fn ignore_external(&mut self, text: String) {
        self.disk_text = Some(text);
    }

    /// A screenshot path next to the scene file (or in the working folder
    /// for a built-in scene) that does not overwrite an earlier one.
    pub fn screenshot_path(&self) -> PathBuf {
        let (dir, stem) = match (&self.path, self.builtin_name) {
            (Some(p), _) => (
                p.parent().map(Path::to_path_buf).unwrap_or_default(),
                p.file_stem()
                    .map_or("scene".into(), |s| s.to_string_lossy().into_owned()),
            ),
            (None, name) => (PathBuf::new(), name.unwrap_or("scene").to_string()),
        };
        (1..)
            .map(|n| dir.join(format!("{stem}-screenshot-{n}.png")))
            .find(|p| !p.exists())
            .expect("some screenshot number is free")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Instance, Placement};

    fn temp_dir(name: &str) -> PathBuf {
        let dir =
            std::env::temp_dir().join(format!("raysandbox-doc-{name}-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn save_writes_a_file_that_loads_back_equal_and_clears_dirty() {
        let dir = temp_dir("save");
        let mut doc = Document::bundled("whitted").unwrap();
        assert!(!doc.is_dirty());
        doc.scene.spheres[0].radius = 0.123;
        assert!(doc.is_dirty());
        assert!(doc.label().ends_with(" *"));
        assert!(doc.save().is_err(), "a built-in scene needs save as");
        let path = dir.join("mine.toml");
        doc.save_as(&path).unwrap();
        assert!(!doc.is_dirty());
        let loaded = Scene::load(&path).unwrap();
        assert_eq!(loaded, doc.scene);
        // No temporary file is left behind.
        let leftovers: Vec<_> = std::fs::read_dir(&dir).unwrap().collect();
        assert_eq!(leftovers.len(), 1);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn the_short_label_is_the_file_name_however_deep_the_folder() {
        let deep = temp_dir("label").join("a-folder-with-a-long-name/and-another-one-below-it");
        std::fs::create_dir_all(&deep).unwrap();
        let path = deep.join("mine.toml");
        let mut doc = Document::bundled("whitted").unwrap();
        assert_eq!(doc.short_label(), "(built-in whitted scene)");
        doc.save_as(&path).unwrap();
        assert_eq!(doc.short_label(), "mine.toml");
        assert_eq!(doc.label(), path.display().to_string());
        doc.scene.camera.fov += 1.0;
        assert_eq!(doc.short_label(), "mine.toml *");
        assert_eq!(doc.label(), format!("{} *", path.display()));
        std::fs::remove_dir_all(temp_dir("label")).unwrap();
    }

    #[test]
    fn own_save_is_not_an_external_change_but_an_edit_is() {
        let dir = temp_dir("external");
        let path = dir.join("s.toml");
        let mut doc = Document::bundled("whitted").unwrap();
        doc.save_as(&path).unwrap();
        assert!(doc.read_external_change().unwrap().is_none());
        let text = std::fs::read_to_string(&path)
            .unwrap()
            .replace("exposure = 1.0", "exposure = 2.0");
        std::fs::write(&path, &text).unwrap();
        let (scene, new_text) = doc.read_external_change().unwrap().expect("a change");
        assert_eq!(scene.render.exposure, 2.0);
        doc.accept_external(scene, new_text);
        assert!(!doc.is_dirty());
        std::fs::write(&path, "[camera]\nfrom = [0, 0, 0]\nto = [0, 0, 0]\n").unwrap();
        assert!(
            doc.read_external_change().is_err(),
            "an invalid edit is an error"
        );
        assert_eq!(doc.scene.render.exposure, 2.0, "the current scene is kept");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn mesh_files_reload_keep_the_last_good_geometry_and_follow_save_as() {
        let dir = temp_dir("mesh");
        std::fs::create_dir_all(dir.join("models")).unwrap();
        std::fs::create_dir_all(dir.join("scenes")).unwrap();
        let obj = dir.join("models/tri.obj");
        std::fs::write(&obj, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
        let path = dir.join("scenes/s.toml");
        let mut doc = Document::bundled("whitted").unwrap();
        doc.save_as(&path).unwrap();
        let NewShape::Mesh(mesh) = doc.shape_reader(ShapeKind::Mesh, &obj)().unwrap() else {
            panic!("an OBJ file makes a mesh");
        };
        assert_eq!(mesh.file.as_deref(), Some(Path::new("../models/tri.obj")));
        let mesh = *mesh;
        // Two meshes show the same file.
        let mesh = Instance::new(mesh, Placement::default());
        doc.scene.meshes.extend([mesh.clone(), mesh]);
        doc.save().unwrap();
        let loaded = Scene::load(&path).unwrap();
        assert_eq!(loaded.meshes[1].geometry.0.triangles.len(), 1);
        let files = doc.files_read();
        assert_eq!(files, [dir.join("scenes").join("../models/tri.obj")]);

        // A different good file: both meshes take it, and it is no edit.
        let quad = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";
        std::fs::write(&obj, quad).unwrap();
        assert_eq!(doc.reload_file(&files[0]), Ok(2));
        let [a, b] = [0, 1].map(|i| doc.scene.meshes[i].geometry.0.clone());
        assert_eq!(a.triangles.len(), 2);
        assert!(std::sync::Arc::ptr_eq(&a, &b), "one load for both");
        assert!(!doc.is_dirty());

        // A bad file: the error names file and line, the geometry stays.
        std::fs::write(&obj, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n").unwrap();
        let error = doc.reload_file(&files[0]).unwrap_err();
        assert!(error.contains("tri.obj:4: face vertex index 9"), "{error}");
        assert!(std::sync::Arc::ptr_eq(&doc.scene.meshes[0].geometry.0, &a));
        assert_eq!(doc.reload_file(&dir.join("models/other.obj")), Ok(0));

        // Saved in another folder, the scene still finds the model.
        std::fs::write(&obj, quad).unwrap();
        let other = dir.join("copies/deeper/s.toml");
        std::fs::create_dir_all(other.parent().unwrap()).unwrap();
        doc.save_as(&other).unwrap();
        let file = doc.scene.meshes[0].file.as_deref();
        assert_eq!(file, Some(Path::new("../../models/tri.obj")));
        assert_eq!(Scene::load(&other).unwrap().meshes.len(), 2);
        assert!(!doc.is_dirty());
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_bad_mesh_file_is_an_error_naming_its_line() {
        let dir = temp_dir("bad-mesh");
        let obj = dir.join("bad.obj");
        std::fs::write(&obj, "v 0 0 0\nv 1 nan 0\n").unwrap();
        let doc = Document::bundled("whitted").unwrap();
        let error = doc.shape_reader(ShapeKind::Mesh, &obj)().unwrap_err();
        assert!(error.contains("bad.obj:2:"), "{error}");
        let error = doc.shape_reader(ShapeKind::Mesh, &dir.join("missing.ply"))().unwrap_err();
        assert!(error.contains("missing.ply"), "{error}");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn screenshot_paths_do_not_overwrite() {
        let dir = temp_dir("shot");
        let path = dir.join("a.toml");
        let mut doc = Document::bundled("whitted").unwrap();
        doc.save_as(&path).unwrap();
        let first = doc.screenshot_path();
        assert_eq!(first, dir.join("a-screenshot-1.png"));
        std::fs::write(&first, "x").unwrap();
        assert_eq!(doc.screenshot_path(), dir.join("a-screenshot-2.png"));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
