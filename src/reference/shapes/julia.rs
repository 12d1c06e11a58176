//! A quaternion Julia set for the f64 tracer (docs/rendering-model.md,
//! "Implicit surfaces": Crane 2005, distance-estimated sphere tracing).

use glam::{DVec3, DVec4};

use super::placement::Placed;
use super::{Prepare, Trace};
use crate::reference::ReferenceOptions;
use crate::reference::hit::Hit;
use crate::reference::ray::{Ray, offset_ray_scale};
use crate::scene::{self, Instance};

/// The set, its iteration and the sphere tracer's settings.
#[derive(Debug, Clone)]
pub struct Julia {
    pub placed: Placed,
    /// The constant c: real, i, j, k.
    pub c: DVec4,
    /// The fourth coordinate of the 3-D slice.
    pub slice: f64,
    pub iterations: u32,
    /// Distance at which a point counts as on the surface, local units.
    pub epsilon: f64,
    /// Grow epsilon with the pixel footprint ([`surface_distance`]).
    pub footprint: bool,
}

/// Radius of the sphere that holds the set (|c| <= 2), local units.
pub const BOUND: f64 = 2.0;

/// Steps of sphere tracing before the ray counts as a miss.
pub const MAX_STEPS: u32 = 1024;

/// Where |z| counts as escaped.
const ESCAPE: f64 = 4.0;

impl Prepare for scene::Julia {
    type Traced = Julia;

    fn prepare(shape: &Instance<Self>) -> Julia {
        Julia {
            placed: Placed::new(&shape.placement),
            c: DVec4::from_array(shape.c),
            slice: shape.slice,
            iterations: shape.iterations,
            epsilon: shape.epsilon,
            footprint: shape.footprint,
        }
    }
}

impl Trace for Julia {
    fn hit(&self, ray: &Ray, t_max: f64, options: &ReferenceOptions) -> Option<Hit> {
        hit_julia(self, ray, t_max, options.pixel_angle)
    }

    fn uses_pixel_angle(&self) -> bool {
        self.footprint
    }
}

/// `z^2` for the quaternion `z = (a, v)`: `(a^2 - v.v, 2 a v)`.
fn square(z: DVec4) -> DVec4 {
    let (a, v) = (z.x, DVec3::new(z.y, z.z, z.w));
    let w = 2.0 * a * v;
    DVec4::new(a * a - v.length_squared(), w.x, w.y, w.z)
}

/// The distance estimate at local point `p`: iterate `z <- z^2 + c` from
/// `z = (p, slice)` with the derivative's length `dz <- 2 |z| dz`, then
/// `0.5 |z| ln|z| / dz` (Crane 2005, after Hart et al. 1989).
pub fn distance(julia: &Julia, p: DVec3) -> f64 {
    let mut z = DVec4::new(p.x, p.y, p.z, julia.slice);
    let mut dz = 1.0;
    for _ in 0..julia.iterations {
        dz *= 2.0 * z.length();
        z = square(z) + julia.c;
        if z.length() > ESCAPE {
            break;
        }
    }
    let r = z.length();
    0.5 * r * r.ln() / dz
}

/// The surface distance (local units) at world parameter `t`: epsilon, or
/// with the footprint on at least the height `pixel_angle * t` that one
/// pixel subtends at the distance travelled along the ray (rays start at
/// the eye or on the surface they leave).
pub fn surface_distance(julia: &Julia, t: f64, pixel_angle: f64) -> f64 {
    if !julia.footprint {
        return julia.epsilon;
    }
    julia.epsilon.max(pixel_angle * t / julia.placed.scale)
}

/// Sphere tracing from where the ray enters the bounding sphere (or from
/// its origin inside it): the first point with `DE < epsilon`
/// ([`surface_distance`]) with `0 < t < t_max`.
pub fn hit_julia(julia: &Julia, ray: &Ray, t_max: f64, pixel_angle: f64) -> Option<Hit> {
    let local = julia.placed.local(ray);
    let qq = local.q.length_squared();
    if qq >= BOUND * BOUND {
        return None;
    }
    let h = (BOUND * BOUND - qq).sqrt();
    let end = h.min(local.u(t_max));
    let mut u = (-h).max(local.u(0.0));
    for _ in 0..MAX_STEPS {
        if u > end {
            return None;
        }
        let de = distance(julia, local.at(u));
        let epsilon = surface_distance(julia, local.t(u), pixel_angle);
        if de < epsilon {
            let p = local.at(u);
            // Secondary rays start 2 epsilon off the surface (the rendering
            // model): the scale that makes offset_ray move them that far.
            let error_scale = offset_ray_scale(2.0 * epsilon * julia.placed.scale)
                .max(julia.placed.error_scale(BOUND));
            let hit = julia
                .placed
                .hit(&local, u, normal(julia, p, epsilon), error_scale);
            return (hit.t > 0.0 && hit.t < t_max).then_some(hit);
        }
        u += de;
    }
    None
}

/// `grad DE` by central differences with step `e`, the hit's epsilon (DE
/// is not smooth enough for more; the rendering model allows it here).
pub fn normal(julia: &Julia, p: DVec3, e: f64) -> DVec3 {
    DVec3::from_array(
        [DVec3::X, DVec3::Y, DVec3::Z]
            .map(|axis| distance(julia, p + e * axis) - distance(julia, p - e * axis)),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn julia(footprint: bool) -> Julia {
        let julia = scene::Julia {
            c: [-0.2, 0.6, 0.2, 0.2],
            slice: 0.0,
            iterations: 6,
            epsilon: 1e-3,
            footprint,
        };
        let placement = scene::Placement {
            scale: 2.0,
            ..Default::default()
        };
        scene::Julia::prepare(&Instance::new(julia, placement))
    }

    /// Off: epsilon at every distance. On: epsilon up close, then one
    /// pixel's height at distance t, in local units (world / scale).
    #[test]
    fn the_footprint_grows_epsilon_with_distance_only_when_on() {
        let pixel_angle = 0.01;
        assert_eq!(surface_distance(&julia(false), 100.0, pixel_angle), 1e-3);
        let on = julia(true);
        assert_eq!(surface_distance(&on, 0.1, pixel_angle), 1e-3);
        assert_eq!(surface_distance(&on, 100.0, pixel_angle), 0.5);
        assert_eq!(surface_distance(&on, 100.0, 0.0), 1e-3);
    }
}
