// camera.wgsl: from a pixel to a primary ray (docs/rendering-model.md, "Camera").

struct Ray {
    origin: vec3<f32>,
    dir: vec3<f32>,          // unit length
    t_min: f32,              // hits count for t_min < t: 0, or < 0 for camera rays
}

/// v / |v| without overflow or underflow: v is first divided by its largest
/// component, so that the squares inside length() are between 1 and 3 even for
/// |v| ~ 1e-30 or 1e30 (where the plain normalize() would make 0 / 0 or
/// inf / inf). The zero vector, and one whose every component is flushed to
/// zero, gives `fallback`.
fn normalize_or(v: vec3<f32>, fallback: vec3<f32>) -> vec3<f32> {
    let m = max3(abs(v));
    if !(m > 0.0) {
        return fallback;
    }
    return normalize(v / m);
}

/// |v| without overflow or underflow, by the same division by the largest
/// component as [`normalize_or`]: a camera or a light 1e30 away has a
/// distance (docs/reliability.md, "Extreme scenes on the GPU").
fn scaled_length(v: vec3<f32>) -> f32 {
    let m = max3(abs(v));
    if !(m > 0.0) {
        return 0.0;
    }
    return m * length(v / m);
}

/// Sample k of the R4 sequence (Roberts 2018): fract(0.5 + k alpha) with
/// alpha = (1/g, 1/g^2, 1/g^3, 1/g^4), g^5 = g + 1. Sample 0 is (0.5, ...):
/// the pixel centre and the lens centre. xy = pixel offset, zw = lens sample.
fn sample_r4(k: u32) -> vec4<f32> {
    let alpha = vec4(0.8566748838545029, 0.733891856627126, 0.6287067210378086, 0.53859725722361);
    return fract(vec4(0.5) + f32(k) * alpha);
}

/// Shirley and Chiu's concentric map from the unit square to the unit disk:
/// it keeps strata apart, and maps the square's centre to the disk's centre.
fn concentric_disk(s: vec2<f32>) -> vec2<f32> {
    let a = 2.0 * s - 1.0;
    if a.x == 0.0 && a.y == 0.0 {
        return vec2(0.0);
    }
    let quarter_pi = 0.78539816339744831;
    if abs(a.x) > abs(a.y) {
        let phi = quarter_pi * (a.y / a.x);
        return a.x * vec2(cos(phi), sin(phi));
    }
    let phi = 2.0 * quarter_pi - quarter_pi * (a.x / a.y);
    return a.y * vec2(cos(phi), sin(phi));
}

/// The ray through film position `pixel` (in pixels, y down from the top) with
/// lens sample `lens` in the unit disk. The direction is built from the basis
/// (`globals().u`, `v`, `w`, computed once in f64 on the CPU: `Camera::film`
/// in src/scene/camera.rs), x u + y v - w, never as the difference of two
/// far-away world points.
///
/// The robust ray starts where its position is known best: where it crosses
/// the plane in focus (the target's plane for a pinhole), written relative to
/// the target as (D - F) w + F (x u + y v), with D = |eye - target| and F the
/// focus distance. Its t_min = -|F (x u + y v - w) - lens offset| reaches
/// back to the eye (or the lens point), so nothing in front of the focus
/// plane is missed. From there, an f32 direction rounded by ~6e-8 rad moves
/// the ray by 6e-8 times the distance from the focus plane, not from the
/// eye: a small sphere framed from 1e6 units stays where it is
/// (docs/accuracy.md). The textbook ray (ROBUST = false) starts at the eye.
fn camera_ray(pixel: vec2<f32>, lens: vec2<f32>) -> Ray {
    let size = vec2<f32>(globals().resolution);
    let h = globals().film_height;
    let x = h * (size.x / size.y) * (pixel.x / size.x - 0.5);
    let y = h * (0.5 - pixel.y / size.y);
    let to_film = x * globals().u + y * globals().v - globals().w;
    let target_distance = globals().target_distance;
    var focus = target_distance;
    var lens_offset = vec3(0.0);
    if HAS_LENS && globals().aperture > 0.0 {
        // Thin lens: aim from the lens point at P = e + focus_distance * to_film.
        focus = globals().focus_distance;
        lens_offset = globals().aperture * (lens.x * globals().u + lens.y * globals().v);
    } else if !ROBUST {
        return Ray(globals().camera_from, normalize(to_film), 0.0);
    }
    // Its -w component is -focus, so it is zero only for a zero focus
    // distance (eye == target in f32): then the pinhole ray from the eye. The
    // scaled normalisation keeps a tiny focus distance finite.
    let to_focus = focus * to_film - lens_offset;
    let dir = normalize_or(to_focus, normalize(to_film));
    let reach = dot(to_focus, dir);
    if !ROBUST || !(reach > 0.0) {
        return Ray(globals().camera_from + lens_offset, dir, 0.0);
    }
    let on_focus_plane = (target_distance - focus) * globals().w + focus * (x * globals().u + y * globals().v);
    return Ray(globals().camera_to + on_focus_plane, dir, -reach);
}
