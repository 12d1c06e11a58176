//! The scene: plain data loaded from TOML (docs/scene-format.md), plus validation.
//!
//! This module knows nothing of the GPU or the UI. A [`Scene`] that came out of
//! [`Scene::from_toml_str`] or [`Scene::load`] has passed every rule of the rendering model,
//! so renderers may rely on positive radii, known material names and so on.

pub mod bundled;
mod camera;
mod document;
mod error;
mod files;
mod flattened;
mod key_path;
mod mesh_file;
mod named;
mod parse;
mod render;
mod shapes;
#[cfg(test)]
pub mod test_scenes;
#[cfg(test)]
mod tests;
mod validate;
mod write;

use std::path::{Path, PathBuf};

use glam::DVec3;
use indexmap::IndexMap;
use serde::{Deserialize, Serialize};

pub use camera::{Film, camera_basis, normalize_or};
pub use error::SceneError;
pub use files::{Folder, GivenFiles, SceneFiles};
pub use key_path::KeyPath;
pub use mesh_file::{Derived, Geometry, load_bytes, load_file};
pub use named::{NamedOption, named_option};
use render::render_with_kinds;
pub use render::{Intersections, MAX_DEPTH, RenderSettings};
pub use shapes::Context;
pub use shapes::{
    AxisScale, Centered, Choices, Cube, Implicit, Instance, Julia, Loaded, Mesh, MeshSettings,
    NoChoices, Place, Placement, Plane, Scale, Shape, Sphere, Torus, TorusMethod, TriangleTest,
    Unplaced, for_each_shape_kind, implicit, julia, rotation_degrees,
};
pub use validate::{Check, Issue};

/// Writes the [`Scene`] struct, [`ShapeKind`], [`ShapeId`] and the methods
/// that visit every shape kind, from the registry [`for_each_shape_kind!`].
macro_rules! scene_with_shapes {
    ($($kind:ident: $field:ident),* $(,)?) => {
        /// A whole scene file. Every section but `camera` is optional; the
        /// shape arrays follow the registry of `scene::shapes`.
        #[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
        #[serde(deny_unknown_fields)]
        pub struct Scene {
            #[serde(default)]
            pub render: Render,
            pub camera: Camera,
            #[serde(default, skip_serializing_if = "Vec::is_empty")]
            pub lights: Vec<Light>,
            /// Named materials, in file order (the order also fixes GPU indices).
            #[serde(default, skip_serializing_if = "IndexMap::is_empty")]
            pub materials: IndexMap<String, Material>,
            $(
                #[serde(default, skip_serializing_if = "Vec::is_empty")]
                pub $field: Vec<Instance<$kind>>,
            )*
        }

        /// A shape kind, in registry order.
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
        pub enum ShapeKind {
            $($kind,)*
        }

        impl ShapeKind {
            /// Every kind, in registry order.
            pub const ALL: &[ShapeKind] = &[$(ShapeKind::$kind),*];

            /// The kind's name in lists: "Sphere".
            pub fn name(self) -> &'static str {
                match self {
                    $(ShapeKind::$kind => stringify!($kind),)*
                }
            }

            /// The scene file's array of tables: "spheres".
            pub fn key(self) -> &'static str {
                match self {
                    $(ShapeKind::$kind => stringify!($field),)*
                }
            }

            /// Whether shapes of this kind have bounds ([`Shape::BOUNDED`]).
            pub fn bounded(self) -> bool {
                match self {
                    $(ShapeKind::$kind => <$kind as Shape>::BOUNDED,)*
                }
            }

            /// Whether shapes of this kind are thin ([`Shape::THIN`]).
            pub fn thin(self) -> bool {
                match self {
                    $(ShapeKind::$kind => <$kind as Shape>::THIN,)*
                }
            }

            /// Whether shapes of this kind are opaque ([`Shape::OPAQUE`]).
            pub fn opaque(self) -> bool {
                match self {
                    $(ShapeKind::$kind => <$kind as Shape>::OPAQUE,)*
                }
            }

            /// The kind whose array of tables is `key` ("spheres").
            pub fn from_key(key: &str) -> Option<ShapeKind> {
                match key {
                    $(stringify!($field) => Some(ShapeKind::$kind),)*
                    _ => None,
                }
            }

            /// The kind a new shape is made from when the user adds the
            /// file at `path` or drops it, by the file's extension in any
            /// case ([`Shape::FILE_EXTENSIONS`]); `None` for a file no kind
            /// reads.
            pub fn for_file(path: &Path) -> Option<ShapeKind> {
                let extension = path.extension()?.to_str()?.to_ascii_lowercase();
                ShapeKind::ALL
                    .iter()
                    .copied()
                    .find(|kind| kind.file_extensions().contains(&extension.as_str()))
            }

            /// The extensions of the files it is made from ([`Shape::FILE_EXTENSIONS`]).
            pub fn file_extensions(self) -> &'static [&'static str] {
                match self {
                    $(ShapeKind::$kind => <$kind as Shape>::FILE_EXTENSIONS,)*
                }
            }

            /// Its keys whose arrays are not vectors of 3 ([`Shape::NOT_VECTORS`]).
            pub fn not_vectors(self) -> &'static [&'static str] {
                match self {
                    $(ShapeKind::$kind => <$kind as Shape>::NOT_VECTORS,)*
                }
            }

            /// The number the shader reports for this kind (`KIND_*`, 0 is
            /// "nothing"): the position in the registry, from 1.
            pub fn number(self) -> u32 {
                self as u32 + 1
            }
        }

        /// Which shape of the scene: its kind and its index in that kind's array.
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
        pub enum ShapeId {
            $($kind(usize),)*
        }

        impl ShapeId {
            pub fn kind(self) -> ShapeKind {
                match self {
                    $(ShapeId::$kind(_) => ShapeKind::$kind,)*
                }
            }

            /// The index in the kind's array.
            pub fn index(self) -> usize {
                match self {
                    $(ShapeId::$kind(i) => i,)*
                }
            }

            /// Whether the shape is thin ([`Shape::THIN`]).
            pub fn is_thin(self) -> bool {
                self.kind().thin()
            }

            /// Whether the shape is opaque ([`Shape::OPAQUE`]).
            pub fn is_opaque(self) -> bool {
                self.kind().opaque()
            }

            /// The shape of kind `kind` at `index`.
            pub fn new(kind: ShapeKind, index: usize) -> ShapeId {
                match kind {
                    $(ShapeKind::$kind => ShapeId::$kind(index),)*
                }
            }
        }

        /// A shape made from a file the user added or dropped, not yet in
        /// a scene ([`Shape::from_file`]): read on any thread, then added
        /// in front of the camera ([`Scene::add_in_view`]).
        #[derive(Debug, Clone, PartialEq)]
        pub enum NewShape {
            $($kind(Box<$kind>),)*
        }

        impl NewShape {
            /// The shape of kind `kind` read from `file`, named as the
            /// scene writes it (relative to `base`, the scene file's folder).
            pub fn from_file(kind: ShapeKind, file: PathBuf, base: Option<&Path>) -> Result<NewShape, String> {
                match kind {
                    $(ShapeKind::$kind => <$kind as Shape>::from_file(file, base).map(|s| NewShape::$kind(Box::new(s))),)*
                }
            }

            /// The shape of kind `kind` from the `bytes` of a file named
            /// `name` that has no path (a file dropped on the web page).
            pub fn from_bytes(kind: ShapeKind, name: &str, bytes: &[u8]) -> Result<NewShape, String> {
                match kind {
                    $(ShapeKind::$kind => <$kind as Shape>::from_bytes(name, bytes).map(|s| NewShape::$kind(Box::new(s))),)*
                }
            }

            /// The file it reads, to name it for the scene open now.
            pub fn file_mut(&mut self) -> Option<&mut PathBuf> {
                match self {
                    $(NewShape::$kind(s) => s.file_mut(),)*
                }
            }

            /// For a message: " (12 triangles)" ([`Shape::parts`]); empty
            /// for a shape of one piece.
            pub fn summary(&self) -> String {
                let parts = match self {
                    $(NewShape::$kind(s) => s.parts(),)*
                };
                parts_summary(parts.into_iter())
            }
        }

        $(
            impl ShapeList for $kind {
                const KIND: ShapeKind = ShapeKind::$kind;

                fn list(scene: &Scene) -> &[Instance<Self>] {
                    &scene.$field
                }

                fn list_mut(scene: &mut Scene) -> &mut Vec<Instance<Self>> {
                    &mut scene.$field
                }
            }
        )*

        /// Every kind's options ([`Choices::Options`]), one field per kind
        /// named after the scene's array of it (`tori`): both renderers'
        /// options carry them without naming a kind, and each kind's code
        /// in a renderer reads its own.
        #[derive(Debug, Clone, Default, PartialEq, Eq, Hash)]
        pub struct KindOptions {
            $(pub $field: <$kind as Choices>::Options,)*
        }

        impl KindOptions {
            /// What `scene` asks of every kind ([`Choices::options`]).
            pub fn of(scene: &Scene) -> Self {
                KindOptions {
                    $($field: <$kind as Choices>::options(scene),)*
                }
            }

            /// Every kind's flag ([`Choices::FLAG`]): its name and help.
            pub fn flags() -> Vec<(&'static str, &'static str)> {
                [$(<$kind as Choices>::FLAG),*].into_iter().flatten().collect()
            }

            /// The options of the kind whose flag is `flag` replaced by the
            /// ones its value `name` names ([`Choices::options_named`]).
            pub fn set_named(&mut self, flag: &str, name: &str) -> Result<(), String> {
                $(if <$kind as Choices>::FLAG.is_some_and(|(f, _)| f == flag) {
                    self.$field = <$kind as Choices>::options_named(name)?;
                    return Ok(());
                })*
                Err(format!("--{flag}: no shape kind has this flag"))
            }
        }

        impl Scene {
            /// Every shape, kind by kind in registry order.
            pub fn shape_ids(&self) -> Vec<ShapeId> {
                let mut ids = Vec::with_capacity(self.shape_count());
                $(ids.extend((0..self.$field.len()).map(ShapeId::$kind));)*
                ids
            }

            /// Number of shapes of every kind together.
            pub fn shape_count(&self) -> usize {
                0 $(+ self.$field.len())*
            }

            /// The material name of a shape, `None` if there is no such shape.
            pub fn shape_material(&self, id: ShapeId) -> Option<&Option<String>> {
                match id {
                    $(ShapeId::$kind(i) => self.$field.get(i).map(|s| &s.material),)*
                }
            }

            pub fn shape_material_mut(&mut self, id: ShapeId) -> Option<&mut Option<String>> {
                match id {
                    $(ShapeId::$kind(i) => self.$field.get_mut(i).map(|s| &mut s.material),)*
                }
            }

            /// The bounding box of every shape of a bounded kind (all but planes).
            pub fn shape_bounds(&self) -> Vec<(ShapeId, [DVec3; 2])> {
                let mut bounds = Vec::new();
                $(if <$kind as Shape>::BOUNDED {
                    bounds.extend(self.$field.iter().enumerate().map(|(i, s)| (ShapeId::$kind(i), s.bounds())));
                })*
                bounds
            }

            /// The shapes of unbounded kinds (planes), in registry order.
            pub fn unbounded_shapes(&self) -> Vec<ShapeId> {
                let mut ids = Vec::new();
                $(if !<$kind as Shape>::BOUNDED {
                    ids.extend((0..self.$field.len()).map(ShapeId::$kind));
                })*
                ids
            }

            /// Removes a shape; returns whether it existed.
            pub fn remove_shape(&mut self, id: ShapeId) -> bool {
                match id {
                    $(ShapeId::$kind(i) if i < self.$field.len() => {
                        self.$field.remove(i);
                        true
                    })*
                    _ => false,
                }
            }

            /// Whether the shapes of two scenes are equal, kind by kind.
            pub fn same_shapes(&self, other: &Scene) -> bool {
                true $(&& self.$field == other.$field)*
            }

            /// "2 spheres, 1 planes, 0 cubes, ..., 1 meshes (12 triangles)":
            /// the count of every kind, and of the parts of its shapes
            /// ([`Shape::parts`]) if it has any.
            fn shape_summary(&self) -> String {
                let counts = [$(format!(
                    "{} {}{}",
                    self.$field.len(),
                    stringify!($field),
                    parts_summary(self.$field.iter().filter_map(|s| s.parts())),
                )),*];
                counts.join(", ")
            }

            /// Every file the shapes read ([`Shape::file_read`]), each once,
            /// relative to `base` (the scene file's folder) unless absolute.
            pub fn files_read(&self, base: Option<&Path>) -> Vec<PathBuf> {
                let mut files: Vec<PathBuf> = Vec::new();
                $(for file in self.$field.iter().filter_map(|s| s.file_read(base)) {
                    if !files.contains(&file) {
                        files.push(file);
                    }
                })*
                files
            }

            /// Reads `file` (one of [`Scene::files_read`]) again for every
            /// shape of `scenes` that reads it ([`Shape::read_again`]): a
            /// scene and its saved state, which share the new contents.
            /// Returns how many shapes of the first scene read it. On an
            /// error those shapes keep their last good state.
            pub fn read_again(scenes: &mut [&mut Scene], file: &Path, base: Option<&Path>) -> Result<usize, String> {
                let mut count = 0;
                $({
                    let mut shapes: Vec<&mut $kind> = Vec::new();
                    for (i, scene) in scenes.iter_mut().enumerate() {
                        for s in scene.$field.iter_mut() {
                            if s.file_read(base).as_deref() == Some(file) {
                                count += usize::from(i == 0);
                                shapes.push(&mut s.shape);
                            }
                        }
                    }
                    if !shapes.is_empty() {
                        <$kind as Shape>::read_again(&mut shapes, base)?;
                    }
                })*
                Ok(count)
            }

            /// Renames every file the shapes read ([`Shape::file_mut`]) as
            /// `rename` says: the scene saved in another folder names the
            /// same files by new relative paths.
            pub fn rename_files(&mut self, mut rename: impl FnMut(&Path) -> PathBuf) {
                $(for file in self.$field.iter_mut().filter_map(|s| s.shape.file_mut()) {
                    *file = rename(file);
                })*
            }

            /// Adds `shape` (made from a file) in front of the camera
            /// ([`Scene::placed_in_view`]) and returns its id.
            pub fn add_in_view(&mut self, shape: NewShape) -> ShapeId {
                match shape {
                    $(NewShape::$kind(s) => {
                        let instance = self.placed_in_view(*s);
                        self.$field.push(instance);
                        ShapeId::$kind(self.$field.len() - 1)
                    })*
                }
            }

            /// Moves every shape by `offset`.
            fn translate_shapes(&mut self, offset: DVec3) {
                $(self.$field.iter_mut().for_each(|s| s.translate(offset));)*
            }

            /// Validates every shape, kind by kind in registry order.
            fn validate_shapes(&mut self, root: &key_path::KeyPath, files: &dyn SceneFiles) -> validate::Check {
                let context = shapes::Context { materials: &self.materials, files };
                $(for (i, shape) in self.$field.iter_mut().enumerate() {
                    shape.validate(&root.key(stringify!($field)).index(i), &context)?;
                })*
                Ok(())
            }
        }
    };
}
for_each_shape_kind!(scene_with_shapes);
for_each_shape_kind!(render_with_kinds);

/// " (12 triangles)": the sum of the `parts` of some shapes of a kind,
/// empty if none has parts.
fn parts_summary(parts: impl Iterator<Item = (usize, &'static str)>) -> String {
    let mut total = None;
    for (count, name) in parts {
        let (sum, _) = total.get_or_insert((0, name));
        *sum += count;
    }
    total
        .map(|(sum, name)| format!(" ({sum} {name})"))
        .unwrap_or_default()
}

/// The array of one shape kind in a scene.
pub trait ShapeList: Shape + Sized {
    const KIND: ShapeKind;
    fn list(scene: &Scene) -> &[Instance<Self>];
    fn list_mut(scene: &mut Scene) -> &mut Vec<Instance<Self>>;
}

/// `[camera]`: the lecture's pinhole camera with an optional thin lens.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Camera {
    pub from: DVec3,
    pub to: DVec3,
    #[serde(default = "default_up")]
    pub up: DVec3,
    /// Vertical field of view in degrees.
    #[serde(default = "default_fov")]
    pub fov: f64,
    /// Lens radius; 0 is a pinhole.
    #[serde(default)]
    pub aperture: f64,
    /// Distance to the plane in focus; `None` means `|from - to|`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub focus_distance: Option<f64>,
}

fn default_up() -> DVec3 {
    DVec3::Y
}

fn default_fov() -> f64 {
    45.0
}

impl Camera {
    /// The world point that both renderers take positions relative to
    /// before tracing: the target, where what the camera looks at is, so
    /// that the numbers stay at the size of the view wherever the scene
    /// lies (docs/implementation.md, "Camera-relative coordinates").
    pub fn frame_origin(&self) -> DVec3 {
        self.to
    }

    /// The focus distance in effect: the given one, else `|from - to|`.
    pub fn focus_distance(&self) -> f64 {
        self.focus_distance
            .unwrap_or_else(|| (self.from - self.to).length())
    }
}

/// `[[lights]]`: a point light. Lights do not fall off with distance.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Light {
    pub position: DVec3,
    #[serde(default = "default_light_color")]
    pub color: DVec3,
    #[serde(default = "default_intensity")]
    pub intensity: f64,
}

fn default_light_color() -> DVec3 {
    DVec3::ONE
}

fn default_intensity() -> f64 {
    1.0
}

/// `[materials.NAME]`: docs/rendering-model.md, "Materials". Missing fields take the defaults, and a
/// shape without a material uses `Material::default()`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Material {
    pub color: DVec3,
    pub diffuse: f64,
    pub specular: f64,
    pub shininess: f64,
    pub mirror: f64,
    pub transparency: f64,
    pub ior: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub checker: Option<Checker>,
}

impl Default for Material {
    fn default() -> Self {
        Self {
            color: DVec3::splat(0.8),
            diffuse: 1.0,
            specular: 0.0,
            shininess: 32.0,
            mirror: 0.0,
            transparency: 0.0,
            ior: 1.5,
            checker: None,
        }
    }
}

/// The checker texture: `color` on odd cells of edge `size`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Checker {
    pub color: DVec3,
    pub size: f64,
}

/// How large a shape from a file appears beside the target, as a fraction
/// of the scene's [`Scene::view_scale`]: seen whole.
pub const NEW_SHAPE_SIZE: f64 = 0.4;

impl Scene {
    /// Parses and validates a scene from TOML text. `origin` names the file in
    /// error messages (it is not read).
    pub fn from_toml_str(text: &str, origin: Option<&Path>) -> Result<Scene, SceneError> {
        let folder = Folder(origin.and_then(Path::parent));
        validate::parse_and_validate(text, origin, &folder)
    }

    /// As [`Scene::from_toml_str`], with the files its shapes read (a
    /// mesh's model) taken from `files` rather than from the scene file's
    /// folder (the web page gives the bytes it fetched).
    pub fn from_toml_with_files(
        text: &str,
        origin: Option<&Path>,
        files: &dyn SceneFiles,
    ) -> Result<Scene, SceneError> {
        validate::parse_and_validate(text, origin, files)
    }

    /// The file each shape of the scene's text reads ([`Shape::file`]),
    /// as written, each once, without reading them: what a caller with no
    /// file system must fetch before [`Scene::from_toml_with_files`].
    /// Empty for a text that does not parse (parsing it reports why).
    pub fn files_named(text: &str) -> Vec<PathBuf> {
        let scene = document::Document::parse(text).and_then(|doc| parse::deserialize(&doc));
        scene
            .map(|scene| scene.files_read(None))
            .unwrap_or_default()
    }

    /// Reads, parses and validates a scene file.
    pub fn load(path: &Path) -> Result<Scene, SceneError> {
        let text = std::fs::read_to_string(path).map_err(|e| SceneError::io(path, &e))?;
        Scene::from_toml_str(&text, Some(path))
    }

    /// The material a shape names, or the default material for `None`.
    /// Panics only on a name that validation would have rejected.
    pub fn material(&self, name: Option<&str>) -> &Material {
        static DEFAULT: std::sync::OnceLock<Material> = std::sync::OnceLock::new();
        match name {
            None => DEFAULT.get_or_init(Material::default),
            Some(n) => &self.materials[n],
        }
    }

    /// Index of a shape's material in the list `[default, materials in file
    /// order...]` that the GPU buffers use: 0 for `None`.
    pub fn material_slot(&self, name: Option<&str>) -> u32 {
        name.and_then(|n| self.materials.get_index_of(n))
            .map_or(0, |i| i as u32 + 1)
    }

    /// The size of the scene as the camera frames it: the distance from the
    /// eye to the target (clamped; 1 for a degenerate camera). New shapes
    /// are sized and placed in this unit, so that they appear at a useful
    /// size whatever units the scene uses.
    pub fn view_scale(&self) -> f64 {
        let distance = (self.camera.from - self.camera.to).length();
        if distance.is_finite() {
            distance.clamp(1e-3, 1e6)
        } else {
            1.0
        }
    }

    /// `shape` (just made from a file) in front of the camera: the centre
    /// of its box on the target, scaled uniformly so that its longest side
    /// is [`NEW_SHAPE_SIZE`] of the [`Scene::view_scale`] (files come in
    /// any unit: the bunny is 0.15 across, the teapot 6); a kind that
    /// cannot be so placed keeps the place it has ([`Place::fitted`]).
    pub fn placed_in_view<K: Shape>(&self, shape: K) -> Instance<K> {
        let local = shape.bounds(&K::Placement::default());
        let placement =
            K::Placement::fitted(local, self.camera.to, NEW_SHAPE_SIZE * self.view_scale());
        Instance::new(shape, placement)
    }

    /// The scene moved by `offset` (in f64): camera, lights and shapes. The
    /// checker grid stays where it is in the world.
    pub fn translated(&self, offset: DVec3) -> Scene {
        let mut s = self.clone();
        s.camera.from += offset;
        s.camera.to += offset;
        for light in &mut s.lights {
            light.position += offset;
        }
        s.translate_shapes(offset);
        s
    }

    /// The camera, settings, lights and materials, with no shapes: what a
    /// renderer starts from before it knows the shapes fit.
    pub fn without_shapes(&self) -> Scene {
        let mut empty = self.clone();
        for id in self.shape_ids().into_iter().rev() {
            empty.remove_shape(id);
        }
        empty
    }

    /// A one-line summary for `raysandbox check`.
    pub fn summary(&self) -> String {
        format!(
            "{}, {} materials, {} lights",
            self.shape_summary(),
            self.materials.len(),
            self.lights.len()
        )
    }
}
