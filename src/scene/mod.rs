//! The scene: plain data loaded from TOML (docs/scene-format.md), plus validation.
//!
//! This module knows nothing of the GPU or the UI. A [`Scene`] that came out of
//! [`Scene::from_toml_str`] or [`Scene::load`] has passed every rule of the rendering model,
//! so renderers may rely on positive radii, known material names and so on.

pub mod bundled;
mod document;
mod error;
mod key_path;
mod parse;
#[cfg(test)]
mod tests;
mod validate;
mod write;

use std::path::Path;

use glam::DVec3;
use indexmap::IndexMap;
use serde::{Deserialize, Serialize};

pub use error::SceneError;

/// A whole scene file. Every section but `camera` is optional.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    #[serde(default)]
    pub render: RenderSettings,
    pub camera: Camera,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub lights: Vec<Light>,
    /// Named materials, in file order (the order also fixes GPU indices).
    #[serde(default, skip_serializing_if = "IndexMap::is_empty")]
    pub materials: IndexMap<String, Material>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub spheres: Vec<Sphere>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub planes: Vec<Plane>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub cubes: Vec<Cube>,
}

/// Deepest secondary ray a scene may ask for (`max_depth` in
/// docs/scene-format.md): the shader's ray-tree stack is sized from it.
pub const MAX_DEPTH: u32 = 16;

/// `[render]`: global shading settings (defaults in docs/scene-format.md).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RenderSettings {
    /// Deepest secondary ray, 0..=16; 0 = primary rays only.
    pub max_depth: u32,
    /// Secondary rays whose weight falls below this are not traced.
    pub min_weight: f64,
    pub background: DVec3,
    pub ambient: DVec3,
    pub exposure: f64,
}

impl Default for RenderSettings {
    fn default() -> Self {
        Self {
            max_depth: 5,
            min_weight: 0.0,
            background: DVec3::ZERO,
            ambient: DVec3::splat(0.1),
            exposure: 1.0,
        }
    }
}

/// `[camera]`: the lecture's pinhole camera with an optional thin lens.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Camera {
    pub from: DVec3,
    pub to: DVec3,
    #[serde(default = "default_up")]
    pub up: DVec3,
    /// Vertical field of view in degrees.
    #[serde(default = "default_fov")]
    pub fov: f64,
    /// Lens radius; 0 is a pinhole.
    #[serde(default)]
    pub aperture: f64,
    /// Distance to the plane in focus; `None` means `|from - to|`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub focus_distance: Option<f64>,
}

fn default_up() -> DVec3 {
    DVec3::Y
}

fn default_fov() -> f64 {
    45.0
}

impl Camera {
    /// The focus distance in effect: the given one, else `|from - to|`.
    pub fn focus_distance(&self) -> f64 {
        self.focus_distance
            .unwrap_or_else(|| (self.from - self.to).length())
    }
}

/// `[[lights]]`: a point light. Lights do not fall off with distance.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Light {
    pub position: DVec3,
    #[serde(default = "default_light_color")]
    pub color: DVec3,
    #[serde(default = "default_intensity")]
    pub intensity: f64,
}

fn default_light_color() -> DVec3 {
    DVec3::ONE
}

fn default_intensity() -> f64 {
    1.0
}

/// `[materials.NAME]`: docs/rendering-model.md, "Materials". Missing fields take the defaults, and a
/// shape without a material uses `Material::default()`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Material {
    pub color: DVec3,
    pub diffuse: f64,
    pub specular: f64,
    pub shininess: f64,
    pub mirror: f64,
    pub transparency: f64,
    pub ior: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub checker: Option<Checker>,
}

impl Default for Material {
    fn default() -> Self {
        Self {
            color: DVec3::splat(0.8),
            diffuse: 1.0,
            specular: 0.0,
            shininess: 32.0,
            mirror: 0.0,
            transparency: 0.0,
            ior: 1.5,
            checker: None,
        }
    }
}

/// The checker texture: `color` on odd cells of edge `size`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Checker {
    pub color: DVec3,
    pub size: f64,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Sphere {
    pub center: DVec3,
    pub radius: f64,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub material: Option<String>,
}

/// An infinite, two-sided, thin plane. `normal` is unit length after loading.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Plane {
    pub point: DVec3,
    pub normal: DVec3,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub material: Option<String>,
}

/// A box: `center + Rz(rz) Ry(ry) Rx(rx) p_local` for `p_local` in the box of
/// edge lengths `size` centred at the origin.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Cube {
    pub center: DVec3,
    pub size: CubeSize,
    /// Degrees about the world x, y, z axes, applied in that order.
    #[serde(default)]
    pub rotation: DVec3,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub material: Option<String>,
}

/// `size = 1` (a cube) or `size = [x, y, z]` (a box).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum CubeSize {
    Uniform(f64),
    PerAxis(DVec3),
}

impl CubeSize {
    /// Edge lengths along the local x, y, z axes.
    pub fn edges(self) -> DVec3 {
        match self {
            CubeSize::Uniform(s) => DVec3::splat(s),
            CubeSize::PerAxis(v) => v,
        }
    }
}

impl Cube {
    /// The rotation matrix `Rz(rz) Ry(ry) Rx(rx)` (docs/rendering-model.md, "Shapes"), in f64.
    pub fn rotation_matrix(&self) -> glam::DMat3 {
        let r = self.rotation * (std::f64::consts::PI / 180.0);
        glam::DMat3::from_rotation_z(r.z)
            * glam::DMat3::from_rotation_y(r.y)
            * glam::DMat3::from_rotation_x(r.x)
    }
}

impl Scene {
    /// Parses and validates a scene from TOML text. `origin` names the file in
    /// error messages (it is not read).
    pub fn from_toml_str(text: &str, origin: Option<&Path>) -> Result<Scene, SceneError> {
        validate::parse_and_validate(text, origin)
    }

    /// Reads, parses and validates a scene file.
    pub fn load(path: &Path) -> Result<Scene, SceneError> {
        let text = std::fs::read_to_string(path).map_err(|e| SceneError::io(path, &e))?;
        Scene::from_toml_str(&text, Some(path))
    }

    /// The material a shape names, or the default material for `None`.
    /// Panics only on a name that validation would have rejected.
    pub fn material(&self, name: Option<&str>) -> &Material {
        static DEFAULT: std::sync::OnceLock<Material> = std::sync::OnceLock::new();
        match name {
            None => DEFAULT.get_or_init(Material::default),
            Some(n) => &self.materials[n],
        }
    }

    /// Index of a shape's material in the list `[default, materials in file
    /// order...]` that the GPU buffers use: 0 for `None`.
    pub fn material_slot(&self, name: Option<&str>) -> u32 {
        name.and_then(|n| self.materials.get_index_of(n))
            .map_or(0, |i| i as u32 + 1)
    }

    /// Number of shapes of every kind together.
    pub fn shape_count(&self) -> usize {
        self.spheres.len() + self.planes.len() + self.cubes.len()
    }

    /// A one-line summary for `raysandbox check`.
    pub fn summary(&self) -> String {
        format!(
            "{} spheres, {} planes, {} cubes, {} materials, {} lights",
            self.spheres.len(),
            self.planes.len(),
            self.cubes.len(),
            self.materials.len(),
            self.lights.len()
        )
    }
}
