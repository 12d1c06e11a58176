//! The stress scenes of `assets/scenes/stress/` (embedded, so the command
//! runs from any directory), their series, and the scene transformations the
//! measurements need: rounding to f32, translating and scaling.

use std::path::Path;
use std::sync::Arc;

use glam::DVec3;

use crate::scene::{AxisScale, Geometry, Loaded, Placement, Scene};

/// Declares the embedded scene files: `(name, TOML text)`.
macro_rules! stress_scenes {
    ($($name:literal),* $(,)?) => {
        /// Every stress scene: `(file stem, TOML text)`, in report order.
        pub const SCENES: &[(&str, &str)] = &[
            $(($name, include_str!(concat!("../../assets/scenes/stress/", $name, ".toml")))),*
        ];
    };
}

stress_scenes!(
    "small_sphere_1e2",
    "small_sphere_1e3",
    "small_sphere_1e4",
    "small_sphere_1e5",
    "small_sphere_1e6",
    "small_sphere_oblique_1e2",
    "small_sphere_oblique_1e3",
    "small_sphere_oblique_1e4",
    "small_sphere_oblique_1e5",
    "small_sphere_oblique_1e6",
    "ground_sphere_1e4",
    "ground_sphere_1e5",
    "grazing_light_1deg",
    "grazing_light_0.1deg",
    "grazing_light_0.01deg",
    "contact_gaps",
    "far_box_1e4",
    "facing_mirrors",
    "glass_critical_angle",
    "box_axis_rays",
    "camera_straight_down",
    "camera_straight_up",
    "camera_target_1e-6",
    "camera_target_1e-8",
    "translate_1e0",
    "translate_1e1",
    "translate_1e2",
    "translate_1e3",
    "translate_1e4",
    "translate_1e5",
    "translate_1e6",
    "scale_1e-4",
    "scale_1e-3",
    "scale_1e-2",
    "scale_1e-1",
    "scale_1e0",
    "scale_1e1",
    "scale_1e2",
    "scale_1e3",
    "scale_1e4",
    "torus_edge_on",
    "torus_from_far",
    "torus_inner_equator",
    "julia_zoom",
    "implicit_tangent_sphere",
);

/// The TOML text of a stress scene.
pub fn text(name: &str) -> Option<&'static str> {
    SCENES.iter().find(|(n, _)| *n == name).map(|(_, t)| *t)
}

/// The stress scene `name`, parsed and validated.
pub fn load(name: &str) -> Scene {
    let text = text(name).unwrap_or_else(|| panic!("no stress scene {name}"));
    Scene::from_toml_str(text, None).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// A scene that is one member of a series: `series_1e<k>` (e.g.
/// `translate_1e4`: series `translate`, k = 4).
pub fn series_member(name: &str) -> Option<(&str, i32)> {
    let (series, power) = name.rsplit_once("_1e")?;
    Some((series, power.parse().ok()?))
}

/// The series of the stress scenes, with what the exponent k means.
pub const SERIES: &[(&str, &str)] = &[
    (
        "small_sphere",
        "sphere r = 0.1 seen from D = 10^k, camera on an axis",
    ),
    (
        "small_sphere_oblique",
        "sphere r = 0.1 seen from D = 10^k, oblique camera",
    ),
    ("translate", "whole scene translated by 10^k (1, 1, 1)"),
    ("scale", "whole scene scaled by 10^k"),
    (
        "moved",
        "whole scene translated by 10^k (-1, 1, -1), against the unmoved scene's f64 image",
    ),
    (
        "scaled",
        "whole scene scaled by 10^k, against the unscaled scene's f64 image",
    ),
    (
        "bunny_far",
        "bunny mesh seen from D = 10^k, oblique camera, field of view narrowed to keep the framing",
    ),
    (
        "bunny_moved",
        "bunny mesh scene translated by 10^k (-1, 1, -1), against the unmoved scene's f64 image",
    ),
];

/// Rounds every number of the scene to the nearest f32, as the GPU buffers
/// receive them, so that a reference render of the result measures the
/// shader's arithmetic and not the rounding of its input. Positions are
/// rounded as the GPU gets them: relative to the frame origin (the camera
/// target), subtracted in f64 (`gpu::layout`). Plane normals are rounded as
/// given (unit length in f64); the reference normalises them again, which
/// moves them by less than an f32 ulp.
pub fn round_to_f32(scene: &Scene) -> Scene {
    let r = |x: f64| x as f32 as f64;
    let v = |x: DVec3| x.as_vec3().as_dvec3();
    let origin = scene.camera.frame_origin();
    let at = |x: DVec3| origin + v(x - origin);
    let mut s = scene.clone();
    let render = &mut s.render;
    render.min_weight = r(render.min_weight);
    render.background = v(render.background);
    render.ambient = v(render.ambient);
    render.exposure = r(render.exposure);
    let cam = &mut s.camera;
    cam.from = at(cam.from);
    cam.to = at(cam.to);
    cam.up = v(cam.up);
    cam.fov = r(cam.fov);
    cam.aperture = r(cam.aperture);
    cam.focus_distance = cam.focus_distance.map(r);
    for light in &mut s.lights {
        light.position = at(light.position);
        light.color = v(light.color);
        light.intensity = r(light.intensity);
    }
    for m in s.materials.values_mut() {
        m.color = v(m.color);
        m.diffuse = r(m.diffuse);
        m.specular = r(m.specular);
        m.shininess = r(m.shininess);
        m.mirror = r(m.mirror);
        m.transparency = r(m.transparency);
        m.ior = r(m.ior);
        if let Some(c) = &mut m.checker {
            c.color = v(c.color);
            c.size = r(c.size);
        }
    }
    for sphere in &mut s.spheres {
        sphere.center = at(sphere.center);
        sphere.radius = r(sphere.radius);
    }
    for plane in &mut s.planes {
        plane.point = at(plane.point);
        plane.normal = v(plane.normal);
    }
    let placement = |p: &mut Placement| {
        p.translate = at(p.translate);
        p.scale = r(p.scale);
        p.rotation = v(p.rotation);
    };
    let per_axis = |p: &mut Placement<AxisScale>| {
        p.translate = at(p.translate);
        p.scale = AxisScale::PerAxis(v(p.scale.edges()));
        p.rotation = v(p.rotation);
    };
    for cube in &mut s.cubes {
        per_axis(&mut cube.placement);
    }
    for t in &mut s.tori {
        placement(&mut t.placement);
        t.major_radius = r(t.major_radius);
        t.minor_radius = r(t.minor_radius);
    }
    for i in &mut s.implicits {
        placement(&mut i.placement);
        i.bounds = i.bounds.map(v);
    }
    for j in &mut s.julias {
        placement(&mut j.placement);
        j.c = j.c.map(r);
        j.slice = r(j.slice);
        j.epsilon = r(j.epsilon);
    }
    for m in &mut s.meshes {
        per_axis(&mut m.placement);
        // The GPU gets the vertices in the mesh's own coordinates, in f32.
        let g = &m.geometry.0;
        let rounded = Geometry {
            positions: g.positions.iter().map(|&p| v(p)).collect(),
            normals: g.normals.iter().map(|&n| v(n)).collect(),
            ..Geometry::clone(g)
        };
        if rounded != **g {
            m.geometry = Loaded(Arc::new(rounded));
        }
    }
    s
}

/// The scene scaled by `factor` about the origin: every position and length,
/// the checker cells and the lens included, so that the image stays the same
/// (lights do not fall off with distance).
pub fn scaled(scene: &Scene, factor: f64) -> Scene {
    let mut s = scene.clone();
    s.camera.from *= factor;
    s.camera.to *= factor;
    s.camera.aperture *= factor;
    s.camera.focus_distance = s.camera.focus_distance.map(|d| d * factor);
    for light in &mut s.lights {
        light.position *= factor;
    }
    for m in s.materials.values_mut() {
        if let Some(c) = &mut m.checker {
            c.size *= factor;
        }
    }
    for sphere in &mut s.spheres {
        sphere.center *= factor;
        sphere.radius *= factor;
    }
    for plane in &mut s.planes {
        plane.point *= factor;
    }
    for cube in &mut s.cubes {
        let p = &mut cube.placement;
        p.translate *= factor;
        p.scale = match p.scale {
            AxisScale::Uniform(e) => AxisScale::Uniform(e * factor),
            AxisScale::PerAxis(e) => AxisScale::PerAxis(e * factor),
        };
    }
    // The implicit surfaces are written in local units: scaling the scene
    // scales their placement.
    let grow = |p: &mut Placement| {
        p.translate *= factor;
        p.scale *= factor;
    };
    s.tori.iter_mut().for_each(|t| grow(&mut t.placement));
    s.implicits.iter_mut().for_each(|i| grow(&mut i.placement));
    s.julias.iter_mut().for_each(|j| grow(&mut j.placement));
    s
}

/// A stress scene moved or scaled, with the scene whose image is its exact
/// answer: `raysandbox stress` compares the GPU's render of `scene` with
/// the f64 reference's render of `exact`, which shares no rounding with it.
pub struct Moved {
    pub name: String,
    pub scene: Scene,
    pub exact: Scene,
}

/// The position-independence targets (docs/accuracy.md), each with the
/// scene whose f64 image is its exact answer (translating or scaling a scene
/// leaves its image as it is: lights do not fall off with distance):
/// - `moved_1e<k>`: the base scene of the series translated by
///   10^k (-1, 1, -1), k = 6 to 12 (the limit is in f64 itself);
/// - `base_at_...`: translated by 1e6 along four more directions;
/// - `scaled_1e<k>`: the base scene scaled by 10^k, k = -6 to 8 (1e0: the
///   base against its own reference, the comparison's floor);
/// - the oblique small sphere seen from 1e6 units, moved 1e6 away from the
///   origin.
pub fn moved() -> Vec<Moved> {
    let base = load("scale_1e0");
    let oblique = load("small_sphere_oblique_1e6");
    let member = |name: String, scene: Scene| Moved {
        name,
        scene,
        exact: base.clone(),
    };
    let mut out = Vec::new();
    for k in [6, 8, 10, 12, 14] {
        let offset = power_of_ten(k) * DVec3::new(-1.0, 1.0, -1.0);
        out.push(member(format!("moved_1e{k}"), base.translated(offset)));
    }
    let directions: [(&str, [f64; 3]); 4] = [
        ("+1e6x", [1.0, 0.0, 0.0]),
        ("-1e6y", [0.0, -1.0, 0.0]),
        ("+1e6z", [0.0, 0.0, 1.0]),
        ("+1e6xyz", [1.0, 1.0, 1.0]),
    ];
    for (label, dir) in directions {
        let offset = 1e6 * DVec3::from_array(dir);
        out.push(member(format!("base_at_{label}"), base.translated(offset)));
    }
    for k in [-7, -6, -5, -4, 0, 4, 8, 12, 16] {
        let scene = scaled(&base, power_of_ten(k));
        out.push(member(format!("scaled_1e{k}"), scene));
    }
    out.push(Moved {
        name: "oblique_1e6_at_-1e6x+1e6y-1e6z".to_string(),
        scene: oblique.translated(DVec3::new(-1e6, 1e6, -1e6)),
        exact: oblique,
    });
    out
}

/// The base scene of the mesh series, `assets/scenes/stress/meshes/bunny.toml`,
/// read from the project folder (its mesh file is not embedded in the
/// binary).
pub fn bunny() -> Result<Scene, String> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/scenes/stress/meshes/bunny.toml");
    Scene::load(&path).map_err(|e| e.to_string())
}

/// `scene` seen from `distance` units away along its camera's own line of
/// sight, the field of view narrowed so that the target keeps its size in
/// the image: only the size of the numbers changes.
pub fn seen_from(scene: &Scene, distance: f64) -> Scene {
    let mut s = scene.clone();
    let camera = &mut s.camera;
    let offset = camera.from - camera.to;
    let near = offset.length();
    camera.from = camera.to + offset * (distance / near);
    let half_width = (camera.fov.to_radians() / 2.0).tan() * near / distance;
    camera.fov = 2.0 * half_width.atan().to_degrees();
    s
}

/// The mesh series of the stress command: the bunny seen from 10^k units
/// (`bunny_far_1e<k>`, k = 1 to 6, each against the reference of its own
/// f32-rounded scene), and the bunny's scene translated by 10^k (-1, 1, -1)
/// (`bunny_moved_1e<k>`, k = 2 to 6, against the unmoved scene's f64
/// image).
pub fn mesh_series() -> Result<MeshSeries, String> {
    let base = bunny()?;
    let far = (1..=6)
        .map(|k| {
            (
                format!("bunny_far_1e{k}"),
                seen_from(&base, power_of_ten(k)),
            )
        })
        .collect();
    let moved = (2..=6)
        .map(|k| Moved {
            name: format!("bunny_moved_1e{k}"),
            scene: base.translated(power_of_ten(k) * DVec3::new(-1.0, 1.0, -1.0)),
            exact: base.clone(),
        })
        .collect();
    Ok(MeshSeries { far, moved })
}

/// The two mesh series: `(name, scene)` seen from far, and the moved scenes.
pub struct MeshSeries {
    pub far: Vec<(String, Scene)>,
    pub moved: Vec<Moved>,
}

/// `10^k` as the literal `1e<k>` reads, exactly as in the scene files.
pub fn power_of_ten(k: i32) -> f64 {
    format!("1e{k}").parse().expect("a float literal")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_stress_file_is_embedded_and_valid() {
        let on_disk = crate::scene::bundled::toml_stems("assets/scenes/stress");
        let mut embedded: Vec<String> = SCENES.iter().map(|(n, _)| n.to_string()).collect();
        embedded.sort();
        assert_eq!(
            embedded, on_disk,
            "embed every file of assets/scenes/stress"
        );
        for (name, text) in SCENES {
            let first = text.lines().next().unwrap_or_default();
            assert!(first.starts_with('#'), "{name}: say what it provokes");
            load(name);
        }
    }

    /// The translated and scaled files are the base scene moved by exactly
    /// 10^k (the same f64 arithmetic), so that the series measures nothing
    /// but the size of the numbers.
    #[test]
    fn series_files_are_the_base_transformed() {
        let base = load("scale_1e0");
        for (name, _) in SCENES {
            let Some((series, k)) = series_member(name) else {
                continue;
            };
            let expected = match series {
                "translate" => base.translated(DVec3::splat(power_of_ten(k))),
                "scale" => scaled(&base, power_of_ten(k)),
                _ => continue,
            };
            let mut actual = load(name);
            // The files spell a cube size as a number or a list; compare edges.
            for (a, e) in actual.cubes.iter_mut().zip(&expected.cubes) {
                if a.placement.scale.edges() == e.placement.scale.edges() {
                    a.placement.scale = e.placement.scale;
                }
            }
            assert_eq!(actual, expected, "{name}");
        }
    }

    #[test]
    fn series_names() {
        assert_eq!(series_member("translate_1e4"), Some(("translate", 4)));
        assert_eq!(series_member("scale_1e-3"), Some(("scale", -3)));
        assert_eq!(
            series_member("small_sphere_oblique_1e5"),
            Some(("small_sphere_oblique", 5))
        );
        assert_eq!(series_member("contact_gaps"), None);
        assert_eq!(
            series_member("camera_target_1e-6"),
            Some(("camera_target", -6))
        );
    }

    #[test]
    fn rounding_to_f32_is_idempotent_and_close() {
        let s = load("translate_1e6");
        let r = round_to_f32(&s);
        assert_eq!(round_to_f32(&r), r);
        let moved = (r.spheres[0].center - s.spheres[0].center)
            .abs()
            .max_element();
        // Rounded relative to the target (within 3 units of it): by at most
        // half an f32 ulp of 4, not of 1e6.
        assert!(moved > 0.0 && moved <= 2f64.powi(-22), "{moved}");
    }
}
