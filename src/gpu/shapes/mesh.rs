//! A triangle mesh as `shaders/shapes/mesh.wgsl` reads it: the placement
//! per mesh, and in the kind's second buffer `mesh_data` each loaded
//! geometry once (its BVH nodes, its triangles in leaf order, its vertex
//! normals when smooth), in the mesh's own coordinates, so that a moved
//! mesh repacks nothing but its placement.

use std::sync::Arc;

use bytemuck::Zeroable;

use super::placement::columns;
use super::{Frame, PackShape, Words, material_slot, packed_struct, round_out};
use crate::bvh::triangle_bvh;
use crate::scene::{self, Geometry, Instance, Scene};

packed_struct! {
    /// The fields a BVH walk reads come first, in four texels (a texel
    /// fetch is the walk's price on lavapipe: docs/performance.md, "Fewer
    /// fetches per mesh"): `to_local` (the inverse of R diag(scale)) by
    /// columns, each with a start offset in its fourth word, and `origin`.
    /// The hit reads `to_world` too; `material` only the shading.
    pub struct Mesh for scene::Mesh, "../../../shaders/shapes/mesh.wgsl" {
        pub to_local_x: [f32; 3],
        pub node_start: u32,
        pub to_local_y: [f32; 3],
        pub tri_start: u32,
        pub to_local_z: [f32; 3],
        pub normal_start: u32,
        /// `translate`, relative to the frame origin.
        pub origin: [f32; 3],
        pub error_scale: f32,
        /// `mat3x3<f32>`: three columns, each padded to 16 bytes.
        pub to_world: [[f32; 4]; 3],
        pub material: u32,
    }
}

impl PackShape for scene::Mesh {
    const DATA: Option<&'static str> = Some("mesh_data");
    const VIEW_COORDINATES: bool = true;

    fn constants(test: &scene::TriangleTest) -> Vec<(&'static str, u32)> {
        vec![("TRIANGLE_TEST", test.number())]
    }

    /// The placement; the data offsets are set by [`PackShape::pack_kind`].
    fn pack(_: &Scene, frame: &Frame, m: &Instance<scene::Mesh>, material: u32) -> Mesh {
        let linear = m.placement.linear();
        let to_local = linear.inverse();
        let [lo, hi] = m.bounds();
        let error_scale = (lo - frame.origin)
            .abs()
            .max((hi - frame.origin).abs())
            .max_element();
        let [x, y, z] = [to_local.x_axis, to_local.y_axis, to_local.z_axis];
        Mesh {
            to_local_x: x.as_vec3().to_array(),
            to_local_y: y.as_vec3().to_array(),
            to_local_z: z.as_vec3().to_array(),
            origin: frame.point(m.placement.translate),
            error_scale: error_scale as f32,
            to_world: columns(linear),
            material,
            ..Zeroable::zeroed()
        }
    }

    /// Each geometry's data goes into `mesh_data` once, however many meshes
    /// show it. A scene with one geometry shares its packed block as is, so
    /// that moving the mesh copies no triangle.
    fn pack_kind(scene: &Scene, frame: &Frame) -> (Vec<Mesh>, Words) {
        let mut blocks: Vec<(*const Geometry, Arc<PackedGeometry>, u32)> = Vec::new();
        let mut next = 0;
        let meshes = scene
            .meshes
            .iter()
            .map(|m| {
                let geometry = &m.geometry.0;
                let key = Arc::as_ptr(geometry);
                let (block, start) = match blocks.iter().find(|(g, _, _)| *g == key) {
                    Some((_, block, start)) => (block.clone(), *start),
                    None => {
                        let block = packed_geometry(geometry);
                        let start = next;
                        next += block.entries();
                        blocks.push((key, block.clone(), start));
                        (block, start)
                    }
                };
                Mesh {
                    node_start: start,
                    tri_start: start + block.tri_offset,
                    normal_start: block.normal_offset.map_or(0, |offset| start + offset),
                    ..Self::pack(scene, frame, m, material_slot(scene, m))
                }
            })
            .collect();
        let data = match blocks.as_slice() {
            [(_, only, _)] => only.words.clone(),
            _ => Arc::new(
                blocks
                    .iter()
                    .flat_map(|(_, block, _)| block.words.iter().copied())
                    .collect(),
            ),
        };
        (meshes, data)
    }
}

/// How much every node box grows, relative to its largest edge. The faces
/// of a tessellated box give boxes of zero thickness, and lavapipe's slab
/// test (`hit_box`) does not keep their entry and exit equal: rays missed
/// whole faces until the boxes were padded (seen on the tessellated cube of
/// tests/meshes.rs). 2^-16 costs nothing measurable in box hits.
const FLAT_PAD: f64 = 1.0 / 65536.0;

/// A geometry's block of `mesh_data`: its BVH nodes, its triangles in leaf
/// order and (smooth) its normals, with where the triangles and normals
/// start within the block, in `vec4<u32>` entries.
struct PackedGeometry {
    words: Words,
    tri_offset: u32,
    normal_offset: Option<u32>,
}

impl PackedGeometry {
    /// Its length in `vec4<u32>` entries.
    fn entries(&self) -> u32 {
        (self.words.len() / 4) as u32
    }
}

/// Each geometry is packed once ([`Geometry::derived`]): a mesh moved in
/// the viewer reuses its block instead of walking a million triangles
/// again.
fn packed_geometry(geometry: &Geometry) -> Arc<PackedGeometry> {
    geometry.derived(|| pack_geometry(geometry))
}

/// The block of `geometry` (see [`PackedGeometry`]), in the mesh's own
/// coordinates: the same wherever the mesh is placed.
fn pack_geometry(geometry: &Geometry) -> PackedGeometry {
    let bvh = triangle_bvh(geometry);
    let bits = |v: [f32; 3], w: u32| [v[0].to_bits(), v[1].to_bits(), v[2].to_bits(), w];
    let mut words = Vec::with_capacity(2 * bvh.nodes.len() + 6 * bvh.prims.len());
    for node in &bvh.nodes {
        let pad = FLAT_PAD * (node.bounds.max - node.bounds.min).max_element();
        let (lo, hi) = round_out(node.bounds.min - pad, node.bounds.max + pad);
        words.push(bits(lo, node.first));
        words.push(bits(hi, node.count));
    }
    let vertex = |v: u32, of: &[glam::DVec3]| bits(of[v as usize].as_vec3().to_array(), 0);
    let tri_offset = words.len() as u32;
    for &t in &bvh.prims {
        for v in geometry.triangles[t as usize] {
            words.push(vertex(v, &geometry.positions));
        }
    }
    let mut normal_offset = None;
    if !geometry.normals.is_empty() {
        normal_offset = Some(words.len() as u32);
        for &t in &bvh.prims {
            for v in geometry.triangles[t as usize] {
                words.push(vertex(v, &geometry.normals));
            }
        }
    }
    PackedGeometry {
        words: Arc::new(bytemuck::cast_slice(&words).to_vec()),
        tri_offset,
        normal_offset,
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;
    use crate::bvh::triangle_bvh_built;
    use crate::gpu::layout::PackedScene;
    use crate::scene::{AxisScale, ShapeKind};

    /// What the viewer does when a mesh is moved, turned or scaled in the
    /// panel: the scene is copied and the placement edited. The geometry,
    /// its BVH and the packed triangles stay; only the placement changes.
    #[test]
    fn a_rigid_move_keeps_the_triangle_bvh_and_repacks_only_the_placement() {
        let text = r#"
            [camera]
            from = [0, 1, 5]
            to = [0, 0, 0]
            [[meshes]]
            positions = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]]
            triangles = [[0, 2, 1], [0, 1, 3], [1, 2, 3], [2, 0, 3]]
        "#;
        let scene = Scene::from_toml_str(text, None).unwrap();
        let built = triangle_bvh_built(&scene.meshes[0].geometry.0);
        let before = PackedScene::new(&scene, 8, 8);

        let mut moved = scene.clone();
        let mesh = &mut moved.meshes[0];
        mesh.placement.translate = DVec3::new(0.5, -0.25, 1.0);
        mesh.placement.rotation = DVec3::new(10.0, 45.0, 0.0);
        mesh.placement.scale = AxisScale::PerAxis(DVec3::new(2.0, 1.0, 0.5));
        let after = PackedScene::new(&moved, 8, 8);

        let again = triangle_bvh_built(&moved.meshes[0].geometry.0);
        assert!(Arc::ptr_eq(&built.bvh, &again.bvh), "the BVH was rebuilt");
        assert_eq!(built.build_time, again.build_time);
        let data = crate::gpu::shapes::buffer_position(ShapeKind::Mesh) + 1;
        assert!(
            Arc::ptr_eq(&before.shapes[data], &after.shapes[data]),
            "the triangle data is shared, not packed again"
        );
        assert_ne!(
            before.shapes_of::<scene::Mesh>()[0],
            after.shapes_of::<scene::Mesh>()[0],
            "the placement is repacked"
        );
    }
}
