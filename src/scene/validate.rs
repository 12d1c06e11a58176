//! Loading a scene: the pipeline from text to a checked [`Scene`], and the
//! rules of docs/rendering-model.md and docs/scene-format.md that serde cannot express:
//! ranges, finiteness, distinct camera points, non-zero directions and known
//! material names. Each shape kind checks its own fields (`scene::shapes`)
//! with the helpers here.

use std::path::Path;

use glam::DVec3;
use indexmap::IndexMap;

use super::document::Document;
use super::files::SceneFiles;
use super::key_path::KeyPath;
use super::parse;
use super::{Camera, Light, MAX_DEPTH, Material, RenderSettings, Scene, SceneError};

/// How far from 1 the squared length of a plane normal may be for it to count
/// as unit length already. `normalize` lands within a few ulps of 1.
const UNIT_TOLERANCE: f64 = 8.0 * f64::EPSILON;

/// Parses and checks a scene; `origin` names the file in the error,
/// `files` gives the files its shapes read.
pub(super) fn parse_and_validate(
    text: &str,
    origin: Option<&Path>,
    files: &dyn SceneFiles,
) -> Result<Scene, SceneError> {
    load(text, files).map_err(|e| e.in_file(origin))
}

fn load(text: &str, files: &dyn SceneFiles) -> Result<Scene, SceneError> {
    let doc = Document::parse(text)?;
    let mut scene = parse::deserialize(&doc)?;
    validate(&mut scene, files).map_err(|issue| doc.error(&issue.path, issue.message))?;
    Ok(scene)
}

/// A broken rule: which value, and what is wrong with it. The line is looked
/// up later, from the path, in the document.
pub struct Issue {
    pub(crate) path: KeyPath,
    pub(crate) message: String,
}

impl Issue {
    pub(crate) fn new(path: &KeyPath, message: String) -> Self {
        Self {
            path: path.clone(),
            message,
        }
    }
}

pub type Check = Result<(), Issue>;

/// A range a number must lie in; every number must also be finite.
pub(super) struct Rule {
    holds: fn(f64) -> bool,
    /// How a message states the rule: "must be {text}".
    text: &'static str,
}

pub(super) const FINITE: Rule = Rule {
    holds: |_| true,
    text: "finite",
};
pub(super) const NON_NEGATIVE: Rule = Rule {
    holds: |x| x >= 0.0,
    text: ">= 0",
};
pub(super) const POSITIVE: Rule = Rule {
    holds: |x| x > 0.0,
    text: "> 0",
};
const FIELD_OF_VIEW: Rule = Rule {
    holds: |x| x > 0.0 && x < 180.0,
    text: "> 0 and < 180",
};

/// Checks every rule, first problem first (sections in the order of the
/// example file in docs/scene-format.md), and normalises plane normals.
fn validate(scene: &mut Scene, files: &dyn SceneFiles) -> Check {
    let root = KeyPath::default();
    render(&scene.render, &root.key("render"))?;
    camera(&scene.camera, &root.key("camera"))?;
    for (i, light) in scene.lights.iter().enumerate() {
        self::light(light, &root.key("lights").index(i))?;
    }
    for (name, material) in &scene.materials {
        self::material(material, &root.key("materials").key(name))?;
    }
    scene.validate_shapes(&root, files)
}

fn render(r: &RenderSettings, path: &KeyPath) -> Check {
    if r.max_depth > MAX_DEPTH {
        let message = format!("must be an integer in 0..={MAX_DEPTH}, got {}", r.max_depth);
        return Err(Issue::new(&path.key("max_depth"), message));
    }
    number(&path.key("min_weight"), r.min_weight, &NON_NEGATIVE)?;
    vector(&path.key("background"), r.background, &NON_NEGATIVE)?;
    vector(&path.key("ambient"), r.ambient, &NON_NEGATIVE)?;
    number(&path.key("exposure"), r.exposure, &POSITIVE)
}

fn camera(c: &Camera, path: &KeyPath) -> Check {
    vector(&path.key("from"), c.from, &FINITE)?;
    vector(&path.key("to"), c.to, &FINITE)?;
    view_direction(c, path)?;
    vector(&path.key("up"), c.up, &FINITE)?;
    direction(&path.key("up"), c.up)?;
    number(&path.key("fov"), c.fov, &FIELD_OF_VIEW)?;
    number(&path.key("aperture"), c.aperture, &NON_NEGATIVE)?;
    match c.focus_distance {
        Some(d) => number(&path.key("focus_distance"), d, &POSITIVE),
        None => Ok(()),
    }
}

/// `from - to` gives the view direction. Equal points give none, and points
/// so close together or so far apart that the length of their difference
/// under- or overflows give none that f64 can normalise. (An `up` parallel
/// to the view is fine: the renderers replace it, docs/rendering-model.md, "Camera".)
fn view_direction(c: &Camera, path: &KeyPath) -> Check {
    let offset = c.from - c.to;
    let message = if offset == DVec3::ZERO {
        format!(
            "must differ from camera.from, both are {}",
            plain_vector(c.to)
        )
    } else if offset.try_normalize().is_none() {
        let length = plain(offset.length());
        format!("is too close to or too far from camera.from, |from - to| = {length}")
    } else {
        return Ok(());
    };
    Err(Issue::new(&path.key("to"), message))
}

fn light(l: &Light, path: &KeyPath) -> Check {
    vector(&path.key("position"), l.position, &FINITE)?;
    vector(&path.key("color"), l.color, &NON_NEGATIVE)?;
    number(&path.key("intensity"), l.intensity, &NON_NEGATIVE)
}

fn material(m: &Material, path: &KeyPath) -> Check {
    vector(&path.key("color"), m.color, &NON_NEGATIVE)?;
    number(&path.key("diffuse"), m.diffuse, &NON_NEGATIVE)?;
    number(&path.key("specular"), m.specular, &NON_NEGATIVE)?;
    number(&path.key("shininess"), m.shininess, &POSITIVE)?;
    number(&path.key("mirror"), m.mirror, &NON_NEGATIVE)?;
    number(&path.key("transparency"), m.transparency, &NON_NEGATIVE)?;
    number(&path.key("ior"), m.ior, &POSITIVE)?;
    match &m.checker {
        Some(checker) => {
            let path = path.key("checker");
            vector(&path.key("color"), checker.color, &NON_NEGATIVE)?;
            number(&path.key("size"), checker.size, &POSITIVE)
        }
        None => Ok(()),
    }
}

/// A shape's material must be defined; the message lists the names that are,
/// in file order, since the usual cause is a typo.
pub(super) fn material_name(
    shape: &KeyPath,
    name: Option<&str>,
    materials: &IndexMap<String, Material>,
) -> Check {
    let Some(name) = name.filter(|name| !materials.contains_key(*name)) else {
        return Ok(());
    };
    let defined = if materials.is_empty() {
        "no materials defined".to_owned()
    } else {
        let names: Vec<&str> = materials.keys().map(String::as_str).collect();
        format!("defined: {}", names.join(", "))
    };
    let message = format!("no material named {name:?} ({defined})");
    Err(Issue::new(&shape.key("material"), message))
}

/// A finite number that satisfies `rule`.
pub(super) fn number(path: &KeyPath, x: f64, rule: &Rule) -> Check {
    if x.is_finite() && (rule.holds)(x) {
        return Ok(());
    }
    let must = if x.is_finite() { rule.text } else { "finite" };
    Err(Issue::new(
        path,
        format!("must be {must}, got {}", plain(x)),
    ))
}

/// Each component checked as a [`number`], named `path[i]`.
pub(super) fn vector(path: &KeyPath, v: DVec3, rule: &Rule) -> Check {
    v.to_array()
        .into_iter()
        .enumerate()
        .try_for_each(|(i, x)| number(&path.index(i), x, rule))
}

/// A direction must have a length, and one that f64 can normalise: a
/// length that under- or overflows when squared would turn into NaN in the
/// renderers.
pub(super) fn direction(path: &KeyPath, v: DVec3) -> Check {
    let message = if v == DVec3::ZERO {
        "must be non-zero"
    } else if v.try_normalize().is_none() {
        "is too short or too long to normalise"
    } else {
        return Ok(());
    };
    Err(Issue::new(
        path,
        format!("{message}, got {}", plain_vector(v)),
    ))
}

/// `n` at unit length. A vector that is unit length up to rounding is kept bit
/// for bit: normalising again can move the last bit, and a saved scene must
/// load back equal to the one that was saved.
pub(super) fn unit(n: DVec3) -> DVec3 {
    if (n.length_squared() - 1.0).abs() <= UNIT_TOLERANCE {
        n
    } else {
        n.normalize()
    }
}

/// A number as a student would write it: `-1`, `0.5`, `nan`, `inf`, and
/// `1e300` rather than 301 digits.
fn plain(x: f64) -> String {
    let tiny_or_huge = x != 0.0 && !(1e-6..1e16).contains(&x.abs());
    if x.is_nan() {
        "nan".to_owned()
    } else if x.is_finite() && tiny_or_huge {
        format!("{x:e}")
    } else {
        format!("{x}")
    }
}

fn plain_vector(v: DVec3) -> String {
    format!("[{}, {}, {}]", plain(v.x), plain(v.y), plain(v.z))
}
