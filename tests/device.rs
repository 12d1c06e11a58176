//! The GPU device's limits and its loss (docs/reliability.md, "The GPU's
//! limits and a lost device"): a scene whose data does not fit in one of the
//! device's buffers or textures is refused with an error naming the limit, never a
//! wgpu validation panic; a lost device is reported as such, and a new one
//! renders the same scene again.

mod common;

use raysandbox::gpu::layout::{PackedArray, PackedScene};
use raysandbox::gpu::{Gpu, RenderError, check_buffers, render_image};
use raysandbox::scene::Scene;

const WIDTH: u32 = 48;
const HEIGHT: u32 = 32;

fn scene(name: &str) -> Scene {
    Scene::load(&common::scenes_dir().join(name)).unwrap()
}

/// A device whose textures stop between the two largest arrays of a scene
/// of many spheres (every array is a data texture of 4096 texels a row)
/// refuses the scene and names the array and the limit; the same device
/// still renders a scene that fits.
#[test]
fn a_scene_beyond_the_texture_limit_is_refused_naming_the_limit() {
    let gpu = common::gpu();
    let mut scene = scene("many_spheres.toml");
    let base = scene.spheres.clone();
    for k in 1..400 {
        scene.spheres.extend(base.iter().map(|s| {
            let mut s = s.clone();
            s.center.x += 100.0 * f64::from(k);
            s
        }));
    }
    let row = 4096 * 16;
    let mut arrays: Vec<PackedArray> = PackedScene::new(&scene, WIDTH, HEIGHT)
        .arrays()
        .into_iter()
        .filter(|a| a.texture)
        .collect();
    arrays.sort_by_key(|a| std::cmp::Reverse(a.bytes));
    let rows = |a: &PackedArray| a.bytes.div_ceil(row) as u32;
    let (largest, second) = (&arrays[0], rows(&arrays[1]));
    // At least the image's width: the device must still render a frame.
    let limit = ((rows(largest) + second) / 2).max(WIDTH);
    assert!(second <= limit && limit < rows(largest), "{arrays:?}");
    let small = pollster::block_on(Gpu::request_with_limits(
        gpu.instance.clone(),
        gpu.adapter.clone(),
        |limits| limits.max_texture_dimension_2d = limit,
    ))
    .expect("a device with a smaller limit");

    match render_image(&small, &scene, WIDTH, HEIGHT, 1) {
        Err(RenderError::Buffers(e)) => {
            assert_eq!(e.limit, "max_texture_dimension_2d");
            assert_eq!(
                (e.what.as_str(), e.bytes, e.allowed),
                (largest.what.as_str(), largest.bytes, u64::from(limit) * row)
            );
            let message = e.to_string();
            println!("{message}");
            assert!(
                message.contains("max_texture_dimension_2d") && message.contains(&largest.what),
                "{message}"
            );
            assert!(RenderError::Buffers(e).is_input());
        }
        Ok(_) => panic!("{largest:?} rendered with {limit} rows"),
        Err(e) => panic!("the wrong error: {e}"),
    }
    render_image(&small, &scene.without_shapes(), WIDTH, HEIGHT, 1)
        .expect("a scene that fits renders on the same device");
}

/// A mesh's BVH and triangles live in a texture 4096 texels wide: the
/// rows it needs are checked against the largest texture.
#[test]
fn a_mesh_beyond_the_largest_texture_is_refused_naming_the_limit() {
    let packed = PackedScene::new(&scene("meshes/mirror_teapot.toml"), WIDTH, HEIGHT);
    let limits = wgpu::Limits {
        max_texture_dimension_2d: 1,
        ..wgpu::Limits::default()
    };
    let e = check_buffers(&limits, &packed).expect_err("a teapot in one row of 4096 texels");
    assert_eq!(
        (e.what.as_str(), e.limit),
        ("meshes (mesh_data)", "max_texture_dimension_2d")
    );
    assert_eq!(e.allowed, 4096 * 16);
    check_buffers(&wgpu::Limits::default(), &packed).expect("the teapot fits the default limits");
}

/// A device destroyed under the renderer (as a driver reset would lose it)
/// makes rendering fail with an error, not a panic; the device says why it
/// was lost; a new device renders the same picture as before the loss.
#[test]
fn a_lost_device_is_reported_and_a_new_one_renders_the_scene() {
    let gpu = common::gpu();
    let scene = scene("whitted.toml");
    let before = render_image(&gpu, &scene, WIDTH, HEIGHT, 1).expect("the first render");
    assert_eq!(gpu.lost(), None);

    gpu.device.destroy();
    let after_loss = render_image(&gpu, &scene, WIDTH, HEIGHT, 1);
    assert!(after_loss.is_err(), "a destroyed device rendered a picture");
    let lost = gpu.lost().expect("the device reports its loss");
    assert!(lost.contains("destroyed"), "{lost}");

    let again = Gpu::headless().expect("a new device");
    let image = render_image(&again, &scene, WIDTH, HEIGHT, 1).expect("the render on a new device");
    assert_eq!(image, before, "the new device renders the same picture");
}
