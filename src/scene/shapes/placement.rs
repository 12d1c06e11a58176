//! `translate`, `scale` and `rotation`: how a shape written in local
//! coordinates (a box, a torus, a user's function, a Julia set, a mesh) sits
//! in the world (docs/rendering-model.md, "Implicit surfaces" and "Triangle
//! meshes"): a local point `p` is at `translate + Rz Ry Rx (scale p)`.
//!
//! The placement is not part of a kind: [`super::Instance`] holds it beside
//! the kind's own keys, read flattened (`#[serde(flatten)]`), so its keys
//! stay in the shape's own table of the scene file. Each kind names its
//! form ([`super::Shape::Placement`]): a [`Placement`], a [`Centered`] one
//! (a cube's `center`, `size`, `rotation`) or none ([`Unplaced`], a sphere
//! and a plane, placed by their own keys).

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
pub enum AxisScale {
    Uniform(f64),
    PerAxis(DVec3),
}

impl AxisScale {
    /// Edge lengths along the local x, y, z axes.
    pub fn edges(self) -> DVec3 {
        match self {
            AxisScale::Uniform(s) => DVec3::splat(s),
            AxisScale::PerAxis(v) => v,
        }
    }
}

/// A placement's `scale`: one factor (`f64`, the implicit surfaces, whose
/// distances and normals need a uniform scale) or a number or one factor
/// per axis ([`AxisScale`], meshes and a cube's `size`).
pub trait Scale: Copy + PartialEq + Debug + Serialize {
    /// No scaling: the default of `scale`.
    const ONE: Self;

    /// The same factor `s` along every axis.
    fn uniform(s: f64) -> Self;

    /// The factors along the local x, y, z axes.
    fn axes(self) -> DVec3;

    /// Checks that every factor is > 0; `path` names the key.
    fn validate(self, path: &KeyPath) -> Check;
}

impl Scale for f64 {
    const ONE: f64 = 1.0;

    fn uniform(s: f64) -> f64 {
        s
    }

    fn axes(self) -> DVec3 {
        DVec3::splat(self)
    }

    fn validate(self, path: &KeyPath) -> Check {
        number(path, self, &POSITIVE)
    }
}

impl Scale for AxisScale {
    const ONE: AxisScale = AxisScale::Uniform(1.0);

    fn uniform(s: f64) -> AxisScale {
        AxisScale::Uniform(s)
    }

    fn axes(self) -> DVec3 {
        self.edges()
    }

    fn validate(self, path: &KeyPath) -> Check {
        match self {
            AxisScale::Uniform(s) => number(path, s, &POSITIVE),
            AxisScale::PerAxis(s) => vector(path, s, &POSITIVE),
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
    /// `Rz(rz) Ry(ry) Rx(rx)` (docs/rendering-model.md, "Shapes").
    pub fn rotation_matrix(&self) -> DMat3 {
        super::rotation_degrees(self.rotation)
    }

    /// The linear part of local to world: `R * diag(scale)`.
    pub fn linear(&self) -> DMat3 {
        self.rotation_matrix() * DMat3::from_diagonal(self.scale.axes())
    }

    /// Checks the three keys in the shape's table at `path`, named
    /// `[translate, scale, rotation]` in the file.
    fn validate_keys(&self, path: &KeyPath, [translate, scale, rotation]: [&str; 3]) -> Check {
        vector(&path.key(translate), self.translate, &FINITE)?;
        self.scale.validate(&path.key(scale))?;
        vector(&path.key(rotation), self.rotation, &FINITE)
    }
}

impl Placement<AxisScale> {
    /// The world box of the box of edge lengths `scale` centred on the
    /// local origin: along each world axis, `translate` plus or minus `|R|`
    /// times its half size.
    pub fn box_bounds(&self) -> [DVec3; 2] {
        let m = self.rotation_matrix();
        let abs = DMat3::from_cols(m.x_axis.abs(), m.y_axis.abs(), m.z_axis.abs());
        let half = abs * (self.scale.edges() * 0.5);
        [self.translate - half, self.translate + half]
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

/// Where a shape of one kind is and how it moves: the part of an
/// [`super::Instance`] that every kind of the same form shares, validated
/// and moved here once. The default is where a shape sits in its own
/// coordinates (at the origin, unscaled).
pub trait Place:
    Clone + Default + PartialEq + Debug + Serialize + serde::de::DeserializeOwned
{
    /// Checks its keys in the shape's table at `path`.
    fn validate(&self, path: &KeyPath) -> Check;

    /// Moves it by `offset` (`Scene::translated`).
    fn translate(&mut self, offset: DVec3);

    /// The placement that puts a shape whose own box is `local` with the
    /// centre of that box on `center`, scaled uniformly to a longest side
    /// of `size`: how a shape made from a file joins the scene in view.
    /// A form without a scale keeps the shape where it is.
    fn fitted(local: [DVec3; 2], center: DVec3, size: f64) -> Self;
}

impl<S: Scale + serde::de::DeserializeOwned> Place for Placement<S> {
    fn validate(&self, path: &KeyPath) -> Check {
        self.validate_keys(path, ["translate", "scale", "rotation"])
    }

    fn translate(&mut self, offset: DVec3) {
        self.translate += offset;
    }

    fn fitted([lo, hi]: [DVec3; 2], center: DVec3, size: f64) -> Self {
        let factor = size / (hi - lo).max_element().max(f64::MIN_POSITIVE);
        Placement {
            translate: center - 0.5 * (lo + hi) * factor,
            scale: S::uniform(factor),
            rotation: DVec3::ZERO,
        }
    }
}

/// A cube's placement: the shared [`Placement`] of a unit box, whose keys
/// the scene file names `center` and `size` (both required) and `rotation`
/// (docs/scene-format.md, "`[[cubes]]`").
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
#[serde(from = "CenteredKeys", into = "CenteredKeys")]
pub struct Centered(pub Placement<AxisScale>);

/// [`Centered`] as the scene file writes it.
#[derive(Clone, Copy, Serialize, Deserialize)]
struct CenteredKeys {
    center: DVec3,
    size: AxisScale,
    #[serde(default)]
    rotation: DVec3,
}

impl From<CenteredKeys> for Centered {
    fn from(keys: CenteredKeys) -> Self {
        Centered(Placement {
            translate: keys.center,
            scale: keys.size,
            rotation: keys.rotation,
        })
    }
}

impl From<Centered> for CenteredKeys {
    fn from(Centered(p): Centered) -> Self {
        CenteredKeys {
            center: p.translate,
            size: p.scale,
            rotation: p.rotation,
        }
    }
}

impl std::ops::Deref for Centered {
    type Target = Placement<AxisScale>;

    fn deref(&self) -> &Placement<AxisScale> {
        &self.0
    }
}

impl std::ops::DerefMut for Centered {
    fn deref_mut(&mut self) -> &mut Placement<AxisScale> {
        &mut self.0
    }
}

impl Place for Centered {
    fn validate(&self, path: &KeyPath) -> Check {
        self.0.validate_keys(path, ["center", "size", "rotation"])
    }

    fn translate(&mut self, offset: DVec3) {
        self.0.translate += offset;
    }

    fn fitted(local: [DVec3; 2], center: DVec3, size: f64) -> Self {
        Centered(Placement::fitted(local, center, size))
    }
}

/// No placement keys: the kind places itself by its own (a sphere's
/// `center`, a plane's `point`) and moves them in [`super::Shape::translate`].
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct Unplaced;

/// Reads nothing: the keys of the table belong to the kind and the
/// instance (and a table read alone for an error's place has them).
impl<'de> Deserialize<'de> for Unplaced {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        serde::de::IgnoredAny::deserialize(deserializer).map(|_| Unplaced)
    }
}

impl Place for Unplaced {
    fn validate(&self, _path: &KeyPath) -> Check {
        Ok(())
    }

    fn translate(&mut self, _offset: DVec3) {}

    fn fitted(_local: [DVec3; 2], _center: DVec3, _size: f64) -> Self {
        Unplaced
    }
}
