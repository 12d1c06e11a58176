//! `[[julias]]`: a quaternion Julia set (docs/scene-format.md, "Implicit
//! surfaces"; Crane 2005).

use glam::{DVec3, DVec4};
use serde::{Deserialize, Serialize};

use super::{Context, NoChoices, Placement, Shape};
use crate::scene::key_path::KeyPath;
use crate::scene::validate::{Check, FINITE, Issue, POSITIVE, number};

/// The set of quaternions whose orbit under `z <- z^2 + c` stays bounded,
/// cut by the slice `w = slice`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Julia {
    /// Real, i, j, k; `|c| <= 2`.
    pub c: [f64; 4],
    #[serde(default)]
    pub slice: f64,
    #[serde(default = "default_iterations")]
    pub iterations: u32,
    #[serde(default = "default_epsilon")]
    pub epsilon: f64,
    /// Grow epsilon with the pixel footprint: at distance t along a ray the
    /// surface distance is `max(epsilon, t * pixel angle)` (world units;
    /// docs/rendering-model.md, "Implicit surfaces"), so detail stays about
    /// one pixel wide at any zoom.
    #[serde(default, skip_serializing_if = "is_false")]
    pub footprint: bool,
}

/// Most iterations a Julia set may ask for.
pub const MAX_ITERATIONS: u32 = 64;

fn default_iterations() -> u32 {
    10
}

fn default_epsilon() -> f64 {
    1e-3
}

fn is_false(b: &bool) -> bool {
    !*b
}

impl NoChoices for Julia {}

impl Shape for Julia {
    fn validate(&mut self, path: &KeyPath, _context: &Context) -> Check {
        let c_path = path.key("c");
        for (i, &x) in self.c.iter().enumerate() {
            number(&c_path.index(i), x, &FINITE)?;
        }
        let length = DVec4::from_array(self.c).length();
        if length > 2.0 {
            return Err(Issue::new(
                &c_path,
                format!("|c| must be <= 2, got {length}"),
            ));
        }
        number(&path.key("slice"), self.slice, &FINITE)?;
        if !(1..=MAX_ITERATIONS).contains(&self.iterations) {
            return Err(Issue::new(
                &path.key("iterations"),
                format!("must be 1..={MAX_ITERATIONS}, got {}", self.iterations),
            ));
        }
        number(&path.key("epsilon"), self.epsilon, &POSITIVE)?;
        Ok(())
    }

    type Placement = Placement;

    const OPAQUE: bool = true;

    const NOT_VECTORS: &[&str] = &["c"];

    /// The sphere of radius 2 that holds the set.
    fn bounds(&self, placement: &Placement) -> [DVec3; 2] {
        placement.bounds([DVec3::splat(-2.0), DVec3::splat(2.0)])
    }
}
