//! Buffer packing: `#[repr(C)]` twins of the structs in `shaders/scene.wgsl`,
//! field for field and with the same names, and the code that fills them from
//! a [`Scene`]. The test at the bottom asks naga for the WGSL layout and checks
//! every size and offset against these structs.

use bytemuck::{Pod, Zeroable};
use glam::DVec3;

use super::shapes::glue::{Element, struct_array, word_array};
use super::shapes::{Frame, PackShape, Words, buffer_position, f32x3, pack_all, round_out};
use crate::bvh::{Aabb, Bvh};
use crate::scene::{self, Scene, ShapeKind};

crate::packed_struct! {
    /// The camera, render settings and counts (`shaders/scene.wgsl`): a data
    /// texture of one row, read where used through `globals()` (shaders/scene.wgsl).
    pub struct Globals {
        /// The camera's `from` and `to` (`from` is a reserved word in WGSL).
        pub camera_from: [f32; 3],
        pub film_height: f32,
        pub camera_to: [f32; 3],
        pub aperture: f32,
        /// The camera's basis ([`scene::Film`]), computed in f64 on the CPU.
        pub u: [f32; 3],
        pub focus_distance: f32,
        pub v: [f32; 3],
        /// `|from - to|`, in f64 on the CPU.
        pub target_distance: f32,
        pub w: [f32; 3],
        pub min_weight: f32,
        pub background: [f32; 3],
        pub exposure: f32,
        pub ambient: [f32; 3],
        pub max_depth: u32,
        pub resolution: [u32; 2],
        pub sample_start: u32,
        pub sample_count: u32,
        pub light_count: u32,
        pub bvh_node_count: u32,
        pub output_size: [u32; 2],
        /// A scalar view's colour bar: the quantity shown blue, and red
        /// (`shaders/views.wgsl`; 0 for the shaded picture).
        pub view_range: [f32; 2],
        pub _view_pad: [u32; 2],
    }
}

/// The viewer's selection outline (`shaders/outline.wgsl`): the shape whose
/// silhouette is outlined, by the id pass's (kind, index), and how.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct Selection {
    /// `ShapeKind::number`; 0 outlines nothing.
    pub kind: u32,
    pub index: u32,
    /// Outline width in output pixels.
    pub radius: u32,
    pub _pad: u32,
    /// sRGB-encoded RGBA.
    pub color: [f32; 4],
}

crate::packed_struct! {
    pub struct Material {
        pub color: [f32; 3],
        pub diffuse: f32,
        pub checker_color: [f32; 3],
        pub checker_size: f32,
        pub checker_phase: [f32; 3],
        pub specular: f32,
        pub shininess: f32,
        pub mirror: f32,
        pub transparency: f32,
        pub ior: f32,
    }
}

crate::packed_struct! {
    /// A BVH node (see `crate::bvh::Node`): an inner node (`count == 0`) has its
    /// children at `first` and `first + 1`, a leaf holds `count` entries of the
    /// shape list from `first`.
    pub struct BvhNode {
        pub bounds_min: [f32; 3],
        pub first: u32,
        pub bounds_max: [f32; 3],
        pub count: u32,
    }
}

/// An entry of the BVH's shape list is the shape's kind number
/// (`ShapeKind::number`) shifted up by this, or'ed with its index in the
/// kind's array (`KIND_SHIFT` in `shaders/scene.wgsl`).
pub const KIND_SHIFT: u32 = 24;

crate::packed_struct! {
    pub struct Light {
        pub position: [f32; 3],
        pub _pad: u32,
        pub radiance: [f32; 3],
        pub _pad1: u32,
    }
}

/// A scene packed for the GPU. Arrays hold at least one (zeroed) element,
/// because a storage buffer may not be empty; the counts in [`Globals`] say
/// how many are real.
#[derive(Debug, Clone, PartialEq)]
pub struct PackedScene {
    /// The frame the positions are measured in (camera-relative, or the
    /// world for the naive variant). Kept on the CPU in f64:
    /// [`PackedScene::set_view`] writes the camera in the same frame.
    pub frame: Frame,
    pub globals: Globals,
    /// Every shape kind's buffers as `u32` words, in the registry order of
    /// `gpu::shapes`, a kind's second buffer after its own (see
    /// [`PackedScene::shapes_of`] for typed access).
    pub shapes: Vec<Words>,
    /// The number of shapes of each kind, by kind number (entry 0 unused).
    pub shape_counts: Vec<u32>,
    pub materials: Vec<Material>,
    pub lights: Vec<Light>,
    pub bvh_nodes: Vec<BvhNode>,
    /// `kind number << KIND_SHIFT | index`, in leaf order.
    pub bvh_prims: Vec<u32>,
}

/// One array of a packed scene, as the GPU holds it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PackedArray {
    /// What it holds ("BVH nodes", "meshes (mesh_data)").
    pub what: String,
    pub bytes: u64,
    /// In a data texture ([`super::shapes::glue::DATA_TEXTURE_WIDTH`] texels
    /// of 16 bytes a row) rather than a storage buffer.
    pub texture: bool,
}

impl PackedScene {
    /// Packs `scene` for an image of `width` x `height` pixels, with every
    /// position relative to the camera target ([`Frame::around_target`]),
    /// so that the image does not depend on where the scene is in the
    /// world. The sample range in the globals starts empty; the renderer
    /// sets it per pass.
    pub fn new(scene: &Scene, width: u32, height: u32) -> Self {
        Self::in_frame(scene, width, height, Frame::around_target(&scene.camera))
    }

    /// Packs `scene` in world coordinates, as the textbook does: the frame
    /// of the naive variant (`ROBUST = false`), which shows what
    /// camera-relative coordinates fix.
    pub fn in_world(scene: &Scene, width: u32, height: u32) -> Self {
        Self::in_frame(scene, width, height, Frame::WORLD)
    }

    fn in_frame(scene: &Scene, width: u32, height: u32, frame: Frame) -> Self {
        let bvh = Bvh::build(scene);
        let mut globals = pack_globals(scene, width, height, &frame);
        globals.bvh_node_count = bvh.nodes.len() as u32;
        PackedScene {
            frame,
            globals,
            shapes: pack_all(scene, &frame),
            shape_counts: shape_counts(scene),
            materials: std::iter::once(scene::Material::default())
                .chain(scene.materials.values().cloned())
                .map(|m| pack_material(&m, &frame))
                .collect(),
            lights: non_empty(scene.lights.iter().map(|l| pack_light(l, &frame))),
            bvh_nodes: non_empty(
                bvh.nodes
                    .iter()
                    .map(|n| pack_node(n.bounds, n.first, n.count, &frame)),
            ),
            bvh_prims: non_empty(
                bvh.prims
                    .iter()
                    .map(|id| (id.kind().number() << KIND_SHIFT) | id.index() as u32),
            ),
        }
    }

    /// Every array the GPU holds, named for a user (what
    /// [`super::limits::check_buffers`] reports), with its size in bytes.
    pub fn arrays(&self) -> Vec<PackedArray> {
        use std::mem::size_of_val;
        // The globals are a storage buffer; every array is a data texture
        // (src/gpu/shapes/glue.rs).
        let fixed = [
            ("globals", size_of_val(&self.globals)),
            ("materials", size_of_val(self.materials.as_slice())),
            ("lights", size_of_val(self.lights.as_slice())),
            ("BVH nodes", size_of_val(self.bvh_nodes.as_slice())),
            ("BVH shape list", size_of_val(self.bvh_prims.as_slice())),
        ]
        .map(|(what, bytes)| (what.to_string(), bytes));
        // A kind's own array, then its shared data (a mesh's BVH and
        // triangles).
        let shape_names = super::shapes::kinds().into_iter().flat_map(|k| {
            let data = k.data.map(|data| format!("{} ({data})", k.kind.key()));
            std::iter::once(k.kind.key().to_string()).chain(data)
        });
        let shapes = shape_names
            .zip(&self.shapes)
            .map(|(what, words)| (what, size_of_val(words.as_slice())));
        fixed
            .into_iter()
            .chain(shapes)
            .map(|(what, bytes)| PackedArray {
                texture: what != "globals",
                what,
                bytes: bytes as u64,
            })
            .collect()
    }

    /// The packed shapes of the scene kind `T`, padded to at least one
    /// element (the count is in [`PackedScene::shape_counts`]).
    pub fn shapes_of<T: PackShape>(&self) -> &[T::Packed] {
        let position = buffer_position(T::KIND);
        bytemuck::cast_slice(self.shapes[position].as_slice())
    }
}

/// The number of shapes of every kind, indexed by kind number.
fn shape_counts(scene: &Scene) -> Vec<u32> {
    let mut counts = vec![0; ShapeKind::ALL.len() + 1];
    for id in scene.shape_ids() {
        counts[id.kind().number() as usize] += 1;
    }
    counts
}

/// A node with its box, relative to the frame, rounded outwards to f32
/// ([`round_out`]).
fn pack_node(bounds: Aabb, first: u32, count: u32, frame: &Frame) -> BvhNode {
    let (bounds_min, bounds_max) = round_out(bounds.min - frame.origin, bounds.max - frame.origin);
    BvhNode {
        bounds_min,
        first,
        bounds_max,
        count,
    }
}

fn non_empty<T: Zeroable>(items: impl Iterator<Item = T>) -> Vec<T> {
    let mut v: Vec<T> = items.collect();
    if v.is_empty() {
        v.push(T::zeroed());
    }
    v
}

impl PackedScene {
    /// Writes the camera and the render settings: what changes while the
    /// shapes stay (orbiting, a slider on exposure), without repacking them.
    /// The frame stays where the shapes were packed: orbiting keeps the
    /// target, and a target moved by panning is as precise as any other
    /// position that near the frame's origin.
    pub fn set_view(&mut self, camera: &scene::Camera, render: &scene::RenderSettings) {
        self.globals.set_view(camera, render, &self.frame);
    }
}

impl Globals {
    fn set_view(&mut self, camera: &scene::Camera, render: &scene::RenderSettings, frame: &Frame) {
        let film = camera.film();
        self.camera_from = frame.point(camera.from);
        self.film_height = film.height as f32;
        self.camera_to = frame.point(camera.to);
        self.aperture = camera.aperture as f32;
        self.u = f32x3(film.u);
        self.focus_distance = camera.focus_distance() as f32;
        self.v = f32x3(film.v);
        self.target_distance = (camera.from - camera.to).length() as f32;
        self.w = f32x3(film.w);
        self.background = f32x3(render.background);
        self.min_weight = render.min_weight as f32;
        self.ambient = f32x3(render.ambient);
        self.exposure = render.exposure as f32;
        self.max_depth = render.max_depth;
    }
}

fn pack_globals(scene: &Scene, width: u32, height: u32, frame: &Frame) -> Globals {
    let mut globals = Globals {
        resolution: [width, height],
        light_count: scene.lights.len() as u32,
        output_size: [width, height],
        ..Zeroable::zeroed()
    };
    globals.set_view(&scene.camera, &scene.render, frame);
    globals
}

/// The checker's cells are counted in world coordinates, but the shader
/// sees positions relative to the frame's origin: `checker_phase` is what
/// the dropped `origin / size` adds to the cell coordinate, reduced modulo 2
/// in f64 (only the parity of the cell sum matters), so the shader's
/// `p / size + checker_phase` stays small and exact enough.
fn pack_material(m: &scene::Material, frame: &Frame) -> Material {
    let (checker_color, checker_size, checker_phase) = match &m.checker {
        Some(c) => (
            f32x3(c.color),
            c.size as f32,
            f32x3((frame.origin / c.size).rem_euclid(DVec3::splat(2.0))),
        ),
        None => ([0.0; 3], 0.0, [0.0; 3]),
    };
    Material {
        color: f32x3(m.color),
        diffuse: m.diffuse as f32,
        checker_color,
        checker_size,
        checker_phase,
        specular: m.specular as f32,
        shininess: m.shininess as f32,
        mirror: m.mirror as f32,
        transparency: m.transparency as f32,
        ior: m.ior as f32,
    }
}

fn pack_light(l: &scene::Light, frame: &Frame) -> Light {
    Light {
        position: frame.point(l.position),
        radiance: f32x3(l.color * l.intensity),
        ..Zeroable::zeroed()
    }
}

/// The globals and the scene's arrays that are not a kind's (bindings 0 to
/// 5, before the kinds' arrays; their structs are in `shaders/scene.wgsl`):
/// the WGSL that declares their data textures and loaders.
pub fn fixed_arrays() -> String {
    [
        struct_array(
            "globals_texture",
            "load_globals",
            &Element::of::<Globals>("Globals"),
            Some(0),
        ),
        struct_array(
            "materials",
            "load_material",
            &Element::of::<Material>("Material"),
            Some(1),
        ),
        struct_array(
            "lights",
            "load_light",
            &Element::of::<Light>("Light"),
            Some(2),
        ),
        struct_array(
            "bvh_nodes",
            "load_bvh_node",
            &Element::of::<BvhNode>("BvhNode"),
            Some(3),
        ),
        word_array("bvh_shapes", "bvh_shape", 4),
        word_array("shape_counts", "shape_count", 5),
    ]
    .concat()
}

#[cfg(test)]
mod tests {

    #[test]
    fn every_fixed_array_has_a_loader() {
        let fixed = super::fixed_arrays();
        for f in [
            "load_globals",
            "load_material",
            "load_light",
            "load_bvh_node",
            "bvh_shape",
            "shape_count",
        ] {
            assert!(fixed.contains(&format!("fn {f}(i: u32)")), "{f}");
        }
    }

    use super::*;
    use crate::scene::test_scenes::{FULL, NEAR_THE_ORIGIN};
    use std::mem::{offset_of, size_of};

    /// (field name, offset) of each field, in declaration order.
    macro_rules! rust_layout {
        ($t:ident { $($f:ident),* $(,)? }) => {
            (stringify!($t), size_of::<$t>(), vec![$((stringify!($f), offset_of!($t, $f))),*])
        };
    }

    /// The layout naga computes for the struct named `name` in the shader.
    fn wgsl_layout(module: &naga::Module, name: &str) -> (usize, Vec<(String, usize)>) {
        let ty = module
            .types
            .iter()
            .find(|(_, t)| t.name.as_deref() == Some(name))
            .unwrap_or_else(|| panic!("no struct {name} in the shader"))
            .1;
        match &ty.inner {
            naga::TypeInner::Struct { members, span } => (
                *span as usize,
                members
                    .iter()
                    .map(|m| (m.name.clone().unwrap_or_default(), m.offset as usize))
                    .collect(),
            ),
            other => panic!("{name} is not a struct: {other:?}"),
        }
    }

    #[test]
    fn rust_structs_mirror_the_wgsl_structs() {
        let source = crate::gpu::shaders::ShaderSource::embedded();
        let module = source.validate().expect("embedded shader is valid").0;
        let expected = [
            rust_layout!(Globals {
                camera_from,
                film_height,
                camera_to,
                aperture,
                u,
                focus_distance,
                v,
                target_distance,
                w,
                min_weight,
                background,
                exposure,
                ambient,
                max_depth,
                resolution,
                sample_start,
                sample_count,
                light_count,
                bvh_node_count,
                output_size,
                view_range,
                _view_pad
            }),
            rust_layout!(Material {
                color,
                diffuse,
                checker_color,
                checker_size,
                checker_phase,
                specular,
                shininess,
                mirror,
                transparency,
                ior
            }),
            rust_layout!(Selection {
                kind,
                index,
                radius,
                _pad,
                color
            }),
            rust_layout!(BvhNode {
                bounds_min,
                first,
                bounds_max,
                count
            }),
            rust_layout!(Light {
                position,
                _pad,
                radiance,
                _pad1
            }),
        ];
        for (name, size, fields) in expected.clone() {
            let (wgsl_size, wgsl_fields) = wgsl_layout(&module, name);
            assert_eq!(size, wgsl_size, "size of {name}");
            let fields: Vec<(String, usize)> = fields
                .into_iter()
                .map(|(f, o)| (f.to_string(), o))
                .collect();
            assert_eq!(fields, wgsl_fields, "fields and offsets of {name}");
        }
        // Every shape kind's struct, from the fields its file lists.
        for kind in crate::gpu::shapes::kinds() {
            let (wgsl_size, wgsl_fields) = wgsl_layout(&module, kind.wgsl_struct);
            assert_eq!(kind.size, wgsl_size, "size of {}", kind.wgsl_struct);
            let fields: Vec<(String, usize)> = kind
                .fields
                .iter()
                .map(|&(f, o)| (f.to_string(), o))
                .collect();
            assert_eq!(
                fields, wgsl_fields,
                "fields and offsets of {}",
                kind.wgsl_struct
            );
        }
    }

    #[test]
    fn empty_arrays_get_one_zeroed_element_and_zero_counts() {
        let scene = Scene::from_toml_str("[camera]\nfrom = [0, 0, 5]\nto = [0, 0, 0]\n", None)
            .expect("valid scene");
        let packed = PackedScene::new(&scene, 4, 3);
        assert_eq!(packed.shapes_of::<scene::Sphere>().len(), 1);
        assert_eq!(packed.lights.len(), 1);
        assert!(packed.shape_counts.iter().all(|&n| n == 0));
        assert_eq!(packed.globals.light_count, 0);
        assert_eq!(packed.materials.len(), 1, "the default material only");
        assert_eq!(packed.globals.resolution, [4, 3]);
    }

    #[test]
    fn materials_are_indexed_default_first_then_in_file_order() {
        let scene = Scene::from_toml_str(FULL, None).expect("valid scene");
        let packed = PackedScene::new(&scene, 4, 3);
        // glass, floor, "brushed steel": the file's order, not the alphabet's.
        assert_eq!(packed.materials[1].color, [1.0, 1.0, 1.0]);
        assert_eq!(packed.materials[2].color, [0.9, 0.9, 0.9]);
        assert_eq!(packed.shapes_of::<scene::Sphere>()[0].material, 1);
        assert_eq!(packed.shapes_of::<scene::Sphere>()[1].material, 0);
        assert_eq!(packed.shapes_of::<scene::Plane>()[0].material, 2);
        assert_eq!(packed.shapes_of::<scene::Cube>()[0].material, 3);
        assert_eq!(packed.materials[0].color, [0.8, 0.8, 0.8]);
    }

    #[test]
    fn bvh_boxes_are_rounded_outwards() {
        let b = Aabb {
            min: glam::DVec3::splat(0.1),
            max: glam::DVec3::splat(0.1),
        };
        let node = pack_node(b, 0, 1, &Frame::WORLD);
        assert!(f64::from(node.bounds_min[0]) <= 0.1 && f64::from(node.bounds_max[0]) >= 0.1);
        assert!(node.bounds_min[0] < node.bounds_max[0], "0.1 is not an f32");
        let exact = pack_node(
            Aabb {
                min: glam::DVec3::ONE,
                max: glam::DVec3::ONE,
            },
            0,
            1,
            &Frame::WORLD,
        );
        assert_eq!(exact.bounds_min, exact.bounds_max, "f32 values stay put");
    }

    /// A scene and its copy 1e6 away pack to the same numbers (to an f32
    /// rounding: the f64 subtractions differ by ~1e-10), so the GPU sees
    /// the same scene; the checker's phase keeps its world cells.
    #[test]
    fn positions_are_packed_relative_to_the_target() {
        let scene = Scene::from_toml_str(NEAR_THE_ORIGIN, None).expect("valid scene");
        let offset = DVec3::new(-1e6, 1e6, -1e6);
        let near = PackedScene::new(&scene, 4, 3);
        let far = PackedScene::new(&scene.translated(offset), 4, 3);
        assert_eq!(near.frame.origin, scene.camera.to);
        assert_eq!(near.globals.camera_to, [0.0; 3]);
        let close = |a: [f32; 3], b: [f32; 3]| {
            (0..3).all(|i| (a[i] - b[i]).abs() <= f32::EPSILON * a[i].abs().max(1.0))
        };
        assert!(close(near.globals.camera_from, far.globals.camera_from));
        assert!(close(
            near.shapes_of::<scene::Sphere>()[0].center,
            far.shapes_of::<scene::Sphere>()[0].center
        ));
        assert!(close(
            near.shapes_of::<scene::Plane>()[0].point,
            [0.0, -0.6, 0.0]
        ));
        assert!(close(
            near.shapes_of::<scene::Plane>()[0].point,
            far.shapes_of::<scene::Plane>()[0].point
        ));
        assert!(close(
            near.shapes_of::<scene::Cube>()[0].center,
            far.shapes_of::<scene::Cube>()[0].center
        ));
        assert!(close(near.lights[0].position, far.lights[0].position));
        assert!(close(
            near.bvh_nodes[0].bounds_min,
            far.bvh_nodes[0].bounds_min
        ));
        // Phase: (origin / 0.5) mod 2 per axis. Near: (0, 1.2, 0).
        let phase = near.materials[1].checker_phase;
        assert!(close(phase, [0.0, 1.2, 0.0]), "{phase:?}");
        // Far: origin (-1e6, 1e6 + 0.6, -1e6) / 0.5 = (-2e6, 2e6 + 1.2, -2e6),
        // the same phase modulo 2.
        assert!(close(far.materials[1].checker_phase, phase));
        // The textbook frame keeps world coordinates.
        let world = PackedScene::in_world(&scene.translated(offset), 4, 3);
        assert_eq!(world.frame, Frame::WORLD);
        assert_eq!(
            world.shapes_of::<scene::Sphere>()[0].center,
            [-999999.1, 1000000.7, -999999.0]
        );
        assert_eq!(world.materials[1].checker_phase, [0.0; 3]);
    }

    #[test]
    fn cube_rotation_columns_are_the_rotated_local_axes() {
        let text = r#"
            [camera]
            from = [0, 0, 5]
            to = [0, 0, 0]
            [[cubes]]
            center = [1, 2, 3]
            size = [2, 4, 6]
            rotation = [0, 0, 90]
        "#;
        let scene = Scene::from_toml_str(text, None).expect("valid scene");
        let cube = PackedScene::new(&scene, 4, 3).shapes_of::<scene::Cube>()[0];
        assert_eq!(cube.half_size, [1.0, 2.0, 3.0]);
        // Rz(90) maps +x to +y: the first column is the image of +x.
        let x = cube.rotation[0];
        assert!(x[0].abs() < 1e-7 && (x[1] - 1.0).abs() < 1e-7 && x[2] == 0.0);
    }
}
