//! The WGSL the program writes for the shape kinds of the registry
//! (`for_each_shape_kind!`): per kind its number, flag and bindings, the
//! loops and the dispatch that call each kind's `hit_<kind>`, and the
//! lookups by kind (material, thin, opaque). Joined in front of the shader
//! files by `gpu::shaders`.

use super::{KindInfo, has_flag};
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

/// The WGSL that visits every shape kind of the registry (`gpu::shapes`):
/// per kind its `KIND_*` number, `HAS_*` flag and array binding, then the
/// dispatch and loops that call each kind's `hit_<kind>` from
/// `shaders/shapes/<kind>.wgsl`, the material lookup and the thin test.
///
/// A kind not in `bound_kinds` keeps its binding number unused and gets a
/// one-element private array instead: its code still compiles (and its
/// `HAS_*` flag, false for a scene without it, makes it dead), while the
/// pipeline binds fewer storage buffers. WebGPU guarantees only 8 per
/// shader stage, fewer than all kinds need (docs/web.md).
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
        declarations += &if bound {
            format!(
                "@group(0) @binding({binding}) var<storage, read> {}: array<{}>;\n",
                k.kind.key(),
                k.wgsl_struct
            )
        } else {
            format!(
                "var<private> {}: array<{}, 1>;\n",
                k.kind.key(),
                k.wgsl_struct
            )
        };
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
                visit(k, &format!("{}[index]", k.kind.key()), "index")
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
                "        case {}: {{ return {}[hit.index].material; }}\n",
                kind_const(k),
                k.kind.key()
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

/// Width in texels of a kind's data texture (a mesh's BVH and triangles);
/// its rows follow one another, so texel i is at (i % width, i / width).
pub const DATA_TEXTURE_WIDTH: u32 = 4096;

/// A kind's shared data (`mesh_data`) and `<data>_at(i)`, its `vec4<u32>`
/// number i. The data is an `Rgba32Uint` texture, not a storage buffer:
/// llvmpipe reads a storage buffer at an index that differs between the
/// lanes one lane at a time, with a bounds test each, and a texel fetch
/// with one gather; two more texel fetches per BVH node cost a tenth of two
/// more storage reads (docs/performance.md, "Where the time goes").
/// Unbound (a scene without the kind), `<data>_at` returns zeros.
fn data_texture(data: &str, binding: Option<u32>) -> String {
    match binding {
        Some(binding) => format!(
            "@group(0) @binding({binding}) var {data}: texture_2d<u32>;\n\
             fn {data}_at(i: u32) -> vec4<u32> {{\n\
             \x20   return textureLoad({data}, vec2(i % {DATA_TEXTURE_WIDTH}u, i / {DATA_TEXTURE_WIDTH}u), 0);\n\
             }}\n"
        ),
        None => format!("fn {data}_at(i: u32) -> vec4<u32> {{\n    return vec4(0u);\n}}\n"),
    }
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
                "    if {flag} && shape_counts[{kind}] > 0u {{\n\
                 \x20       var i = 0u;\n\
                 \x20       loop {{\n\
                 \x20           count_test();\n\
                 \x20           best = {visit};\n\
                 \x20           if any && best.kind != KIND_NONE {{\n\
                 \x20               return best;\n\
                 \x20           }}\n\
                 \x20           continuing {{\n\
                 \x20               i++;\n\
                 \x20               break if i >= shape_counts[{kind}];\n\
                 \x20           }}\n\
                 \x20       }}\n\
                 \x20   }}\n",
                flag = has_flag(k.kind),
                kind = kind_const(k),
                visit = visit(k, &format!("{}[i]", k.kind.key()), "i"),
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
