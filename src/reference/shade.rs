//! Whitted shading (docs/rendering-model.md, "Materials" and "Whitted shading"): local Lambert and Blinn-Phong
//! light with hard shadows, ambient light, and recursive perfect reflection
//! and refraction weighted by the exact Fresnel term.

use glam::DVec3;

use super::PreparedScene;
use super::intersect::{Hit, ShapeId, any_hit, nearest_hit};
use super::ray::{Ray, offset_ray, offset_ray_naive};
use super::record::{RayKind, Recorder};
use crate::scene::Material;

/// The radiance arriving along `ray`: the background on a miss, else the
/// shaded hit.
///
/// `depth` counts the bounces so far (0 for camera rays) and `weight` is how
/// much this ray can still contribute to the pixel (1 for camera rays); both
/// decide which child rays are worth tracing (see [`shade`]).
pub fn trace(scene: &PreparedScene, ray: &Ray, depth: u32, weight: f64) -> DVec3 {
    trace_recorded(scene, ray, depth, weight, &mut ())
}

/// [`trace`], telling `rec` every ray and hit (a pixel's ray tree,
/// `ray_tree.rs`; the caller has begun `ray`).
pub(super) fn trace_recorded<R: Recorder>(
    scene: &PreparedScene,
    ray: &Ray,
    depth: u32,
    weight: f64,
    rec: &mut R,
) -> DVec3 {
    match nearest_hit(scene, ray) {
        None => {
            rec.missed(scene.background);
            scene.background
        }
        Some((shape, hit)) => shade(scene, ray, (shape, &hit), (depth, weight), rec),
    }
}

/// Whitted's shading of one hit:
/// `local + wr * trace(reflected) + wt * albedo * trace(refracted)`.
///
/// A child ray has depth `depth + 1` and weight `weight * wr` (reflected) or
/// `weight * wt * max(albedo)` (refracted, the most its tint lets through).
/// It is traced only if its depth is at most `max_depth` and its weight is
/// positive and at least `min_weight`; otherwise it adds nothing. The weight
/// test is what keeps a glass scene from tracing `2^max_depth` rays per pixel,
/// and the `> 0` part skips rays that could not change the image anyway.
fn shade<R: Recorder>(
    scene: &PreparedScene,
    ray: &Ray,
    (shape, hit): (ShapeId, &Hit),
    (depth, weight): (u32, f64),
    rec: &mut R,
) -> DVec3 {
    let m = scene.material(shape);
    let d = ray.dir;
    // Closed shapes: the ray enters where it meets the outward normal head on.
    let entering = d.dot(hit.n) < 0.0;
    // The shading normal faces the ray, whichever side was hit; secondary
    // rays start off the surface along the geometric normal.
    let ns = if entering { hit.shading } else { -hit.shading };
    let ng = if entering { hit.n } else { -hit.n };
    rec.hit(shape, hit, ns);
    let albedo = albedo(m, hit.p + scene.frame_origin, hit.n, scene.options.robust);
    let mut radiance = local(scene, (m, albedo), hit, ns, d, rec);

    let thin = shape.is_thin();
    let opaque;
    let m = if shape.is_opaque() {
        opaque = Material {
            transparency: 0.0,
            ..m.clone()
        };
        &opaque
    } else {
        m
    };
    let split = split(m, d, ns, entering, thin);
    rec.split(radiance, split.fresnel, split.wr, split.wt);
    if depth >= scene.max_depth {
        return radiance;
    }
    let traced = |child_weight: f64| child_weight > 0.0 && child_weight >= scene.min_weight;

    let reflected_weight = weight * split.wr;
    if scene.reflection && traced(reflected_weight) {
        let child = Ray::new(offset(scene, hit, ng), reflect(d, ns));
        // Glass met from inside beyond the critical angle reflects it all.
        let total = m.transparency > 0.0 && split.fresnel >= 1.0 && !entering && !thin;
        let kind = if total {
            RayKind::TotalInternal
        } else {
            RayKind::Reflected
        };
        rec.begin(kind, &child, DVec3::splat(split.wr));
        radiance += split.wr * trace_recorded(scene, &child, depth + 1, reflected_weight, rec);
        rec.end();
    }
    if let Some(dir) = split.transmitted.filter(|_| scene.refraction) {
        let refracted_weight = weight * split.wt * albedo.max_element();
        if traced(refracted_weight) {
            let child = Ray::new(offset(scene, hit, -ng), dir);
            rec.begin(RayKind::Refracted, &child, split.wt * albedo);
            radiance +=
                split.wt * albedo * trace_recorded(scene, &child, depth + 1, refracted_weight, rec);
            rec.end();
        }
    }
    radiance
}

/// The local term: `ambient * albedo * kd` plus, for every light that the
/// surface faces and that is not in shadow,
/// `light * (kd * albedo * dot(ns, l) + ks * max(0, dot(ns, h))^shininess)`.
///
/// `l` points from `p` to the light and `h = normalize(l - d)` is Blinn's
/// half vector between it and the direction back to the viewer. Lights do not
/// fall off with distance (docs/rendering-model.md, "Whitted shading").
fn local<R: Recorder>(
    scene: &PreparedScene,
    (m, albedo): (&Material, DVec3),
    hit: &Hit,
    ns: DVec3,
    d: DVec3,
    rec: &mut R,
) -> DVec3 {
    let mut radiance = scene.ambient * albedo * m.diffuse;
    if m.diffuse == 0.0 && m.specular == 0.0 {
        // No light could add anything: spare the shadow rays.
        return radiance;
    }
    for (index, light) in scene.lights.iter().enumerate() {
        // A light exactly at p has no direction; it lights nothing.
        let Some(l) = (light.position - hit.p).try_normalize() else {
            continue;
        };
        let cos = ns.dot(l);
        if cos <= 0.0 {
            continue;
        }
        let shadow = shadow_ray(scene, hit, ns, light.position);
        let blocked = shadow.is_some_and(|(ray, distance)| any_hit(scene, &ray, distance));
        // l = d only if cos = dot(ns, d) < 0, excluded above; or_zero is a
        // guard against NaN, not a case that occurs.
        let h = (l - d).normalize_or_zero();
        let highlight = ns.dot(h).max(0.0).powf(m.shininess);
        let term = if blocked {
            DVec3::ZERO
        } else {
            light.radiance * (m.diffuse * albedo * cos + m.specular * highlight)
        };
        if let Some((ray, distance)) = shadow {
            rec.shadow(index, &ray, distance, blocked, term);
        }
        radiance += term;
    }
    radiance
}

/// The shadow ray from a hit to a light and the distance to the light: it
/// starts at `p` offset to the lit side `ns` (along the geometric normal on
/// that side) and is blocked by any hit with `0 < t < |L - o|`. `None`
/// where no shadow ray is cast: with the lecture switch `shadows` off, and
/// for a light at the origin itself (nothing fits strictly between a light
/// and itself).
fn shadow_ray(scene: &PreparedScene, hit: &Hit, ns: DVec3, light: DVec3) -> Option<(Ray, f64)> {
    if !scene.shadows {
        return None;
    }
    let ng = if hit.n.dot(ns) >= 0.0 { hit.n } else { -hit.n };
    let origin = offset(scene, hit, ng);
    let distance = (light - origin).length();
    (distance > 0.0).then(|| (Ray::new(origin, light - origin), distance))
}

/// The origin of a secondary or shadow ray leaving `hit` to the side `n`:
/// the scale-aware [`offset_ray`], or the fixed textbook offset in the naive
/// variant.
fn offset(scene: &PreparedScene, hit: &Hit, n: DVec3) -> DVec3 {
    if scene.options.robust {
        offset_ray(hit.p, n, hit.error_scale)
    } else {
        offset_ray_naive(hit.p, n)
    }
}

/// The albedo at `p`: the material colour, or the checker's second colour on
/// odd cells.
///
/// The cell is looked up at `q = p - 0.001 s n`, a small step into the
/// surface along the outward normal `n`, so that a plane lying exactly on a
/// cell boundary (the floor y = 0 with cells of size 1) does not flicker
/// between the cells above and below it. Both sides of a plane step the same
/// way and show the same pattern.
///
/// As in the shader, `floor(p / s - 0.001 n)` is evaluated by [`checker_cell`]
/// without forming the sum, whose step is lost in the rounding of `p / s`
/// far from the origin; the naive variant forms it as the rendering model writes it.
pub fn albedo(m: &Material, p: DVec3, n: DVec3, robust: bool) -> DVec3 {
    let Some(checker) = &m.checker else {
        return m.color;
    };
    let s = checker.size;
    let cell = if robust {
        checker_cell(p / s, 0.001 * n)
    } else {
        ((p - 0.001 * s * n) / s)
            .floor()
            .to_array()
            .map(|c| c as i64)
    };
    // Integer sum as the shader does; wrapping only matters beyond 2^62 cells.
    let sum = cell[0].wrapping_add(cell[1]).wrapping_add(cell[2]);
    if sum & 1 == 0 { m.color } else { checker.color }
}

/// `floor(x - step)` per component for `|step| < 1`, exactly: with
/// `k = floor(x)` and `f = x - k` (exact), `k - 1` where `f < step`
/// (`step > 0`), `k + 1` where `f >= 1 + step` (`step < 0`), else `k`.
pub fn checker_cell(x: DVec3, step: DVec3) -> [i64; 3] {
    let k = x.floor();
    let f = x - k;
    std::array::from_fn(|i| {
        // In integers: k - 1 may not be representable next to a huge k.
        let k_i = k[i] as i64;
        if step[i] > 0.0 && f[i] < step[i] {
            k_i - 1
        } else if step[i] < 0.0 && f[i] >= 1.0 + step[i] {
            k_i + 1
        } else {
            k_i
        }
    })
}

/// How a hit divides its light between the mirror and the dielectric parts.
struct Split {
    /// Fresnel's reflectance F (0 where there is no dielectric part).
    fresnel: f64,
    /// Weight of the reflected ray, `kr + kt F`.
    wr: f64,
    /// Weight of the transmitted ray, `kt (1 - F)`.
    wt: f64,
    /// Direction of the transmitted ray, if there is one (`wt > 0`).
    transmitted: Option<DVec3>,
}

/// The Fresnel split of docs/rendering-model.md, "Whitted shading". Closed shapes go from index 1 to
/// `ior` when the ray enters and from `ior` to 1 when it leaves, and bend the
/// transmitted ray by Snell's law. Planes are thin: F as for entering, and
/// the ray goes straight on (a sheet of glass shifts it sideways by its
/// thickness, which is zero). F is only computed where `kt > 0`, so a
/// material without transparency mirrors with exactly `kr`.
fn split(m: &Material, d: DVec3, ns: DVec3, entering: bool, thin: bool) -> Split {
    let (kr, kt) = (m.mirror, m.transparency);
    if kt <= 0.0 {
        return Split {
            fresnel: 0.0,
            wr: kr,
            wt: 0.0,
            transmitted: None,
        };
    }
    let (n1, n2) = if thin || entering {
        (1.0, m.ior)
    } else {
        (m.ior, 1.0)
    };
    // The angle to the shading normal, as for the mirror direction (`ns`
    // faces the ray; a smooth normal that turns away reflects fully, as
    // the shader's `fresnel` does for cos_i <= 0).
    let cos_i = -d.dot(ns);
    let f = if cos_i <= 0.0 {
        1.0
    } else {
        fresnel(cos_i, n1, n2)
    };
    let wt = kt * (1.0 - f);
    let transmitted = if wt <= 0.0 {
        None
    } else if thin {
        Some(d)
    } else {
        // Not None: F < 1 rules out total internal reflection.
        refract(d, ns, n1 / n2)
    };
    Split {
        fresnel: f,
        wr: kr + kt * f,
        wt,
        transmitted,
    }
}

/// The exact Fresnel reflectance of unpolarised light at a smooth dielectric
/// boundary from index `n1` to `n2`, `cos_i` the cosine of the angle of
/// incidence: `F = (r_s^2 + r_p^2) / 2` with
/// `r_s = (n1 cos_i - n2 cos_t) / (n1 cos_i + n2 cos_t)` and
/// `r_p = (n2 cos_i - n1 cos_t) / (n2 cos_i + n1 cos_t)` (Hecht, Optics).
///
/// Exact rather than Schlick's approximation because this is the yardstick.
/// Total internal reflection (`sin_t^2 >= 1`) and grazing incidence
/// (`cos_i = 0`) reflect everything: F = 1.
pub fn fresnel(cos_i: f64, n1: f64, n2: f64) -> f64 {
    let sin2_t = sin2_transmitted(cos_i, n1 / n2);
    if cos_i == 0.0 || sin2_t >= 1.0 {
        return 1.0;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    let r_s = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t);
    let r_p = (n2 * cos_i - n1 * cos_t) / (n2 * cos_i + n1 * cos_t);
    0.5 * (r_s * r_s + r_p * r_p)
}

/// `sin^2` of the refraction angle by Snell's law, `n1 sin_i = n2 sin_t`,
/// with `eta = n1 / n2`. Shared by [`fresnel`] and [`refract`] so that both
/// agree on when total internal reflection happens.
fn sin2_transmitted(cos_i: f64, eta: f64) -> f64 {
    // |cos_i| may exceed 1 by rounding; sin^2 is never negative.
    eta * eta * (1.0 - cos_i * cos_i).max(0.0)
}

/// The mirror direction of `d` about the unit normal `n`:
/// `d - 2 dot(d, n) n`, normalised (it has length 1 up to rounding).
pub fn reflect(d: DVec3, n: DVec3) -> DVec3 {
    (d - 2.0 * d.dot(n) * n).normalize()
}

/// The refracted direction of unit `d` through a boundary with shading
/// normal `ns` (facing the incoming ray) and `eta = n1 / n2`:
/// `eta d + (eta cos_i - cos_t) ns` with `cos_i = -dot(d, ns)`, which keeps
/// the tangential part scaled by eta (Snell) and makes the result unit
/// length; normalised against rounding. `None` on total internal reflection.
pub fn refract(d: DVec3, ns: DVec3, eta: f64) -> Option<DVec3> {
    let cos_i = -d.dot(ns);
    let sin2_t = sin2_transmitted(cos_i, eta);
    if sin2_t >= 1.0 {
        return None;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    Some((eta * d + (eta * cos_i - cos_t) * ns).normalize())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reference::camera::camera_ray;
    use crate::scene::{Checker, Scene};
    use glam::DVec2;

    #[test]
    fn fresnel_at_normal_incidence() {
        for (n1, n2) in [(1.0f64, 1.5f64), (1.5, 1.0), (1.0, 2.4), (1.33, 1.0)] {
            let expected = ((n2 - n1) / (n2 + n1)).powi(2);
            assert!(
                (fresnel(1.0, n1, n2) - expected).abs() < 1e-15,
                "{n1} -> {n2}"
            );
        }
        assert!((fresnel(1.0, 1.0, 1.5) - 0.04).abs() < 1e-15);
        assert_eq!(fresnel(0.7, 1.5, 1.5), 0.0, "no boundary, no reflection");
    }

    #[test]
    fn fresnel_total_internal_reflection() {
        // Glass to air: the critical angle has sin = 1/1.5.
        let cos_critical = (1.0 - 1.0 / 2.25f64).sqrt();
        assert_eq!(fresnel(cos_critical - 1e-9, 1.5, 1.0), 1.0);
        assert_eq!(fresnel(0.1, 1.5, 1.0), 1.0);
        assert!(fresnel(cos_critical + 1e-3, 1.5, 1.0) < 1.0);
        // Air to glass never reflects totally, but grazing reflects all.
        assert!(fresnel(1e-9, 1.0, 1.5) < 1.0);
        assert_eq!(fresnel(0.0, 1.0, 1.5), 1.0);
        assert_eq!(fresnel(0.0, 1.5, 1.0), 1.0);
    }

    #[test]
    fn fresnel_energy_sanity() {
        for i in 0..=1000 {
            let cos_i = f64::from(i) / 1000.0;
            for (n1, n2) in [(1.0, 1.5), (1.5, 1.0), (1.0, 0.5)] {
                let f = fresnel(cos_i, n1, n2);
                assert!((0.0..=1.0).contains(&f), "{cos_i} {n1} {n2}: {f}");
            }
            // Reciprocity (Stokes): the same reflectance from either side
            // for a pair of angles related by Snell's law.
            let sin2_t = sin2_transmitted(cos_i, 1.0 / 1.5);
            let cos_t = (1.0 - sin2_t).sqrt();
            if cos_i > 0.0 {
                let (a, b) = (fresnel(cos_i, 1.0, 1.5), fresnel(cos_t, 1.5, 1.0));
                assert!((a - b).abs() < 1e-10, "{cos_i}: {a} vs {b}");
            }
        }
        // Reflectance grows toward grazing incidence (unpolarised, n1 < n2).
        assert!(fresnel(0.2, 1.0, 1.5) > fresnel(0.8, 1.0, 1.5));
    }

    #[test]
    fn refraction_obeys_snell() {
        let ns = DVec3::Y;
        for (angle_deg, eta) in [
            (30.0f64, 1.0 / 1.5),
            (60.0, 1.0 / 1.5),
            (20.0, 1.5),
            (0.0, 1.5),
        ] {
            let a = angle_deg.to_radians();
            let d = DVec3::new(a.sin(), -a.cos(), 0.0);
            let t = refract(d, ns, eta).unwrap();
            assert!((t.length() - 1.0).abs() < 1e-15);
            // sin_t = eta sin_i, same side of the normal, continuing downwards.
            assert!((t.x - eta * a.sin()).abs() < 1e-15, "{angle_deg} {eta}");
            assert!(t.y < 0.0 && t.z == 0.0);
        }
        // Beyond the critical angle for glass to air: none.
        let a = 45f64.to_radians();
        assert_eq!(refract(DVec3::new(a.sin(), -a.cos(), 0.0), ns, 1.5), None);
    }

    #[test]
    fn reflection_mirrors_about_the_normal() {
        let d = DVec3::new(1.0, -1.0, 0.5).normalize();
        let r = reflect(d, DVec3::Y);
        assert!((r - DVec3::new(1.0, 1.0, 0.5).normalize()).length() < 1e-15);
    }

    fn material(kr: f64, kt: f64) -> Material {
        Material {
            mirror: kr,
            transparency: kt,
            ..Material::default()
        }
    }

    #[test]
    fn split_rules() {
        let d = DVec3::new(0.0, -1.0, 0.0);
        // kt = 0: F is not involved, wr = kr exactly.
        let s = split(&material(0.3, 0.0), d, DVec3::Y, true, false);
        assert_eq!((s.wr, s.wt, s.transmitted), (0.3, 0.0, None));
        // Entering glass head on: F = 0.04.
        let s = split(&material(0.1, 0.5), d, DVec3::Y, true, false);
        assert!((s.wr - (0.1 + 0.5 * 0.04)).abs() < 1e-15);
        assert!((s.wt - 0.5 * 0.96).abs() < 1e-15);
        assert!((s.transmitted.unwrap() - d).length() < 1e-15);
        // Leaving a closed shape obliquely past the critical angle: TIR.
        let oblique = DVec3::new(1.0, 1.0, 0.0).normalize();
        let s = split(&material(0.0, 1.0), oblique, -DVec3::Y, false, false);
        assert_eq!((s.wr, s.wt, s.transmitted), (1.0, 0.0, None));
        // A thin plane: F as for entering even from the back, ray unbent.
        let s = split(&material(0.0, 1.0), oblique, -DVec3::Y, false, true);
        let f = fresnel(oblique.y, 1.0, 1.5);
        assert!(f > 0.04 && f < 1.0);
        assert_eq!((s.wr, s.wt, s.transmitted), (f, 1.0 - f, Some(oblique)));
    }

    #[test]
    fn checker_parity() {
        let m = Material {
            color: DVec3::ONE,
            checker: Some(Checker {
                color: DVec3::ZERO,
                size: 2.0,
            }),
            ..Material::default()
        };
        // Cells of size 2: (0.5, 0.5, 0.5) is cell (0, 0, 0), even.
        assert_eq!(albedo(&m, DVec3::splat(0.5), DVec3::Y, true), DVec3::ONE);
        assert_eq!(
            albedo(&m, DVec3::new(2.5, 0.5, 0.5), DVec3::Y, true),
            DVec3::ZERO
        );
        // Negative coordinates: floor(-0.25) = -1, odd.
        assert_eq!(
            albedo(&m, DVec3::new(-0.5, 0.5, 0.5), DVec3::Y, true),
            DVec3::ZERO
        );
        assert_eq!(
            albedo(&m, DVec3::new(-2.5, 0.5, 0.5), DVec3::Y, true),
            DVec3::ONE
        );
        // On the cell boundary y = 0 with outward normal +y, q lies below:
        // cell y = -1. With normal -y, above: cell y = 0.
        assert_eq!(
            albedo(&m, DVec3::new(0.5, 0.0, 0.5), DVec3::Y, true),
            DVec3::ZERO
        );
        assert_eq!(
            albedo(&m, DVec3::new(0.5, 0.0, 0.5), -DVec3::Y, true),
            DVec3::ONE
        );
        // Without a checker: the colour.
        assert_eq!(
            albedo(&Material::default(), DVec3::splat(-7.3), DVec3::Y, true),
            DVec3::splat(0.8)
        );
        // Far from the origin the step of 0.001 s is below the spacing of
        // p (1e17 has an ulp of 16): the rendering model's q = p - 0.001 s n rounds back
        // to p and the naive formula lands in the cell above the boundary;
        // checker_cell still steps into the floor.
        let far = DVec3::new(0.5, 1e17, 0.5);
        let m1 = Material {
            checker: Some(Checker {
                color: DVec3::ZERO,
                size: 1.0,
            }),
            ..m.clone()
        };
        assert_eq!(
            albedo(&m1, far, DVec3::Y, true),
            DVec3::ZERO,
            "cell 1e17 - 1: odd"
        );
        assert_eq!(
            albedo(&m1, far, DVec3::Y, false),
            DVec3::ONE,
            "cell 1e17: even"
        );
    }

    #[test]
    fn checker_cell_is_floor_of_x_minus_step() {
        for x in [
            -2.0, -1.9995, -0.5, 0.0, 0.0004, 0.001, 0.3, 0.9995, 0.99999, 1.0, 7.0,
        ] {
            for step in [-0.001f64, 0.0, 0.001] {
                let expected = (x - step).floor() as i64;
                let cell = checker_cell(DVec3::splat(x), DVec3::splat(step));
                assert_eq!(cell, [expected; 3], "x {x} step {step}");
            }
        }
    }

    /// Whether a shape lies between the hit point and the light (classic
    /// Whitted shadows: glass blocks fully too).
    fn in_shadow(scene: &PreparedScene, hit: &Hit, ns: DVec3, light: DVec3) -> bool {
        shadow_ray(scene, hit, ns, light)
            .is_some_and(|(ray, distance)| any_hit(scene, &ray, distance))
    }

    /// Over a 320 x 180 image of a scene with one convex shape and one
    /// light: how many camera rays hit a point facing the light, and how many
    /// of those the shape wrongly shadows itself.
    fn self_shadowed(text: &str) -> (usize, usize) {
        let scene = PreparedScene::new(&toml::from_str::<Scene>(text).unwrap());
        let light = scene.lights[0].position;
        let (mut facing, mut shadowed) = (0, 0);
        for j in 0..180 {
            for i in 0..320 {
                let (x, y) = (f64::from(i) + 0.5, f64::from(j) + 0.5);
                let ray = camera_ray(&scene.camera, 320, 180, x, y, DVec2::ZERO);
                let Some((_, hit)) = nearest_hit(&scene, &ray) else {
                    continue;
                };
                let ns = if ray.dir.dot(hit.n) < 0.0 {
                    hit.n
                } else {
                    -hit.n
                };
                if ns.dot(light - hit.p) > 0.0 {
                    facing += 1;
                    shadowed += usize::from(in_shadow(&scene, &hit, ns, light));
                }
            }
        }
        (facing, shadowed)
    }

    #[test]
    fn no_shadow_acne_on_a_ground_sphere() {
        // The classic ground: radius 1000, top at y = 0. Points near y = 0
        // carry the rounding error of the centre's magnitude.
        for radius in ["1000", "100000"] {
            let text = format!(
                "camera = {{ from = [0, 2, 8], to = [0, 0, 0] }}
                lights = [{{ position = [3, 10, 4] }}]
                spheres = [{{ center = [0, -{radius}, 0], radius = {radius} }}]"
            );
            let (facing, shadowed) = self_shadowed(&text);
            assert!(facing > 20_000);
            assert_eq!(shadowed, 0, "radius {radius}");
        }
    }

    #[test]
    fn no_shadow_acne_on_boxes_seen_from_afar() {
        // A face at x = 0.04 or 0.1, the box slightly turned or not, the eye
        // up to 1e4 away: the hit point's error grows with the distance
        // travelled unless it is re-projected onto the face.
        for face in [0.04, 0.1] {
            for (eye, fov) in [(9.0, 45.0), (90.0, 5.0), (1e4, 0.05)] {
                for turn in [0.0, 0.001] {
                    let text = format!(
                        "camera = {{ from = [{eye}, 1, 0.3], to = [{face}, 0, 0], fov = {fov} }}
                        lights = [{{ position = [20, 3, 1] }}]
                        cubes = [{{ center = [{}, 0, 0], size = [2, 3, 3], rotation = [0, {turn}, 0] }}]",
                        face - 1.0
                    );
                    let (facing, shadowed) = self_shadowed(&text);
                    assert!(facing > 1000, "{facing}");
                    assert_eq!(shadowed, 0, "face {face} eye {eye} turn {turn}");
                }
            }
        }
    }
}
