//! What the implicit surfaces (torus, user function, Julia set) share: a
//! shape written in local coordinates, placed in the world by `translate`,
//! `scale` and `rotation` (docs/rendering-model.md, "Implicit surfaces").

use glam::{DMat3, DVec3};

use crate::reference::hit::{Hit, foot};
use crate::reference::ray::Ray;
use crate::scene::Placement;

/// A placement made ready for ray tests: world = `center + scale * rotation * local`.
#[derive(Debug, Clone)]
pub struct Placed {
    pub center: DVec3,
    pub scale: f64,
    /// Local to world.
    pub rotation: DMat3,
    /// World to local (the transpose).
    pub inverse: DMat3,
}

/// A ray in a shape's local coordinates, measured from the foot of the
/// perpendicular from the shape's centre (docs/implementation.md,
/// "Intersections", its item "Foot of the perpendicular"): local points `q + u d`, world parameter `t = s + scale u`.
/// The numbers stay at the size of the shape however far away the ray starts.
#[derive(Debug, Clone, Copy)]
pub struct LocalRay {
    /// The foot, local: perpendicular to `d`.
    pub q: DVec3,
    /// Unit direction, local (a rotation keeps it unit).
    pub d: DVec3,
    /// World ray parameter of the foot.
    pub s: f64,
    pub scale: f64,
}

impl LocalRay {
    /// The local parameter of world parameter `t`.
    pub fn u(&self, t: f64) -> f64 {
        (t - self.s) / self.scale
    }

    /// The world parameter of local parameter `u`.
    pub fn t(&self, u: f64) -> f64 {
        self.s + self.scale * u
    }

    pub fn at(&self, u: f64) -> DVec3 {
        self.q + u * self.d
    }
}

impl Placed {
    pub fn new(placement: &Placement) -> Self {
        let rotation = placement.rotation_matrix();
        Placed {
            center: placement.translate,
            scale: placement.scale,
            rotation,
            inverse: rotation.transpose(),
        }
    }

    pub fn local(&self, ray: &Ray) -> LocalRay {
        let (g, s) = foot(ray, self.center);
        LocalRay {
            q: self.inverse * g / self.scale,
            d: self.inverse * ray.dir,
            s,
            scale: self.scale,
        }
    }

    /// The hit at local parameter `u` with the local (not necessarily unit)
    /// normal `n`, which falls back to `-d` when it is zero or not finite.
    pub fn hit(&self, ray: &LocalRay, u: f64, n: DVec3, error_scale: f64) -> Hit {
        let world_n = (self.rotation * n).normalize_or_zero();
        let n = if world_n == DVec3::ZERO || !world_n.is_finite() {
            -(self.rotation * ray.d)
        } else {
            world_n
        };
        Hit::new(
            ray.t(u),
            self.center + self.scale * (self.rotation * ray.at(u)),
            n,
            error_scale,
        )
    }

    /// `|center|_max + scale * extent`: the size of the numbers of a hit
    /// point on a shape whose local points are at most `extent` from its
    /// centre (see `Hit::error_scale`).
    pub fn error_scale(&self, extent: f64) -> f64 {
        self.center.abs().max_element() + self.scale * extent
    }
}
