//! The WGSL the program writes for the shape kinds of the registry
//! (`for_each_shape_kind!`): per kind its number, flag and bindings, the
//! loops and the dispatch that call each kind's `hit_<kind>`, and the
//! lookups by kind (material, thin, opaque). Joined in front of the shader
//! files by `gpu::shaders`.

use super::{KindInfo, Layout, has_flag};
use crate::scene::ShapeKind;

/// The binding of the first shape kind's array; the fixed bindings of
/// `shaders/scene.wgsl` come before it.
pub const FIRST_SHAPE_BINDING: u32 = 6;

/// Every shape kind's arrays bound (bit `ShapeKind::number` per kind): the
/// generic source, which draws any scene.
pub const ALL_KINDS_BOUND: u32 = u32::MAX;

/// Whether the arrays of `kind` are storage bindings in a source or layout
/// made for `bound_kinds` (bit `ShapeKind::number` per kind).
pub fn is_bound(bound_kinds: u32, kind: ShapeKind) -> bool {
    bound_kinds & (1 << kind.number()) != 0
}

/// The WGSL that reads the scene's arrays and visits every shape kind of
/// the registry (`gpu::shapes`): the fixed arrays' textures and loaders,
/// per kind its `KIND_*` number, `HAS_*` flag, array texture and
/// `load_<kind>`, then the dispatch and loops that call each kind's
/// `hit_<kind>` from `shaders/shapes/<kind>.wgsl`, the material lookup and
/// the thin test.
///
/// A kind not in `bound_kinds` keeps its binding number unused and its
/// loader returns a zeroed struct: its code still compiles (and its `HAS_*`
/// flag, false for a scene without it, makes it dead), while the pipeline
/// binds fewer textures. WebGPU guarantees 16 sampled textures per shader
/// stage: the generic pipeline binds 13 here and the radiance sum
/// (docs/web.md).
pub(in crate::gpu) fn shape_glue(kinds: &[KindInfo], bound_kinds: u32) -> String {
    let mut declarations = String::from("// The shape kinds (src/gpu/shapes/mod.rs).\n");
    let mut binding = FIRST_SHAPE_BINDING;
    for k in kinds {
        declarations += &format!(
            "const {kind}: u32 = {number}u;\noverride {flag}: bool = true;\n",
            kind = kind_const(k),
            number = k.kind.number(),
            flag = has_flag(k.kind),
        );
        let bound = is_bound(bound_kinds, k.kind);
        declarations += &struct_array(
            k.kind.key(),
            &loader(k),
            &Element::of_kind(k),
            bound.then_some(binding),
        );
        binding += 1;
        if let Some(data) = k.data {
            declarations += &data_texture(data, bound.then_some(binding));
            binding += 1;
        }
    }
    let (bounded, unbounded): (Vec<&KindInfo>, Vec<&KindInfo>) =
        kinds.iter().partition(|k| k.kind.bounded());
    let cases: String = bounded
        .iter()
        .map(|k| {
            format!(
                "        case {}: {{ if {} {{ return {}; }} }}\n",
                kind_const(k),
                has_flag(k.kind),
                visit(k, &format!("{}(index)", loader(k)), "index")
            )
        })
        .collect();
    let queries: String = kinds
        .iter()
        .filter(|k| k.occludes)
        .map(occlusion_query)
        .collect();
    let materials: String = kinds
        .iter()
        .map(|k| {
            format!(
                "        case {}: {{ return {}(hit.index).material; }}\n",
                kind_const(k),
                loader(k)
            )
        })
        .collect();
    let coordinates: String = kinds
        .iter()
        .filter(|k| k.view_coordinates)
        .map(|k| {
            format!(
                "        case {}: {{ return view_coordinates_{}(hit); }}\n",
                kind_const(k),
                k.name()
            )
        })
        .collect();
    let thin = kind_test(kinds, |k| k.kind.thin());
    let opaque = kind_test(kinds, |k| k.kind.opaque());
    format!(
        "{declarations}\n{queries}\
         /// The hit of one bounded shape, by kind number and index (BVH leaves);\n\
         /// with `any`, any hit will do.\n\
         fn hit_bounded(kind: u32, index: u32, ray: Ray, best: Hit, any: bool) -> Hit {{\n\
         \x20   switch kind {{\n{cases}\
         \x20       default: {{}}\n\
         \x20   }}\n\
         \x20   return best;\n\
         }}\n\n\
         /// The unbounded shapes (planes), in a loop.\n\
         fn hit_unbounded_loop(ray: Ray, best_in: Hit, any: bool) -> Hit {{\n\
         \x20   var best = best_in;\n{}\
         \x20   return best;\n\
         }}\n\n\
         /// The bounded shapes in a loop (USE_BVH = false: the lecture's loop,\n\
         /// and the baseline of the BVH's speed-up).\n\
         fn hit_bounded_loop(ray: Ray, best_in: Hit, any: bool) -> Hit {{\n\
         \x20   var best = best_in;\n{}\
         \x20   return best;\n\
         }}\n\n\
         /// The material slot of the shape hit.\n\
         fn material_of(hit: Hit) -> u32 {{\n\
         \x20   switch hit.kind {{\n{materials}\
         \x20       default: {{ return 0u; }}\n\
         \x20   }}\n\
         }}\n\n\
         /// Thin shapes (planes) have no inside: a ray through one always\n\
         /// enters, and refraction passes it on unbent.\n\
         fn is_thin(kind: u32) -> bool {{\n\
         \x20   return {thin};\n\
         }}\n\n\
         /// Opaque shapes (Julia sets) let no light through: their\n\
         /// material's transparency counts as 0.\n\
         fn is_opaque(kind: u32) -> bool {{\n\
         \x20   return {opaque};\n\
         }}\n\n\
         /// What the barycentric view shows at the hit: the kind's own\n\
         /// coordinates (a mesh's triangle weights), zeros for a kind without.\n\
         fn view_coordinates(hit: Hit) -> vec3<f32> {{\n\
         \x20   switch hit.kind {{\n{coordinates}\
         \x20       default: {{ return vec3(0.0); }}\n\
         \x20   }}\n\
         }}\n",
        kind_loops(&unbounded),
        kind_loops(&bounded),
    )
}

/// The WGSL condition that `kind` is one of the kinds `which` picks:
/// `kind == KIND_A || kind == KIND_B`, or `false` for none.
fn kind_test(kinds: &[KindInfo], which: impl Fn(&KindInfo) -> bool) -> String {
    let tests: Vec<String> = kinds
        .iter()
        .filter(|k| which(k))
        .map(|k| format!("kind == {}", kind_const(k)))
        .collect();
    if tests.is_empty() {
        "false".to_string()
    } else {
        tests.join(" || ")
    }
}

/// Width in texels of a data texture (every array the tracer reads); its
/// rows follow one another, so texel i is at (i % width, i / width).
pub const DATA_TEXTURE_WIDTH: u32 = 4096;

/// A kind's shared data (`mesh_data`) and `<data>_at(i)`, its `vec4<u32>`
/// number i, from a data texture ([`data_texels`]). Unbound (a scene
/// without the kind), `<data>_at` returns zeros.
fn data_texture(data: &str, binding: Option<u32>) -> String {
    match binding {
        Some(binding) => format!(
            "{}fn {data}_at(i: u32) -> vec4<u32> {{\n    return {data}_texel(i);\n}}\n",
            data_texels(data, binding)
        ),
        None => format!("fn {data}_at(i: u32) -> vec4<u32> {{\n    return vec4(0u);\n}}\n"),
    }
}

/// The binding of an array as an `Rgba32Uint` texture and `<name>_texel(i)`,
/// its texel number i. Every array the tracer reads is such a texture, not
/// a storage buffer: llvmpipe reads a storage buffer at an index that
/// differs between the lanes one lane at a time, with a bounds test each,
/// and a texel fetch with one gather; two more texel fetches per BVH node
/// cost a tenth of two more storage reads (docs/performance.md, "Where the
/// time goes"). Its type, `DataTexture`, is the [`DataAccess`]'s.
fn data_texels(name: &str, binding: u32) -> String {
    format!(
        "@group(0) @binding({binding}) var {name}: DataTexture;\n\
         fn {name}_texel(i: u32) -> vec4<u32> {{\n\
         \x20   return fetch_data({name}, i);\n\
         }}\n"
    )
}

/// How the tracer binds and reads its data textures: the same texels (an
/// `Rgba32Uint` texture made for both uses) through either binding type,
/// chosen per device by [`DataAccess::for_device`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DataAccess {
    /// `texture_2d<u32>`, read by `textureLoad(t, xy, 0)`: every device.
    Sampled,
    /// `texture_storage_2d<rgba32uint, read>`, read by `textureLoad(t, xy)`.
    /// lavapipe (Mesa 22.3) compiles a sampled texel fetch into a call
    /// that clamps a mip level and looks up its size for each of the 8
    /// lanes (even for the constant level 0), a storage texel load into a
    /// few inline instructions: the same texels, 1.1x to 1.6x faster by
    /// scene, pictures within a few pixels of each other
    /// (docs/performance.md, "Data textures read as storage textures").
    Storage,
}

/// How many data textures the generic pipeline binds: the fixed arrays
/// and every shape kind's.
pub fn data_texture_count() -> u32 {
    FIRST_SHAPE_BINDING + super::buffer_count() as u32
}

impl DataAccess {
    /// Storage textures where the device binds as many per shader stage as
    /// the generic pipeline needs, else sampled ones. `gpu::context` asks
    /// for that many on a CPU adapter (lavapipe) that has them; WebGPU's
    /// default is 4, so a GPU reads sampled textures, as does the page:
    /// the gain was measured on lavapipe, not on GPUs or the browser's
    /// SwiftShader.
    pub fn for_device(device: &wgpu::Device) -> Self {
        let storage = device.limits().max_storage_textures_per_shader_stage;
        if cfg!(target_arch = "wasm32") || storage < data_texture_count() {
            DataAccess::Sampled
        } else {
            DataAccess::Storage
        }
    }

    /// `DataTexture`, the type of every data texture, and `fetch_data(t,
    /// i)`, its texel number i (row `i / DATA_TEXTURE_WIDTH`).
    pub fn wgsl(self) -> String {
        let (ty, level) = match self {
            DataAccess::Sampled => ("texture_2d<u32>", ", 0"),
            DataAccess::Storage => ("texture_storage_2d<rgba32uint, read>", ""),
        };
        format!(
            "alias DataTexture = {ty};\n\
             fn fetch_data(t: DataTexture, i: u32) -> vec4<u32> {{\n\
             \x20   return textureLoad(t, vec2(i % {DATA_TEXTURE_WIDTH}u, i / {DATA_TEXTURE_WIDTH}u){level});\n\
             }}\n"
        )
    }

    /// The bind group layout entry of a data texture at `binding`.
    pub fn layout_entry(self, binding: u32) -> wgpu::BindGroupLayoutEntry {
        let sampled = crate::gpu::fullscreen::uint_texture_entry(binding);
        match self {
            DataAccess::Sampled => sampled,
            DataAccess::Storage => wgpu::BindGroupLayoutEntry {
                ty: wgpu::BindingType::StorageTexture {
                    access: wgpu::StorageTextureAccess::ReadOnly,
                    format: wgpu::TextureFormat::Rgba32Uint,
                    view_dimension: wgpu::TextureViewDimension::D2,
                },
                ..sampled
            },
        }
    }
}

/// What one element of a struct array is: its WGSL struct and the fields of
/// its Rust twin (`packed_struct!`).
pub struct Element {
    pub wgsl_struct: &'static str,
    pub fields: &'static [(&'static str, usize)],
    pub types: &'static [&'static str],
    pub size: usize,
}

impl Element {
    /// The element of a `packed_struct!` named as its WGSL twin.
    pub(in crate::gpu) fn of<T: Layout>(wgsl_struct: &'static str) -> Self {
        Element {
            wgsl_struct,
            fields: T::FIELDS,
            types: T::TYPES,
            size: size_of::<T>(),
        }
    }

    /// The element of a shape kind's array.
    fn of_kind(k: &KindInfo) -> Self {
        Element {
            wgsl_struct: k.wgsl_struct,
            fields: k.fields,
            types: k.types,
            size: k.size,
        }
    }

    /// Texels (16 bytes) per element: every packed struct is a whole
    /// number of them, so an element starts at a texel.
    fn texels(&self) -> usize {
        assert!(
            self.size.is_multiple_of(16),
            "{} is not a multiple of 16 bytes",
            self.wgsl_struct
        );
        self.size / 16
    }
}

/// An array of structs in a data texture and `<loader>(i)`, its element i
/// built field by field from the element's texels, so that the WGSL reads
/// `load_sphere(i)` where it read `spheres[i]` and gets the same struct.
/// Unbound (a scene without the kind), the loader returns a zeroed struct.
pub(in crate::gpu) fn struct_array(
    name: &str,
    loader: &str,
    element: &Element,
    binding: Option<u32>,
) -> String {
    let ty = element.wgsl_struct;
    let Some(binding) = binding else {
        return format!("fn {loader}(i: u32) -> {ty} {{\n    return {ty}();\n}}\n");
    };
    let texels = element.texels();
    let reads: String = (0..texels)
        .map(|t| format!("    let t{t} = {name}_texel(i * {texels}u + {t}u);\n"))
        .collect();
    let fields: Vec<String> = element
        .fields
        .iter()
        .zip(element.types)
        .map(|(&(_, offset), &rust)| field_from_texels(rust, offset))
        .collect();
    format!(
        "{}/// Element i of `{name}` (src/gpu/shapes/glue.rs).\n\
         fn {loader}(i: u32) -> {ty} {{\n{reads}    return {ty}({});\n}}\n",
        data_texels(name, binding),
        fields.join(", ")
    )
}

/// An array of `u32` in a data texture, four a texel, and `<accessor>(i)`,
/// its number i.
pub(in crate::gpu) fn word_array(name: &str, accessor: &str, binding: u32) -> String {
    format!(
        "{}fn {accessor}(i: u32) -> u32 {{\n    return {name}_texel(i / 4u)[i % 4u];\n}}\n",
        data_texels(name, binding)
    )
}

/// The WGSL that reads a field of Rust type `rust` (as `packed_struct!`
/// writes it) at byte `offset` of an element from its texels `t0`, `t1`,
/// ...: the words as they are for `u32`, their bits as floats for `f32`.
/// WGSL's alignment keeps a vector inside one texel.
fn field_from_texels(rust: &str, offset: usize) -> String {
    let word = offset / 4;
    let part = |word: usize, n: usize| {
        let first = word % 4;
        assert!(first + n <= 4, "a field at byte {offset} crosses a texel");
        format!("t{}.{}", word / 4, &"xyzw"[first..first + n])
    };
    let floats = |ty: &str, word: usize, n: usize| format!("bitcast<{ty}>({})", part(word, n));
    match rust.replace(' ', "").as_str() {
        "u32" => part(word, 1),
        "[u32;2]" => part(word, 2),
        "f32" => floats("f32", word, 1),
        "[f32;2]" => floats("vec2<f32>", word, 2),
        "[f32;3]" => floats("vec3<f32>", word, 3),
        "[f32;4]" => floats("vec4<f32>", word, 4),
        // mat3x3<f32>: three columns, each padded to 16 bytes.
        "[[f32;4];3]" => format!(
            "mat3x3<f32>({}, {}, {})",
            floats("vec3<f32>", word, 3),
            floats("vec3<f32>", word + 4, 3),
            floats("vec3<f32>", word + 8, 3)
        ),
        other => panic!("no WGSL type is read for the Rust field type {other}"),
    }
}

/// `load_sphere`: the loader of a kind's array.
fn loader(k: &KindInfo) -> String {
    format!("load_{}", k.name())
}

/// `KIND_SPHERE`.
fn kind_const(k: &KindInfo) -> String {
    format!("KIND_{}", k.name().to_uppercase())
}

/// One loop per kind over all its shapes; with `any`, the first hit ends it.
/// The loop tests its end after the body (`break if` in `continuing`), not
/// before: on llvmpipe loops that test first made every scene measured
/// slower (docs/performance.md, "The torus against its sphere", the table
/// "kind loops tested last").
fn kind_loops(kinds: &[&KindInfo]) -> String {
    kinds
        .iter()
        .map(|k| {
            format!(
                "    if {flag} && shape_count({kind}) > 0u {{\n\
                 \x20       var i = 0u;\n\
                 \x20       loop {{\n\
                 \x20           count_test();\n\
                 \x20           best = {visit};\n\
                 \x20           if any && best.kind != KIND_NONE {{\n\
                 \x20               return best;\n\
                 \x20           }}\n\
                 \x20           continuing {{\n\
                 \x20               i++;\n\
                 \x20               break if i >= shape_count({kind});\n\
                 \x20           }}\n\
                 \x20       }}\n\
                 \x20   }}\n",
                flag = has_flag(k.kind),
                kind = kind_const(k),
                visit = visit(k, &format!("{}(i)", loader(k)), "i"),
            )
        })
        .collect()
}

/// The call that tests `shape` (number `index`) of kind `k` against `ray`
/// and `best`: `hit_<kind>`, or for a kind with `occludes_<kind>` its
/// [`occlusion_query`], which needs `any`.
fn visit(k: &KindInfo, shape: &str, index: &str) -> String {
    if k.occludes {
        format!("query_{}(ray, {shape}, {index}, best, any)", k.name())
    } else {
        format!("hit_{}(ray, {shape}, {index}, best)", k.name())
    }
}

/// `query_<kind>`: the nearest hit by `hit_<kind>`, or for shadow rays
/// (`any`) only whether `occludes_<kind>` finds one, reported as a hit of
/// the shape at `best.t` (an any-hit query reads no more than the kind).
/// `any` is a constant wherever the query is inlined, so each use keeps one
/// of the two branches.
fn occlusion_query(k: &KindInfo) -> String {
    format!(
        "/// The {name} for nearest-hit (hit_{name}) or any-hit (occludes_{name}) queries.\n\
         fn query_{name}(ray: Ray, s: {ty}, index: u32, best: Hit, any: bool) -> Hit {{\n\
         \x20   if !any {{\n\
         \x20       return hit_{name}(ray, s, index, best);\n\
         \x20   }}\n\
         \x20   var blocked = best;\n\
         \x20   if occludes_{name}(ray, s, best.t) {{\n\
         \x20       blocked.kind = {kind};\n\
         \x20       blocked.index = index;\n\
         \x20   }}\n\
         \x20   return blocked;\n\
         }}\n\n",
        name = k.name(),
        ty = k.wgsl_struct,
        kind = kind_const(k),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sphere() -> Element {
        let kinds = super::super::kinds();
        let k = kinds.iter().find(|k| k.kind == ShapeKind::Sphere);
        Element::of_kind(k.expect("the sphere is a kind"))
    }

    #[test]
    fn a_struct_is_read_field_by_field_from_its_texels() {
        let wgsl = struct_array("spheres", "load_sphere", &sphere(), Some(6));
        assert!(wgsl.contains("@group(0) @binding(6) var spheres: DataTexture;"));
        assert!(wgsl.contains("let t0 = spheres_texel(i * 2u + 0u);"));
        assert!(wgsl.contains("let t1 = spheres_texel(i * 2u + 1u);"));
        assert!(
            wgsl.contains("return Sphere(bitcast<vec3<f32>>(t0.xyz), bitcast<f32>(t0.w), t1.x);")
        );
    }

    #[test]
    fn an_unbound_array_reads_zeros() {
        let wgsl = struct_array("spheres", "load_sphere", &sphere(), None);
        assert!(!wgsl.contains("@binding"));
        assert!(wgsl.contains("return Sphere();"));
    }

    #[test]
    fn a_matrix_is_read_as_three_padded_columns() {
        assert_eq!(
            field_from_texels("[[f32; 4]; 3]", 16),
            "mat3x3<f32>(bitcast<vec3<f32>>(t1.xyz), bitcast<vec3<f32>>(t2.xyz), bitcast<vec3<f32>>(t3.xyz))"
        );
        assert_eq!(field_from_texels("[u32; 2]", 40), "t2.zw");
    }

    #[test]
    fn every_kind_has_a_loader() {
        for k in super::super::kinds() {
            let wgsl = struct_array(k.kind.key(), &loader(&k), &Element::of_kind(&k), Some(9));
            assert!(wgsl.contains(&format!("fn load_{}(i: u32)", k.name())));
        }
    }
}
