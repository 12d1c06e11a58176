//! The shape kinds of a scene, one file each: the serde struct of a kind's
//! own keys (read into its TOML table beside the placement and material of
//! an [`Instance`], docs/scene-format.md), their validation and bounds.
//! A kind is registered by one line in [`for_each_shape_kind!`], which the
//! other layers (BVH, reference, GPU, panel) expand to visit every kind, so a
//! kind that one of them does not handle is a compile error there (see
//! docs/implementation.md, "Adding a shape kind").

mod choices;
mod cube;
pub mod implicit;
mod instance;
pub mod julia;
mod mesh;
mod placement;
mod plane;
mod sphere;
mod torus;

pub use choices::{Choices, NoChoices, NoSettings};
pub use cube::Cube;
pub use implicit::Implicit;
pub use instance::Instance;
pub use julia::Julia;
pub use mesh::{Loaded, Mesh, MeshSettings, TriangleTest};
pub use placement::{AxisScale, Centered, Place, Placement, Scale, Unplaced};
pub use plane::Plane;
pub use sphere::Sphere;
pub use torus::{Torus, TorusMethod};

use std::path::{Path, PathBuf};

use glam::{DMat3, DVec3};
use indexmap::IndexMap;
use serde::Serialize;
use serde::de::DeserializeOwned;

use super::Material;
use super::files::{Folder, SceneFiles};
use super::key_path::KeyPath;
use super::validate::Check;

/// The registry of shape kinds: calls `$m!` once with the whole list, as
/// `Kind: field` pairs (the Rust type and the scene's array of tables, in
/// the order of the scene file). The order also fixes the kind numbers the
/// GPU reports (`ShapeKind::number`).
#[macro_export]
#[doc(hidden)]
macro_rules! for_each_shape_kind {
    ($m:ident) => {
        $m! {
            Sphere: spheres,
            Plane: planes,
            Cube: cubes,
            Torus: tori,
            Implicit: implicits,
            Julia: julias,
            Mesh: meshes,
        }
    };
}
pub use for_each_shape_kind;

/// What validation knows besides the shape: the materials defined, and
/// where the files shapes read come from (the scene file's folder,
/// natively).
pub struct Context<'a> {
    pub materials: &'a IndexMap<String, Material>,
    pub files: &'a dyn SceneFiles,
}

/// `Rz(rz) Ry(ry) Rx(rx)` for angles in degrees (docs/rendering-model.md,
/// "Shapes"), in f64: the rotation of boxes and meshes.
pub fn rotation_degrees(degrees: DVec3) -> DMat3 {
    let r = degrees * (std::f64::consts::PI / 180.0);
    DMat3::from_rotation_z(r.z) * DMat3::from_rotation_y(r.y) * DMat3::from_rotation_x(r.x)
}

/// What every shape kind of the scene provides: its own keys, read
/// flattened into an [`Instance`] beside its placement and material (a
/// kind is not `deny_unknown_fields`: the instance is).
pub trait Shape:
    Choices + Clone + PartialEq + std::fmt::Debug + Serialize + DeserializeOwned
{
    /// How shapes of this kind are placed: a [`Placement`], a [`Centered`]
    /// one, or [`Unplaced`] for a kind placed by its own keys.
    type Placement: Place;

    /// Checks the rules of docs/rendering-model.md that serde cannot express
    /// (ranges, finiteness) for the kind's own keys; `path` names the shape
    /// in messages. May make values canonical (a plane's unit normal) or
    /// load what the keys name (a mesh's file).
    fn validate(&mut self, path: &KeyPath, context: &Context) -> Check;

    /// Moves the kind's own position keys by `offset`; the placement moves
    /// itself ([`Place::translate`]).
    fn translate(&mut self, _offset: DVec3) {}

    /// Whether shapes of this kind have bounds. An unbounded kind (planes)
    /// stays out of the BVH; renderers test its shapes in a loop.
    const BOUNDED: bool = true;

    /// The world-space bounding box `[min, max]` of a bounded shape placed
    /// by `placement`.
    fn bounds(&self, placement: &Self::Placement) -> [DVec3; 2];

    /// A thin shape (a plane) has no inside: a ray through it always
    /// enters, and refraction passes it on unbent (docs/rendering-model.md,
    /// "Materials").
    const THIN: bool = false;

    /// An opaque shape (a Julia set, whose inside has no distance estimate)
    /// lets no light through: its material's transparency counts as 0
    /// (docs/rendering-model.md, "Implicit surfaces").
    const OPAQUE: bool = false;

    /// The file the shape reads (a mesh's model) as the scene writes it:
    /// relative to the scene file's folder unless absolute.
    fn file(&self) -> Option<&Path> {
        None
    }

    /// The same file, to rename it (the scene saved in another folder,
    /// a shape read from a file named for the scene open now).
    fn file_mut(&mut self) -> Option<&mut PathBuf> {
        None
    }

    /// The shape's [`Shape::file`] relative to `base` (the scene file's
    /// folder) unless absolute: what the viewer watches.
    fn file_read(&self, base: Option<&Path>) -> Option<PathBuf> {
        self.file().map(|file| Folder(base).path(file))
    }

    /// The extensions (lower case) of the files a new shape of this kind
    /// is made from, when the user adds one from a file or drops one on the
    /// window or the page (a mesh's `obj` and `ply`); none for a kind that
    /// only the scene's text makes.
    const FILE_EXTENSIONS: &[&str] = &[];

    /// A new shape from `file` (one of [`Shape::FILE_EXTENSIONS`], named as
    /// the scene will write it, relative to `base`), unplaced; the error
    /// names the file and its line.
    fn from_file(file: PathBuf, _base: Option<&Path>) -> Result<Self, String> {
        Err(format!(
            "{}: no shape is made from this file",
            file.display()
        ))
    }

    /// A new shape from the `bytes` of a file named `name` that the scene
    /// cannot name by a path (a file dropped on the web page), so written
    /// into the scene itself; errors as [`Shape::from_file`]'s.
    fn from_bytes(name: &str, _bytes: &[u8]) -> Result<Self, String> {
        Err(format!("{name}: no shape is made from this file"))
    }

    /// How many parts make the shape and what they are called, for
    /// messages (a mesh's triangles: `(12, "triangles")`); `None` for a
    /// kind of one piece.
    fn parts(&self) -> Option<(usize, &'static str)> {
        None
    }

    /// Reads the file of `shapes` again (they all read one file, which
    /// changed on disk), sharing one read between shapes that read it
    /// alike. On an error nothing changes: the last good state stays.
    fn read_again(_shapes: &mut [&mut Self], _base: Option<&Path>) -> Result<(), String> {
        Ok(())
    }

    /// The kind's keys whose arrays of numbers are not vectors of 3 (a
    /// Julia set's quaternion `c`); serde checks their length, the parser
    /// every other array's (src/scene/parse.rs).
    const NOT_VECTORS: &[&str] = &[];
}
