//! `[[planes]]`: an infinite, two-sided, thin plane (docs/scene-format.md).

use glam::DVec3;
use serde::{Deserialize, Serialize};

use super::{Context, NoChoices, Shape, Unplaced};
use crate::scene::key_path::KeyPath;
use crate::scene::validate::{Check, FINITE, direction, unit, vector};

/// An infinite, two-sided, thin plane. `normal` is unit length after loading.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Plane {
    pub point: DVec3,
    pub normal: DVec3,
}

impl NoChoices for Plane {}

impl Shape for Plane {
    type Placement = Unplaced;
    const THIN: bool = true;
    const BOUNDED: bool = false;

    /// Checks a plane and makes its normal unit length (docs/rendering-model.md, "Shapes").
    fn validate(&mut self, path: &KeyPath, _context: &Context) -> Check {
        vector(&path.key("point"), self.point, &FINITE)?;
        vector(&path.key("normal"), self.normal, &FINITE)?;
        direction(&path.key("normal"), self.normal)?;
        self.normal = unit(self.normal);
        Ok(())
    }

    fn translate(&mut self, offset: DVec3) {
        self.point += offset;
    }

    /// All of space: a plane is unbounded.
    fn bounds(&self, _: &Unplaced) -> [DVec3; 2] {
        [DVec3::NEG_INFINITY, DVec3::INFINITY]
    }
}
