//! The open scene and its file: what is unsaved, saving without ever leaving
//! a broken file behind, and telling our own writes from external edits.

use std::path::{Path, PathBuf};

use crate::files::write_atomically;
use crate::scene::{Camera, Scene, SceneError, bundled};

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
    /// A bundled example scene, embedded in the binary.
    pub fn bundled(name: &'static str) -> Result<Self, SceneError> {
        let text = bundled::text(name).unwrap_or_default();
        let scene =
            Scene::from_toml_str(text, Some(Path::new(&format!("(built-in) {name}.toml"))))?;
        Ok(Document {
            saved: scene.clone(),
            scene,
            path: None,
            disk_text: None,
            builtin_name: Some(name),
        })
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

    pub fn is_dirty(&self) -> bool {
        self.scene != self.saved
    }

    /// The camera as last loaded or saved (what "reset camera" returns to).
    pub fn saved_camera(&self) -> &Camera {
        &self.saved.camera
    }

    /// "whitted.toml" or "built-in whitted", with " *" when unsaved.
    pub fn label(&self) -> String {
        let name = match (&self.path, self.builtin_name) {
            (Some(p), _) => p.display().to_string(),
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

    /// Writes the scene to `path` and makes it the document's file.
    pub fn save_as(&mut self, path: &Path) -> Result<PathBuf, String> {
        let text = self.scene.to_toml_string();
        write_atomically(path, &text).map_err(|e| format!("{}: {e}", path.display()))?;
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
