//! `[[planes]]`: an infinite, two-sided, thin plane (docs/scene-format.md).

use glam::DVec3;
use serde::{Deserialize, Serialize};

use serde::de::IgnoredAny;

use super::{Context, Shape};
use crate::scene::key_path::KeyPath;
use crate::scene::validate::{Check, FINITE, direction, material_name, unit, vector};

/// An infinite, two-sided, thin plane. `normal` is unit length after loading.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Plane {
    pub point: DVec3,
    pub normal: DVec3,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub material: Option<String>,
}

impl Shape for Plane {
    const THIN: bool = true;
    const BOUNDED: bool = false;

    /// Checks a plane and makes its normal unit length (docs/rendering-model.md, "Shapes").
    fn validate(&mut self, path: &KeyPath, context: &Context) -> Check {
        vector(&path.key("point"), self.point, &FINITE)?;
        vector(&path.key("normal"), self.normal, &FINITE)?;
        direction(&path.key("normal"), self.normal)?;
        self.normal = unit(self.normal);
        material_name(path, self.material.as_deref(), context.materials)
    }

    type Flattened = IgnoredAny;

    shape_accessors!(point);

    /// All of space: a plane is unbounded.
    fn bounds(&self) -> [DVec3; 2] {
        [DVec3::NEG_INFINITY, DVec3::INFINITY]
    }
}
