//! The f64 CPU reference tracer: the yardstick the GPU image is measured
//! against.
//!
//! It follows the rendering model (`docs/rendering-model.md`) and the
//! implementation choices the shader makes too (`docs/implementation.md`),
//! in f64 and written to be read beside those two documents rather than for
//! speed. One file per concern:
//!
//! - `camera.rs`: the basis and the camera rays, thin lens included;
//! - `sampling.rs`: where the samples of a pixel go;
//! - `ray.rs`: rays and the offset of secondary rays;
//! - `hit.rs`: what a hit reports, and constructions the hit tests share;
//! - `shapes/`: one file per shape kind, its f64 hit test;
//! - `intersect.rs`: the nearest hit and shadow hits over the scene;
//! - `shade.rs`: Whitted's recursive shading;
//! - `output.rs`: exposure, sRGB and 8 bits;
//! - `views.rs`: what the views inside the tracer show of a first hit;
//! - `error.rs`: the error view's reference, coarse to fine, and its measure;
//! - `record.rs`: what `shade.rs` tells while it traces, ray by ray;
//! - `ray_tree.rs`: a pixel's ray tree, every ray recorded as `shade.rs` traces it.
//!
//! Here: the scene prepared for tracing, and the renderers over it.

mod camera;
mod error;
mod hit;
pub mod intersect;
mod output;
pub mod ray;
mod ray_tree;
mod record;
mod sampling;
mod shade;
pub mod shapes;
mod views;

use glam::{DVec2, DVec3};
use rayon::prelude::*;

use crate::bvh::Bvh;
use crate::scene::{KindOptions, Material, Scene};

pub use camera::{Camera, camera_ray};
pub use error::ErrorImage;
pub use intersect::ShapeId;
pub use output::{encode_srgb8, to_rgba8};
pub use ray_tree::{
    RayDifference, RayTree, TreeRay, compare as compare_trees, describe as describe_trees, ray_tree,
};
pub use record::RayKind;
pub use sampling::{r4, r4_rotated};
pub use shapes::prepare_ahead;
pub use views::{ViewHit, view_hit};

use intersect::nearest_hit;
use sampling::concentric_disk;
use shade::trace;

/// A point light, its colour already multiplied by its intensity.
#[derive(Debug, Clone)]
struct PointLight {
    position: DVec3,
    radiance: DVec3,
}

/// A [`Scene`] turned into what tracing needs: camera basis, every shape
/// as its kind prepares it, and materials by index, all in f64. Prepare
/// once, render many times.
#[derive(Debug, Clone)]
pub struct PreparedScene {
    /// The world point every position below is relative to: the camera
    /// target (robust), or zero (the naive variant's world coordinates).
    /// Subtracted in f64 before tracing, as the GPU's packing does, so that
    /// offsets and rounding scale with the view and not with the distance
    /// from the world origin (docs/implementation.md, "Camera-relative
    /// coordinates"). The checker and `pick` add it back.
    frame_origin: DVec3,
    camera: Camera,
    lights: Vec<PointLight>,
    /// The default material, then the scene's materials in file order: the
    /// same slots as `Scene::material_slot` and the GPU buffers.
    materials: Vec<Material>,
    shapes: shapes::Shapes,
    /// The shapes without bounds (planes), tested in a loop.
    unbounded: Vec<ShapeId>,
    /// The bounded shapes (every kind but planes) in a bounding volume hierarchy.
    bvh: Bvh,
    background: DVec3,
    ambient: DVec3,
    max_depth: u32,
    min_weight: f64,
    /// The lecture switches: shadow, reflected and refracted rays traced.
    shadows: bool,
    reflection: bool,
    refraction: bool,
    exposure: f64,
    /// The robust routines or the textbook ones, the triangle test and the
    /// pixel angle.
    options: ReferenceOptions,
    /// Whether a shape's hit depends on the pixel angle (a Julia set that
    /// grows its epsilon with the pixel footprint): then each render sets
    /// `options.pixel_angle` for its image height.
    uses_pixel_angle: bool,
}

/// Variants of the reference, the twin of the shader's `gpu::ShaderOptions`.
#[derive(Debug, Clone, PartialEq)]
pub struct ReferenceOptions {
    /// true: the robust routines (docs/implementation.md); false: the naive
    /// quadratic, the plain slab test, the plane without re-projection and a
    /// fixed offset of 1e-3, as the shader with `ROBUST = false`.
    pub robust: bool,
    /// Each shape kind's own choices (a mesh's ray-triangle test), as the
    /// shader's options carry them.
    pub kinds: KindOptions,
    /// The height one pixel subtends at unit distance (film height / image
    /// height), for Julia sets with `footprint` (docs/rendering-model.md,
    /// "Implicit surfaces"). The render functions set it for their image.
    pub pixel_angle: f64,
}

impl Default for ReferenceOptions {
    fn default() -> Self {
        ReferenceOptions {
            robust: true,
            kinds: KindOptions::default(),
            pixel_angle: 0.0,
        }
    }
}

impl ReferenceOptions {
    /// The variant `scene` asks for: its `intersections` (docs/rendering-model.md,
    /// "Lecture switches") and what it asks of its kinds (its `triangles`),
    /// else the defaults.
    pub fn of(scene: &Scene) -> Self {
        ReferenceOptions {
            robust: scene.render.intersections.is_robust(),
            kinds: KindOptions::of(scene),
            ..ReferenceOptions::default()
        }
    }
}

impl PreparedScene {
    /// Prepares a validated scene, with the intersections it asks for. (A
    /// material name that validation would have rejected falls back to the
    /// default material instead of panicking.)
    pub fn new(scene: &Scene) -> Self {
        Self::with_options(scene, &ReferenceOptions::of(scene))
    }

    /// Prepares a validated scene for the variant `options` chooses.
    pub fn with_options(scene: &Scene, options: &ReferenceOptions) -> Self {
        let frame_origin = if options.robust {
            scene.camera.frame_origin()
        } else {
            DVec3::ZERO
        };
        let scene = &scene.translated(-frame_origin);
        let materials = std::iter::once(Material::default())
            .chain(scene.materials.values().cloned())
            .collect();
        let shapes = shapes::Shapes::new(scene);
        Self {
            uses_pixel_angle: shapes.use_pixel_angle(),
            frame_origin,
            bvh: Bvh::build(scene),
            camera: Camera::new(&scene.camera),
            lights: scene
                .lights
                .iter()
                .map(|l| PointLight {
                    position: l.position,
                    radiance: l.color * l.intensity,
                })
                .collect(),
            materials,
            shapes,
            unbounded: scene.unbounded_shapes(),
            background: scene.render.background,
            ambient: scene.render.ambient,
            max_depth: scene.render.max_depth,
            min_weight: scene.render.min_weight,
            shadows: scene.render.shadows,
            reflection: scene.render.reflection,
            refraction: scene.render.refraction,
            exposure: scene.render.exposure,
            options: options.clone(),
        }
    }

    /// This scene as a render of `height` rows traces it: with the pixel
    /// angle of that height when a Julia set needs it (a copy), else itself.
    fn sized(&self, height: u32) -> std::borrow::Cow<'_, PreparedScene> {
        let pixel_angle = self.camera.film_height / f64::from(height.max(1));
        if !self.uses_pixel_angle || self.options.pixel_angle == pixel_angle {
            return std::borrow::Cow::Borrowed(self);
        }
        let mut sized = self.clone();
        sized.options.pixel_angle = pixel_angle;
        std::borrow::Cow::Owned(sized)
    }

    /// The material of a shape.
    fn material(&self, shape: ShapeId) -> &Material {
        &self.materials[self.shapes.material(shape)]
    }
}

/// The linear radiance of every pixel of a `width x height` image, row-major
/// with row `j = 0` at the top, averaged over `spp` samples per pixel (0 is
/// taken as 1), before exposure.
///
/// Sample `k` of every pixel is R4 sample `k`: pixel offset and lens point
/// (docs/implementation.md), so at 1 sample per pixel it is the pixel centre
/// through the lens centre. Rows are traced in parallel.
pub fn render_linear(scene: &PreparedScene, width: u32, height: u32, spp: u32) -> Vec<DVec3> {
    render_linear_rotated(scene, width, height, spp, [0.0; 4])
}

/// [`render_linear`] with the samples of [`r4_rotated`] by `shift`: the
/// same image, traced through other points of the pixels and the lens. With
/// a shift of zero it is [`render_linear`].
pub fn render_linear_rotated(
    scene: &PreparedScene,
    width: u32,
    height: u32,
    spp: u32,
    shift: [f64; 4],
) -> Vec<DVec3> {
    let samples: Vec<(DVec2, DVec2)> = (0..spp.max(1))
        .map(|k| {
            let s = r4_rotated(k, shift);
            (
                DVec2::new(s[0], s[1]),
                concentric_disk(DVec2::new(s[2], s[3])),
            )
        })
        .collect();
    let mut image = vec![DVec3::ZERO; width as usize * height as usize];
    if image.is_empty() {
        return image;
    }
    let scene = &*scene.sized(height);
    image
        .par_chunks_mut(width as usize)
        .enumerate()
        .for_each(|(j, row)| {
            for (i, pixel) in row.iter_mut().enumerate() {
                *pixel = pixel_radiance(scene, width, height, i as f64, j as f64, &samples);
            }
        });
    image
}

/// The average radiance of the camera rays of pixel `(i, j)`.
fn pixel_radiance(
    scene: &PreparedScene,
    width: u32,
    height: u32,
    i: f64,
    j: f64,
    samples: &[(DVec2, DVec2)],
) -> DVec3 {
    let sum: DVec3 = samples
        .iter()
        .map(|&(offset, lens)| {
            let ray = camera_ray(
                &scene.camera,
                width,
                height,
                i + offset.x,
                j + offset.y,
                lens,
            );
            trace(scene, &ray, 0, 1.0)
        })
        .sum();
    sum / samples.len() as f64
}

/// Renders `scene` to 8-bit sRGB: [`render_linear`], then per channel the
/// exposure, clamping and [`encode_srgb8`]; alpha is 255.
pub fn render_rgba8(scene: &Scene, width: u32, height: u32, spp: u32) -> image::RgbaImage {
    let prepared = PreparedScene::new(scene);
    let linear = render_linear(&prepared, width, height, spp);
    output::to_rgba8(&linear, width, height, prepared.exposure)
}

/// Renders a prepared scene to 8-bit sRGB, as [`render_rgba8`] does.
pub fn render_prepared_rgba8(
    scene: &PreparedScene,
    width: u32,
    height: u32,
    spp: u32,
) -> image::RgbaImage {
    let linear = render_linear(scene, width, height, spp);
    output::to_rgba8(&linear, width, height, scene.exposure)
}

/// The id/depth image: for the ray through the centre of every pixel (and
/// the lens centre) the shape it hits first and the distance `t`, row-major
/// with the top row first; the twin of the shader's `fs_id` pass.
pub fn first_hits(scene: &PreparedScene, width: u32, height: u32) -> Vec<Option<(ShapeId, f64)>> {
    let mut hits = vec![None; width as usize * height as usize];
    if hits.is_empty() {
        return hits;
    }
    hits.par_chunks_mut(width as usize)
        .enumerate()
        .for_each(|(j, row)| {
            for (i, hit) in row.iter_mut().enumerate() {
                let (x, y) = (i as f64 + 0.5, j as f64 + 0.5);
                let ray = camera_ray(&scene.camera, width, height, x, y, DVec2::ZERO);
                *hit = nearest_hit(scene, &ray).map(|(shape, h)| (shape, h.t));
            }
        });
    hits
}

/// The shape that the ray through pixel coordinates `(x, y)` of a
/// `width x height` image hits first, and the point where it hits; `None`
/// when it hits nothing (or the image is empty).
///
/// `(x, y)` may be fractional: pixel `(i, j)` covers `[i, i + 1) x [j, j + 1)`
/// and its centre is `(i + 0.5, j + 0.5)`. The ray goes through the lens
/// centre, as at 1 sample per pixel.
pub fn pick(
    scene: &PreparedScene,
    width: u32,
    height: u32,
    x: f64,
    y: f64,
) -> Option<(ShapeId, DVec3)> {
    if width == 0 || height == 0 {
        return None;
    }
    lens_ray(scene, width, height, (x, y), DVec2::ZERO).1
}

/// The camera ray through pixel coordinates `(x, y)` (as [`pick`]'s) and
/// the point `lens` of the unit disc (the lens centre is `(0, 0)`), in
/// world coordinates, with the shape it hits first and where: the camera
/// model draws these (docs/ray-tree.md, "The camera model"). The image
/// must not be empty.
pub fn lens_ray(
    scene: &PreparedScene,
    width: u32,
    height: u32,
    (x, y): (f64, f64),
    lens: DVec2,
) -> (ray::Ray, Option<(ShapeId, DVec3)>) {
    let ray = camera_ray(&scene.camera, width, height, x, y, lens);
    let hit = nearest_hit(scene, &ray).map(|(shape, hit)| (shape, hit.p + scene.frame_origin));
    let world = ray::Ray {
        origin: ray.origin + scene.frame_origin,
        dir: ray.dir,
    };
    (world, hit)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::test_scenes::{FULL, NEAR_THE_ORIGIN};

    /// Camera on +z looking at the origin; 5 x 5 pixels put pixel (2, 2)'s
    /// centre on the axis. Extra TOML is appended.
    fn scene(extra: &str) -> Scene {
        toml::from_str(&format!(
            "camera = {{ from = [0, 0, 5], to = [0, 0, 0] }}\n{extra}"
        ))
        .unwrap()
    }

    fn centre_pixel(scene: &Scene) -> DVec3 {
        render_linear(&PreparedScene::new(scene), 5, 5, 1)[2 * 5 + 2]
    }

    fn close(a: DVec3, b: DVec3) -> bool {
        (a - b).length() < 1e-12
    }

    const RED_SPHERE: &str = r#"
        [render]
        background = [0.2, 0.3, 0.4]
        [materials.red]
        color = [0.8, 0.1, 0.1]
        [[spheres]]
        center = [0, 0, 0]
        radius = 1
        material = "red"
    "#;

    #[test]
    fn red_sphere_lit_from_the_camera_side() {
        let s = scene(&format!("{RED_SPHERE}\n[[lights]]\nposition = [0, 0, 10]"));
        // The centre ray hits (0, 0, 1) head on: n = l = +z, dot = 1, and
        // local = ambient 0.1 * albedo + 1 * albedo * 1 = 1.1 * albedo.
        let expected = 1.1 * DVec3::new(0.8, 0.1, 0.1);
        assert!(close(centre_pixel(&s), expected));
        // sRGB: 1.055 * 0.88^(1/2.4) - 0.055 = 0.94528 (241.05),
        //       1.055 * 0.11^(1/2.4) - 0.055 = 0.36557 (93.22).
        let img = render_rgba8(&s, 5, 5, 1);
        assert_eq!(img.get_pixel(2, 2).0, [241, 93, 93, 255]);
        // The corner ray passes the sphere at distance 5 sin(25.1 deg) > 1.
        let linear = render_linear(&PreparedScene::new(&s), 5, 5, 1);
        assert_eq!(linear[0], DVec3::new(0.2, 0.3, 0.4));
        assert_eq!(img.get_pixel(0, 0).0[3], 255);
    }

    #[test]
    fn exposure_applies_to_the_image_only() {
        let mut s = scene(&format!("{RED_SPHERE}\n[[lights]]\nposition = [0, 0, 10]"));
        s.render.exposure = 0.5;
        assert!(close(centre_pixel(&s), 1.1 * DVec3::new(0.8, 0.1, 0.1)));
        // 0.44 -> 0.69438 (177.07); 0.055 -> 0.26006 (66.31)
        assert_eq!(
            render_rgba8(&s, 5, 5, 1).get_pixel(2, 2).0,
            [177, 66, 66, 255]
        );
    }

    #[test]
    fn sphere_in_full_shadow_shows_only_ambient() {
        // The light at (3, 0, 4) sees (0, 0, 1) at 45 degrees, but a sphere
        // at the midpoint of that segment blocks it (and stays 1.5 away from
        // the camera axis).
        let s = scene(&format!(
            "{RED_SPHERE}
            [[lights]]
            position = [3, 0, 4]
            [[spheres]]
            center = [1.5, 0, 2.5]
            radius = 0.5"
        ));
        assert!(close(centre_pixel(&s), 0.1 * DVec3::new(0.8, 0.1, 0.1)));
        // Without the blocker: ambient + albedo cos 45.
        let unblocked = scene(&format!("{RED_SPHERE}\n[[lights]]\nposition = [3, 0, 4]"));
        let cos = std::f64::consts::FRAC_1_SQRT_2;
        let expected = (0.1 + cos) * DVec3::new(0.8, 0.1, 0.1);
        assert!(close(centre_pixel(&unblocked), expected));
    }

    #[test]
    fn light_behind_the_surface_adds_nothing() {
        let s = scene(&format!("{RED_SPHERE}\n[[lights]]\nposition = [0, 0, -10]"));
        assert!(close(centre_pixel(&s), 0.1 * DVec3::new(0.8, 0.1, 0.1)));
    }

    #[test]
    fn blinn_phong_highlight() {
        // Light at the camera: h = normalize(l - d) = +z = ns, highlight 1.
        let s = scene(
            r#"
            [[lights]]
            position = [0, 0, 5]
            color = [1, 0.5, 0.25]
            intensity = 2
            [materials.shiny]
            color = [0.5, 0.5, 0.5]
            diffuse = 0.5
            specular = 0.3
            [[spheres]]
            center = [0, 0, 0]
            radius = 1
            material = "shiny"
            "#,
        );
        let light = DVec3::new(2.0, 1.0, 0.5);
        // ambient * albedo * kd + light * (kd * albedo * 1 + ks * 1^32)
        let expected = DVec3::splat(0.1 * 0.5 * 0.5) + light * (0.5 * 0.5 + 0.3);
        assert!(close(centre_pixel(&s), expected));
    }

    const MIRROR: &str = r#"
        [render]
        background = [1, 1, 1]
        [materials.mirror]
        color = [0.5, 0.5, 0.5]
        diffuse = 0.5
        mirror = 0.5
        [[spheres]]
        center = [0, 0, 0]
        radius = 1
        material = "mirror"
    "#;

    #[test]
    fn max_depth_zero_gives_no_reflection() {
        // No lights: local = ambient 0.1 * 0.5 * kd 0.5 = 0.025. The centre
        // ray reflects straight back into the white background.
        let local = DVec3::splat(0.025);
        let mut s = scene(MIRROR);
        assert!(close(centre_pixel(&s), local + 0.5 * DVec3::ONE));
        s.render.max_depth = 0;
        assert!(close(centre_pixel(&s), local));
    }

    #[test]
    fn min_weight_above_kr_gives_no_reflection() {
        let local = DVec3::splat(0.025);
        let mut s = scene(MIRROR);
        s.render.min_weight = 0.6;
        assert!(close(centre_pixel(&s), local));
        // "at least min_weight": equal is traced.
        s.render.min_weight = 0.5;
        assert!(close(centre_pixel(&s), local + 0.5 * DVec3::ONE));
    }

    #[test]
    fn glass_sphere_head_on() {
        // kt = 1, ior 1.5, no local light: each surface reflects F = 0.04 and
        // transmits 0.96 (tinted by white). Depth 1: the entry's reflection
        // (background) and a refracted ray whose own children are cut off.
        let mut s = scene(
            r#"
            [render]
            background = [1, 0.5, 0.25]
            ambient = [0, 0, 0]
            [materials.glass]
            color = [1, 1, 1]
            diffuse = 0
            transparency = 1
            [[spheres]]
            center = [0, 0, 0]
            radius = 1
            material = "glass"
            "#,
        );
        let bg = DVec3::new(1.0, 0.5, 0.25);
        s.render.max_depth = 1;
        assert!(close(centre_pixel(&s), 0.04 * bg));
        // Depth 2: the refracted ray leaves through (0, 0, -1), again F = 0.04
        // (ior to 1), into the background; its internal reflection is cut off.
        s.render.max_depth = 2;
        assert!(close(centre_pixel(&s), 0.04 * bg + 0.96 * 0.96 * bg));
        // Depth 3: the internal reflection goes back to (0, 0, 1) and out.
        s.render.max_depth = 3;
        let expected = (0.04 + 0.96 * 0.96 + 0.96 * 0.04 * 0.96) * bg;
        assert!(close(centre_pixel(&s), expected));
    }

    #[test]
    fn thin_glass_plane_passes_rays_unbent_and_casts_shadows() {
        // A tilted glass plane in front of the red sphere. Its reflection
        // goes up into the black background; the transmitted ray goes on
        // along the axis (a bent ray would hit the sphere elsewhere) and sees
        // the sphere with ambient light only: the plane blocks the light.
        let mut s = scene(&format!(
            "{RED_SPHERE}
            [[lights]]
            position = [0, 0, 10]
            [materials.glass]
            color = [0.9, 1, 1]
            diffuse = 0
            transparency = 1
            ior = 1.5
            [[planes]]
            point = [0, 0, 3]
            normal = [0, 1, 1]
            material = \"glass\""
        ));
        s.render.background = DVec3::ZERO;
        let f = shade::fresnel(std::f64::consts::FRAC_1_SQRT_2, 1.0, 1.5);
        let sphere = 0.1 * DVec3::new(0.8, 0.1, 0.1);
        let expected = (1.0 - f) * DVec3::new(0.9, 1.0, 1.0) * sphere;
        assert!(close(centre_pixel(&s), expected), "{}", centre_pixel(&s));
    }

    #[test]
    fn checker_floor_seen_from_above() {
        // Looking straight down (degenerate up) at y = 0 with cells of size 1
        // and the light at the eye: pixel (2, 2) sees (0.5, 0, 0.5), in cell
        // (0, -1, 0) as q steps into the floor: odd, the checker colour.
        let s: Scene = toml::from_str(
            r#"
            camera = { from = [0.5, 3, 0.5], to = [0.5, 0, 0.5] }
            [[lights]]
            position = [0.5, 3, 0.5]
            [materials.floor]
            color = [1, 1, 1]
            checker = { color = [0.2, 0.4, 0.6], size = 1 }
            [[planes]]
            point = [0, 0, 0]
            normal = [0, 1, 0]
            material = "floor"
            "#,
        )
        .unwrap();
        let expected = 1.1 * DVec3::new(0.2, 0.4, 0.6);
        assert!(close(centre_pixel(&s), expected));
    }

    #[test]
    fn pick_finds_the_nearest_shape() {
        let s = scene(
            r#"
            [[spheres]]
            center = [0, 0, 0]
            radius = 1
            [[planes]]
            point = [0, 0, -2]
            normal = [0, 0, 1]
            [[cubes]]
            center = [0, 0, 2]
            size = 0.5
            "#,
        );
        let p = PreparedScene::new(&s);
        let (shape, point) = pick(&p, 100, 50, 50.0, 25.0).unwrap();
        assert_eq!(shape, ShapeId::Cube(0));
        assert!(
            (point - DVec3::new(0.0, 0.0, 2.25)).length() < 1e-12,
            "{point}"
        );
        // At the left edge: beside the cube and the sphere, on the back plane.
        assert_eq!(pick(&p, 100, 50, 0.0, 25.0).unwrap().0, ShapeId::Plane(0));
        assert_eq!(pick(&p, 0, 50, 0.0, 25.0), None);
    }

    #[test]
    fn first_hits_are_the_picks_of_the_pixel_centres() {
        let s = scene(
            r#"
            [[spheres]]
            center = [0, 0, 0]
            radius = 1
            [[cubes]]
            center = [0, 0, 2]
            size = 0.5
            "#,
        );
        let p = PreparedScene::new(&s);
        let hits = first_hits(&p, 9, 7);
        assert_eq!(hits.len(), 63);
        for j in 0..7 {
            for i in 0..9 {
                let picked = pick(&p, 9, 7, f64::from(i) + 0.5, f64::from(j) + 0.5);
                assert_eq!(
                    hits[j as usize * 9 + i as usize].map(|h| h.0),
                    picked.map(|p| p.0)
                );
            }
        }
        assert_eq!(hits[3 * 9 + 4].unwrap().0, ShapeId::Cube(0));
        assert_eq!(hits[3 * 9 + 4].unwrap().1, 2.75);
        assert!(first_hits(&p, 0, 7).is_empty());
    }

    #[test]
    fn naive_variant_breaks_where_the_robust_one_does_not() {
        // A glass ball of radius 2e-4 under a light: the fixed offset of
        // 1e-3 starts the refracted ray beyond the ball's far side, so the
        // naive image differs; the robust one is the image of the same
        // scene 1000 times larger.
        let text = |k: f64| {
            format!(
                "camera = {{ from = [0, 0, {}], to = [0, 0, 0], fov = 30 }}
                render = {{ background = [0.2, 0.4, 0.8] }}
                lights = [{{ position = [{}, {}, {}] }}]
                materials.glass = {{ color = [1, 1, 1], diffuse = 0.2, transparency = 0.8 }}
                [[spheres]]
                center = [0, 0, 0]
                radius = {}
                material = \"glass\"
                [[planes]]
                point = [0, {}, 0]
                normal = [0, 1, 0]",
                1e-3 * k,
                k,
                k,
                k,
                2e-4 * k,
                -3e-4 * k
            )
        };
        let small: Scene = toml::from_str(&text(1.0)).unwrap();
        let big: Scene = toml::from_str(&text(1000.0)).unwrap();
        let robust = |s: &Scene| render_linear(&PreparedScene::new(s), 24, 16, 1);
        let naive = |s: &Scene| {
            let options = ReferenceOptions {
                robust: false,
                ..Default::default()
            };
            render_linear(&PreparedScene::with_options(s, &options), 24, 16, 1)
        };
        // Mean over the pixels of the largest channel difference.
        let diff = |a: &[DVec3], b: &[DVec3]| {
            a.iter()
                .zip(b)
                .map(|(x, y)| (*x - *y).abs().max_element())
                .sum::<f64>()
                / a.len() as f64
        };
        let (same, naive_big, naive_small) = (
            diff(&robust(&small), &robust(&big)),
            diff(&naive(&big), &robust(&big)),
            diff(&naive(&small), &robust(&small)),
        );
        assert!(same < 1e-9, "{same}");
        assert!(naive_big < 0.001, "1e-3 is small against 0.2: {naive_big}");
        assert!(naive_small > 0.01, "{naive_small}");
    }

    /// The reference traces relative to the target in f64: the scene moved
    /// 1e6 away renders the image of the scene at the origin (its exact
    /// answer) to far below an 8-bit level, and `pick` answers in world
    /// coordinates.
    #[test]
    fn a_translated_scene_renders_the_same_image() {
        let s: Scene = toml::from_str(NEAR_THE_ORIGIN).unwrap();
        let offset = DVec3::new(-1e6, 1e6, -1e6);
        let far = s.translated(offset);
        let a = render_linear(&PreparedScene::new(&s), 24, 16, 1);
        let b = render_linear(&PreparedScene::new(&far), 24, 16, 1);
        let worst = a
            .iter()
            .zip(&b)
            .map(|(x, y)| (*x - *y).abs().max_element())
            .fold(0.0, f64::max);
        assert!(worst < 1e-6, "largest difference {worst}");
        let (shape, p) = pick(&PreparedScene::new(&far), 24, 16, 12.5, 8.5).unwrap();
        let (shape0, p0) = pick(&PreparedScene::new(&s), 24, 16, 12.5, 8.5).unwrap();
        assert_eq!(shape, shape0);
        assert!((p - offset - p0).length() < 1e-8, "{p} vs {p0}");
    }

    #[test]
    fn pick_misses() {
        let p = PreparedScene::new(&scene(RED_SPHERE));
        assert_eq!(pick(&p, 10, 10, 0.0, 0.0), None);
        assert_eq!(pick(&p, 10, 10, 5.0, 5.0).unwrap().0, ShapeId::Sphere(0));
    }

    #[test]
    fn empty_images_and_zero_spp() {
        let p = PreparedScene::new(&scene(RED_SPHERE));
        assert!(render_linear(&p, 0, 7, 1).is_empty());
        assert_eq!(
            render_rgba8(&scene(RED_SPHERE), 7, 0, 1).dimensions(),
            (7, 0)
        );
        assert_eq!(render_linear(&p, 3, 3, 0), render_linear(&p, 3, 3, 1));
    }

    #[test]
    fn many_samples_average_and_stay_finite() {
        // A thin lens with several samples: everything finite, and a pixel
        // that sees only background stays exactly background.
        let mut s = scene(&format!("{RED_SPHERE}\n[[lights]]\nposition = [0, 0, 10]"));
        s.camera.aperture = 0.1;
        let linear = render_linear(&PreparedScene::new(&s), 9, 9, 16);
        assert!(linear.iter().all(|c| c.is_finite()));
        assert!(close(linear[0], DVec3::new(0.2, 0.3, 0.4)));
    }

    #[test]
    fn full_scene_has_no_nan() {
        // The scene with every feature of the format, with a camera straight above as well.
        let mut s: Scene = toml::from_str(FULL).unwrap();
        for from in [DVec3::new(0.0, 1.5, 6.0), DVec3::new(0.0, 9.0, 0.0)] {
            s.camera.from = from;
            let linear = render_linear(&PreparedScene::new(&s), 40, 30, 2);
            assert!(
                linear
                    .iter()
                    .all(|c| c.is_finite() && c.min_element() >= 0.0)
            );
        }
    }
}
