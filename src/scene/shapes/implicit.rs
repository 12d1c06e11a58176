//! `[[implicits]]`: a user's surface `f(x, y, z) = 0` (docs/scene-format.md,
//! "Implicit surfaces").

use glam::DVec3;
use serde::{Deserialize, Serialize};

use super::{Choices, Context, NoSettings, Placement, Shape};
use crate::expr::Function;
use crate::scene::Scene;
use crate::scene::key_path::KeyPath;
use crate::scene::validate::{Check, FINITE, Issue, vector};

/// The surface where `f` changes sign, looked for inside the local box
/// `bounds`; the outside is where `f > 0`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Implicit {
    /// The function of x, y, z, in the syntax of docs/scene-format.md.
    pub f: String,
    /// `[[xmin, ymin, zmin], [xmax, ymax, zmax]]`, local coordinates.
    pub bounds: [DVec3; 2],
    #[serde(default = "default_steps")]
    pub steps: u32,
}

/// Most samples along a ray.
pub const MAX_STEPS: u32 = 4096;

fn default_steps() -> u32 {
    256
}

impl Choices for Implicit {
    /// The scene's distinct functions ([`functions`]), which the shader is
    /// written from.
    type Options = Vec<String>;
    type Settings = NoSettings;

    fn options(scene: &crate::scene::Scene) -> Vec<String> {
        functions(scene)
    }
}

impl Shape for Implicit {
    fn validate(&mut self, path: &KeyPath, _context: &Context) -> Check {
        Function::parse(&self.f).map_err(|e| Issue::new(&path.key("f"), e.to_string()))?;
        let bounds = path.key("bounds");
        vector(&bounds.index(0), self.bounds[0], &FINITE)?;
        vector(&bounds.index(1), self.bounds[1], &FINITE)?;
        for (axis, name) in ["x", "y", "z"].into_iter().enumerate() {
            let (lo, hi) = (self.bounds[0][axis], self.bounds[1][axis]);
            if lo >= hi {
                return Err(Issue::new(
                    &bounds,
                    format!("min {name} must be < max {name}, got {lo} and {hi}"),
                ));
            }
        }
        if !(1..=MAX_STEPS).contains(&self.steps) {
            return Err(Issue::new(
                &path.key("steps"),
                format!("must be 1..={MAX_STEPS}, got {}", self.steps),
            ));
        }
        Ok(())
    }

    type Placement = Placement;

    fn bounds(&self, placement: &Placement) -> [DVec3; 2] {
        placement.bounds(self.bounds)
    }
}

/// The scene's distinct functions (as written), in order of first use: the
/// shader has one WGSL function per entry, and a scene whose functions are
/// the same set reuses its pipeline.
pub fn functions(scene: &Scene) -> Vec<String> {
    let mut distinct: Vec<String> = Vec::new();
    for implicit in &scene.implicits {
        if !distinct.contains(&implicit.f) {
            distinct.push(implicit.f.clone());
        }
    }
    distinct
}
