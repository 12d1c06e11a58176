//! Triangle meshes (docs/rendering-model.md, "Triangle meshes"): loading
//! and its errors through the command line, saving, the reference's
//! tessellated cube against the analytic one, the GPU against the reference
//! on the bundled mesh scenes, and the watertightness of the three
//! ray-triangle tests on rays aimed exactly at shared edges and vertices
//! (in f64 and in the shader's f32).

mod common;

use std::path::PathBuf;
use std::process::{Command, Output};

use glam::DVec3;
use raysandbox::bench::storage;
use raysandbox::compare::diff_images;
use raysandbox::gpu::ShaderSource;
use raysandbox::scene::{Geometry, Scene, TriangleTest};
use raysandbox::stress::{Entry, Harness, leaks, scenes};

fn raysandbox(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_raysandbox"))
        .args(args)
        .output()
        .expect("run raysandbox")
}

fn temp_dir() -> PathBuf {
    let dir = std::env::temp_dir().join(format!("raysandbox-meshes-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn mesh_scenes_dir() -> PathBuf {
    common::scenes_dir().join("meshes")
}

/// A scene in a temporary folder that shows the mesh file `name` holding
/// `contents`.
fn scene_with_mesh_file(name: &str, contents: &[u8]) -> PathBuf {
    let dir = temp_dir();
    std::fs::write(dir.join(name), contents).unwrap();
    let scene = dir.join(format!("{name}.toml"));
    let text =
        format!("[camera]\nfrom = [0, 0, 5]\nto = [0, 0, 0]\n[[meshes]]\nfile = \"{name}\"\n");
    std::fs::write(&scene, text).unwrap();
    scene
}

/// `check` of a scene with a broken mesh file: exit 2, no panic, and the
/// message names the file and `expected` (its line or element).
fn assert_rejected(name: &str, contents: &[u8], expected: &str) {
    let scene = scene_with_mesh_file(name, contents);
    let out = raysandbox(&["check", scene.to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{name}: {stderr}");
    assert!(!stderr.contains("panicked"), "{name}: {stderr}");
    assert!(
        stderr.contains(expected),
        "{name}: expected {expected:?} in {stderr}"
    );
}

const GOOD_OBJ: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 2 4\n";

#[test]
fn malformed_obj_and_ply_files_exit_2_naming_the_line_or_element() {
    let truncated = &GOOD_OBJ[..GOOD_OBJ.find("v 0 1 0").unwrap() + 5];
    assert_rejected(
        "truncated.obj",
        truncated.as_bytes(),
        "truncated.obj:3: a vertex needs three numbers",
    );
    assert_rejected(
        "index.obj",
        b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n",
        "index.obj:4: face vertex index 9 out of range",
    );
    assert_rejected(
        "nan.obj",
        b"v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n",
        "nan.obj:2: vertex coordinates must be finite",
    );
    let mut garbage = b"v 0 0 0\n".to_vec();
    garbage.extend([0xff, 0xfe, 0x00, 0x81, b'\n', 0xc3]);
    assert_rejected("garbage.obj", &garbage, "garbage.obj:2: not a text file");
    let ply = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n\
               element face 2\nproperty list uchar int vertex_indices\nend_header\n\
               0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 7\n";
    assert_rejected(
        "index.ply",
        ply.as_bytes(),
        "index.ply: face 1: vertex index 7 out of range",
    );
    assert_rejected("short.ply", &ply.as_bytes()[..ply.len() - 12], "short.ply");
    let header = &ply[..ply.find("0 0 0\n").unwrap()];
    let nan_ascii = format!("{header}0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n3 0 1 2\n");
    assert_rejected("nan.ply", nan_ascii.as_bytes(), "nan.ply: Line 11");
    let mut nan_binary = header.replace("ascii", "binary_little_endian").into_bytes();
    for x in [0.0, 0.0, 0.0, f32::NAN, 0.0, 0.0, 0.0, 1.0, 0.0] {
        nan_binary.extend(f32::to_le_bytes(x));
    }
    let face: Vec<u8> = std::iter::once(3u8)
        .chain([0i32, 1, 2].into_iter().flat_map(i32::to_le_bytes))
        .collect();
    nan_binary.extend(face.repeat(2));
    assert_rejected(
        "nan_binary.ply",
        &nan_binary,
        "nan_binary.ply: vertex 1: coordinates must be finite",
    );
    let mut garbage = format!("{header}0 0 0\n").into_bytes();
    garbage.extend([0xff, 0xfe, 0x00, 0x81, b'\n']);
    assert_rejected("garbage.ply", &garbage, "garbage.ply:11: not a text file");
    assert_rejected("missing.obj.ply", b"", "missing.obj.ply");
    assert_rejected("model.stl", b"solid x", "model.stl:unknown mesh format");
}

#[test]
fn inline_errors_name_the_index_and_degenerate_triangles_are_dropped() {
    let base = "[camera]\nfrom = [0, 0, 5]\nto = [0, 0, 0]\n[[meshes]]\n\
                positions = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [2, 0, 0]]\n";
    let bad = format!("{base}triangles = [[0, 1, 2], [0, 1, 4]]\n");
    let e = Scene::from_toml_str(&bad, None).unwrap_err().to_string();
    assert!(
        e.contains("meshes[0]: triangles[1]: vertex index 4 out of range"),
        "{e}"
    );
    // [0, 1, 3] is collinear: zero area.
    let ok = format!("{base}triangles = [[0, 1, 2], [0, 1, 3]]\n");
    let scene = Scene::from_toml_str(&ok, None).unwrap();
    let g: &Geometry = &scene.meshes[0].geometry.0;
    assert_eq!((g.triangles.len(), g.dropped), (1, 1));
    assert!(
        scene.summary().contains("1 meshes (1 triangles)"),
        "{}",
        scene.summary()
    );
}

#[test]
fn smooth_normals_are_area_weighted_and_a_saved_scene_keeps_its_file() {
    let path = mesh_scenes_dir().join("glass_bunny.toml");
    let scene = Scene::load(&path).unwrap_or_else(|e| panic!("{e}"));
    let g = &scene.meshes[0].geometry.0;
    assert_eq!(g.normals.len(), g.positions.len());
    assert!(g.normals.iter().all(|n| (n.length() - 1.0).abs() < 1e-12));
    let saved = scene.to_toml_string();
    assert!(
        saved.contains("file = \"../../meshes/bunny.obj\""),
        "{saved}"
    );
    let again = Scene::from_toml_str(&saved, Some(&path)).unwrap();
    assert_eq!(again, scene);
    // Two squares sharing an edge, one twice the other: the shared
    // vertices' normals lean towards the larger one's.
    let text = "[camera]\nfrom = [0, 0, 5]\nto = [0, 0, 0]\n[[meshes]]\nsmooth = true\n\
                positions = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 2]]\n\
                triangles = [[0, 1, 2], [0, 3, 1]]\n";
    let scene = Scene::from_toml_str(text, None).unwrap();
    let n = scene.meshes[0].geometry.0.normals[0];
    let expected = (DVec3::Z + 2.0 * DVec3::Y).normalize();
    assert!((n - expected).length() < 1e-12, "{n}");
}

/// The box of edge 1 at `centre`, turned by `turn` about y, as a `[[cubes]]`
/// table or as a mesh of 12 triangles.
fn box_scene(as_mesh: bool) -> Scene {
    let shape = if as_mesh {
        "[[meshes]]\ntranslate = [0.3, 0.5, 0]\nrotation = [10, 35, 0]\nscale = 0.5\n\
         positions = [[-1,-1,-1],[1,-1,-1],[1,1,-1],[-1,1,-1],[-1,-1,1],[1,-1,1],[1,1,1],[-1,1,1]]\n\
         triangles = [[0,2,1],[0,3,2],[4,5,6],[4,6,7],[0,1,5],[0,5,4],[3,7,6],[3,6,2],[0,4,7],[0,7,3],[1,2,6],[1,6,5]]\n"
    } else {
        "[[cubes]]\ncenter = [0.3, 0.5, 0]\nrotation = [10, 35, 0]\nsize = 1\n"
    };
    let text = format!(
        "[camera]\nfrom = [2, 2.2, 4]\nto = [0, 0.5, 0]\nfov = 40\n\
         [[lights]]\nposition = [-3, 5, 4]\n\
         [materials.floor]\nchecker = {{ color = [0.1, 0.1, 0.1], size = 0.5 }}\n\
         [[planes]]\npoint = [0, -0.4, 0]\nnormal = [0, 1, 0]\nmaterial = \"floor\"\n{shape}"
    );
    Scene::from_toml_str(&text, None).unwrap()
}

#[test]
fn a_tessellated_cube_renders_like_the_analytic_cube() {
    let (w, h) = (160, 120);
    let cube = raysandbox::reference::render_rgba8(&box_scene(false), w, h, 1);
    let mesh = raysandbox::reference::render_rgba8(&box_scene(true), w, h, 1);
    let d = diff_images(&cube, &mesh);
    println!(
        "tessellated vs analytic cube: mean |d| {:.4}, > 8: {:.3}%",
        d.mean_abs,
        d.frac_over_8 * 100.0
    );
    assert!(d.mean_abs < 0.1 && d.frac_over_8 < 0.002, "{d:?}");
}

#[test]
fn gpu_matches_reference_on_the_mesh_scenes() {
    let mut scenes = common::toml_files(&mesh_scenes_dir());
    scenes.push(PathBuf::from("tessellated cube"));
    let mut failures = Vec::new();
    for (gpu, access) in common::both_data_accesses(&common::gpu()) {
        let harness = Harness::new(&gpu, &ShaderSource::embedded()).unwrap();
        for path in &scenes {
            let scene = if path.exists() {
                Scene::load(path).unwrap_or_else(|e| panic!("{e}"))
            } else {
                box_scene(true)
            };
            let m = harness.measure(&gpu, &scene, 160, 90).unwrap();
            let c = m.robust_cmp;
            println!(
                "{} ({access}): FLIP {:.5}, first-hit mismatch {:.4}%, NaN {}",
                path.display(),
                c.flip_mean,
                c.id_mismatch * 100.0,
                c.nan_pixels
            );
            if !c.passes() {
                failures.push(format!("{} ({access}): {c:?}", path.display()));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The bunny seen from a million units away and its scene moved a million
/// units (`raysandbox stress`, series `bunny_far` and `bunny_moved`): the
/// robust shader still matches the reference.
#[test]
fn the_far_and_moved_bunny_match_the_reference() {
    let gpu = common::gpu();
    let harness = Harness::new(&gpu, &ShaderSource::embedded()).unwrap();
    let series = scenes::mesh_series().unwrap();
    let (name, scene) = series.far.last().unwrap();
    let m = harness.measure(&gpu, scene, 160, 90).unwrap();
    let exact = series.moved.last().unwrap();
    let entry = Entry {
        name: exact.name.clone(),
        group: "moved",
        scene: exact.scene.clone(),
        exact: Some(exact.exact.clone()),
    };
    let n = harness.measure_entry(&gpu, &entry, 160, 90).unwrap();
    for (name, c) in [(name, m.robust_cmp), (&entry.name, n.robust_cmp)] {
        println!(
            "{name}: FLIP {:.5}, first-hit mismatch {:.4}%",
            c.flip_mean,
            c.id_mismatch * 100.0
        );
        assert!(c.passes(), "{name}: {c:?}");
    }
}

/// Rays aimed exactly at shared edges and vertices (`stress::leaks`): the
/// watertight test lets none through, in f64 and in the shader's f32, on
/// every mesh; the lecture's other two tests leak on the closed sphere and
/// the bunny, so the count does see cracks.
#[test]
fn watertight_test_leaks_no_ray_through_shared_edges_and_vertices() {
    let gpu = common::gpu();
    let rows = leaks::measure(&gpu, &ShaderSource::embedded(), 20_000).unwrap();
    println!("{}", leaks::markdown(&rows));
    for r in &rows {
        if r.test == TriangleTest::Watertight {
            assert_eq!((r.f64_leaks, r.gpu_leaks), (0, 0), "{r:?}");
        } else if r.mesh != "fan of 1000 slivers" {
            assert!(r.f64_leaks > 0 && r.gpu_leaks > 0, "{r:?}");
        }
    }
}

#[test]
fn check_loads_every_mesh_scene() {
    for path in common::toml_files(&mesh_scenes_dir()) {
        let out = raysandbox(&["check", path.to_str().unwrap()]);
        let stdout = String::from_utf8_lossy(&out.stdout);
        assert!(
            out.status.success(),
            "{}: {}",
            path.display(),
            String::from_utf8_lossy(&out.stderr)
        );
        assert!(stdout.contains("triangles)"), "{stdout}");
    }
}

/// The storage comparison of `raysandbox bench --meshes` times equal work:
/// on a closed sphere, every ray tested against every triangle finds the
/// same nearest triangle at the same t (to the bit) whether the triangles
/// are read as the renderer stores them or through indices, and most rays
/// do hit.
#[test]
fn both_storage_layouts_find_identical_hits() {
    let gpu = common::gpu();
    let (positions, triangles) = leaks::uv_sphere(8);
    let geometry = Geometry {
        positions,
        triangles,
        ..Geometry::default()
    };
    let layouts = storage::Layouts::new(&geometry, 1024, geometry.triangles.len());
    let leaf = storage::nearest_hits(&gpu, &layouts, false).unwrap();
    let indexed = storage::nearest_hits(&gpu, &layouts, true).unwrap();
    assert_eq!(leaf, indexed);
    let hits = leaf.iter().filter(|h| h[1] != u32::MAX).count();
    assert!(hits > 500, "only {hits} of 1024 rays hit the sphere");
    let missed = leaf
        .iter()
        .find(|h| h[1] == u32::MAX)
        .expect("rays past the sphere");
    assert_eq!(
        f32::from_bits(missed[0]),
        raysandbox::stress::f32_intersect::T_FAR,
        "a miss keeps t = T_FAR"
    );
}
