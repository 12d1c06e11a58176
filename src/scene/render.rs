//! `[render]`: the settings every scene has, and beside them in the same
//! table the keys a shape kind adds for its own shapes (a mesh's
//! `triangles`), so that no shared code names a kind (docs/scene-format.md,
//! "`[render]`: how the image is computed").

use std::ops::{Deref, DerefMut};

use glam::DVec3;
use serde::{Deserialize, Serialize};

use super::Render;

/// Deepest secondary ray a scene may ask for (`max_depth` in
/// docs/scene-format.md): the shader's ray-tree stack is sized from it.
pub const MAX_DEPTH: u32 = 16;

/// `[render]`: global shading settings (defaults in docs/scene-format.md).
/// Read flattened into [`Render`] beside every kind's own keys.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct RenderSettings {
    /// Deepest secondary ray, 0..=16; 0 = primary rays only.
    pub max_depth: u32,
    /// Secondary rays whose weight falls below this are not traced.
    pub min_weight: f64,
    pub background: DVec3,
    pub ambient: DVec3,
    pub exposure: f64,
    /// The lecture's switches (docs/rendering-model.md, "Lecture
    /// switches"): shadow rays, reflected rays and refracted rays, each on
    /// unless the scene turns it off. Written to a file only when off.
    #[serde(skip_serializing_if = "is_on")]
    pub shadows: bool,
    #[serde(skip_serializing_if = "is_on")]
    pub reflection: bool,
    #[serde(skip_serializing_if = "is_on")]
    pub refraction: bool,
    /// The intersection and offset routines both renderers use: the robust
    /// ones, or the lecture's textbook ones, to show the leaks and acne
    /// they cause (docs/rendering-model.md, "Lecture switches"). Written to
    /// a file only when textbook.
    #[serde(skip_serializing_if = "Intersections::is_robust")]
    pub intersections: Intersections,
}

crate::named_option! {
    /// `intersections` in `[render]`: which intersection routines trace
    /// the scene (docs/accuracy.md compares them).
    #[derive(Serialize, Deserialize)]
    #[serde(rename_all = "lowercase")]
    pub enum Intersections {
        /// The robust routines (docs/implementation.md): camera-relative
        /// positions, stable roots, offsets that scale with the scene.
        #[default]
        Robust = "robust",
        /// The lecture's: the naive quadratic, the plain slab test, world
        /// coordinates and a fixed offset of 1e-3.
        Textbook = "textbook",
    }
}

impl Intersections {
    pub fn is_robust(&self) -> bool {
        *self == Intersections::Robust
    }
}

/// A lecture switch left at its default, on: not written to the file.
fn is_on(switch: &bool) -> bool {
    *switch
}

impl Default for RenderSettings {
    fn default() -> Self {
        Self {
            max_depth: 5,
            min_weight: 0.0,
            background: DVec3::ZERO,
            ambient: DVec3::splat(0.1),
            exposure: 1.0,
            shadows: true,
            reflection: true,
            refraction: true,
            intersections: Intersections::Robust,
        }
    }
}

/// Writes [`Render`] from the registry `for_each_shape_kind!` (expanded
/// in `scene`, where the kinds are): one field per kind, named after the
/// scene's array of it (`meshes`), holding the kind's `Choices::Settings`.
macro_rules! render_with_kinds {
    ($($kind:ident: $field:ident),* $(,)?) => {
        /// The whole `[render]` table: the settings every scene has, and
        /// each kind's own keys ([`Choices::Settings`], which only that kind's
        /// code reads), read flattened side by side so that the file has
        /// one table. It dereferences to the shared settings, so
        /// `render.max_depth` reads the shared key.
        #[derive(Debug, Clone, Default, PartialEq, serde::Serialize, serde::Deserialize)]
        #[serde(deny_unknown_fields, default)]
        pub struct Render {
            #[serde(flatten)]
            pub settings: RenderSettings,
            $(#[serde(flatten)] pub $field: <$kind as Choices>::Settings,)*
        }

        impl Render {
            /// serde reads the parts flattened and blames an error in one
            /// of them on the table; the first unknown key, or else each
            /// part read alone from the `table`, gives the error at its key
            /// (src/scene/parse.rs).
            pub(crate) fn error_at_key<'de, D>(table: impl Fn() -> D) -> Option<D::Error>
            where
                D: serde::Deserializer<'de>,
            {
                use serde::Deserialize as _;
                use $crate::scene::flattened::{keys_of, unknown_key};
                let known = [keys_of::<RenderSettings>() $(, keys_of::<<$kind as Choices>::Settings>())*].concat();
                unknown_key(table(), &known)
                    .or_else(|| RenderSettings::deserialize(table()).err())
                    $(.or_else(|| <<$kind as Choices>::Settings>::deserialize(table()).err()))*
            }
        }
    };
}
pub(super) use render_with_kinds;

impl Deref for Render {
    type Target = RenderSettings;

    fn deref(&self) -> &RenderSettings {
        &self.settings
    }
}

impl DerefMut for Render {
    fn deref_mut(&mut self) -> &mut RenderSettings {
        &mut self.settings
    }
}
