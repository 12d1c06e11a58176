//! A toy shape kind, a disk, written here as a new kind would be, to show
//! that the kinds' traits are all a kind needs (docs/implementation.md,
//! "Adding a shape kind"): its keys beside the shared placement and
//! material ([`scene::Shape`], read and validated by [`Instance`]), its f64
//! hit test ([`Prepare`], [`Trace`]), its WGSL and the packed twin of its
//! WGSL struct (`packed_struct!`, checked against naga's layout). What it
//! cannot show is the one line of `for_each_shape_kind!` that a real kind
//! adds, which a test cannot add: that line gives it a `ShapeKind`, its
//! array in `Scene` and the registry's code in every layer.

use glam::DVec3;
use indexmap::IndexMap;
use serde::{Deserialize, Serialize};

use super::shapes::{Frame, Layout, f32x3, packed_struct};
use crate::gpu::ShaderSource;
use crate::reference::ReferenceOptions;
use crate::reference::intersect::Hit;
use crate::reference::ray::Ray;
use crate::reference::shapes::placement::Placed;
use crate::reference::shapes::{Prepare, Trace};
use crate::scene::{
    self, Check, Folder, Instance, Issue, KeyPath, Material, NEW_SHAPE_SIZE, NoChoices, Placement,
    Scene, Shape, bundled,
};

/// `[[disks]]`: a disk of `radius` about the origin in the local xy plane,
/// placed by the shared `translate`, `scale` and `rotation`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
struct Disk {
    radius: f64,
}

impl NoChoices for Disk {}

impl Shape for Disk {
    type Placement = Placement;
    const THIN: bool = true;

    fn validate(&mut self, path: &KeyPath, _context: &scene::Context) -> Check {
        if self.radius > 0.0 && self.radius.is_finite() {
            Ok(())
        } else {
            let message = format!("must be > 0, got {}", self.radius);
            Err(Issue::new(&path.key("radius"), message))
        }
    }

    fn bounds(&self, placement: &Placement) -> [DVec3; 2] {
        let r = self.radius;
        placement.bounds([DVec3::new(-r, -r, 0.0), DVec3::new(r, r, 0.0)])
    }

    /// A `.disk` file holds its radius.
    const FILE_EXTENSIONS: &[&str] = &["disk"];

    fn from_bytes(name: &str, bytes: &[u8]) -> Result<Disk, String> {
        let text = String::from_utf8_lossy(bytes);
        match text.trim().parse() {
            Ok(radius) => Ok(Disk { radius }),
            Err(e) => Err(format!("{name}:1: {e}")),
        }
    }
}

/// The disk as the f64 tracer reads it.
#[derive(Debug, Clone)]
struct TracedDisk {
    placed: Placed,
    radius: f64,
}

impl Prepare for Disk {
    type Traced = TracedDisk;

    fn prepare(shape: &Instance<Disk>) -> TracedDisk {
        TracedDisk {
            placed: Placed::new(&shape.placement),
            radius: shape.radius,
        }
    }
}

impl Trace for TracedDisk {
    fn hit(&self, ray: &Ray, t_max: f64, _options: &ReferenceOptions) -> Option<Hit> {
        let p = &self.placed;
        let origin = p.inverse * (ray.origin - p.center) / p.scale;
        let dir = p.inverse * ray.dir;
        if dir.z == 0.0 {
            return None;
        }
        let t = -origin.z / dir.z * p.scale;
        let local = origin + dir * (t / p.scale);
        let inside = local.truncate().length() <= self.radius;
        let normal = p.rotation * DVec3::Z;
        (inside && t > 0.0 && t < t_max)
            .then(|| Hit::new(t, ray.at(t), normal, p.center.abs().max_element()))
    }
}

packed_struct! {
    /// The twin of the WGSL `struct Disk`.
    pub struct PackedDisk {
        pub center: [f32; 3],
        pub radius: f32,
        pub normal: [f32; 3],
        pub material: u32,
    }
}

/// The disk's WGSL: its struct and `hit_disk`, as a kind's file of
/// `shaders/shapes/` has them.
const WGSL: &str = "
struct Disk {
    center: vec3<f32>,
    radius: f32,
    normal: vec3<f32>,
    material: u32,
}

/// The disk's plane through its centre, then the hit's squared distance
/// from the centre against the squared radius. A ray along the plane, for
/// which the division means nothing (WGSL does not promise an infinity),
/// gets `best.t` and misses.
fn hit_disk(ray: Ray, s: Disk, index: u32, best: Hit) -> Hit {
    let denom = dot(s.normal, ray.dir);
    let t = select(dot(s.center - ray.origin, s.normal) / denom, best.t, abs(denom) < 1e-8);
    let p = ray.origin + t * ray.dir;
    let d = p - s.center;
    if !(t > ray.t_min && t < best.t && dot(d, d) <= s.radius * s.radius) {
        return best;
    }
    return surface_hit(t, p, s.normal, KIND_NONE, index, max3(abs(s.center)));
}";

fn pack(frame: &Frame, shape: &Instance<Disk>, material: u32) -> PackedDisk {
    let placement = &shape.placement;
    PackedDisk {
        center: frame.point(placement.translate),
        radius: (shape.radius * placement.scale) as f32,
        normal: f32x3(placement.rotation_matrix() * DVec3::Z),
        material,
    }
}

const TABLE: &str = "radius = 2.0\n\
                     translate = [0.0, 0.0, -4.0]\n\
                     rotation = [0.0, 0.0, 30.0]\n\
                     material = \"red\"\n";

fn materials() -> IndexMap<String, Material> {
    IndexMap::from([("red".to_string(), Material::default())])
}

fn read(table: &str) -> Result<Instance<Disk>, String> {
    let mut disk: Instance<Disk> = toml::from_str(table).map_err(|e| e.to_string())?;
    let materials = materials();
    let context = scene::Context {
        materials: &materials,
        files: &Folder(None),
    };
    let path = KeyPath::default().key("disks").index(0);
    disk.validate(&path, &context)
        .map_err(|issue| format!("{}: {}", issue.path, issue.message))?;
    Ok(disk)
}

#[test]
fn a_disk_reads_its_keys_beside_the_shared_placement_and_material() {
    let disk = read(TABLE).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(disk.radius, 2.0);
    assert_eq!(disk.placement.translate, DVec3::new(0.0, 0.0, -4.0));
    assert_eq!(disk.material.as_deref(), Some("red"));
    let [lo, hi] = disk.bounds();
    assert!(lo.z <= -4.0 && hi.z >= -4.0 && hi.x >= 1.99, "{lo} {hi}");

    let bad = read(&TABLE.replace("radius = 2.0", "radius = -1.0")).unwrap_err();
    assert_eq!(bad, "disks[0].radius: must be > 0, got -1");
    let unknown = read(&format!("{TABLE}colour = 1\n")).unwrap_err();
    assert!(unknown.contains("unknown field `colour`"), "{unknown}");
    let material = read(&TABLE.replace("\"red\"", "\"blue\"")).unwrap_err();
    assert!(material.starts_with("disks[0].material"), "{material}");
}

#[test]
fn a_disk_made_from_a_file_is_placed_in_view_as_any_kind_is() {
    let disk = Disk::from_bytes("a.disk", b"3\n").unwrap();
    assert_eq!(
        Disk::from_bytes("b.disk", b"wide").unwrap_err(),
        "b.disk:1: invalid float literal"
    );
    let scene = Scene::from_toml_str(bundled::text("whitted").unwrap(), None).unwrap();
    let placed = scene.placed_in_view(disk);
    let [lo, hi] = placed.bounds();
    let centre = 0.5 * (lo + hi);
    assert!((centre - scene.camera.to).length() < 1e-9, "{centre}");
    let longest = (hi - lo).max_element();
    assert!(
        (longest - NEW_SHAPE_SIZE * scene.view_scale()).abs() < 1e-9,
        "{longest}"
    );
}

#[test]
fn the_reference_traces_a_disk_through_its_trace_hook() {
    let disk = read(TABLE).unwrap();
    let traced = Disk::prepare(&disk);
    let options = ReferenceOptions::default();
    let down_the_axis = Ray::new(DVec3::new(1.0, 1.0, 6.0), DVec3::NEG_Z);
    let hit = traced
        .hit(&down_the_axis, f64::INFINITY, &options)
        .expect("a hit");
    assert!((hit.t - 10.0).abs() < 1e-12, "{}", hit.t);
    assert!((hit.n.abs() - DVec3::Z).length() < 1e-12, "{}", hit.n);
    let beside = Ray::new(DVec3::new(2.5, 0.0, 6.0), DVec3::NEG_Z);
    assert!(traced.hit(&beside, f64::INFINITY, &options).is_none());
    assert!(traced.hit(&down_the_axis, 9.0, &options).is_none(), "t_max");
}

#[test]
fn a_disks_wgsl_validates_with_the_shader_and_its_twin_matches() {
    let parts = ShaderSource::embedded()
        .parts()
        .map(|(name, text)| (name.to_string(), text.to_string()))
        .chain([("shapes/disk.wgsl".to_string(), WGSL.to_string())])
        .collect::<Vec<_>>();
    let (module, _) = ShaderSource::from_parts(parts)
        .validate()
        .unwrap_or_else(|e| panic!("{e}"));
    let (_, ty) = module
        .types
        .iter()
        .find(|(_, t)| t.name.as_deref() == Some("Disk"))
        .expect("struct Disk");
    let naga::TypeInner::Struct { members, span } = &ty.inner else {
        panic!("a struct");
    };
    assert_eq!(*span as usize, size_of::<PackedDisk>());
    let wgsl: Vec<(&str, usize)> = members
        .iter()
        .map(|m| (m.name.as_deref().unwrap(), m.offset as usize))
        .collect();
    assert_eq!(wgsl, PackedDisk::FIELDS);

    let disk = read(TABLE).unwrap();
    let frame = Frame {
        origin: DVec3::new(0.0, 0.0, -4.0),
    };
    let packed = pack(&frame, &disk, 3);
    assert_eq!(packed.center, [0.0; 3], "relative to the frame");
    assert_eq!((packed.radius, packed.material), (2.0, 3));
}
