//! The shape kinds of a scene, one file each: the serde struct of one shape
//! (its TOML table, docs/scene-format.md), its validation and its moves.
//! A kind is registered by one line in [`for_each_shape_kind!`], which the
//! other layers (BVH, reference, GPU, panel) expand to visit every kind, so a
//! kind that one of them does not handle is a compile error there (see
//! docs/implementation.md, "Adding a shape kind").

/// The [`Shape`] methods every kind writes alike: `translate` moves the
/// point at `$point` (a sphere's `center`, a placed kind's
/// `placement.translate`); `material` and `material_mut` give the
/// `material` key.
macro_rules! shape_accessors {
    ($($point:ident).+) => {
        fn translate(&mut self, offset: glam::DVec3) {
            self.$($point).+ += offset;
        }

        fn material(&self) -> &Option<String> {
            &self.material
        }

        fn material_mut(&mut self) -> &mut Option<String> {
            &mut self.material
        }
    };
}

mod cube;
pub mod implicit;
pub mod julia;
mod mesh;
mod placement;
mod plane;
mod sphere;
mod torus;

pub use cube::Cube;
pub use implicit::Implicit;
pub use julia::Julia;
pub use mesh::{Loaded, Mesh, TriangleTest};
pub use placement::{CubeSize, Placement, Scale};
pub use plane::Plane;
pub use sphere::Sphere;
pub use torus::{Torus, TorusMethod};

use glam::{DMat3, DVec3};
use indexmap::IndexMap;

use super::Material;
use super::key_path::KeyPath;
use super::mesh_file::MeshFiles;
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
/// where mesh files are read from (the scene file's folder, natively).
pub struct Context<'a> {
    pub materials: &'a IndexMap<String, Material>,
    pub meshes: &'a dyn MeshFiles,
}

/// `Rz(rz) Ry(ry) Rx(rx)` for angles in degrees (docs/rendering-model.md,
/// "Shapes"), in f64: the rotation of boxes and meshes.
pub fn rotation_degrees(degrees: DVec3) -> DMat3 {
    let r = degrees * (std::f64::consts::PI / 180.0);
    DMat3::from_rotation_z(r.z) * DMat3::from_rotation_y(r.y) * DMat3::from_rotation_x(r.x)
}

/// What every shape kind of the scene provides.
pub trait Shape: Clone {
    /// Checks the rules of docs/rendering-model.md that serde cannot express
    /// (ranges, finiteness, known material names); `path` names the shape in
    /// messages. May make values canonical (a plane's unit normal).
    fn validate(&mut self, path: &KeyPath, context: &Context) -> Check;

    /// The keys serde reads flattened into the shape: a [`Placement`], or
    /// [`serde::de::IgnoredAny`] for a kind placed by its own keys. serde
    /// sees flattened keys without their place in the text and would blame
    /// an error in one on its table; the parser reads them alone to name
    /// the key (src/scene/parse.rs).
    type Flattened: serde::de::DeserializeOwned;

    /// Moves the shape by `offset` (`Scene::translated`).
    fn translate(&mut self, offset: DVec3);

    /// The name of its material; `None` is the default material.
    fn material(&self) -> &Option<String>;

    fn material_mut(&mut self) -> &mut Option<String>;

    /// Whether shapes of this kind have bounds. An unbounded kind (planes)
    /// stays out of the BVH; renderers test its shapes in a loop.
    const BOUNDED: bool = true;

    /// The world-space bounding box `[min, max]` of a bounded shape.
    fn bounds(&self) -> [DVec3; 2];

    /// A thin shape (a plane) has no inside: a ray through it always
    /// enters, and refraction passes it on unbent (docs/rendering-model.md,
    /// "Materials").
    const THIN: bool = false;

    /// An opaque shape (a Julia set, whose inside has no distance estimate)
    /// lets no light through: its material's transparency counts as 0
    /// (docs/rendering-model.md, "Implicit surfaces").
    const OPAQUE: bool = false;
}
