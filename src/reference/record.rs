//! What the f64 tracer tells while it traces (`shade.rs`), ray by ray: the
//! interface between the recursion and the recorder of a pixel's ray tree
//! (`ray_tree.rs`, docs/ray-tree.md), kept apart so that neither imports
//! the other.

use glam::DVec3;

use super::intersect::{Hit, ShapeId};
use super::ray::Ray;

/// What a ray of the tree is for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RayKind {
    /// From the eye through the pixel.
    Camera,
    /// A mirror ray (the mirror term, or the Fresnel part of glass).
    Reflected,
    /// A ray bent into or out of glass by Snell's law.
    Refracted,
    /// The reflected ray of glass met from inside beyond the critical
    /// angle: Fresnel's F is 1 and nothing is transmitted.
    TotalInternal,
    /// From a hit point towards a light.
    Shadow,
}

impl RayKind {
    /// The names the panel and `raysandbox ray-tree` print.
    pub fn name(self) -> &'static str {
        match self {
            RayKind::Camera => "camera",
            RayKind::Reflected => "reflected",
            RayKind::Refracted => "refracted",
            RayKind::TotalInternal => "total internal",
            RayKind::Shadow => "shadow",
        }
    }

    /// The kind from its number (the shader's `TREE_*` in
    /// `shaders/ray_tree.wgsl`, this enum's order).
    pub fn from_number(n: u32) -> Option<RayKind> {
        [
            RayKind::Camera,
            RayKind::Reflected,
            RayKind::Refracted,
            RayKind::TotalInternal,
            RayKind::Shadow,
        ]
        .get(n as usize)
        .copied()
    }
}

/// What `shade.rs` tells while it traces. Every method does nothing by
/// default: `()` is the recorder of the renderers.
pub(super) trait Recorder {
    /// A ray of `kind` is about to be traced; its radiance counts `factor`
    /// times in its parent's (the weight `wr`, or `wt * albedo`).
    fn begin(&mut self, _kind: RayKind, _ray: &Ray, _factor: DVec3) {}
    /// It hit `shape`; `ns` is the shading normal facing it.
    fn hit(&mut self, _shape: ShapeId, _hit: &Hit, _ns: DVec3) {}
    /// It hit nothing and sees `background`.
    fn missed(&mut self, _background: DVec3) {}
    /// A shadow ray from its hit to light `light`, `distance` away;
    /// `term` is what the light adds (zero when `blocked`).
    fn shadow(&mut self, _light: usize, _ray: &Ray, _distance: f64, _blocked: bool, _term: DVec3) {}
    /// Its hit's local light and how the rest divides.
    fn split(&mut self, _local: DVec3, _fresnel: f64, _wr: f64, _wt: f64) {}
    /// It and its children are done.
    fn end(&mut self) {}
}

impl Recorder for () {}
