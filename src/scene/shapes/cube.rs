//! `[[cubes]]`: a box, possibly rotated (docs/scene-format.md).

use glam::{DMat3, DVec3};
use serde::{Deserialize, Serialize};

use serde::de::IgnoredAny;

use super::placement::Scale;
use super::{Context, CubeSize, Placement, Shape, rotation_degrees};
use crate::scene::key_path::KeyPath;
use crate::scene::validate::{Check, FINITE, material_name, vector};

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

impl Cube {
    /// The rotation matrix `Rz(rz) Ry(ry) Rx(rx)` (docs/rendering-model.md, "Shapes"), in f64.
    pub fn rotation_matrix(&self) -> DMat3 {
        rotation_degrees(self.rotation)
    }

    /// The box as a placed shape: the local box of its `size` about the
    /// origin, moved to `center` and turned by `rotation`, unscaled.
    pub fn placement(&self) -> Placement {
        Placement {
            translate: self.center,
            scale: 1.0,
            rotation: self.rotation,
        }
    }
}

impl Shape for Cube {
    fn validate(&mut self, path: &KeyPath, context: &Context) -> Check {
        vector(&path.key("center"), self.center, &FINITE)?;
        self.size.validate(&path.key("size"))?;
        vector(&path.key("rotation"), self.rotation, &FINITE)?;
        material_name(path, self.material.as_deref(), context.materials)
    }

    type Flattened = IgnoredAny;

    shape_accessors!(center);

    fn bounds(&self) -> [DVec3; 2] {
        let half = self.size.edges() * 0.5;
        self.placement().bounds([-half, half])
    }
}
