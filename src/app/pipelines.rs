//! Pipelines per shader source and scene feature set (`ShaderOptions`),
//! built on a worker thread so that the window never freezes: an edit that
//! changes the feature set, or a shader reload, keeps drawing with the
//! pipelines in use until the new ones are ready.
//!
//! The cache is bounded (docs/reliability.md, "Memory under live editing"):
//! at most [`MAX_FEATURE_SETS`] built feature sets, the least recently used
//! dropped first, everything dropped when the source changes, and one build
//! at a time, so that typing an implicit function in the panel (a new
//! feature set per keystroke) never starts a compiler per keystroke.

use crate::gpu::{Pipelines, ShaderOptions, ShaderSource};

/// How many feature sets keep their pipelines: enough to switch back and
/// forth between a few edits (a material's mirror on and off, a shape
/// added and removed) and among the handful of scenes a lecture shows
/// without a rebuild, few enough that compiled pipelines (megabytes each in
/// the driver) never pile up. With 4, switching among five bundled scenes
/// rebuilt a pipeline at every switch, and in Chromium every such rebuild
/// left about 0.3 MB in the browser's GPU process (docs/reliability.md,
/// "The soak").
pub const MAX_FEATURE_SETS: usize = 8;

/// A finished build, as the worker reports it.
pub struct Built<P = Pipelines> {
    /// Which shader source it was built from (see [`PipelineCache::generation`]).
    pub generation: u64,
    pub options: ShaderOptions,
    pub result: Result<P, String>,
}

/// `P`: the pipelines (a plain value in the tests below).
pub struct PipelineCache<P = Pipelines> {
    /// The last good shader source.
    source: ShaderSource,
    /// Counts source changes, so builds from an older source are dropped.
    generation: u64,
    /// Built feature sets, the most recently used last.
    built: Vec<(ShaderOptions, P)>,
    /// The feature set being built from the current source, if any.
    in_flight: Option<ShaderOptions>,
    /// What the viewport draws with now.
    pub current: Option<ShaderOptions>,
}

impl<P: Clone> PipelineCache<P> {
    /// A cache holding `first`, already built for `options` from `source`.
    pub fn new(source: ShaderSource, options: ShaderOptions, first: P) -> Self {
        PipelineCache {
            source,
            generation: 0,
            built: vec![(options.clone(), first)],
            in_flight: None,
            current: Some(options),
        }
    }

    /// Replaces the shader source (a reload that validated): everything is
    /// built anew from it; the pipelines in use keep drawing meanwhile.
    pub fn set_source(&mut self, source: ShaderSource) {
        self.source = source;
        self.generation += 1;
        self.built.clear();
        self.in_flight = None;
    }

    /// The pipelines for `options` if they are built; otherwise starts
    /// building them with `spawn` (unless another build is running: the
    /// caller asks again when that one is [`finished`](Self::finished)) and
    /// returns `None`.
    pub fn get_or_build(
        &mut self,
        options: ShaderOptions,
        spawn: impl FnOnce(ShaderSource, u64),
    ) -> Option<P> {
        if let Some(i) = self.built.iter().position(|(o, _)| *o == options) {
            let entry = self.built.remove(i);
            let pipelines = entry.1.clone();
            self.built.push(entry);
            return Some(pipelines);
        }
        if self.in_flight.is_none() {
            self.in_flight = Some(options);
            spawn(self.source.clone(), self.generation);
        }
        None
    }

    /// Takes a finished build. Returns the error of a build from the current
    /// source, if it failed (a stale build is dropped silently).
    pub fn finished(&mut self, built: Built<P>) -> Result<(), String> {
        if built.generation != self.generation {
            return Ok(());
        }
        self.in_flight = None;
        let pipelines = built.result?;
        self.built.retain(|(o, _)| *o != built.options);
        self.built.push((built.options, pipelines));
        if self.built.len() > MAX_FEATURE_SETS {
            self.built.remove(0);
        }
        Ok(())
    }

    /// Counts the source changes: a build spawned with an older generation
    /// is dropped when it finishes.
    pub fn generation(&self) -> u64 {
        self.generation
    }

    /// Makes every build spawned by a cache of generation `older` or
    /// before stale: a cache that replaces one on a lost device drops the
    /// builds still running on the old device.
    pub fn follow(&mut self, older: u64) {
        self.generation = self.generation.max(older + 1);
    }

    /// Whether a build from the current source is still running.
    pub fn building(&self) -> bool {
        self.in_flight.is_some()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gpu::Features;

    /// Options that differ only in their stack size.
    fn options(n: u32) -> ShaderOptions {
        ShaderOptions {
            stack_size: n,
            features: Features::ALL,
            ..ShaderOptions::default()
        }
    }

    /// Builds `n` at once (as the worker would) and returns what it spawned.
    fn build(cache: &mut PipelineCache<u32>, n: u32) -> u32 {
        let mut spawned = 0;
        assert_eq!(cache.get_or_build(options(n), |_, _| spawned += 1), None);
        let generation = cache.generation;
        let built = Built {
            generation,
            options: options(n),
            result: Ok(n),
        };
        cache.finished(built).unwrap();
        spawned
    }

    #[test]
    fn at_most_the_limit_of_feature_sets_is_kept_least_recently_used_first_out() {
        let mut cache = PipelineCache::new(ShaderSource::embedded(), options(0), 0);
        for n in 1..20 {
            assert_eq!(build(&mut cache, n), 1);
            assert!(cache.built.len() <= MAX_FEATURE_SETS);
        }
        // The last MAX_FEATURE_SETS of them are kept, from `oldest` to 19;
        // using `oldest` makes the one after it the oldest.
        let oldest = 20 - MAX_FEATURE_SETS as u32;
        let mut spawned = 0;
        assert_eq!(
            cache.get_or_build(options(oldest), |_, _| spawned += 1),
            Some(oldest)
        );
        build(&mut cache, 20);
        assert_eq!(spawned, 0);
        let kept: Vec<u32> = cache.built.iter().map(|(_, p)| *p).collect();
        let expected: Vec<u32> = (oldest + 2..20).chain([oldest, 20]).collect();
        assert_eq!(kept, expected);
    }

    #[test]
    fn one_build_runs_at_a_time_and_a_new_source_drops_everything() {
        let mut cache = PipelineCache::new(ShaderSource::embedded(), options(0), 0);
        let mut spawned = 0;
        for n in 1..10 {
            assert_eq!(cache.get_or_build(options(n), |_, _| spawned += 1), None);
        }
        assert_eq!(spawned, 1, "one build for nine feature sets asked in a row");
        assert!(cache.building());
        cache.set_source(ShaderSource::embedded());
        assert!(cache.built.is_empty() && !cache.building());
        // The build of the old source finishes late: dropped.
        let stale = Built {
            generation: 0,
            options: options(1),
            result: Ok(1),
        };
        cache.finished(stale).unwrap();
        assert!(cache.built.is_empty());
    }

    /// The scene's `intersections` are part of the key: flipping them
    /// builds once each way, flipping back uses the pipelines kept.
    #[test]
    fn switching_intersections_back_uses_the_cached_pipelines() {
        use crate::scene::{Intersections, Scene, bundled};
        let mut scene = Scene::from_toml_str(bundled::text("whitted").unwrap(), None).unwrap();
        let robust = ShaderOptions::for_scene(&scene);
        scene.render.intersections = Intersections::Textbook;
        let textbook = ShaderOptions::for_scene(&scene);
        assert!(robust.robust && !textbook.robust);
        let mut cache = PipelineCache::new(ShaderSource::embedded(), robust.clone(), 0);
        let mut spawned = 0;
        assert_eq!(
            cache.get_or_build(textbook.clone(), |_, _| spawned += 1),
            None
        );
        let generation = cache.generation();
        let built = Built {
            generation,
            options: textbook.clone(),
            result: Ok(1),
        };
        cache.finished(built).unwrap();
        assert_eq!(cache.get_or_build(robust, |_, _| spawned += 1), Some(0));
        assert_eq!(cache.get_or_build(textbook, |_, _| spawned += 1), Some(1));
        assert_eq!(
            spawned, 1,
            "one build for the textbook pipelines, none back"
        );
    }
}
