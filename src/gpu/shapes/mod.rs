//! One file per shape kind: the `#[repr(C)]` twin of the kind's WGSL struct
//! (field for field, same names, written with [`packed_struct!`]), how one
//! scene shape is packed into it ([`PackShape`], implemented on the scene's
//! kind), and the kind's WGSL file (`shaders/shapes/<kind>.wgsl`). Adding a
//! kind here is one file (see docs/implementation.md, "Adding a shape
//! kind"); the buffers, bindings, counts, feature flags, WGSL loops and the
//! layout test follow from the registry `for_each_shape_kind!` through
//! [`kinds`].

use std::sync::Arc;

use bytemuck::{Pod, Zeroable};
use glam::DVec3;

use super::ShaderOptions;
use crate::scene::{
    Camera, Instance, KindOptions, Scene, ShapeKind, ShapeList, for_each_shape_kind,
};

mod cube;
pub mod glue;
pub mod implicit;
mod julia;
mod mesh;
mod placement;
mod plane;
mod sphere;
mod torus;

/// A `#[repr(C)]` struct that mirrors a WGSL struct, with the list of its
/// fields, their offsets and their Rust types ([`Layout`]): the layout test
/// compares the offsets with naga's view of the shader, and the generated
/// WGSL reads the struct from its data texture field by field
/// (`glue::struct_array`).
#[macro_export]
#[doc(hidden)]
macro_rules! packed_struct {
    ($(#[$meta:meta])* pub struct $name:ident {
        $($(#[$field_meta:meta])* pub $field:ident: $ty:ty,)*
    }) => {
        $crate::packed_struct!(@struct $(#[$meta])* $name { $($(#[$field_meta])* $field: $ty,)* } []);
    };
    // A shape kind's struct, named with the scene kind it packs and the
    // WGSL file that declares its twin. WGSL rounds a struct with a vector
    // up to a whole 16 bytes without naming the padding; `_tail`, not among
    // the listed fields, does the same here (set it with
    // `..Zeroable::zeroed()`).
    ($(#[$meta:meta])* pub struct $name:ident for $kind:ty, $wgsl:literal {
        $($(#[$field_meta:meta])* pub $field:ident: $ty:ty,)*
    }) => {
        $crate::packed_struct!(@struct $(#[$meta])* $name { $($(#[$field_meta])* $field: $ty,)* } [
            pub _tail: [u32; $crate::gpu::shapes::tail_words(&[$(size_of::<$ty>()),*])],
        ]);

        impl $crate::gpu::shapes::PackedKind for $kind {
            type Packed = $name;
            const WGSL: &'static str = include_str!($wgsl);
        }
    };
    // A placed kind's struct starts with the fields `center`, `scale` and
    // `rotation` that `placement::pack` fills, as its WGSL struct does.
    ($(#[$meta:meta])* pub struct $name:ident for $kind:ty, $wgsl:literal, placed {
        $($(#[$field_meta:meta])* pub $field:ident: $ty:ty,)*
    }) => {
        $crate::packed_struct! {
            $(#[$meta])* pub struct $name for $kind, $wgsl {
                pub center: [f32; 3],
                pub scale: f32,
                /// `mat3x3<f32>`: three columns, each padded to 16 bytes.
                pub rotation: [[f32; 4]; 3],
                $($(#[$field_meta])* pub $field: $ty,)*
            }
        }
    };
    (@struct $(#[$meta:meta])* $name:ident {
        $($(#[$field_meta:meta])* $field:ident: $ty:ty,)*
    } [$($tail:tt)*]) => {
        $(#[$meta])*
        #[repr(C)]
        #[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
        pub struct $name {
            $($(#[$field_meta])* pub $field: $ty,)*
            $($tail)*
        }

        impl $crate::gpu::shapes::Layout for $name {
            const FIELDS: &[(&str, usize)] = &[$((stringify!($field), std::mem::offset_of!($name, $field))),*];
            const TYPES: &[&str] = &[$(stringify!($ty)),*];
        }
    };
}
pub use packed_struct;

/// The `u32` words that pad fields of `field_bytes` (all of 4-byte
/// alignment, so none between them) to a multiple of 16 bytes.
pub const fn tail_words(field_bytes: &[usize]) -> usize {
    let mut bytes = 0;
    let mut i = 0;
    while i < field_bytes.len() {
        bytes += field_bytes[i];
        i += 1;
    }
    (16 - bytes % 16) % 16 / 4
}

/// The fields of a struct the shader reads, in declaration order, with
/// their byte offsets and their Rust types (`[f32; 3]`, `u32`, ...).
pub trait Layout: Pod {
    const FIELDS: &[(&str, usize)];
    const TYPES: &[&str];
}

/// A scene kind's packed struct and WGSL, declared together
/// (`packed_struct! { pub struct X for scene::X, "x.wgsl" { ... } }`).
pub trait PackedKind: ShapeList {
    /// The twin of the kind's WGSL struct, of the same name.
    type Packed: Layout;

    /// The kind's WGSL: its struct and `hit_<kind>` (embedded; hot reload
    /// reads `shapes/<kind>.wgsl` of the shader folder instead).
    const WGSL: &'static str;
}

/// The frame that packed positions are measured in. Positions are made
/// relative to `origin` in f64 *before* rounding to f32, so that a scene far
/// from the world origin keeps its f32 precision near the camera
/// (docs/implementation.md, "Camera-relative coordinates"). The renderer
/// packs around the camera target ([`Frame::around_target`]); the naive
/// variant keeps the world frame ([`Frame::WORLD`]) to show what that fixes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frame {
    pub origin: DVec3,
}

impl Frame {
    /// The world frame: positions packed as they are in the scene file.
    pub const WORLD: Frame = Frame {
        origin: DVec3::ZERO,
    };

    /// The frame centred on the camera's target (`Camera::frame_origin`).
    pub fn around_target(camera: &Camera) -> Frame {
        Frame {
            origin: camera.frame_origin(),
        }
    }

    /// A point, relative to the frame, rounded to the f32 triple the shader reads.
    pub fn point(&self, p: DVec3) -> [f32; 3] {
        f32x3(p - self.origin)
    }
}

/// How the shapes of one scene kind reach the GPU: implemented on the
/// scene's kind in the kind's file of this module.
pub trait PackShape: PackedKind {
    /// Packs `shape` with the slot of its material (looked up once for
    /// every kind); `scene` has what a kind's shapes share (an implicit's
    /// function list), `frame` says where positions are measured from.
    fn pack(scene: &Scene, frame: &Frame, shape: &Instance<Self>, material: u32) -> Self::Packed;

    /// The name of the kind's second buffer, an `array<vec4<u32>>` of data
    /// its shapes share (a mesh's triangles and BVH), if it has one.
    const DATA: Option<&'static str> = None;

    /// Whether the kind's WGSL also has `occludes_<kind>(ray, shape, t_max)
    /// -> bool`, which shadow rays call instead of `hit_<kind>`: they need
    /// only whether something blocks them, not the nearest hit, and a shape
    /// whose hit is costly to refine (the torus, an implicit surface)
    /// answers that for less (docs/implementation.md, "Torus").
    const OCCLUDES: bool = false;

    /// Whether the kind's WGSL has `view_coordinates_<kind>(hit) ->
    /// vec3<f32>`, what the barycentric view shows on it (docs/views.md: a
    /// mesh's triangle weights, a sphere's texture coordinates); zeros
    /// elsewhere. The twin of the reference's `Prepare::view_coordinates`.
    const VIEW_COORDINATES: bool = false;

    /// The kind's own pipeline constants (`override` in its WGSL) and their
    /// values for its options ([`crate::scene::Choices::Options`]): how it
    /// chooses between methods by name (a torus's `TORUS_METHOD`, a mesh's
    /// `TRIANGLE_TEST`).
    fn constants(_options: &Self::Options) -> Vec<(&'static str, u32)> {
        Vec::new()
    }

    /// WGSL the kind writes from its `options` (an implicit surface's
    /// functions), as a named part joined after the shader files
    /// (`src/gpu/shaders.rs`), if it writes any. Called with the default
    /// options, it gives the part's name and the WGSL that stands in until
    /// a scene brings its own.
    fn generated(_options: &Self::Options) -> Option<(String, String)> {
        None
    }

    /// Packs every shape of the kind and the second buffer's contents
    /// (empty without [`PackShape::DATA`]); by default each shape alone.
    fn pack_kind(scene: &Scene, frame: &Frame) -> (Vec<Self::Packed>, Words) {
        let shapes = Self::list(scene)
            .iter()
            .map(|s| Self::pack(scene, frame, s, material_slot(scene, s)))
            .collect();
        (shapes, Words::default())
    }
}

/// The slot of a shape's material in the material buffer.
pub fn material_slot<K: ShapeList>(scene: &Scene, shape: &Instance<K>) -> u32 {
    scene.material_slot(shape.material.as_deref())
}

/// A buffer's contents as `u32` words, shared: a kind's second buffer (a
/// mesh's triangles) stays the same when its shapes only move, and the
/// viewer then keeps the GPU buffer it made from it.
pub type Words = Arc<Vec<u32>>;

/// A box rounded outwards to f32, so that the box the shader tests always
/// holds what is inside it (rounding to nearest could cut a sliver off a
/// shape, and rays through that sliver would miss it).
pub fn round_out(min: DVec3, max: DVec3) -> ([f32; 3], [f32; 3]) {
    let down = |x: f64| {
        let f = x as f32;
        if f64::from(f) > x { f.next_down() } else { f }
    };
    let up = |x: f64| {
        let f = x as f32;
        if f64::from(f) < x { f.next_up() } else { f }
    };
    (min.to_array().map(down), max.to_array().map(up))
}

/// Rounds an f64 vector (a direction, a size, a colour) to the f32 triple the
/// shader reads. Positions go through [`Frame::point`] instead.
pub(crate) fn f32x3(v: DVec3) -> [f32; 3] {
    v.as_vec3().to_array()
}

/// A packed kind as the shader composer and the buffers see it.
#[derive(Debug, Clone, Copy)]
pub struct KindInfo {
    pub kind: ShapeKind,
    /// The WGSL struct name, e.g. `Sphere`.
    pub wgsl_struct: &'static str,
    /// The embedded `shaders/shapes/<kind>.wgsl`.
    pub wgsl: &'static str,
    /// The name of its second buffer ([`PackShape::DATA`]).
    pub data: Option<&'static str>,
    /// Whether shadow rays call its `occludes_<kind>` ([`PackShape::OCCLUDES`]).
    pub occludes: bool,
    /// Whether the barycentric view calls its `view_coordinates_<kind>`
    /// ([`PackShape::VIEW_COORDINATES`]).
    pub view_coordinates: bool,
    /// The packed struct's fields and offsets ([`Layout`]).
    pub fields: &'static [(&'static str, usize)],
    /// The packed struct's fields' Rust types ([`Layout`]).
    pub types: &'static [&'static str],
    /// The packed struct's size in bytes.
    pub size: usize,
}

impl KindInfo {
    /// `sphere`: the kind's WGSL file stem and the suffix of `hit_<name>`.
    pub fn name(&self) -> String {
        self.kind.name().to_lowercase()
    }

    /// The file of the shader folder that holds its WGSL.
    pub fn file(&self) -> String {
        format!("shapes/{}.wgsl", self.name())
    }
}

/// The name of a kind's pipeline flag (`override` in WGSL): `HAS_SPHERES`.
pub fn has_flag(kind: ShapeKind) -> String {
    format!("HAS_{}", kind.key().to_uppercase())
}

/// Every packed kind, in registry order (which is also the order of their
/// buffers' bindings, from `FIRST_SHAPE_BINDING`).
pub fn kinds() -> Vec<KindInfo> {
    macro_rules! info {
        ($($kind:ident: $field:ident),* $(,)?) => {
            vec![$(KindInfo {
                kind: ShapeKind::$kind,
                wgsl_struct: stringify!($kind),
                wgsl: <crate::scene::$kind as PackedKind>::WGSL,
                data: <crate::scene::$kind as PackShape>::DATA,
                occludes: <crate::scene::$kind as PackShape>::OCCLUDES,
                view_coordinates: <crate::scene::$kind as PackShape>::VIEW_COORDINATES,
                fields: <<crate::scene::$kind as PackedKind>::Packed as Layout>::FIELDS,
                types: <<crate::scene::$kind as PackedKind>::Packed as Layout>::TYPES,
                size: size_of::<<crate::scene::$kind as PackedKind>::Packed>(),
            }),*]
        };
    }
    for_each_shape_kind!(info)
}

/// The buffers of one kind as `u32` words (every packed struct is made of
/// 4-byte fields): its shapes, then its second buffer if it has one. Each
/// holds at least one zeroed element, since a storage buffer may not be
/// empty.
pub fn pack_kind<T: PackShape>(scene: &Scene, frame: &Frame) -> Vec<Words> {
    let (mut shapes, data) = T::pack_kind(scene, frame);
    if shapes.is_empty() {
        shapes.push(T::Packed::zeroed());
    }
    let mut buffers = vec![Arc::new(bytemuck::cast_slice(&shapes).to_vec())];
    if T::DATA.is_some() {
        buffers.push(if data.is_empty() {
            Arc::new(vec![0; 4])
        } else {
            data
        });
    }
    buffers
}

/// Every kind's buffers, in registry order: the order of their bindings.
pub fn pack_all(scene: &Scene, frame: &Frame) -> Vec<Words> {
    let mut buffers = Vec::new();
    macro_rules! pack {
        ($($kind:ident: $field:ident),* $(,)?) => {
            $(buffers.extend(pack_kind::<crate::scene::$kind>(scene, frame));)*
        };
    }
    for_each_shape_kind!(pack);
    buffers
}

/// The position of `kind`'s shape buffer among the buffers of [`pack_all`].
pub fn buffer_position(kind: ShapeKind) -> usize {
    let mut position = 0;
    for k in kinds() {
        if k.kind == kind {
            return position;
        }
        position += 1 + usize::from(k.data.is_some());
    }
    panic!("{} is not a packed kind", kind.name());
}

/// How many buffers the shape kinds bind.
pub fn buffer_count() -> usize {
    kinds()
        .iter()
        .map(|k| 1 + usize::from(k.data.is_some()))
        .sum()
}

/// Every kind's pipeline constants for `kinds` ([`PackShape::constants`]).
fn kind_constants(kinds: &KindOptions) -> Vec<(&'static str, u32)> {
    let mut constants = Vec::new();
    macro_rules! visit {
        ($($kind:ident: $field:ident),* $(,)?) => {
            $(constants.extend(<crate::scene::$kind as PackShape>::constants(&kinds.$field));)*
        };
    }
    for_each_shape_kind!(visit);
    constants
}

/// Every part of WGSL the kinds write for `kinds` ([`PackShape::generated`]).
pub fn generated_parts(kinds: &KindOptions) -> Vec<(String, String)> {
    let mut parts = Vec::new();
    macro_rules! visit {
        ($($kind:ident: $field:ident),* $(,)?) => {
            $(parts.extend(<crate::scene::$kind as PackShape>::generated(&kinds.$field));)*
        };
    }
    for_each_shape_kind!(visit);
    parts
}

/// The pipeline constants are the kinds' business as much as the
/// features': written here, beside the kinds they visit, so that the
/// features need not know the kinds' modules.
impl ShaderOptions {
    /// The `(name, value)` pairs for `PipelineCompilationOptions::constants`:
    /// the fixed flags, then `HAS_<KINDS>` for every shape kind, then each
    /// kind's own ([`PackShape::constants`]).
    pub(in crate::gpu) fn constants(&self) -> Vec<(String, f64)> {
        let f = &self.features;
        let fixed = [
            ("ROBUST", self.robust),
            ("HAS_LIGHTS", f.lights),
            ("HAS_MIRRORS", f.mirrors),
            ("HAS_TRANSPARENCY", f.transparency),
            ("HAS_CHECKER", f.checker),
            ("HAS_LENS", f.lens),
            ("USE_BVH", f.bvh),
            ("COUNT_RAYS", self.count_rays),
            ("RAY_TREE", self.ray_tree),
            ("SHADOWS", self.rays.shadows),
            ("REFLECTION", self.rays.reflection),
            ("REFRACTION", self.rays.refraction),
        ]
        .map(|(name, on)| (name.to_string(), on));
        let present = ShapeKind::ALL.iter().map(|&k| (has_flag(k), f.has(k)));
        let methods = kind_constants(&self.kinds)
            .into_iter()
            .map(|(name, value)| (name.to_string(), f64::from(value)));
        fixed
            .into_iter()
            .chain(present)
            .map(|(name, on)| (name, f64::from(u8::from(on))))
            .chain(methods)
            .chain([("VIEW".to_string(), f64::from(self.view.number()))])
            .collect()
    }
}
