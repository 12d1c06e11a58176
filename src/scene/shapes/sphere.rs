//! `[[spheres]]`: a sphere (docs/scene-format.md).

use glam::DVec3;
use serde::{Deserialize, Serialize};

use super::{Context, NoChoices, Shape, Unplaced};
use crate::scene::key_path::KeyPath;
use crate::scene::validate::{Check, FINITE, POSITIVE, number, vector};

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Sphere {
    pub center: DVec3,
    pub radius: f64,
}

impl NoChoices for Sphere {}

impl Shape for Sphere {
    type Placement = Unplaced;

    fn validate(&mut self, path: &KeyPath, _context: &Context) -> Check {
        vector(&path.key("center"), self.center, &FINITE)?;
        number(&path.key("radius"), self.radius, &POSITIVE)
    }

    fn translate(&mut self, offset: DVec3) {
        self.center += offset;
    }

    fn bounds(&self, _: &Unplaced) -> [DVec3; 2] {
        let r = DVec3::splat(self.radius);
        [self.center - r, self.center + r]
    }
}
