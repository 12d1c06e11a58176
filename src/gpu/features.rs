//! Shader specialisation: one WGSL source, compiled per scene *feature set*
//! through pipeline-overridable constants (`override` in WGSL). A constant
//! that is false turns the code behind it into dead code that the driver's
//! compiler removes, so a spheres-only scene runs no plane, box, refraction
//! or checker code at all.

use super::view::View;
use crate::scene::{KindOptions, Scene, ShapeKind};

/// What a scene needs from the shader. Every flag that is true for a scene
/// must be true in the pipeline that draws it; extra flags only cost time.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Features {
    /// The shape kinds present: bit `ShapeKind::number` for each.
    pub shape_kinds: u32,
    /// Point lights: diffuse and specular terms and shadow rays.
    pub lights: bool,
    /// Materials with a mirror term (reflected rays).
    pub mirrors: bool,
    /// Materials with a dielectric term (Fresnel, reflected and refracted rays).
    pub transparency: bool,
    pub checker: bool,
    /// A camera with aperture > 0 (thin lens sampling).
    pub lens: bool,
    /// Bounded shapes through the BVH (true) or a loop over all of them.
    pub bvh: bool,
}

/// From this many bounded shapes (every kind but planes) on, a specialised
/// pipeline traverses the BVH; below it, it loops over them, since the
/// traversal stack has a fixed cost on lavapipe. The value was chosen from
/// an earlier run of `raysandbox bench`; where the loop and the BVH cross
/// in the latest run is in docs/performance.md, "Scaling with the number
/// of spheres".
pub const BVH_MIN_SHAPES: usize = 128;

impl Features {
    /// The generic pipeline: every feature compiled in.
    pub const ALL: Features = Features {
        shape_kinds: u32::MAX,
        lights: true,
        mirrors: true,
        transparency: true,
        checker: true,
        lens: true,
        bvh: true,
    };

    /// Exactly what `scene` uses: shapes present, materials that shapes use
    /// (a material no shape refers to costs nothing), lights, lens.
    pub fn of(scene: &Scene) -> Features {
        let ids = scene.shape_ids();
        let used: Vec<_> = ids
            .iter()
            .filter_map(|&id| scene.shape_material(id))
            .map(|name| scene.material(name.as_deref()))
            .collect();
        let bounded = ids.iter().filter(|id| id.kind().bounded()).count();
        Features {
            shape_kinds: ids
                .iter()
                .fold(0, |bits, id| bits | (1 << id.kind().number())),
            lights: !scene.lights.is_empty(),
            mirrors: used.iter().any(|m| m.mirror > 0.0),
            transparency: used.iter().any(|m| m.transparency > 0.0),
            checker: used.iter().any(|m| m.checker.is_some()),
            lens: scene.camera.aperture > 0.0,
            bvh: bounded >= BVH_MIN_SHAPES,
        }
    }

    /// The ray-tree stack a scene needs: `max_depth + 1` entries, but one
    /// when no material reflects or transmits, since then no ray has a
    /// child and the camera ray is the only entry. On lavapipe a stack
    /// larger than it needs costs time even when it is never filled
    /// (docs/performance.md, "The torus against its sphere": the opaque
    /// torus scene is faster with one entry than with nine).
    pub fn stack_size(&self, max_depth: u32) -> u32 {
        if self.mirrors || self.transparency {
            max_depth + 1
        } else {
            1
        }
    }

    /// Whether shapes of `kind` are present.
    pub fn has(&self, kind: ShapeKind) -> bool {
        self.shape_kinds & (1 << kind.number()) != 0
    }
}

/// The largest ray-tree stack a scene can need: the deepest `max_depth`,
/// plus one.
pub const MAX_STACK_SIZE: u32 = crate::scene::MAX_DEPTH + 1;

/// Values for the shader's pipeline-overridable constants: the variants of
/// one source.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct ShaderOptions {
    /// The robust intersection and offset routines (true) or the lecture's
    /// textbook versions (false), to show what the robust ones fix: the
    /// scene's `intersections` (docs/rendering-model.md, "Lecture
    /// switches").
    pub robust: bool,
    pub features: Features,
    /// Entries of the ray-tree stack: the scene's `max_depth + 1`, or 1 when
    /// it has no mirror and no glass (see [`Features::stack_size`]). Not a
    /// pipeline constant: WGSL sizes arrays only with `const`s, so it is
    /// written into the source, see `ShaderSource::with_stack_size`.
    pub stack_size: u32,
    /// Each shape kind's own choices: a method chosen by name (a pipeline
    /// constant of its WGSL) or WGSL written from the scene (compiled into
    /// the source, see `ShaderSource::with_generated`: a pipeline per
    /// distinct set of implicit functions).
    pub kinds: KindOptions,
    /// The ray-counting variant (`COUNT_RAYS`): the trace pass writes the
    /// number of rays traced per pixel by kind instead of the radiance
    /// (docs/performance.md, "Rays per second"). Off in every pipeline
    /// that draws.
    pub count_rays: bool,
    /// The ray tree's debug pass (`RAY_TREE`, `shaders/ray_tree.wgsl`):
    /// the trace loop records every ray of one pixel. Only
    /// `gpu::RayTreeRenderer` sets it.
    pub ray_tree: bool,
    /// What the trace and display passes show (`VIEW`): the shaded
    /// picture, or a view inside the tracer (docs/views.md).
    pub view: View,
    /// The scene's lecture switches (`SHADOWS`, `REFLECTION`,
    /// `REFRACTION`; docs/rendering-model.md, "Lecture switches"): shadow,
    /// reflected and refracted rays traced. Compiled in rather than read
    /// at run time, which cost a few per cent of the frame time
    /// (docs/views.md, "The shaded picture's frame time").
    pub rays: Rays,
}

/// Which kinds of secondary rays are traced: the lecture switches of
/// `[render]`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Rays {
    pub shadows: bool,
    pub reflection: bool,
    pub refraction: bool,
}

impl Rays {
    /// Every kind traced: the rendering model without switches.
    pub const ALL: Rays = Rays {
        shadows: true,
        reflection: true,
        refraction: true,
    };

    /// What `scene`'s switches trace.
    pub fn of(scene: &Scene) -> Rays {
        let r = &scene.render;
        Rays {
            shadows: r.shadows,
            reflection: r.reflection,
            refraction: r.refraction,
        }
    }
}

impl Default for ShaderOptions {
    /// Robust and generic: draws any scene.
    fn default() -> Self {
        ShaderOptions {
            robust: true,
            features: Features::ALL,
            stack_size: MAX_STACK_SIZE,
            kinds: KindOptions::default(),
            count_rays: false,
            ray_tree: false,
            view: View::Shaded,
            rays: Rays::ALL,
        }
    }
}

impl ShaderOptions {
    /// Generic, with what `scene` asks of its kinds (its implicit
    /// functions, which no pipeline can do without: they are the scene's
    /// own code) and its intersections.
    pub fn generic(scene: &Scene) -> Self {
        ShaderOptions {
            robust: scene.render.intersections.is_robust(),
            kinds: KindOptions::of(scene),
            rays: Rays::of(scene),
            ..ShaderOptions::default()
        }
    }

    /// The pipeline specialised for `scene`, with its intersections.
    pub fn for_scene(scene: &Scene) -> Self {
        let features = Features::of(scene);
        ShaderOptions {
            features,
            stack_size: features.stack_size(scene.render.max_depth),
            ..ShaderOptions::generic(scene)
        }
    }
}

/// The constants as wgpu takes them.
pub(super) fn borrowed(constants: &[(String, f64)]) -> Vec<(&str, f64)> {
    constants.iter().map(|(n, v)| (n.as_str(), *v)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::bundled;

    fn bundled_scene(name: &str) -> Scene {
        Scene::from_toml_str(bundled::text(name).unwrap(), None).unwrap()
    }

    #[test]
    fn features_follow_the_scene() {
        let f = Features::of(&bundled_scene("many_spheres"));
        let has = |k| f.has(k);
        assert!(has(ShapeKind::Sphere) && has(ShapeKind::Plane) && !has(ShapeKind::Cube));
        assert!(f.lights && f.mirrors && f.transparency && f.checker && !f.lens && f.bvh);
        let f = Features::of(&bundled_scene("cornell"));
        assert!(f.has(ShapeKind::Cube) && f.transparency && !f.checker && !f.bvh);
    }

    #[test]
    fn unused_materials_add_no_features() {
        let scene = Scene::from_toml_str(
            "[camera]\nfrom = [0, 0, 5]\nto = [0, 0, 0]\n\
             [materials.glass]\ntransparency = 1.0\n\
             [[spheres]]\ncenter = [0, 0, 0]\nradius = 1\n",
            None,
        )
        .unwrap();
        let f = Features::of(&scene);
        assert!(f.has(ShapeKind::Sphere) && !f.transparency && !f.mirrors && !f.lights);
    }

    /// The scene's lecture switches reach both pipelines' options, and the
    /// reference's (docs/rendering-model.md, "Lecture switches").
    #[test]
    fn the_scenes_triangle_test_and_intersections_reach_both_renderers() {
        use crate::reference::ReferenceOptions;
        use crate::scene::{Intersections, TriangleTest};
        let mut scene = bundled_scene("whitted");
        scene.render.meshes.triangles = TriangleTest::Cramer;
        scene.render.intersections = Intersections::Textbook;
        for options in [
            ShaderOptions::for_scene(&scene),
            ShaderOptions::generic(&scene),
        ] {
            assert_eq!(options.kinds.meshes, TriangleTest::Cramer);
            assert!(!options.robust);
        }
        let reference = ReferenceOptions::of(&scene);
        assert_eq!(reference.kinds.meshes, TriangleTest::Cramer);
        assert!(!reference.robust);
    }

    #[test]
    fn only_scenes_with_child_rays_get_a_deep_stack() {
        let glass = bundled_scene("torus");
        assert_eq!(ShaderOptions::for_scene(&glass).stack_size, 9);
        let mut opaque = glass.clone();
        for m in opaque.materials.values_mut() {
            m.transparency = 0.0;
            m.mirror = 0.0;
        }
        assert_eq!(opaque.render.max_depth, 8);
        assert_eq!(ShaderOptions::for_scene(&opaque).stack_size, 1);
    }

    #[test]
    fn every_override_in_the_shader_gets_a_value_and_no_other() {
        let source = super::super::ShaderSource::embedded();
        let module = source.validate().unwrap().0;
        let mut declared: Vec<String> = module
            .overrides
            .iter()
            .filter_map(|(_, o)| o.name.clone())
            .filter(|n| n != "ENCODE_SRGB")
            .collect();
        declared.sort();
        let mut given: Vec<String> = ShaderOptions::default()
            .constants()
            .into_iter()
            .map(|(n, _)| n)
            .collect();
        given.sort();
        assert_eq!(declared, given);
    }
}
