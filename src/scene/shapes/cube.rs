//! `[[cubes]]`: a box, possibly rotated (docs/scene-format.md).

use glam::DVec3;
use serde::{Deserialize, Serialize};

use super::{Centered, Context, NoChoices, Shape};
use crate::scene::key_path::KeyPath;
use crate::scene::validate::Check;

/// A box: the unit box about the origin, placed by [`Centered`]: scaled by
/// the edge lengths `size`, turned by `rotation`, moved to `center`. It has
/// no keys of its own.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Cube {}

impl NoChoices for Cube {}

impl Shape for Cube {
    type Placement = Centered;

    fn validate(&mut self, _path: &KeyPath, _context: &Context) -> Check {
        Ok(())
    }

    fn bounds(&self, placement: &Centered) -> [DVec3; 2] {
        placement.box_bounds()
    }
}
