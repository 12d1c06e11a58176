//! Saving a scene: the inverse of [`Scene::from_toml_str`].

use super::Scene;

impl Scene {
    /// The scene as TOML text, so that a scene changed in a UI can be saved.
    /// [`Scene::from_toml_str`] loads the text back equal to `self` whenever
    /// `self` is a scene it could have produced: every value in range and
    /// plane normals of unit length. Comments and the layout of the original
    /// file are not kept; defaults are written out.
    ///
    /// # Panics
    ///
    /// Never in practice: the `toml` serializer fails only on types a
    /// `Scene` does not contain (maps with non-string keys, bare `None`s).
    #[must_use]
    pub fn to_toml_string(&self) -> String {
        toml::to_string(self)
            .expect("a Scene is tables, arrays, strings and numbers, which TOML can all hold")
    }
}
