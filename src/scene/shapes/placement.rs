//! `translate`, `scale` and `rotation`: how a shape written in local
//! coordinates (a torus, a user's function, a Julia set, a mesh) sits in the
//! world (docs/rendering-model.md, "Implicit surfaces" and "Triangle
//! meshes"): a local point `p` is at `translate + Rz Ry Rx (scale p)`.
//!
//! A placed kind holds one [`Placement`] read flattened (`#[serde(flatten)]`),
//! so its three keys stay in the shape's own table of the scene file.

use std::fmt::Debug;

use glam::{DMat3, DVec3};
use serde::{Deserialize, Serialize};

use crate::scene::key_path::KeyPath;
use crate::scene::validate::{Check, FINITE, POSITIVE, number, vector};

/// Where a shape written in local coordinates sits in the world.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, bound(deserialize = "S: Scale + Deserialize<'de>"))]
pub struct Placement<S = f64> {
    pub translate: DVec3,
    pub scale: S,
    /// Degrees about the world x, y, z axes, applied in that order.
    pub rotation: DVec3,
}

/// `size = 1` (a cube) or `size = [x, y, z]` (a box); a mesh's `scale`
/// takes the same two forms.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum CubeSize {
    Uniform(f64),
    PerAxis(DVec3),
}

impl CubeSize {
    /// Edge lengths along the local x, y, z axes.
    pub fn edges(self) -> DVec3 {
        match self {
            CubeSize::Uniform(s) => DVec3::splat(s),
            CubeSize::PerAxis(v) => v,
        }
    }
}

/// A placement's `scale`: one factor (`f64`, the implicit surfaces, whose
/// distances and normals need a uniform scale) or a number or one factor
/// per axis ([`CubeSize`], meshes and a cube's `size`).
pub trait Scale: Copy + PartialEq + Debug + Serialize {
    /// No scaling: the default of `scale`.
    const ONE: Self;

    /// The factors along the local x, y, z axes.
    fn axes(self) -> DVec3;

    /// Checks that every factor is > 0; `path` names the key.
    fn validate(self, path: &KeyPath) -> Check;
}

impl Scale for f64 {
    const ONE: f64 = 1.0;

    fn axes(self) -> DVec3 {
        DVec3::splat(self)
    }

    fn validate(self, path: &KeyPath) -> Check {
        number(path, self, &POSITIVE)
    }
}

impl Scale for CubeSize {
    const ONE: CubeSize = CubeSize::Uniform(1.0);

    fn axes(self) -> DVec3 {
        self.edges()
    }

    fn validate(self, path: &KeyPath) -> Check {
        match self {
            CubeSize::Uniform(s) => number(path, s, &POSITIVE),
            CubeSize::PerAxis(s) => vector(path, s, &POSITIVE),
        }
    }
}

/// At the origin, unscaled, unrotated.
impl<S: Scale> Default for Placement<S> {
    fn default() -> Self {
        Placement {
            translate: DVec3::ZERO,
            scale: S::ONE,
            rotation: DVec3::ZERO,
        }
    }
}

impl<S: Scale> Placement<S> {
    /// `Rz(rz) Ry(ry) Rx(rx)`, the cube's convention.
    pub fn rotation_matrix(&self) -> DMat3 {
        super::rotation_degrees(self.rotation)
    }

    /// The linear part of local to world: `R * diag(scale)`.
    pub fn linear(&self) -> DMat3 {
        self.rotation_matrix() * DMat3::from_diagonal(self.scale.axes())
    }

    /// Checks the three keys in the shape's table at `path`.
    pub fn validate(&self, path: &KeyPath) -> Check {
        vector(&path.key("translate"), self.translate, &FINITE)?;
        self.scale.validate(&path.key("scale"))?;
        vector(&path.key("rotation"), self.rotation, &FINITE)
    }
}

impl Placement {
    /// The world box around the local box `[lo, hi]`: along each world
    /// axis, its centre's image plus or minus `|R|` times its half size.
    pub fn bounds(&self, [lo, hi]: [DVec3; 2]) -> [DVec3; 2] {
        let m = self.rotation_matrix();
        let abs = DMat3::from_cols(m.x_axis.abs(), m.y_axis.abs(), m.z_axis.abs());
        let centre = self.translate + self.scale * (m * (0.5 * (lo + hi)));
        let half = self.scale * (abs * (0.5 * (hi - lo)));
        [centre - half, centre + half]
    }
}
