//! `translate`, `scale` and `rotation`: how the implicit surfaces (tori,
//! user functions, Julia sets) are placed in the world
//! (docs/rendering-model.md, "Implicit surfaces"): a local point `p` is at
//! `translate + Rz Ry Rx (scale p)`.

use glam::{DMat3, DVec3};

use crate::scene::key_path::KeyPath;
use crate::scene::validate::{Check, FINITE, POSITIVE, number, vector};

/// Where a shape written in local coordinates sits in the world.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Placement {
    pub translate: DVec3,
    pub scale: f64,
    /// Degrees about the world x, y, z axes, applied in that order.
    pub rotation: DVec3,
}

impl Placement {
    /// `Rz(rz) Ry(ry) Rx(rx)`, the cube's convention.
    pub fn rotation_matrix(&self) -> DMat3 {
        super::rotation_degrees(self.rotation)
    }

    /// Checks the three keys under `path`.
    pub fn validate(&self, path: &KeyPath) -> Check {
        vector(&path.key("translate"), self.translate, &FINITE)?;
        number(&path.key("scale"), self.scale, &POSITIVE)?;
        vector(&path.key("rotation"), self.rotation, &FINITE)
    }

    /// The world box around the local box `[lo, hi]`.
    pub fn bounds(&self, [lo, hi]: [DVec3; 2]) -> [DVec3; 2] {
        let m = self.rotation_matrix();
        let abs = DMat3::from_cols(m.x_axis.abs(), m.y_axis.abs(), m.z_axis.abs());
        let centre = self.translate + self.scale * (m * (0.5 * (lo + hi)));
        let half = self.scale * (abs * (0.5 * (hi - lo)));
        [centre - half, centre + half]
    }
}

/// The serde default of `scale`.
pub fn one() -> f64 {
    1.0
}
