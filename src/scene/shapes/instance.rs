//! One shape of a scene: a kind's own keys beside what every kind has, its
//! placement and its material (docs/scene-format.md, "Shapes"). Both are
//! read flattened into the shape's table, so the scene file is unchanged,
//! and are validated and moved here, once for every kind.

use std::ops::{Deref, DerefMut};

use glam::DVec3;
use serde::{Deserialize, Serialize};

use super::placement::Place;
use super::{Context, Shape};
use crate::scene::flattened::{keys_of, unknown_key};
use crate::scene::key_path::KeyPath;
use crate::scene::validate::{Check, material_name};

/// A shape of kind `K` in the scene: `[[spheres]]` holds `Instance<Sphere>`s.
/// It dereferences to the kind, so `instance.radius` reads the kind's key.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, bound = "K: Shape")]
pub struct Instance<K: Shape> {
    #[serde(flatten)]
    pub shape: K,
    #[serde(flatten)]
    pub placement: K::Placement,
    /// The name of its material; `None` is the default material.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub material: Option<String>,
}

impl<K: Shape> Instance<K> {
    /// The shape with the default material.
    pub fn new(shape: K, placement: K::Placement) -> Self {
        Instance {
            shape,
            placement,
            material: None,
        }
    }

    /// The same shape with the material `name`.
    #[must_use]
    pub fn with_material(self, name: &str) -> Self {
        Instance {
            material: Some(name.to_owned()),
            ..self
        }
    }

    /// Checks the kind's keys, then the placement's, then that the material
    /// is defined; `path` names the shape in messages.
    pub fn validate(&mut self, path: &KeyPath, context: &Context) -> Check {
        self.shape.validate(path, context)?;
        self.placement.validate(path)?;
        material_name(path, self.material.as_deref(), context.materials)
    }

    /// Moves the shape by `offset` (`Scene::translated`).
    pub fn translate(&mut self, offset: DVec3) {
        self.shape.translate(offset);
        self.placement.translate(offset);
    }

    /// The world-space bounding box `[min, max]` of a bounded shape.
    pub fn bounds(&self) -> [DVec3; 2] {
        self.shape.bounds(&self.placement)
    }

    /// serde reads the kind, the placement and the material flattened into
    /// one table, from keys that no longer know their place in the text,
    /// and blames an error in one of them on the table (and a missing key
    /// before an unknown one). The first unknown key of the `table`, as
    /// serde words it, or else each part read alone from the `table`, gives
    /// the error at its key (src/scene/parse.rs).
    pub(crate) fn error_at_key<'de, D>(table: impl Fn() -> D) -> Option<D::Error>
    where
        D: serde::Deserializer<'de>,
    {
        /// The material key alone, read only for its error.
        #[derive(Deserialize)]
        struct MaterialKey {
            #[serde(default, rename = "material")]
            _material: Option<String>,
        }
        let known = [keys_of::<K>(), keys_of::<K::Placement>(), &["material"]].concat();
        unknown_key(table(), &known)
            .or_else(|| K::deserialize(table()).err())
            .or_else(|| K::Placement::deserialize(table()).err())
            .or_else(|| MaterialKey::deserialize(table()).err())
    }
}

impl<K: Shape> Deref for Instance<K> {
    type Target = K;

    fn deref(&self) -> &K {
        &self.shape
    }
}

impl<K: Shape> DerefMut for Instance<K> {
    fn deref_mut(&mut self) -> &mut K {
        &mut self.shape
    }
}
