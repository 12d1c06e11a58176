//! What the user chooses about how a kind is rendered, apart from what its
//! shapes are ([`super::Shape`]): its keys in `[render]`, the renderers'
//! options they give, and the flag of `raysandbox render` that overrides
//! them. Most kinds have none and say so in one line
//! (`impl NoChoices for Sphere {}`).

use serde::Serialize;
use serde::de::DeserializeOwned;

use crate::scene::Scene;

/// A kind's choices, which [`super::Shape`] requires.
pub trait Choices {
    /// The renderers' choices for the kind ([`crate::scene::KindOptions`]
    /// holds every kind's): a method chosen by name (a torus's
    /// [`super::TorusMethod`], a mesh's [`super::TriangleTest`]) or what the
    /// shader is written from (an implicit surface's functions); `()` for a
    /// kind without any.
    type Options: Clone + std::fmt::Debug + Default + PartialEq + Eq + std::hash::Hash;

    /// The kind's own keys in `[render]` (a mesh's `triangles`), read
    /// flattened into [`crate::scene::Render`] beside the shared ones and
    /// the other kinds'; [`NoSettings`] for a kind without any.
    type Settings: Clone + std::fmt::Debug + Default + PartialEq + Serialize + DeserializeOwned;

    /// The options `scene` asks for (its kind's keys in `[render]`, its
    /// shapes' functions); the default unless the kind says otherwise.
    fn options(_scene: &Scene) -> Self::Options {
        Self::Options::default()
    }

    /// The flag of `raysandbox render` that chooses the kind's options in
    /// place of the scene's (`--torus newton`), as its name and its help;
    /// `None` for a kind without one.
    const FLAG: Option<(&'static str, &'static str)> = None;

    /// The options that the value `name` of [`Choices::FLAG`] names; the
    /// error lists the names there are.
    fn options_named(name: &str) -> Result<Self::Options, String> {
        Err(format!("{name}: this kind has no options to choose"))
    }
}

/// A kind with nothing to choose: no options, no keys in `[render]`, no
/// flag. (Rust has no defaults for associated types yet, so this marker
/// gives them.)
pub trait NoChoices {}

impl<K: NoChoices> Choices for K {
    type Options = ();
    type Settings = NoSettings;
}

/// The [`Choices::Settings`] of a kind that adds no key to `[render]`.
#[derive(Debug, Clone, Default, PartialEq, Serialize, serde::Deserialize)]
pub struct NoSettings {}
