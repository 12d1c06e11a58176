//! A pixel's ray tree (docs/ray-tree.md): the GPU's debug pass against
//! the f64 reference, ray by ray, on a Whitted scene with glass where
//! total internal reflection occurs.

mod common;

use raysandbox::gpu::{RayTreeRenderer, ShaderOptions, ShaderSource, TREE_MAX};
use raysandbox::reference::{self, PreparedScene, RayDifference, RayKind, RayTree};
use raysandbox::scene::Scene;

const WIDTH: u32 = 64;
const HEIGHT: u32 = 36;

/// The Whitted scene with a glass block beside the glass sphere: light
/// that enters the block's front face and meets a side face from inside
/// beyond the critical angle is reflected totally. (A sphere alone never
/// does: inside it every ray meets the surface at the angle it entered by.)
fn glass_scene() -> Scene {
    let whitted = std::fs::read_to_string(common::scenes_dir().join("whitted.toml")).unwrap();
    let text = format!(
        "{whitted}
        [[cubes]]
        center = [-1.3, 0.6, 1.6]
        size = [0.8, 1.2, 0.8]
        rotation = [0, 35, 0]
        material = \"glass\""
    );
    Scene::from_toml_str(&text, None).unwrap()
}

/// The reference's tree at every pixel, row by row.
fn reference_trees(scene: &Scene) -> Vec<RayTree> {
    let prepared = PreparedScene::new(scene);
    (0..HEIGHT)
        .flat_map(|j| (0..WIDTH).map(move |i| (i, j)))
        .map(|(i, j)| reference::ray_tree(&prepared, WIDTH, HEIGHT, i, j))
        .collect()
}

fn has(tree: &RayTree, kind: RayKind) -> bool {
    tree.rays.iter().any(|r| r.kind == kind)
}

/// The GPU's tree equals the reference's at the pixels where total
/// internal reflection occurs and at every fifth pixel: the same rays
/// (kind, parent, shape hit, light, shadow blocked or not) at all but a
/// few pixels where a ray grazes an edge, and, where they are the same,
/// each quantity within the limits below (what was measured is printed).
#[test]
fn the_gpu_tree_equals_the_reference_tree() {
    let gpu = common::gpu();
    let scene = glass_scene();
    let trees = reference_trees(&scene);
    let total_internal: Vec<usize> = (0..trees.len())
        .filter(|&p| has(&trees[p], RayKind::TotalInternal))
        .collect();
    assert!(
        total_internal.len() >= 10,
        "the scene must show total internal reflection: {} pixels",
        total_internal.len()
    );
    let mut pixels: Vec<usize> = (0..trees.len()).step_by(5).collect();
    pixels.extend(&total_internal);
    pixels.sort();
    pixels.dedup();

    let renderer = RayTreeRenderer::new(
        &gpu,
        &ShaderSource::embedded(),
        &ShaderOptions::for_scene(&scene),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    // The largest differences by depth: errors grow with each bounce.
    let mut worst = [RayDifference::default(); 8];
    let mut parted = Vec::new();
    let mut compared_tir = 0;
    let mut largest_radiance = 0.0f64;
    for &p in &pixels {
        let (i, j) = ((p as u32) % WIDTH, (p as u32) / WIDTH);
        let gpu_tree = renderer
            .trace(&gpu, &scene, (WIDTH, HEIGHT), (i, j))
            .unwrap_or_else(|e| panic!("{e}"));
        let expected = &trees[p];
        // Every tree of this scene fits: all its rays are compared.
        assert!(gpu_tree.total <= TREE_MAX, "pixel {i}, {j}");
        match reference::compare_trees(expected, &gpu_tree.tree) {
            Ok(differences) => {
                for (d, ray) in differences.into_iter().zip(&expected.rays) {
                    let depth = (ray.depth as usize).min(worst.len() - 1);
                    worst[depth] = worst[depth].max(d);
                }
                compared_tir += usize::from(has(expected, RayKind::TotalInternal));
                largest_radiance = largest_radiance.max(
                    (expected.radiance - gpu_tree.tree.radiance)
                        .abs()
                        .max_element(),
                );
            }
            Err(e) => parted.push(format!("pixel {i}, {j}: {e}")),
        }
    }
    println!(
        "{} pixels, {} with total internal reflection ({} compared); parted at {}:\n{}",
        pixels.len(),
        total_internal.len(),
        compared_tir,
        parted.len(),
        parted.join("\n")
    );
    for (depth, w) in worst.iter().enumerate() {
        println!("depth {depth}: {w:?}");
    }
    println!("largest difference of a pixel's radiance: {largest_radiance:e}");
    assert!(parted.len() * 50 <= pixels.len(), "more than 2 % parted");
    assert!(
        compared_tir * 10 >= total_internal.len() * 9,
        "total internal reflection must be compared"
    );
    // The camera ray and its shadow rays: a few f32 roundings (6e-8) of
    // the numbers involved; Fresnel's F changes fast at grazing incidence.
    let first = worst[0];
    assert!(
        first.origin < 1e-5 && first.dir < 1e-5 && first.t < 1e-5,
        "{first:?}"
    );
    assert!(first.normal < 1e-5 && first.weights < 1e-4, "{first:?}");
    // Every ray: what it adds to the pixel within 1e-4 (a 40th of an
    // 8-bit level at the top of the range), and so the pixel.
    let all = worst
        .iter()
        .copied()
        .fold(RayDifference::default(), RayDifference::max);
    assert!(all.contribution < 1e-4, "{all:?}");
    // Deeper rays drift as each bounce off curved glass magnifies the
    // error of the one before (measured: 1.9e-4 in direction and 3.9e-4
    // relative in origin at depth 6); they stay on the same shapes.
    assert!(all.dir < 1e-3 && all.origin < 1e-3, "{all:?}");
    assert!(largest_radiance < 1e-4);
}
