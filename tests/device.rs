//! The GPU device's limits and its loss (docs/reliability.md, "The GPU's
//! limits and a lost device"): a scene whose data does not fit in one of the
//! device's buffers is refused with an error naming the limit, never a
//! wgpu validation panic; a lost device is reported as such, and a new one
//! renders the same scene again.

mod common;

use raysandbox::gpu::layout::PackedScene;
use raysandbox::gpu::{Gpu, RenderError, render_image};
use raysandbox::scene::Scene;

const WIDTH: u32 = 48;
const HEIGHT: u32 = 32;

fn teapot_scene() -> Scene {
    Scene::load(&common::scenes_dir().join("meshes/mirror_teapot.toml")).unwrap()
}

/// The teapot's triangles need more bytes than any other array of its
/// scene; a device whose storage bindings stop halfway refuses the scene
/// and names the limit, and the same device still renders a scene that
/// fits.
#[test]
fn a_mesh_beyond_the_storage_buffer_limit_is_refused_naming_the_limit() {
    let gpu = common::gpu().expect("a GPU");
    let scene = teapot_scene();
    let arrays = PackedScene::new(&scene, WIDTH, HEIGHT).arrays();
    let (largest, bytes) = arrays.iter().max_by_key(|(_, bytes)| *bytes).unwrap();
    assert!(
        largest.starts_with("meshes"),
        "the largest array is {largest}"
    );
    let others = arrays
        .iter()
        .filter(|(what, _)| what != largest)
        .map(|(_, bytes)| *bytes)
        .max()
        .unwrap();
    let limit = (bytes / 2).next_multiple_of(256);
    assert!(others <= limit, "{arrays:?}");
    let small = pollster::block_on(Gpu::request_with_limits(
        gpu.instance.clone(),
        gpu.adapter.clone(),
        |limits| limits.max_storage_buffer_binding_size = limit,
    ))
    .expect("a device with a smaller limit");

    match render_image(&small, &scene, WIDTH, HEIGHT, 1) {
        Err(RenderError::Buffers(e)) => {
            assert_eq!(e.limit, "max_storage_buffer_binding_size");
            assert_eq!((e.bytes, e.allowed), (*bytes, limit));
            let message = e.to_string();
            println!("{message}");
            assert!(
                message.contains("max_storage_buffer_binding_size") && message.contains("meshes"),
                "{message}"
            );
            assert!(RenderError::Buffers(e).is_input());
        }
        Ok(_) => {
            panic!("a scene {bytes} bytes large in one buffer rendered with a {limit}-byte limit")
        }
        Err(e) => panic!("the wrong error: {e}"),
    }
    let without_teapot = scene.without_shapes();
    render_image(&small, &without_teapot, WIDTH, HEIGHT, 1)
        .expect("a scene that fits renders on the same device");
}

/// A device destroyed under the renderer (as a driver reset would lose it)
/// makes rendering fail with an error, not a panic; the device says why it
/// was lost; a new device renders the same picture as before the loss.
#[test]
fn a_lost_device_is_reported_and_a_new_one_renders_the_scene() {
    let gpu = common::gpu().expect("a GPU");
    let scene = Scene::load(&common::scenes_dir().join("whitted.toml")).unwrap();
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
