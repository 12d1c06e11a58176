//! `[[spheres]]`: a sphere (docs/scene-format.md).

use glam::DVec3;
use serde::{Deserialize, Serialize};

use serde::de::IgnoredAny;

use super::{Context, Shape};
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
    fn validate(&mut self, path: &KeyPath, context: &Context) -> Check {
        vector(&path.key("center"), self.center, &FINITE)?;
        number(&path.key("radius"), self.radius, &POSITIVE)?;
        material_name(path, self.material.as_deref(), context.materials)
    }

    type Flattened = IgnoredAny;

    shape_accessors!(center);

    fn bounds(&self) -> [DVec3; 2] {
        let r = DVec3::splat(self.radius);
        [self.center - r, self.center + r]
    }
}
