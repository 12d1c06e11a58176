//! `raysandbox stress`: the numerical stress suite. Every stress scene (and
//! the bundled scenes) is rendered on the GPU twice, with the robust
//! intersection code and with the lecture's naive versions (the shader's
//! `ROBUST` pipeline constant), and once with the f64 reference, which is fed
//! the same f32-rounded scene values the GPU gets, so that the difference
//! measures the algorithms and not the rounding of the input. See
//! `docs/accuracy.md` for the results and what they mean.

pub mod f32_intersect;
pub mod leaks;
pub mod metrics;
mod report;
pub mod scenes;
pub mod table;

use std::path::PathBuf;
use std::time::Instant;

use image::{RgbImage, RgbaImage};

use crate::gpu::{
    Accumulator, FirstHit, FrameTarget, Gpu, IdRenderer, PipelineError, Pipelines, RenderError,
    SceneBuffers, ShaderOptions, ShaderSource, encode_frame, layout::PackedScene, read_texture,
    readback_target,
};
use crate::reference::{self, PreparedScene, ReferenceOptions};
use crate::scene::{KindOptions, Scene};
use metrics::{Comparison, ReferenceRender};

/// Arguments of `raysandbox stress`.
#[derive(Debug, Clone, clap::Args)]
pub struct StressArgs {
    /// Write stress.csv, stress.md and per scene the renders, FLIP maps,
    /// difference images (|GPU - reference| x 8) and a panel of them here.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Image width. Odd sizes put a pixel centre on the optical axis, so
    /// that the centre row and column have direction components that are
    /// exactly zero (box_axis_rays needs them).
    #[arg(long, default_value_t = 321, value_parser = clap::value_parser!(u32).range(8..=4096))]
    pub width: u32,
    /// Image height (odd for the same reason).
    #[arg(long, default_value_t = 181, value_parser = clap::value_parser!(u32).range(8..=4096))]
    pub height: u32,
    /// Only the scenes whose name contains this text.
    #[arg(long)]
    pub filter: Option<String>,
    /// Leave out the bundled scenes of assets/scenes.
    #[arg(long)]
    pub no_bundled: bool,
    /// Read the WGSL from this folder instead of the embedded copy.
    #[arg(long)]
    pub shaders: Option<PathBuf>,
    /// Rays per mesh of the watertightness count (rays aimed exactly at
    /// shared edges and vertices, every triangle test, f64 and the GPU's
    /// f32); 0 leaves the count out.
    #[arg(long, default_value_t = 100_000)]
    pub leak_rays: usize,
}

/// Why the stress command failed.
#[derive(Debug)]
pub enum StressError {
    /// Bad input (shader, arguments): exit status 2.
    Input(String),
    /// The machine (no GPU, unwritable output): exit status 1.
    Runtime(String),
}

/// A GPU render and its id/depth pass.
pub struct GpuRender {
    pub image: RgbaImage,
    pub first_hits: Vec<FirstHit>,
}

/// The shader in one variant (robust or naive), built once, rendering any
/// scene at 1 sample per pixel, with its id/depth pass.
pub struct GpuVariant {
    pipelines: Pipelines,
    ids: IdRenderer,
    robust: bool,
    /// Kept to build pipelines for what a scene asks of its kinds (its own
    /// implicit functions).
    source: ShaderSource,
}

const IMAGE_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;

impl GpuVariant {
    pub fn new(gpu: &Gpu, source: &ShaderSource, robust: bool) -> Result<Self, PipelineError> {
        Self::with_kinds(gpu, source, robust, KindOptions::default())
    }

    /// The variant with the kinds' `kinds` options (a scene's implicit
    /// functions compiled in).
    fn with_kinds(
        gpu: &Gpu,
        source: &ShaderSource,
        robust: bool,
        kinds: KindOptions,
    ) -> Result<Self, PipelineError> {
        let options = ShaderOptions {
            robust,
            kinds,
            ..ShaderOptions::default()
        };
        Ok(GpuVariant {
            pipelines: Pipelines::new(&gpu.device, source, &[IMAGE_FORMAT], &options)?,
            ids: IdRenderer::new(gpu, source, &options)?,
            robust,
            source: source.clone(),
        })
    }

    /// The image at 1 sample per pixel (the pixel centre) and the first hits.
    /// The robust variant gets camera-relative positions, the naive one the
    /// textbook's world coordinates.
    pub fn render(
        &self,
        gpu: &Gpu,
        scene: &Scene,
        width: u32,
        height: u32,
    ) -> Result<GpuRender, RenderError> {
        // A scene that asks its kinds for more than the defaults (its own
        // functions) needs pipelines with that compiled in.
        let kinds = KindOptions::of(scene);
        let own;
        let variant = if kinds == KindOptions::default() {
            self
        } else {
            own = Self::with_kinds(gpu, &self.source, self.robust, kinds)?;
            &own
        };
        let device = &gpu.device;
        let packed = if variant.robust {
            PackedScene::new(scene, width, height)
        } else {
            PackedScene::in_world(scene, width, height)
        };
        let buffers = SceneBuffers::new((device, &gpu.queue), &variant.pipelines, packed)?;
        let mut accum = Accumulator::new(device, &variant.pipelines, width, height);
        let texture = readback_target(device, "stress image", (width, height), IMAGE_FORMAT);
        let view = texture.create_view(&Default::default());
        let target = FrameTarget {
            view: &view,
            format: IMAGE_FORMAT,
            size: (width, height),
        };
        let mut encoder = device.create_command_encoder(&Default::default());
        encode_frame(
            &gpu.queue,
            &mut encoder,
            &variant.pipelines,
            &buffers,
            &mut accum,
            1,
            &target,
        );
        gpu.queue.submit([encoder.finish()]);
        Ok(GpuRender {
            image: read_texture(gpu, &texture)?,
            first_hits: variant.ids.render(gpu, scene, width, height)?,
        })
    }
}

/// The reference's image, unlit image and first hits of `scene` (which the
/// caller has rounded to f32 where that is wanted), robust variant.
pub fn reference_render(scene: &Scene, width: u32, height: u32) -> ReferenceRender {
    let prepared = PreparedScene::with_options(scene, &ReferenceOptions::default());
    let mut unlit = scene.clone();
    unlit.lights.clear();
    ReferenceRender {
        image: reference::render_prepared_rgba8(&prepared, width, height, 1),
        unlit: reference::render_rgba8(&unlit, width, height, 1),
        first_hits: reference::first_hits(&prepared, width, height),
    }
}

/// One scene measured: both GPU variants against the reference.
pub struct Measured {
    pub reference: ReferenceRender,
    pub robust: GpuRender,
    pub naive: GpuRender,
    pub robust_cmp: Comparison,
    pub naive_cmp: Comparison,
    pub robust_flip: RgbImage,
    pub naive_flip: RgbImage,
}

/// Both variants of the shader, ready to measure scenes.
pub struct Harness {
    pub robust: GpuVariant,
    pub naive: GpuVariant,
}

impl Harness {
    pub fn new(gpu: &Gpu, source: &ShaderSource) -> Result<Self, PipelineError> {
        Ok(Harness {
            robust: GpuVariant::new(gpu, source, true)?,
            naive: GpuVariant::new(gpu, source, false)?,
        })
    }

    /// Renders `scene` (rounded to f32 first, for both sides) with both
    /// variants and the reference, and compares.
    pub fn measure(
        &self,
        gpu: &Gpu,
        scene: &Scene,
        width: u32,
        height: u32,
    ) -> Result<Measured, RenderError> {
        let scene = scenes::round_to_f32(scene);
        let reference = reference_render(&scene, width, height);
        self.compare(gpu, &scene, reference, width, height)
    }

    /// Measures an entry: against the reference of its own f32-rounded
    /// scene, or, for a moved scene, against the reference of the exact
    /// answer (the scene before it was moved, in f64).
    pub fn measure_entry(
        &self,
        gpu: &Gpu,
        entry: &Entry,
        width: u32,
        height: u32,
    ) -> Result<Measured, RenderError> {
        match &entry.exact {
            None => self.measure(gpu, &entry.scene, width, height),
            Some(exact) => {
                let reference = reference_render(exact, width, height);
                self.compare(gpu, &entry.scene, reference, width, height)
            }
        }
    }

    fn compare(
        &self,
        gpu: &Gpu,
        scene: &Scene,
        reference: ReferenceRender,
        width: u32,
        height: u32,
    ) -> Result<Measured, RenderError> {
        let robust = self.robust.render(gpu, scene, width, height)?;
        let naive = self.naive.render(gpu, scene, width, height)?;
        let (robust_cmp, robust_flip) =
            metrics::compare(&reference, &robust.image, &robust.first_hits);
        let (naive_cmp, naive_flip) = metrics::compare(&reference, &naive.image, &naive.first_hits);
        Ok(Measured {
            reference,
            robust,
            naive,
            robust_cmp,
            naive_cmp,
            robust_flip,
            naive_flip,
        })
    }
}

/// A scene of the run: its name, where it came from, and the scene.
pub struct Entry {
    pub name: String,
    /// "stress", "moved" or "bundled".
    pub group: &'static str,
    pub scene: Scene,
    /// For a moved scene ([`scenes::moved`]): the scene whose f64 image is
    /// the exact answer.
    pub exact: Option<Scene>,
}

/// The scenes the command runs: the stress scenes, their moved and scaled
/// copies, the mesh series, then (unless left out) the bundled ones and the
/// bundled mesh scenes, filtered by name. The mesh scenes are read from the
/// project folder (their mesh files are not embedded): an error if they
/// cannot be read.
pub fn entries(filter: Option<&str>, bundled: bool) -> Result<Vec<Entry>, String> {
    let mut out: Vec<Entry> = scenes::SCENES
        .iter()
        .map(|(name, _)| Entry {
            name: name.to_string(),
            group: "stress",
            scene: scenes::load(name),
            exact: None,
        })
        .collect();
    let meshes = scenes::mesh_series()?;
    out.extend(meshes.far.into_iter().map(|(name, scene)| Entry {
        name,
        group: "stress",
        scene,
        exact: None,
    }));
    out.extend(
        scenes::moved()
            .into_iter()
            .chain(meshes.moved)
            .map(|m| Entry {
                name: m.name,
                group: "moved",
                scene: m.scene,
                exact: Some(m.exact),
            }),
    );
    if bundled {
        for name in crate::scene::bundled::names() {
            let text = crate::scene::bundled::text(name).expect("bundled scene");
            out.push(Entry {
                name: name.to_string(),
                group: "bundled",
                scene: Scene::from_toml_str(text, None).expect("bundled scenes are valid"),
                exact: None,
            });
        }
        out.extend(bundled_mesh_scenes()?);
    }
    out.retain(|e| filter.is_none_or(|f| e.name.contains(f)));
    Ok(out)
}

/// The scenes of `assets/scenes/meshes/`, by file name.
fn bundled_mesh_scenes() -> Result<Vec<Entry>, String> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/scenes/meshes");
    let listing = std::fs::read_dir(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let mut paths: Vec<PathBuf> = listing
        .filter_map(|entry| Some(entry.ok()?.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    paths.sort();
    paths
        .iter()
        .map(|path| {
            Ok(Entry {
                name: path
                    .file_stem()
                    .unwrap_or_default()
                    .to_string_lossy()
                    .into_owned(),
                group: "bundled",
                scene: Scene::load(path).map_err(|e| e.to_string())?,
                exact: None,
            })
        })
        .collect()
}

/// Scenes whose scaled copies (x 1000 and x 1/1000) must render the same
/// image as the original: the grazing-light planes and the contact gaps.
pub const SCALE_INVARIANCE: &[&str] = &[
    "grazing_light_1deg",
    "grazing_light_0.1deg",
    "grazing_light_0.01deg",
    "contact_gaps",
];

/// FLIP between a variant's render of `scene` scaled by `factor` and its
/// render of `scene` itself (both rounded to f32), and the scaled render's
/// false shadows against the scaled reference.
pub struct Invariance {
    pub name: String,
    pub factor_power: i32,
    pub robust_flip: f64,
    pub naive_flip: f64,
    pub robust_false_shadow: f64,
    pub naive_false_shadow: f64,
}

impl Harness {
    /// How much the image of `scene` changes when the scene is scaled by
    /// `10^power`.
    pub fn invariance(
        &self,
        gpu: &Gpu,
        name: &str,
        scene: &Scene,
        power: i32,
        width: u32,
        height: u32,
    ) -> Result<Invariance, RenderError> {
        let base = scenes::round_to_f32(scene);
        let big = scenes::round_to_f32(&scenes::scaled(scene, scenes::power_of_ten(power)));
        let reference = reference_render(&big, width, height);
        let mut flips = [0.0; 2];
        let mut shadows = [0.0; 2];
        for (i, variant) in [&self.robust, &self.naive].into_iter().enumerate() {
            let a = variant.render(gpu, &base, width, height)?;
            let b = variant.render(gpu, &big, width, height)?;
            flips[i] = metrics::flip(&a.image, &b.image).0;
            shadows[i] = metrics::false_shadows(&reference, &b.image).0;
        }
        Ok(Invariance {
            name: name.to_string(),
            factor_power: power,
            robust_flip: flips[0],
            naive_flip: flips[1],
            robust_false_shadow: shadows[0],
            naive_false_shadow: shadows[1],
        })
    }
}

/// The command: measure, print, and write the report if asked.
pub fn run(args: &StressArgs) -> Result<(), StressError> {
    let source = ShaderSource::checked(args.shaders.as_deref())
        .map_err(|e| StressError::Input(e.to_string()))?;
    let entries = entries(args.filter.as_deref(), !args.no_bundled).map_err(StressError::Input)?;
    if entries.is_empty() {
        return Err(StressError::Input(format!(
            "no scene matches --filter {:?}",
            args.filter.as_deref().unwrap_or_default()
        )));
    }
    let gpu = Gpu::headless().map_err(|e| StressError::Runtime(e.to_string()))?;
    println!("adapter: {}", gpu.describe());
    println!(
        "{} scenes at {}x{}, 1 sample per pixel; reference: f64 on the f32-rounded scene \
         (moved scenes: f64 on the scene before it was moved)",
        entries.len(),
        args.width,
        args.height
    );
    let harness = Harness::new(&gpu, &source).map_err(|e| StressError::Input(e.to_string()))?;
    let image_dir = match &args.out {
        Some(dir) => {
            let images = dir.join("images");
            std::fs::create_dir_all(&images)
                .map_err(|e| StressError::Runtime(format!("{}: {e}", images.display())))?;
            Some(images)
        }
        None => None,
    };
    let start = Instant::now();
    let mut rows = Vec::new();
    println!("{}", report::console_header());
    for entry in &entries {
        let m = harness
            .measure_entry(&gpu, entry, args.width, args.height)
            .map_err(|e| StressError::Runtime(e.to_string()))?;
        let row = report::Row {
            name: entry.name.clone(),
            group: entry.group,
            robust: m.robust_cmp,
            naive: m.naive_cmp,
        };
        println!("{}", report::console_row(&row));
        if let Some(dir) = &image_dir {
            save_images(dir, &entry.name, &m)?;
        }
        rows.push(row);
    }
    let mut invariance = Vec::new();
    for name in SCALE_INVARIANCE {
        let Some(entry) = entries.iter().find(|e| e.name == *name) else {
            continue;
        };
        for power in [3, -3] {
            invariance.push(
                harness
                    .invariance(&gpu, name, &entry.scene, power, args.width, args.height)
                    .map_err(|e| StressError::Runtime(e.to_string()))?,
            );
        }
    }
    let summary = report::series_summary(&rows);
    println!();
    println!("{summary}");
    if !invariance.is_empty() {
        println!("{}", report::invariance_markdown(&invariance));
    }
    let leak_rows = if args.leak_rays > 0 {
        let rows = leaks::measure(&gpu, &source, args.leak_rays).map_err(StressError::Runtime)?;
        println!("Watertightness: rays aimed exactly at shared edges and vertices\n");
        println!("{}", leaks::markdown(&rows));
        rows
    } else {
        Vec::new()
    };
    println!("measured in {:.1} s", start.elapsed().as_secs_f64());
    if let Some(dir) = &args.out {
        let write = |name: &str, text: String| {
            let path = dir.join(name);
            std::fs::write(&path, text)
                .map_err(|e| StressError::Runtime(format!("{}: {e}", path.display())))
        };
        write("stress.csv", report::csv(&rows))?;
        let mut md = report::markdown(&rows, &summary, &invariance, args.width, args.height);
        if !leak_rows.is_empty() {
            write("leaks.csv", leaks::csv(&leak_rows))?;
            md.push_str(&report::leaks_markdown(&leak_rows));
        }
        write("stress.md", md)?;
        println!("wrote {}", dir.display());
    }
    Ok(())
}

fn save_images(dir: &std::path::Path, name: &str, m: &Measured) -> Result<(), StressError> {
    let save = |suffix: &str, result: image::ImageResult<()>| {
        result.map_err(|e| StressError::Runtime(format!("{name}-{suffix}: {e}")))
    };
    let path = |suffix: &str| dir.join(format!("{name}-{suffix}.png"));
    save("reference", m.reference.image.save(path("reference")))?;
    save("robust", m.robust.image.save(path("robust")))?;
    save("naive", m.naive.image.save(path("naive")))?;
    save("robust-flip", m.robust_flip.save(path("robust-flip")))?;
    save("naive-flip", m.naive_flip.save(path("naive-flip")))?;
    let diff = |gpu: &RgbaImage| metrics::difference_image(&m.reference.image, gpu, 8);
    save(
        "robust-diff",
        diff(&m.robust.image).save(path("robust-diff")),
    )?;
    save("naive-diff", diff(&m.naive.image).save(path("naive-diff")))?;
    save("panel", panel(m).save(path("panel")))?;
    Ok(())
}

/// One picture of a scene's measurement, 3 x 2 images 4 pixels apart:
/// reference, robust and naive render on top; below, the reference's id
/// pass (a colour per shape, black for the background) and the FLIP maps of
/// robust and naive.
pub fn panel(m: &Measured) -> RgbImage {
    let (w, h) = m.reference.image.dimensions();
    let rgb = |img: &RgbaImage| -> RgbImage {
        RgbImage::from_fn(w, h, |x, y| {
            let p = img.get_pixel(x, y);
            image::Rgb([p[0], p[1], p[2]])
        })
    };
    let ids = RgbImage::from_fn(w, h, |x, y| {
        let hit = m.reference.first_hits[(y * w + x) as usize];
        match hit {
            None => image::Rgb([0, 0, 0]),
            Some((shape, _)) => {
                let (kind, index) = FirstHit::id_of(Some(shape));
                // A fixed bright colour per shape.
                let k = (kind * 7919 + index * 104_729).wrapping_mul(2_654_435_761);
                image::Rgb([
                    96 + (k >> 24) as u8 % 160,
                    96 + (k >> 16) as u8 % 160,
                    96 + (k >> 8) as u8 % 160,
                ])
            }
        }
    });
    let tiles = [
        rgb(&m.reference.image),
        rgb(&m.robust.image),
        rgb(&m.naive.image),
        ids,
        m.robust_flip.clone(),
        m.naive_flip.clone(),
    ];
    let gap = 4;
    let mut out = RgbImage::from_pixel(3 * w + 2 * gap, 2 * h + gap, image::Rgb([255, 255, 255]));
    for (k, tile) in tiles.iter().enumerate() {
        let (col, row) = (k as u32 % 3, k as u32 / 3);
        image::imageops::replace(
            &mut out,
            tile,
            i64::from(col * (w + gap)),
            i64::from(row * (h + gap)),
        );
    }
    out
}
