//! Scenes that the tests of several layers share, each a scene file in
//! `src/scene/test_scenes/`, so that a test names the scene it shares
//! rather than writing it out again.

/// A scene that uses every feature of the format, with materials out of
/// alphabetical order and both forms of cube size: the rendering model's
/// example scene (docs/rendering-model.md) with a thin lens and a second
/// light, sphere and box.
pub const FULL: &str = include_str!("test_scenes/full.toml");

/// A floor with a checker, a sphere and a box near the origin, seen from
/// a camera that looks at `[0, 0.6, 0]`: the scene the tests of
/// camera-relative coordinates move far away (docs/implementation.md,
/// "Camera-relative coordinates").
pub const NEAR_THE_ORIGIN: &str = include_str!("test_scenes/near_the_origin.toml");
