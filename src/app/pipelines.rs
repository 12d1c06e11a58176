//! Pipelines per shader source and scene feature set (`ShaderOptions`),
//! built on a worker thread so that the window never freezes: an edit that
//! changes the feature set, or a shader reload, keeps drawing with the
//! pipelines in use until the new ones are ready.

use std::collections::{HashMap, HashSet};

use crate::gpu::{Pipelines, ShaderOptions, ShaderSource};

/// A finished build, as the worker reports it.
pub struct Built {
    /// Which shader source it was built from (see [`PipelineCache::generation`]).
    pub generation: u64,
    pub options: ShaderOptions,
    pub result: Result<Pipelines, String>,
}

pub struct PipelineCache {
    /// The last good shader source.
    source: ShaderSource,
    /// Counts source changes, so builds from an older source are dropped.
    generation: u64,
    built: HashMap<ShaderOptions, Pipelines>,
    in_flight: HashSet<ShaderOptions>,
    /// What the viewport draws with now.
    pub current: Option<ShaderOptions>,
}

impl PipelineCache {
    /// A cache holding `first`, already built for `options` from `source`.
    pub fn new(source: ShaderSource, options: ShaderOptions, first: Pipelines) -> Self {
        PipelineCache {
            source,
            generation: 0,
            built: HashMap::from([(options.clone(), first)]),
            in_flight: HashSet::new(),
            current: Some(options),
        }
    }

    /// Replaces the shader source (a reload that validated): everything is
    /// built anew from it; the pipelines in use keep drawing meanwhile.
    pub fn set_source(&mut self, source: ShaderSource) {
        self.source = source;
        self.generation += 1;
        self.built.clear();
        self.in_flight.clear();
    }

    /// The pipelines for `options` if they are built; otherwise starts
    /// building them (once) with `spawn` and returns `None`.
    pub fn get_or_build(
        &mut self,
        options: ShaderOptions,
        spawn: impl FnOnce(ShaderSource, u64),
    ) -> Option<Pipelines> {
        if let Some(pipelines) = self.built.get(&options) {
            return Some(pipelines.clone());
        }
        if self.in_flight.insert(options.clone()) {
            spawn(self.source.clone(), self.generation);
        }
        None
    }

    /// Takes a finished build. Returns the error of a build from the current
    /// source, if it failed (a stale build is dropped silently).
    pub fn finished(&mut self, built: Built) -> Result<(), String> {
        if built.generation != self.generation {
            return Ok(());
        }
        self.in_flight.remove(&built.options);
        let pipelines = built.result?;
        self.built.insert(built.options, pipelines);
        Ok(())
    }

    /// Whether a build from the current source is still running.
    pub fn building(&self) -> bool {
        !self.in_flight.is_empty()
    }
}
