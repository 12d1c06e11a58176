//! `[[spheres]]`: a sphere (docs/scene-format.md).

use glam::DVec3;
use indexmap::IndexMap;
use serde::{Deserialize, Serialize};

use super::Shape;
use crate::scene::Material;
use crate::scene::key_path::KeyPath;
use crate::scene::validate::{Check, FINITE, POSITIVE, material_name, number, vector};

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Sphere {
    pub center: DVec3,
    pub radius: f64,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub material: Option<String>,
}

impl Shape for Sphere {
    fn validate(&mut self, path: &KeyPath, materials: &IndexMap<String, Material>) -> Check {
        vector(&path.key("center"), self.center, &FINITE)?;
        number(&path.key("radius"), self.radius, &POSITIVE)?;
        material_name(path, self.material.as_deref(), materials)
    }

    fn translate(&mut self, offset: DVec3) {
        self.center += offset;
    }

    fn material(&self) -> &Option<String> {
        &self.material
    }

    fn material_mut(&mut self) -> &mut Option<String> {
        &mut self.material
    }

    fn bounds(&self) -> [DVec3; 2] {
        let r = DVec3::splat(self.radius);
        [self.center - r, self.center + r]
    }
}
