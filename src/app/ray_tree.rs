//! A pixel's ray tree in the viewer (docs/ray-tree.md): Shift+click or `T`
//! over the picture asks for it. The f64 reference traces it at once (one
//! pixel is cheap); the GPU's debug pass runs on a worker thread, because
//! its pipeline takes seconds to compile on lavapipe and its readback
//! waits for the GPU. The panel shows both trees side by side (the text of
//! `raysandbox ray-tree`), and the rays are drawn in 3D over the picture.

use glam::DVec3;

use crate::gpu::{GpuRayTree, Segment};
use crate::reference::{self, RayKind, RayTree, TreeRay};
use crate::scene::Scene;

/// The colours of the rays drawn over the picture (sRGB), one per kind: a
/// saturated colour that the bundled scenes' pictures do not have, so that
/// each kind stands out (and a test can find it, tests/ray_tree_window.rs).
pub const CAMERA_COLOUR: [u8; 3] = [255, 255, 255];
pub const REFLECTED_COLOUR: [u8; 3] = [0, 255, 255];
pub const REFRACTED_COLOUR: [u8; 3] = [0, 255, 0];
pub const TOTAL_INTERNAL_COLOUR: [u8; 3] = [255, 0, 255];
pub const SHADOW_COLOUR: [u8; 3] = [255, 255, 0];
/// A shadow ray that something blocks before its light.
pub const BLOCKED_COLOUR: [u8; 3] = [110, 110, 110];
/// The shading normal at a hit, drawn as a short arrow.
pub const NORMAL_COLOUR: [u8; 3] = [255, 128, 0];

/// How long a ray that misses everything is drawn, in eye-target
/// distances (it goes on to the background).
const MISS_LENGTH: f64 = 1.5;
/// A normal arrow's length and a hit point's cross's half size, in
/// eye-target distances.
const NORMAL_LENGTH: f64 = 0.08;
const MARKER_SIZE: f64 = 0.01;

/// What the GPU answered for a tree.
#[derive(Debug, Clone, PartialEq)]
pub enum GpuAnswer {
    /// The worker traces it.
    Tracing,
    Traced(GpuRayTree),
    /// Why there is none: an error, or the web page (which cannot wait
    /// for a readback).
    Missing(String),
}

/// The tree of one pixel, as the panel shows it and the overlay draws it.
#[derive(Debug, Clone, PartialEq)]
pub struct PixelTree {
    /// The pixel, from the top left, of an image of `size` (the window's).
    pub pixel: (u32, u32),
    pub size: (u32, u32),
    pub reference: RayTree,
    pub gpu: GpuAnswer,
    /// Both trees as text (`reference::describe_trees`).
    pub text: String,
    /// Its rays, hit points and normals in world coordinates.
    pub segments: Vec<Segment>,
    /// Counts the trees asked for: an answer for an older one is dropped.
    pub number: u64,
}

impl PixelTree {
    /// The reference's tree of `pixel` of a `size` image of `scene` (as the
    /// viewer draws it), waiting for the GPU's.
    pub fn new(scene: &Scene, size: (u32, u32), pixel: (u32, u32), number: u64) -> PixelTree {
        let prepared = reference::PreparedScene::new(scene);
        let reference = reference::ray_tree(&prepared, size.0, size.1, pixel.0, pixel.1);
        let segments = segments(&reference, scene.view_scale());
        let mut tree = PixelTree {
            pixel,
            size,
            reference,
            gpu: GpuAnswer::Tracing,
            text: String::new(),
            segments,
            number,
        };
        tree.describe();
        tree
    }

    /// Takes the GPU's answer.
    pub fn answered(&mut self, gpu: GpuAnswer) {
        self.gpu = gpu;
        self.describe();
    }

    fn describe(&mut self) {
        let gpu = match &self.gpu {
            GpuAnswer::Traced(traced) => Some(&traced.tree),
            _ => None,
        };
        self.text = reference::describe_trees(&self.reference, gpu);
        if let GpuAnswer::Traced(traced) = &self.gpu
            && traced.total > traced.tree.rays.len()
        {
            self.text += &format!(
                "the GPU traced {} rays and kept the first {}\n",
                traced.total,
                traced.tree.rays.len()
            );
        }
    }

    /// One line for the status line and the panel's heading.
    pub fn summary(&self) -> String {
        let (x, y) = self.pixel;
        let rays = self.reference.rays.len();
        let gpu = match &self.gpu {
            GpuAnswer::Tracing => "the GPU's is being traced".to_string(),
            GpuAnswer::Missing(why) => format!("no GPU tree: {why}"),
            GpuAnswer::Traced(traced) => {
                match reference::compare_trees(&self.reference, &traced.tree) {
                    Ok(differences) => format!(
                        "the GPU's has the same rays, contributions within {:.1e}",
                        differences
                            .iter()
                            .map(|d| d.contribution)
                            .fold(0.0, f64::max)
                    ),
                    Err(part) => format!("the GPU's parts at {part}"),
                }
            }
        };
        format!("ray tree of pixel {x},{y}: {rays} rays; {gpu}")
    }

    /// The event line told once the GPU has answered (`--print-events`).
    pub fn event(&self) -> String {
        let (x, y) = self.pixel;
        let gpu = match &self.gpu {
            GpuAnswer::Traced(traced) => traced.tree.rays.len().to_string(),
            _ => "none".to_string(),
        };
        format!(
            "ray-tree {x},{y} rays={} gpu={gpu}",
            self.reference.rays.len()
        )
    }
}

/// The colour a ray is drawn in.
fn colour(ray: &TreeRay) -> [u8; 3] {
    match ray.kind {
        RayKind::Camera => CAMERA_COLOUR,
        RayKind::Reflected => REFLECTED_COLOUR,
        RayKind::Refracted => REFRACTED_COLOUR,
        RayKind::TotalInternal => TOTAL_INTERNAL_COLOUR,
        RayKind::Shadow if ray.blocked => BLOCKED_COLOUR,
        RayKind::Shadow => SHADOW_COLOUR,
    }
}

/// The tree drawn in 3D: each ray from its origin to its hit (a shadow
/// ray to its light, a miss `MISS_LENGTH` eye-target distances `scale`
/// on), and at each hit a small cross and the shading normal as an arrow.
pub fn segments(tree: &RayTree, scale: f64) -> Vec<Segment> {
    let mut out = Vec::new();
    for ray in &tree.rays {
        let end = ray
            .end()
            .unwrap_or(ray.origin + MISS_LENGTH * scale * ray.dir);
        out.push(Segment {
            a: ray.origin,
            b: end,
            colour: colour(ray),
        });
        if ray.kind != RayKind::Shadow && ray.shape.is_some() {
            out.extend(cross(end, MARKER_SIZE * scale));
            out.extend(arrow(end, ray.normal, -ray.dir, NORMAL_LENGTH * scale));
        }
    }
    out
}

/// Three short white segments through `p` along the axes.
fn cross(p: DVec3, half: f64) -> [Segment; 3] {
    [DVec3::X, DVec3::Y, DVec3::Z].map(|axis| Segment {
        a: p - half * axis,
        b: p + half * axis,
        colour: CAMERA_COLOUR,
    })
}

/// An arrow `length` long from `p` along the unit `normal`, its head in
/// the plane of the normal and `towards` (the way back along the ray), so
/// that it shows from the side the ray came from.
fn arrow(p: DVec3, normal: DVec3, towards: DVec3, length: f64) -> [Segment; 3] {
    let tip = p + length * normal;
    let side = towards
        .reject_from(normal)
        .try_normalize()
        .unwrap_or_else(|| normal.any_orthonormal_vector());
    let back = tip - 0.3 * length * normal;
    let segment = |a, b| Segment {
        a,
        b,
        colour: NORMAL_COLOUR,
    };
    [
        segment(p, tip),
        segment(tip, back + 0.15 * length * side),
        segment(tip, back - 0.15 * length * side),
    ]
}

/// The GPU's side on native targets: a thread per tree, which builds the
/// debug pass (kept for the next tree of the same pipeline variant) and
/// traces the pixel, then wakes the window.
#[cfg(not(target_arch = "wasm32"))]
pub mod worker {
    use std::sync::mpsc::{Receiver, Sender, channel};
    use std::sync::{Arc, Mutex, PoisonError};

    use super::GpuAnswer;
    use crate::gpu::{Gpu, RayTreeRenderer, ShaderOptions, ShaderSource};
    use crate::scene::Scene;

    /// The debug pass of the last pipeline variant: one, whatever the
    /// number of variants met (its compilation is what takes seconds).
    type Cached = Option<(ShaderSource, ShaderOptions, Arc<RayTreeRenderer>)>;

    /// What a worker thread needs to trace tree `number`.
    pub struct Request {
        pub gpu: Gpu,
        pub source: ShaderSource,
        pub options: ShaderOptions,
        pub scene: Scene,
        pub size: (u32, u32),
        pub pixel: (u32, u32),
        pub number: u64,
    }

    pub struct Worker {
        sender: Sender<(u64, GpuAnswer)>,
        answers: Receiver<(u64, GpuAnswer)>,
        /// Shared with the threads; one builds at a time, the others wait.
        cached: Arc<Mutex<Cached>>,
    }

    impl Default for Worker {
        fn default() -> Self {
            let (sender, answers) = channel();
            Worker {
                sender,
                answers,
                cached: Arc::default(),
            }
        }
    }

    impl Worker {
        /// Traces `request` on a thread of its own; `wake` is called once
        /// the answer can be taken.
        pub fn trace(&self, request: Request, wake: impl Fn() + Send + 'static) {
            let (sender, cached) = (self.sender.clone(), Arc::clone(&self.cached));
            std::thread::spawn(move || {
                let answer = match traced(&request, &cached) {
                    Ok(tree) => GpuAnswer::Traced(tree),
                    Err(e) => GpuAnswer::Missing(e),
                };
                if sender.send((request.number, answer)).is_ok() {
                    wake();
                }
            });
        }

        /// The answers that came in since the last call, the last one last.
        pub fn take(&self) -> Option<(u64, GpuAnswer)> {
            self.answers.try_iter().last()
        }

        /// Forgets the debug pass: it belongs to a device that is gone.
        pub fn forget(&self) {
            *self.cached.lock().unwrap_or_else(PoisonError::into_inner) = None;
        }
    }

    fn traced(request: &Request, cached: &Mutex<Cached>) -> Result<crate::gpu::GpuRayTree, String> {
        let mut cached = cached.lock().unwrap_or_else(PoisonError::into_inner);
        let renderer = match &*cached {
            Some((source, options, renderer))
                if *source == request.source && *options == request.options =>
            {
                Arc::clone(renderer)
            }
            _ => {
                let renderer =
                    RayTreeRenderer::new(&request.gpu, &request.source, &request.options)
                        .map_err(|e| e.to_string())?;
                let renderer = Arc::new(renderer);
                *cached = Some((
                    request.source.clone(),
                    request.options.clone(),
                    Arc::clone(&renderer),
                ));
                renderer
            }
        };
        drop(cached);
        renderer
            .trace(&request.gpu, &request.scene, request.size, request.pixel)
            .map_err(|e| e.to_string())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A glass sphere in front of the camera: the tree's segments start at
    /// each ray's origin and end at its hit, and every hit gets a cross and
    /// a normal arrow pointing out of the surface towards the ray.
    #[test]
    fn every_ray_and_hit_is_drawn() {
        let scene = Scene::from_toml_str(
            "camera = { from = [0, 0, 5], to = [0, 0, 0] }
            lights = [{ position = [0, 3, 10] }]
            [materials.glass]
            transparency = 1
            ior = 1.5
            [[spheres]]
            center = [0, 0, 0]
            radius = 1
            material = \"glass\"",
            None,
        )
        .unwrap();
        let tree = PixelTree::new(&scene, (9, 9), (4, 4), 1);
        let rays = &tree.reference.rays;
        assert_eq!(rays[0].kind, RayKind::Camera);
        assert!(rays.iter().any(|r| r.kind == RayKind::Refracted));
        let hits = rays
            .iter()
            .filter(|r| r.kind != RayKind::Shadow && r.shape.is_some())
            .count();
        assert_eq!(tree.segments.len(), rays.len() + 6 * hits);
        assert_eq!(tree.segments[0].a, rays[0].origin);
        assert!((tree.segments[0].b - DVec3::new(0.0, 0.0, 1.0)).length() < 1e-9);
        // The camera ray's normal arrow: from the front of the sphere
        // towards the eye, NORMAL_LENGTH eye-target distances long.
        let normal = tree.segments[4];
        assert_eq!(normal.colour, NORMAL_COLOUR);
        assert!((normal.b - normal.a - DVec3::new(0.0, 0.0, 0.4)).length() < 1e-9);
        assert_eq!(tree.gpu, GpuAnswer::Tracing);
        assert!(tree.summary().starts_with("ray tree of pixel 4,4: "));
        assert!(
            tree.text
                .starts_with("ray 0: camera, depth 0, hits Sphere 0")
        );
    }
}
