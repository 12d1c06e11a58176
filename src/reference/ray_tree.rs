//! A pixel's Whitted ray tree (docs/ray-tree.md), in f64: every ray the
//! reference traces for the ray through the centre of one pixel (and the
//! centre of the lens), with what it met and what it added to the pixel.
//!
//! Read it beside the lecture's recursion
//! `trace(ray) = local + wr trace(reflected) + wt albedo trace(refracted)`
//! (docs/rendering-model.md, "Whitted shading"): the tree is not traced
//! again here. `shade.rs` traces it as it always does and tells a
//! [`Recorder`] what happens, ray by ray, in the order it happens (depth
//! first, the reflected child before the refracted one, the shader's order
//! too). [`RayTree`] is the recorder that writes it down; the renderers use
//! `()`, which records nothing and compiles to nothing.

use glam::{DVec2, DVec3};

use super::PreparedScene;
use super::camera::camera_ray;
use super::intersect::{Hit, ShapeId};
use super::ray::Ray;
use super::record::{RayKind, Recorder};
use super::shade::trace_recorded;

/// One ray of a pixel's tree. Positions are in world coordinates.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TreeRay {
    pub kind: RayKind,
    /// Bounces before this ray: 0 for the camera ray; a shadow ray has its
    /// parent's.
    pub depth: u32,
    /// The ray whose hit cast this one (an index into [`RayTree::rays`]).
    pub parent: Option<usize>,
    /// Where it starts: the eye for the camera ray, the offset hit point
    /// for the others.
    pub origin: DVec3,
    /// Unit direction.
    pub dir: DVec3,
    /// The distance to the hit (`None`: it hits nothing and sees the
    /// background); for a shadow ray the distance to its light.
    pub t: Option<f64>,
    /// The shape hit; for a shadow ray, `None`.
    pub shape: Option<ShapeId>,
    /// The shading normal at the hit, turned to face the ray (zero on a
    /// miss and for shadow rays).
    pub normal: DVec3,
    /// Fresnel's reflectance F at the hit (0 where the material has no
    /// transparency), and the weights of the reflected ray,
    /// `wr = kr + kt F`, and of the refracted one, `wt = kt (1 - F)`.
    pub fresnel: f64,
    pub wr: f64,
    pub wt: f64,
    /// What this ray's radiance is multiplied by in the pixel: the product
    /// of the weights (and a refracted ray's albedo) from the camera ray
    /// down to it.
    pub throughput: DVec3,
    /// What it adds to the pixel: `throughput * local` at a hit (ambient
    /// and every light together), `throughput * background` on a miss;
    /// for a shadow ray the light's own term (zero when it is blocked),
    /// part of its parent's. The rays that are not shadow rays add up to
    /// the pixel's colour.
    pub contribution: DVec3,
    /// A shadow ray's light (its index in the scene's `lights`).
    pub light: Option<usize>,
    /// Whether a shadow ray was blocked before its light.
    pub blocked: bool,
}

impl TreeRay {
    /// The hit point, where the ray has one (and a shadow ray's light).
    pub fn end(&self) -> Option<DVec3> {
        self.t.map(|t| self.origin + t * self.dir)
    }
}

/// A pixel's Whitted tree, the rays in the order traced (depth first).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct RayTree {
    pub rays: Vec<TreeRay>,
    /// The pixel's radiance (linear, before exposure): the sum of the
    /// contributions of the rays that are not shadow rays.
    pub radiance: DVec3,
    /// The rays being traced, innermost last (recording only).
    open: Vec<usize>,
    /// Added to every position: the frame origin the scene was moved by.
    frame_origin: DVec3,
}

impl Recorder for RayTree {
    fn begin(&mut self, kind: RayKind, ray: &Ray, factor: DVec3) {
        let parent = self.open.last().copied();
        let (depth, throughput) = match parent {
            Some(p) => (self.rays[p].depth + 1, self.rays[p].throughput * factor),
            None => (0, factor),
        };
        self.open.push(self.rays.len());
        self.rays.push(TreeRay {
            kind,
            depth,
            parent,
            origin: ray.origin + self.frame_origin,
            dir: ray.dir,
            t: None,
            shape: None,
            normal: DVec3::ZERO,
            fresnel: 0.0,
            wr: 0.0,
            wt: 0.0,
            throughput,
            contribution: DVec3::ZERO,
            light: None,
            blocked: false,
        });
    }

    fn hit(&mut self, shape: ShapeId, hit: &Hit, ns: DVec3) {
        let ray = self.current();
        ray.t = Some(hit.t);
        ray.shape = Some(shape);
        ray.normal = ns;
    }

    fn missed(&mut self, background: DVec3) {
        let ray = self.current();
        ray.contribution = ray.throughput * background;
    }

    fn shadow(&mut self, light: usize, ray: &Ray, distance: f64, blocked: bool, term: DVec3) {
        let parent = *self.open.last().expect("a shadow ray has a parent");
        let p = self.rays[parent];
        self.rays.push(TreeRay {
            kind: RayKind::Shadow,
            depth: p.depth,
            parent: Some(parent),
            origin: ray.origin + self.frame_origin,
            dir: ray.dir,
            t: Some(distance),
            shape: None,
            normal: DVec3::ZERO,
            fresnel: 0.0,
            wr: 0.0,
            wt: 0.0,
            throughput: p.throughput,
            contribution: p.throughput * term,
            light: Some(light),
            blocked,
        });
    }

    fn split(&mut self, local: DVec3, fresnel: f64, wr: f64, wt: f64) {
        let ray = self.current();
        ray.contribution = ray.throughput * local;
        (ray.fresnel, ray.wr, ray.wt) = (fresnel, wr, wt);
    }

    fn end(&mut self) {
        self.open.pop();
    }
}

impl RayTree {
    /// A tree of these rays (the GPU's, read back): its radiance is the
    /// sum of their contributions.
    pub fn from_rays(rays: Vec<TreeRay>) -> RayTree {
        let radiance = rays
            .iter()
            .filter(|r| r.kind != RayKind::Shadow)
            .map(|r| r.contribution)
            .sum();
        RayTree {
            rays,
            radiance,
            ..RayTree::default()
        }
    }

    /// The ray being traced.
    fn current(&mut self) -> &mut TreeRay {
        let i = *self.open.last().expect("a ray is being traced");
        &mut self.rays[i]
    }
}

/// The tree of the ray through the centre of pixel `(i, j)` of a
/// `width x height` image (row 0 at the top) and the lens centre: the ray
/// of the first sample, as the GPU's debug pass traces it
/// (`gpu::RayTreeRenderer`).
pub fn ray_tree(scene: &PreparedScene, width: u32, height: u32, i: u32, j: u32) -> RayTree {
    let scene = scene.sized(height);
    let (x, y) = (f64::from(i) + 0.5, f64::from(j) + 0.5);
    let ray = camera_ray(&scene.camera, width, height, x, y, DVec2::ZERO);
    let mut tree = RayTree {
        frame_origin: scene.frame_origin,
        ..RayTree::default()
    };
    tree.begin(RayKind::Camera, &ray, DVec3::ONE);
    tree.radiance = trace_recorded(&scene, &ray, 0, 1.0, &mut tree);
    tree.end();
    tree
}

/// How far one ray of a tree is from the same ray of another tree of the
/// same pixel (the GPU's against the reference's).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct RayDifference {
    /// `|a - b|` of the origins relative to `max(|a|, 1)` (a shadow ray
    /// from the floor near the horizon starts far away), and of the
    /// directions and normals.
    pub origin: f64,
    pub dir: f64,
    pub normal: f64,
    /// `|a - b|` of the distances, relative to the larger.
    pub t: f64,
    /// The largest `|a - b|` of F, `wr` and `wt`.
    pub weights: f64,
    /// The largest `|a - b|` of a channel of the contributions.
    pub contribution: f64,
}

impl RayDifference {
    /// The larger of each field.
    pub fn max(self, o: RayDifference) -> RayDifference {
        RayDifference {
            origin: self.origin.max(o.origin),
            dir: self.dir.max(o.dir),
            normal: self.normal.max(o.normal),
            t: self.t.max(o.t),
            weights: self.weights.max(o.weights),
            contribution: self.contribution.max(o.contribution),
        }
    }
}

/// The differences ray by ray of two trees of the same pixel; `Err`
/// naming the first ray where they part: another kind, parent, shape,
/// light or shadow, or one tree longer (a ray that grazes an edge, or a
/// glass surface met near the critical angle, can go either way in f32).
pub fn compare(a: &RayTree, b: &RayTree) -> Result<Vec<RayDifference>, String> {
    let mut differences = Vec::with_capacity(a.rays.len());
    for (i, (x, y)) in a.rays.iter().zip(&b.rays).enumerate() {
        let same = (x.kind, x.parent, x.shape, x.light, x.blocked, x.t.is_some())
            == (y.kind, y.parent, y.shape, y.light, y.blocked, y.t.is_some());
        if !same {
            return Err(format!("ray {i}: {} against {}", summary(x), summary(y)));
        }
        let t = match (x.t, y.t) {
            (Some(p), Some(q)) => (p - q).abs() / p.abs().max(q.abs()).max(f64::MIN_POSITIVE),
            _ => 0.0,
        };
        differences.push(RayDifference {
            origin: (x.origin - y.origin).length() / x.origin.length().max(1.0),
            dir: (x.dir - y.dir).length(),
            normal: (x.normal - y.normal).length(),
            t,
            weights: (x.fresnel - y.fresnel)
                .abs()
                .max((x.wr - y.wr).abs())
                .max((x.wt - y.wt).abs()),
            contribution: (x.contribution - y.contribution).abs().max_element(),
        });
    }
    if a.rays.len() != b.rays.len() {
        return Err(format!("{} rays against {}", a.rays.len(), b.rays.len()));
    }
    Ok(differences)
}

/// One line naming a ray: its kind, what it came from and what it met.
pub fn summary(r: &TreeRay) -> String {
    let parent = r.parent.map_or(String::new(), |p| format!(" from ray {p}"));
    let met = match (r.kind, r.shape, r.t) {
        (RayKind::Shadow, _, _) => format!(
            "to light {}, {}",
            r.light.unwrap_or(0),
            if r.blocked { "blocked" } else { "free" }
        ),
        (_, Some(shape), Some(_)) => format!("hits {} {}", shape.kind().name(), shape.index()),
        _ => "misses (background)".to_string(),
    };
    format!("{}{parent}, depth {}, {met}", r.kind.name(), r.depth)
}

/// A tree as text, ray by ray; with a second tree of the same pixel (the
/// GPU's), each quantity of both side by side with their difference. What
/// the panel and `raysandbox ray-tree` show.
pub fn describe(reference: &RayTree, gpu: Option<&RayTree>) -> String {
    let mut text = String::new();
    let v = |x: DVec3| format!("({:10.6}, {:10.6}, {:10.6})", x.x, x.y, x.z);
    let s = |x: Option<f64>| x.map_or("-".to_string(), |x| format!("{x:.6}"));
    for (i, r) in reference.rays.iter().enumerate() {
        let other = gpu.and_then(|g| g.rays.get(i));
        text += &format!("ray {i}: {}\n", summary(r));
        let rows: [(&str, String, Option<String>, Option<f64>); 7] = [
            (
                "origin",
                v(r.origin),
                other.map(|o| v(o.origin)),
                other.map(|o| (r.origin - o.origin).length()),
            ),
            (
                "direction",
                v(r.dir),
                other.map(|o| v(o.dir)),
                other.map(|o| (r.dir - o.dir).length()),
            ),
            (
                "t",
                s(r.t),
                other.map(|o| s(o.t)),
                other.and_then(|o| Some((r.t? - o.t?).abs())),
            ),
            (
                "normal",
                v(r.normal),
                other.map(|o| v(o.normal)),
                other.map(|o| (r.normal - o.normal).length()),
            ),
            (
                "F wr wt",
                format!("{:.6} {:.6} {:.6}", r.fresnel, r.wr, r.wt),
                other.map(|o| format!("{:.6} {:.6} {:.6}", o.fresnel, o.wr, o.wt)),
                other.map(|o| {
                    (r.fresnel - o.fresnel)
                        .abs()
                        .max((r.wr - o.wr).abs())
                        .max((r.wt - o.wt).abs())
                }),
            ),
            (
                "throughput",
                v(r.throughput),
                other.map(|o| v(o.throughput)),
                other.map(|o| (r.throughput - o.throughput).abs().max_element()),
            ),
            (
                "contribution",
                v(r.contribution),
                other.map(|o| v(o.contribution)),
                other.map(|o| (r.contribution - o.contribution).abs().max_element()),
            ),
        ];
        for (name, mine, theirs, difference) in rows {
            if r.kind == RayKind::Shadow && matches!(name, "normal" | "F wr wt") {
                continue;
            }
            text += &format!("  {name:<12} {mine}");
            if let (Some(theirs), Some(d)) = (theirs, difference) {
                text += &format!("  gpu {theirs}  diff {d:.1e}");
            }
            text += "\n";
        }
    }
    text += &format!("radiance {}", v(reference.radiance));
    if let Some(g) = gpu {
        text += &format!(
            "  gpu {}  diff {:.1e}",
            v(g.radiance),
            (reference.radiance - g.radiance).abs().max_element()
        );
        if let Err(e) = compare(reference, g) {
            text += &format!("\nthe trees part at {e}");
        }
    }
    text + "\n"
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Scene;

    /// A glass sphere in front of the camera, a light behind the camera.
    fn glass() -> PreparedScene {
        let text = "camera = { from = [0, 0, 5], to = [0, 0, 0] }
            lights = [{ position = [0, 3, 10] }]
            [render]
            max_depth = 4
            min_weight = 0
            [materials.glass]
            color = [1, 1, 1]
            diffuse = 0
            specular = 0.5
            transparency = 1
            ior = 1.5
            [[spheres]]
            center = [0, 0, 0]
            radius = 1
            material = \"glass\"";
        PreparedScene::new(&toml::from_str::<Scene>(text).unwrap())
    }

    #[test]
    fn the_contributions_add_up_to_the_pixel() {
        let scene = glass();
        for (i, j) in [(2, 2), (1, 2), (0, 0), (3, 1)] {
            let tree = ray_tree(&scene, 5, 5, i, j);
            let sum: DVec3 = tree
                .rays
                .iter()
                .filter(|r| r.kind != RayKind::Shadow)
                .map(|r| r.contribution)
                .sum();
            assert!((sum - tree.radiance).length() < 1e-12, "{i} {j}");
            let expected = super::super::render_linear(&scene, 5, 5, 1)[(j * 5 + i) as usize];
            assert!((tree.radiance - expected).length() < 1e-12);
        }
    }

    #[test]
    fn the_centre_ray_passes_through_the_glass() {
        let tree = ray_tree(&glass(), 5, 5, 2, 2);
        let kinds: Vec<RayKind> = tree.rays.iter().map(|r| r.kind).collect();
        // The camera ray hits the front (its shadow ray is blocked by
        // nothing: the light is behind the camera); reflected back out;
        // refracted straight through to the back, where it reflects
        // inside and leaves.
        assert_eq!(kinds[0], RayKind::Camera);
        assert_eq!(kinds[1], RayKind::Shadow);
        assert_eq!(kinds[2], RayKind::Reflected);
        let camera = &tree.rays[0];
        assert!((camera.t.unwrap() - 4.0).abs() < 1e-12);
        assert!((camera.fresnel - 0.04).abs() < 1e-12);
        assert!((camera.normal - DVec3::Z).length() < 1e-12);
        let refracted = tree
            .rays
            .iter()
            .position(|r| r.kind == RayKind::Refracted)
            .unwrap();
        assert_eq!(tree.rays[refracted].parent, Some(0));
        assert!((tree.rays[refracted].t.unwrap() - 2.0).abs() < 1e-9);
        assert!((tree.rays[refracted].throughput - DVec3::splat(0.96)).length() < 1e-12);
    }
}
