//! The fuzz targets (docs/reliability.md, "Fuzzing"): for each parser,
//! its seeds (real inputs: the bundled scenes, meshes and shaders), how an
//! input is made from random bytes (structure-aware where it helps), and
//! what must hold for every input. A target returns `Err` for an input
//! that breaks a rule (an error that does not name the file or line, a
//! valid result that does not survive being written and read again); a
//! panic is caught by the driver.

use std::path::{Path, PathBuf};
use std::sync::LazyLock;

use arbitrary::{Result, Unstructured};
use glam::DVec3;
use raysandbox::expr::{FUNCTIONS, Function};
use raysandbox::sandbox::multipass;
use raysandbox::scene::{GivenFiles, Scene};
use raysandbox::shader_params::{self as params, ParamSet, ParamSpec, ParamType, Scalar};
use raysandbox::web::link;

use super::common;
use super::inputs::{mutate, mutate_bytes, number, random_text, vector};

/// How a target makes an input: from random choices and the seeds.
pub type Make = fn(&mut Unstructured, &[Vec<u8>]) -> Result<Vec<u8>>;

/// One parser under test.
pub struct Target {
    pub name: &'static str,
    /// Inputs of the short run in the test suite: a few seconds each.
    pub quick: u64,
    /// The extension a saved input gets, so an editor shows it right.
    pub extension: &'static str,
    /// The seeds, read once per run.
    pub seeds: fn() -> Vec<Vec<u8>>,
    /// One input from random choices and the seeds.
    pub make: Make,
    pub run: fn(&[u8]) -> std::result::Result<(), String>,
}

pub const TARGETS: [Target; 11] = [
    Target {
        name: "scene",
        quick: 20_000,
        extension: "toml",
        seeds: scene_seeds,
        make: make_scene,
        run: run_scene,
    },
    Target {
        name: "expr",
        quick: 5_000,
        extension: "txt",
        seeds: expr_seeds,
        make: make_expr,
        run: run_expr,
    },
    Target {
        name: "obj",
        quick: 20_000,
        extension: "obj",
        seeds: obj_seeds,
        make: make_obj,
        run: run_obj,
    },
    Target {
        name: "ply",
        quick: 20_000,
        extension: "ply",
        seeds: ply_seeds,
        make: make_ply,
        run: run_ply,
    },
    Target {
        name: "glsl",
        quick: 2_000,
        extension: "glsl",
        seeds: shader_seeds,
        make: make_shader,
        run: run_shader,
    },
    Target {
        name: "link",
        quick: 20_000,
        extension: "txt",
        seeds: link_seeds,
        make: make_link,
        run: run_link,
    },
    Target {
        name: "annotation",
        quick: 50_000,
        extension: "txt",
        seeds: annotation_seeds,
        make: make_annotation,
        run: run_annotation,
    },
    Target {
        name: "sidecar",
        quick: 20_000,
        extension: "toml",
        seeds: sidecar_seeds,
        make: make_sidecar,
        run: run_sidecar,
    },
    Target {
        name: "shadertoy-json",
        quick: 2_000,
        extension: "json",
        seeds: shadertoy_json_seeds,
        make: make_shadertoy_json,
        run: run_shadertoy_json,
    },
    Target {
        name: "include",
        quick: 2_000,
        extension: "txt",
        seeds: shader_seeds,
        make: make_include_folder,
        run: run_include_folder,
    },
    Target {
        name: "channels-toml",
        quick: 20_000,
        extension: "toml",
        seeds: channels_toml_seeds,
        make: make_channels_toml,
        run: run_channels_toml,
    },
];

fn repo() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// Every file under `dir` (recursively) whose extension is in `extensions`.
fn files(dir: &Path, extensions: &[&str]) -> Vec<PathBuf> {
    let mut found = Vec::new();
    let mut stack = vec![repo().join(dir)];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap()) {
            let path = entry.path();
            if path.is_dir() {
                stack.push(path);
            } else if path
                .extension()
                .is_some_and(|e| extensions.contains(&e.to_string_lossy().as_ref()))
            {
                found.push(path);
            }
        }
    }
    found.sort();
    found
}

fn read_all(paths: &[PathBuf]) -> Vec<Vec<u8>> {
    paths.iter().map(|p| std::fs::read(p).unwrap()).collect()
}

/// A seed, as text (the text targets' seeds are UTF-8).
fn seed_text<'a>(u: &mut Unstructured, seeds: &'a [Vec<u8>]) -> Result<&'a str> {
    Ok(std::str::from_utf8(u.choose(seeds)?).expect("the seeds are UTF-8"))
}

/// A seed chosen and mutated with `tokens`.
fn mutate_seed(u: &mut Unstructured, seeds: &[Vec<u8>], tokens: &[&str]) -> Result<String> {
    let seed = seed_text(u, seeds)?;
    mutate(u, seed, tokens)
}

/// What a parser that reads a text file gets: `read_to_string` refuses
/// anything but UTF-8 before any parser runs.
fn text(input: &[u8]) -> std::result::Result<&str, String> {
    std::str::from_utf8(input).map_err(|_| String::new())
}

/// Lines of `text` as an editor counts them: an error's line must be one.
fn line_count(text: &str) -> usize {
    text.split('\n').count()
}

// ----------------------------------------------------------------- scenes

/// What goes wrong in scene files: keys of every section, table headers,
/// TOML's own syntax.
const SCENE_TOKENS: [&str; 30] = [
    "[[spheres]]\n",
    "[[planes]]\n",
    "[[cubes]]\n",
    "[[tori]]\n",
    "[[implicits]]\n",
    "[[julias]]\n",
    "[[meshes]]\n",
    "[[lights]]\n",
    "[materials.m]\n",
    "[render]\n",
    "[camera]\n",
    "radius = ",
    "material = \"m\"\n",
    "material = \"nothing\"\n",
    "max_depth = ",
    "exposure = ",
    "size = ",
    "scale = ",
    "steps = ",
    "iterations = ",
    "f = \"x^2\"\n",
    "positions = [[0,0,0],[1,0,0],[0,1,0]]\n",
    "triangles = [[0,1,2]]\n",
    "file = \"../../meshes/bunny.obj\"\n",
    " = ",
    "\"",
    "[",
    "]",
    "{",
    ",",
];

/// The bundled scenes, the stress scenes, and the mesh scenes.
fn scene_seeds() -> Vec<Vec<u8>> {
    read_all(&files(Path::new("assets/scenes"), &["toml"]))
}

/// Mutated real scenes, and scenes written from scratch whose every
/// number may be at an edge (radii 1e-30 and 1e30, max_depth 2^32, ...).
fn make_scene(u: &mut Unstructured, seeds: &[Vec<u8>]) -> Result<Vec<u8>> {
    let text = match u.int_in_range(0..=9)? {
        0..=4 => mutate_seed(u, seeds, &SCENE_TOKENS)?,
        5..=8 => scene_from_scratch(u)?,
        _ => {
            let scene = scene_from_scratch(u)?;
            mutate(u, &scene, &SCENE_TOKENS)?
        }
    };
    Ok(text.into_bytes())
}

/// A scene that looks valid: every section, each key with a number or
/// vector from [`number`] and [`vector`], a key sometimes left out.
fn scene_from_scratch(u: &mut Unstructured) -> Result<String> {
    let mut s = String::new();
    s.push_str("[render]\n");
    key(u, &mut s, "max_depth", number)?;
    key(u, &mut s, "min_weight", number)?;
    key(u, &mut s, "exposure", number)?;
    key(u, &mut s, "background", vector)?;
    key(u, &mut s, "ambient", vector)?;
    s.push_str("[camera]\n");
    key(u, &mut s, "from", vector)?;
    key(u, &mut s, "to", vector)?;
    key(u, &mut s, "up", vector)?;
    key(u, &mut s, "fov", number)?;
    key(u, &mut s, "aperture", number)?;
    key(u, &mut s, "focus_distance", number)?;
    for _ in 0..u.int_in_range(0..=2)? {
        s.push_str("[[lights]]\n");
        key(u, &mut s, "position", vector)?;
        key(u, &mut s, "color", vector)?;
        key(u, &mut s, "intensity", number)?;
    }
    for _ in 0..u.int_in_range(0..=2)? {
        s.push_str(&format!("[materials.m{}]\n", u.int_in_range(0..=2)?));
        key(u, &mut s, "color", vector)?;
        for name in [
            "diffuse",
            "specular",
            "shininess",
            "mirror",
            "transparency",
            "ior",
        ] {
            key(u, &mut s, name, number)?;
        }
        key(u, &mut s, "checker", |u| {
            Ok(format!(
                "{{ color = {}, size = {} }}",
                vector(u)?,
                number(u)?
            ))
        })?;
    }
    for _ in 0..u.int_in_range(0..=6)? {
        shape_from_scratch(u, &mut s)?;
        key(u, &mut s, "material", |u| {
            Ok(format!("\"m{}\"", u.int_in_range(0..=3)?))
        })?;
    }
    Ok(s)
}

/// `name = VALUE` on a line, but now and then no line: a key left out.
fn key(
    u: &mut Unstructured,
    s: &mut String,
    name: &str,
    value: impl FnOnce(&mut Unstructured) -> Result<String>,
) -> Result<()> {
    if !u.ratio(1, 10)? {
        let value = value(u)?;
        s.push_str(&format!("{name} = {value}\n"));
    }
    Ok(())
}

/// A size: one number, or one per axis.
fn size(u: &mut Unstructured) -> Result<String> {
    if u.arbitrary()? { number(u) } else { vector(u) }
}

/// One shape of any kind, with its keys as [`scene_from_scratch`] writes them.
fn shape_from_scratch(u: &mut Unstructured, s: &mut String) -> Result<()> {
    let placement = |u: &mut Unstructured| -> Result<String> {
        Ok(format!(
            "translate = {}\nscale = {}\nrotation = {}\n",
            vector(u)?,
            size(u)?,
            vector(u)?
        ))
    };
    match u.int_in_range(0..=6)? {
        0 => s.push_str(&format!(
            "[[spheres]]\ncenter = {}\nradius = {}\n",
            vector(u)?,
            number(u)?
        )),
        1 => s.push_str(&format!(
            "[[planes]]\npoint = {}\nnormal = {}\n",
            vector(u)?,
            vector(u)?
        )),
        2 => s.push_str(&format!(
            "[[cubes]]\ncenter = {}\nsize = {}\nrotation = {}\n",
            vector(u)?,
            size(u)?,
            vector(u)?
        )),
        3 => s.push_str(&format!(
            "[[tori]]\nmajor_radius = {}\nminor_radius = {}\n{}",
            number(u)?,
            number(u)?,
            placement(u)?
        )),
        4 => s.push_str(&format!(
            "[[implicits]]\nf = \"{}\"\nbounds = [{}, {}]\nsteps = {}\n{}",
            expression(u, 0)?.replace(['"', '\\'], ""),
            vector(u)?,
            vector(u)?,
            number(u)?,
            placement(u)?
        )),
        5 => s.push_str(&format!(
            "[[julias]]\nc = [{}, {}, {}, {}]\nslice = {}\niterations = {}\nepsilon = {}\n{}",
            number(u)?,
            number(u)?,
            number(u)?,
            number(u)?,
            number(u)?,
            number(u)?,
            number(u)?,
            placement(u)?
        )),
        _ => {
            s.push_str("[[meshes]]\n");
            if u.arbitrary()? {
                let file = u.choose(&MESH_FILES)?;
                s.push_str(&format!("file = \"{file}\"\n"));
            } else {
                let points: Vec<String> = (0..u.int_in_range(0..=4)?)
                    .map(|_| vector(u))
                    .collect::<Result<_>>()?;
                let triangles: Vec<String> = (0..u.int_in_range(0..=3)?)
                    .map(|_| Ok(format!("[{}, {}, {}]", number(u)?, number(u)?, number(u)?)))
                    .collect::<Result<_>>()?;
                s.push_str(&format!(
                    "positions = [{}]\ntriangles = [{}]\n",
                    points.join(", "),
                    triangles.join(", ")
                ));
            }
            s.push_str(&format!(
                "smooth = {}\n{}",
                u.arbitrary::<bool>()?,
                placement(u)?
            ));
        }
    }
    Ok(())
}

/// The mesh files the seeds name, as they name them.
const MESH_FILES: [&str; 4] = [
    "../../meshes/bunny.obj",
    "../../meshes/teapot.obj",
    "../../meshes/dragon_res3.ply",
    "../../../meshes/bunny.obj",
];

/// A tetrahedron in place of every mesh file the seeds name: the scene's
/// parser is under test here, the mesh loaders have targets of their own.
static MESHES: LazyLock<GivenFiles> = LazyLock::new(|| {
    let mut files = GivenFiles::new("not given to the fuzzer");
    for file in MESH_FILES {
        let bytes = if file.ends_with(".ply") {
            TETRAHEDRON_PLY.as_bytes()
        } else {
            TETRAHEDRON_OBJ.as_bytes()
        };
        files.insert(PathBuf::from(file), bytes.to_vec());
    }
    files
});

const SCENE_FILE: &str = "fuzz.toml";

/// A scene is valid or refused with an error that names the file and a
/// line of it; a valid one, written out as the panel saves it, loads again.
fn run_scene(input: &[u8]) -> std::result::Result<(), String> {
    let Ok(text) = text(input) else {
        return Ok(());
    };
    let origin = Path::new(SCENE_FILE);
    match Scene::from_toml_with_files(text, Some(origin), &*MESHES) {
        Ok(scene) => {
            let _ = scene.summary();
            let written = scene.to_toml_string();
            Scene::from_toml_with_files(&written, Some(origin), &*MESHES)
                .map(|_| ())
                .map_err(|e| format!("a valid scene, written out, does not load: {e}\n{written}"))
        }
        Err(e) => {
            if e.file.as_deref() != Some(origin) {
                return Err(format!("the error does not name the file: {e}"));
            }
            match e.line {
                Some(line) if !(1..=line_count(text)).contains(&line) => {
                    Err(format!("the error's line is not in the file: {e}"))
                }
                _ => Ok(()),
            }
        }
    }
}

// ------------------------------------------------------------ expressions

/// A random expression of the implicit surfaces' language (docs/scene-format.md,
/// "Implicit surfaces"): numbers at the edges, every function, every
/// operator, nested past the parser's depth limit now and then.
fn expression(u: &mut Unstructured, depth: u32) -> Result<String> {
    let leaf = depth > 90 || u.ratio(depth.min(60) + 1, 64)?;
    if leaf {
        return Ok(match u.int_in_range(0..=3)? {
            0 => number(u)?,
            1 => u.choose(&["pi", "e", "tau", "w", "xx"])?.to_string(),
            _ => u.choose(&["x", "y", "z"])?.to_string(),
        });
    }
    Ok(match u.int_in_range(0..=4)? {
        0 | 1 => {
            let op = u.choose(&["+", "-", "*", "/", "^", "**", "%"])?;
            format!(
                "{} {op} {}",
                expression(u, depth + 1)?,
                expression(u, depth + 1)?
            )
        }
        2 => {
            let (name, arity) = *u.choose(&FUNCTIONS)?;
            // One argument too many or too few now and then.
            let arity = match u.int_in_range(0..=15)? {
                0 => arity.saturating_sub(1),
                1 => arity + 1,
                _ => arity,
            };
            let args: Vec<String> = (0..arity)
                .map(|_| expression(u, depth + 1))
                .collect::<Result<_>>()?;
            format!("{name}({})", args.join(", "))
        }
        3 => format!("-{}", expression(u, depth + 1)?),
        _ => format!("({})", expression(u, depth + 1)?),
    })
}

/// The `f` of every bundled implicit surface, and the lecture's classics.
fn expr_seeds() -> Vec<Vec<u8>> {
    let mut seeds: Vec<Vec<u8>> = [
        "x^2 + y^2 + z^2 - 1",
        "sin(x)*cos(y) + sin(y)*cos(z) + sin(z)*cos(x)",
        "(x^2 + 9/4*y^2 + z^2 - 1)^3 - x^2*z^3 - 9/80*y^2*z^3",
        "x^4 + y^4 + z^4 - 5*(x^2 + y^2 + z^2) + 11.8",
        "max(abs(x), max(abs(y), abs(z))) - 1",
        "atan2(y, x) - mod(z, 1) + clamp(x, -1, 1) * mix(y, z, 0.5)",
    ]
    .iter()
    .map(|s| s.as_bytes().to_vec())
    .collect();
    for scene in scene_seeds() {
        let text = String::from_utf8(scene).unwrap();
        for line in text.lines() {
            if let Some(f) = line.strip_prefix("f = \"") {
                seeds.push(f.trim_end_matches('"').as_bytes().to_vec());
            }
        }
    }
    seeds
}

fn make_expr(u: &mut Unstructured, seeds: &[Vec<u8>]) -> Result<Vec<u8>> {
    let text = match u.int_in_range(0..=9)? {
        0..=4 => expression(u, 0)?,
        5..=8 => {
            let tokens = [
                "(", ")", ",", "^", "-", "x", "1e39", "sqrt(", "pow(", "..", "e",
            ];
            mutate_seed(u, seeds, &tokens)?
        }
        _ => random_text(u, 40)?,
    };
    Ok(text.into_bytes())
}

/// The points a parsed function is evaluated at: the origin, a plain
/// point, and points at f64's edges.
const POINTS: [DVec3; 4] = [
    DVec3::ZERO,
    DVec3::new(0.5, -0.25, 2.0),
    DVec3::new(1e30, -1e-30, 1e300),
    DVec3::new(f64::MAX, f64::MIN_POSITIVE, -f64::MAX),
];

/// An expression parses or is refused with a column inside it; a parsed
/// one evaluates anywhere without a panic, and its WGSL passes naga's
/// validation as the tracer's shader would.
fn run_expr(input: &[u8]) -> std::result::Result<(), String> {
    let Ok(source) = text(input) else {
        return Ok(());
    };
    match Function::parse(source) {
        Ok(f) => {
            for p in POINTS {
                let _ = f.value_and_gradient(p);
            }
            validate_wgsl(&f.to_wgsl("user_f"))
        }
        Err(e) => {
            let columns = source.chars().count() + 1;
            if !(1..=columns).contains(&e.column) {
                return Err(format!("column {} of {columns}: {e}", e.column));
            }
            Ok(())
        }
    }
}

/// naga's WGSL front end and validator, as wgpu runs them on the tracer.
fn validate_wgsl(wgsl: &str) -> std::result::Result<(), String> {
    let module = naga::front::wgsl::parse_str(wgsl)
        .map_err(|e| format!("the generated WGSL does not parse: {e}\n{wgsl}"))?;
    naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::empty(),
    )
    .validate(&module)
    .map(|_| ())
    .map_err(|e| format!("the generated WGSL does not validate: {e:?}\n{wgsl}"))
}

// ----------------------------------------------------------------- meshes

const TETRAHEDRON_OBJ: &str = "# a tetrahedron\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n\
vt 0 0\nvt 1 0\nvn 0 0 1\nf 1 3 2\nf 1/1 2/2 4\nf 1//1 4//1 3//1\nf -3 -2 -1\n";

const TETRAHEDRON_PLY: &str = "ply\nformat ascii 1.0\nelement vertex 4\n\
property float x\nproperty float y\nproperty float z\nelement face 4\n\
property list uchar int vertex_indices\nend_header\n\
0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n4 1 2 3 0\n";

/// The start of a real file: whole lines up to `bytes`.
fn head(path: &str, bytes: usize) -> Vec<u8> {
    let text = std::fs::read(repo().join(path)).unwrap();
    let cut = text[..bytes.min(text.len())]
        .iter()
        .rposition(|&b| b == b'\n')
        .map_or(0, |i| i + 1);
    text[..cut].to_vec()
}

/// A small mesh and the starts of the bundled models (whole files would
/// take milliseconds each; the start holds every kind of line they have).
fn obj_seeds() -> Vec<Vec<u8>> {
    vec![
        TETRAHEDRON_OBJ.as_bytes().to_vec(),
        head("assets/meshes/teapot.obj", 3000),
        head("assets/meshes/bunny.obj", 3000),
    ]
}

/// An OBJ written from scratch: vertices with numbers at the edges and
/// faces with every index form, positive, negative, zero and past the end.
fn obj_from_scratch(u: &mut Unstructured) -> Result<String> {
    let mut s = String::new();
    for _ in 0..u.int_in_range(0..=8)? {
        let kind = *u.choose(&["v", "vn", "vt", "v", "vp"])?;
        let coordinates: Vec<String> = (0..u.int_in_range(1..=4)?)
            .map(|_| number(u))
            .collect::<Result<_>>()?;
        s.push_str(&format!("{kind} {}\n", coordinates.join(" ")));
    }
    for _ in 0..u.int_in_range(0..=6)? {
        let corners: Vec<String> = (0..u.int_in_range(0..=6)?)
            .map(|_| {
                let index = |u: &mut Unstructured| -> Result<String> {
                    Ok(if u.ratio(1, 4)? {
                        number(u)?
                    } else {
                        u.int_in_range(-10i64..=10)?.to_string()
                    })
                };
                Ok(match u.int_in_range(0..=3)? {
                    0 => index(u)?,
                    1 => format!("{}/{}", index(u)?, index(u)?),
                    2 => format!("{}//{}", index(u)?, index(u)?),
                    _ => format!("{}/{}/{}", index(u)?, index(u)?, index(u)?),
                })
            })
            .collect::<Result<_>>()?;
        let kind = *u.choose(&[
            "f",
            "f",
            "l",
            "p",
            "o x",
            "g",
            "usemtl m",
            "mtllib a.mtl",
            "s 1",
        ])?;
        s.push_str(&format!("{kind} {}\n", corners.join(" ")));
    }
    Ok(s)
}

fn make_obj(u: &mut Unstructured, seeds: &[Vec<u8>]) -> Result<Vec<u8>> {
    let tokens = [
        "v ", "vn ", "vt ", "f ", "/", "//", "-1", "0", " ", "\\\n", "#",
    ];
    let text = match u.int_in_range(0..=9)? {
        0..=4 => mutate_seed(u, seeds, &tokens)?,
        5..=8 => obj_from_scratch(u)?,
        _ => {
            let seed = u.choose(seeds)?;
            return mutate_bytes(u, seed);
        }
    };
    Ok(text.into_bytes())
}

/// A mesh loads or is refused with an error that starts with the file's
/// name; both shadings are tried, on alternate inputs.
fn run_mesh(name: &str, input: &[u8]) -> std::result::Result<(), String> {
    let smooth = input.len() % 2 == 1;
    match raysandbox::scene::load_bytes(name, input, smooth) {
        Ok(_) => Ok(()),
        Err(e) if e.starts_with(name) => Ok(()),
        Err(e) => Err(format!("the error does not name the file: {e}")),
    }
}

fn run_obj(input: &[u8]) -> std::result::Result<(), String> {
    run_mesh("fuzz.obj", input)
}

fn run_ply(input: &[u8]) -> std::result::Result<(), String> {
    run_mesh("fuzz.ply", input)
}

/// A small mesh in each of PLY's encodings, and the start of the bundled
/// dragon (its header and first vertices).
fn ply_seeds() -> Vec<Vec<u8>> {
    let mut seeds = vec![
        TETRAHEDRON_PLY.as_bytes().to_vec(),
        head("assets/meshes/dragon_res4.ply", 2000),
    ];
    for little in [true, false] {
        seeds.push(binary_tetrahedron(little));
    }
    seeds
}

/// [`TETRAHEDRON_PLY`] in binary, little- or big-endian.
fn binary_tetrahedron(little: bool) -> Vec<u8> {
    let format = if little {
        "binary_little_endian"
    } else {
        "binary_big_endian"
    };
    let header = TETRAHEDRON_PLY.split("end_header\n").next().unwrap();
    let mut bytes = header.replace("ascii", format).into_bytes();
    bytes.extend_from_slice(b"end_header\n");
    let float = |x: f32| {
        if little {
            x.to_le_bytes()
        } else {
            x.to_be_bytes()
        }
    };
    let int = |x: i32| {
        if little {
            x.to_le_bytes()
        } else {
            x.to_be_bytes()
        }
    };
    for p in [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
    ] {
        for x in p {
            bytes.extend_from_slice(&float(x));
        }
    }
    for face in [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]] {
        bytes.push(3);
        for i in face {
            bytes.extend_from_slice(&int(i));
        }
    }
    bytes
}

/// A PLY header written from scratch: any encoding, element counts at
/// the edges, properties of every type, lists of every count type; then a
/// body of numbers (ASCII) or random bytes (binary).
fn ply_from_scratch(u: &mut Unstructured) -> Result<Vec<u8>> {
    const TYPES: [&str; 10] = [
        "char", "uchar", "short", "ushort", "int", "uint", "float", "double", "int8", "float32",
    ];
    let ascii = u.arbitrary()?;
    let format = if ascii {
        "ascii"
    } else {
        *u.choose(&["binary_little_endian", "binary_big_endian", "binary"])?
    };
    let mut s = format!("ply\nformat {format} 1.0\n");
    let count = |u: &mut Unstructured| -> Result<String> {
        Ok(if u.ratio(1, 4)? {
            number(u)?
        } else {
            u.int_in_range(0..=6)?.to_string()
        })
    };
    s.push_str(&format!("element vertex {}\n", count(u)?));
    for name in ["x", "y", "z"] {
        if !u.ratio(1, 12)? {
            s.push_str(&format!("property {} {name}\n", u.choose(&TYPES)?));
        }
    }
    if u.ratio(1, 4)? {
        for name in ["nx", "ny", "nz"] {
            s.push_str(&format!("property {} {name}\n", u.choose(&TYPES)?));
        }
    }
    s.push_str(&format!("element face {}\n", count(u)?));
    s.push_str(&format!(
        "property list {} {} {}\n",
        u.choose(&TYPES)?,
        u.choose(&TYPES)?,
        u.choose(&["vertex_indices", "vertex_index", "indices"])?
    ));
    s.push_str("end_header\n");
    let mut bytes = s.into_bytes();
    if ascii {
        for _ in 0..u.int_in_range(0..=40)? {
            bytes.extend_from_slice(number(u)?.as_bytes());
            bytes.push(if u.ratio(1, 4)? { b'\n' } else { b' ' });
        }
    } else {
        for _ in 0..u.int_in_range(0..=200)? {
            bytes.push(u.arbitrary()?);
        }
    }
    Ok(bytes)
}

fn make_ply(u: &mut Unstructured, seeds: &[Vec<u8>]) -> Result<Vec<u8>> {
    match u.int_in_range(0..=9)? {
        0..=3 => {
            let seed = u.choose(seeds)?;
            mutate_bytes(u, seed)
        }
        4 | 5 => {
            let tokens = [
                "element ",
                "property ",
                "list ",
                "uchar ",
                "int ",
                "end_header\n",
            ];
            let seed = String::from_utf8_lossy(&seeds[0]).into_owned();
            Ok(mutate(u, &seed, &tokens)?.into_bytes())
        }
        _ => ply_from_scratch(u),
    }
}

// ---------------------------------------------------------------- shaders

/// The compatibility suite, the bundled shaders of the sandbox, and the
/// shaders in assets/ (GLSL and WGSL).
fn shader_seeds() -> Vec<Vec<u8>> {
    let mut seeds = read_all(&files(
        Path::new("tests/shaders/compat"),
        &["glsl", "frag", "wgsl"],
    ));
    seeds.extend(read_all(&files(
        Path::new("assets/shaders"),
        &["glsl", "frag", "wgsl"],
    )));
    seeds.extend(
        raysandbox::sandbox::bundled::SHADERS
            .iter()
            .map(|(_, text)| text.as_bytes().to_vec()),
    );
    seeds
}

/// What the sandbox's rewrites and annotations look for, besides the
/// mistakes of [`common::SHADER_MISTAKES`].
const SHADER_TOKENS: [&str; 9] = [
    "#else\n",
    "#ifdef GL_ES\n",
    "//",
    "uniform float p; // @slider(0, 1)\n",
    "gl_FragColor",
    "backbuffer",
    "fn ",
    "@",
    "- ",
];

fn make_shader(u: &mut Unstructured, seeds: &[Vec<u8>]) -> Result<Vec<u8>> {
    let tokens: &[&str] = if u.ratio(2, 3)? {
        &common::SHADER_MISTAKES
    } else {
        &SHADER_TOKENS
    };
    Ok(mutate_seed(u, seeds, tokens)?.into_bytes())
}

/// The name a fuzzed shader gets: no extension, so the text decides its
/// language, as for a shader that came in a link.
const SHADER_NAME: &str = "fuzz-shader";

/// A shader compiles or is refused with an error at a line of the user's
/// file (never of the program's prelude).
fn run_shader(input: &[u8]) -> std::result::Result<(), String> {
    let Ok(source) = text(input) else {
        return Ok(());
    };
    match raysandbox::sandbox::compile(SHADER_NAME, source) {
        Ok(_) => Ok(()),
        Err(e) if e.file != SHADER_NAME => Err(format!("the error is not in the file: {e}")),
        Err(e) if !(1..=line_count(source).max(1) as u32).contains(&e.line) => {
            Err(format!("the error's line is not in the file: {e}"))
        }
        Err(_) => Ok(()),
    }
}

// ------------------------------------------------------------------ links

/// Links to every bundled scene and shader, and a deflate bomb: twice the
/// text a link may carry, of one letter, in a link of 11 KB.
fn link_seeds() -> Vec<Vec<u8>> {
    let mut seeds: Vec<Vec<u8>> = raysandbox::scene::bundled::names()
        .into_iter()
        .map(|name| link::scene_hash(raysandbox::scene::bundled::text(name).unwrap()).into_bytes())
        .collect();
    seeds.extend(
        raysandbox::sandbox::bundled::SHADERS
            .iter()
            .map(|(_, text)| link::shader_hash(text).into_bytes()),
    );
    seeds.push(link::scene_hash(&"a".repeat(2 * link::MAX_TEXT)).into_bytes());
    seeds
}

fn make_link(u: &mut Unstructured, seeds: &[Vec<u8>]) -> Result<Vec<u8>> {
    let text = match u.int_in_range(0..=9)? {
        0..=4 => {
            let tokens = [
                "scene=", "shader=", "#", "%", "=", "+", "/", "-", "_", "AAAA",
            ];
            mutate_seed(u, seeds, &tokens)?
        }
        5..=7 => {
            let mut link = link::scene_hash(&random_text(u, 200)?);
            if u.arbitrary()? {
                link = link.replacen("scene=", "shader=", 1);
            }
            link
        }
        _ => {
            let key = u.choose(&["scene=", "#scene=", "shader=", "#shader=", ""])?;
            format!("{key}{}", random_text(u, 200)?)
        }
    };
    Ok(text.into_bytes())
}

/// A link decodes or is refused with a message; never more text than a
/// link may carry.
fn run_link(input: &[u8]) -> std::result::Result<(), String> {
    let Ok(hash) = text(input) else {
        return Ok(());
    };
    for decoded in [link::scene_in_hash(hash), link::shader_in_hash(hash)] {
        if let Some(Ok(text)) = decoded
            && text.len() > link::MAX_TEXT
        {
            return Err(format!("decoded {} bytes", text.len()));
        }
    }
    Ok(())
}

// ------------------------------------------------------------ annotations

/// Annotated declarations as docs/sandbox.md shows them.
fn annotation_seeds() -> Vec<Vec<u8>> {
    [
        "uniform float speed; // @slider(0.0, 5.0, 0.1) speed of the spin\n",
        "uniform float zoom; // @log(0.01, 100) @default(1)\n",
        "uniform vec3 tint; // @color(linear) the tint\n",
        "uniform bool spin; // @checkbox @default(true)\n",
        "// @select(sphere, \"box\", torus)\n// which shape\nuniform int shape;\n",
        "const R: f32 = 2.0; // @drag(0.01) radius\n",
    ]
    .iter()
    .map(|s| s.as_bytes().to_vec())
    .collect()
}

/// A declaration whose comment holds random `@tags` with random arguments.
fn annotation_from_scratch(u: &mut Unstructured) -> Result<String> {
    let mut comment = String::new();
    for _ in 0..u.int_in_range(0..=4)? {
        let tag = u.choose(&[
            "slider", "log", "color", "colour", "checkbox", "select", "default", "drag", "x", "",
        ])?;
        comment.push_str(&format!("@{tag}"));
        if u.ratio(3, 4)? {
            let args: Vec<String> = (0..u.int_in_range(0..=4)?)
                .map(|_| {
                    Ok(match u.int_in_range(0..=4)? {
                        0..=2 => number(u)?,
                        3 => u
                            .choose(&["linear", "srgb", "true", "false", "\"a\"", ""])?
                            .to_string(),
                        _ => random_text(u, 6)?,
                    })
                })
                .collect::<Result<_>>()?;
            let close = if u.ratio(1, 10)? { "" } else { ")" };
            comment.push_str(&format!("({}{close}", args.join(",")));
        }
        comment.push_str(&format!(" {} ", random_text(u, 10)?));
    }
    let style = u.choose(&["// ", "/* ", "//"])?;
    Ok(format!("uniform vec3 p; {style}{comment}\n"))
}

fn make_annotation(u: &mut Unstructured, seeds: &[Vec<u8>]) -> Result<Vec<u8>> {
    let text = if u.ratio(1, 2)? {
        annotation_from_scratch(u)?
    } else {
        let tokens = [
            "@",
            "(",
            ")",
            ",",
            "@slider(",
            "@select(",
            "@default(",
            "//",
            "/*",
        ];
        mutate_seed(u, seeds, &tokens)?
    };
    Ok(text.into_bytes())
}

/// The line of the declaration in [`annotation_seeds`]' texts: the first
/// with `;`.
fn declaration_line(text: &str) -> u32 {
    text.lines().position(|l| l.contains(';')).unwrap_or(0) as u32 + 1
}

/// A float vector: every control fits it but `@checkbox` and `@select`.
const VEC3: ParamType = ParamType {
    scalar: Scalar::F32,
    len: 3,
};

/// An annotation is read or refused at an offset inside the text; one
/// that is read makes a parameter (or a message), whose values survive
/// the sidecar file.
fn run_annotation(input: &[u8]) -> std::result::Result<(), String> {
    let Ok(text) = text(input) else {
        return Ok(());
    };
    match params::annotation_of_line(text, declaration_line(text)) {
        Ok(annotation) => {
            let Ok(spec) = ParamSpec::new("p", Ok(VEC3), 0, annotation, None, 1) else {
                return Ok(());
            };
            sidecar_round_trip(ParamSet::new(vec![spec], 16))
        }
        Err((offset, message)) if offset > text.len() || !text.is_char_boundary(offset) => {
            Err(format!(
                "offset {offset} is not a place in the {} bytes: {message}",
                text.len()
            ))
        }
        Err(_) => Ok(()),
    }
}

/// The values, saved and read back, are the same.
fn sidecar_round_trip(mut set: ParamSet) -> std::result::Result<(), String> {
    let _ = set.bytes();
    let saved = set.to_toml("fuzz.frag");
    let before = set.values.clone();
    set.reset();
    let warnings = set.apply_toml(&saved)?;
    if !warnings.is_empty() || set.values != before {
        return Err(format!(
            "the sidecar did not round-trip: {warnings:?}\n{saved}"
        ));
    }
    Ok(())
}

// --------------------------------------------------------------- sidecars

/// A sidecar file for the parameters of [`sidecar_params`].
fn sidecar_seeds() -> Vec<Vec<u8>> {
    vec![b"speed = 1.5\ntint = [0.1, 0.2, 0.3]\nshape = \"box\"\nspin = true\ncount = 3\n".to_vec()]
}

/// One parameter of each control, to apply sidecar files to.
fn sidecar_params() -> ParamSet {
    let spec = |name: &str, scalar, len, comment: &str| {
        let annotation = params::annotation_of_line(&format!("x; // {comment}\n"), 1).unwrap();
        ParamSpec::new(name, Ok(ParamType { scalar, len }), 0, annotation, None, 1).unwrap()
    };
    let specs = vec![
        spec("speed", Scalar::F32, 1, "@slider(0, 5, 0.1)"),
        spec("tint", Scalar::F32, 3, "@color"),
        spec("shape", Scalar::I32, 1, "@select(sphere, box)"),
        spec("spin", Scalar::Bool, 1, "@checkbox"),
        spec("count", Scalar::U32, 1, "@drag"),
    ];
    ParamSet::new(specs, 64)
}

fn make_sidecar(u: &mut Unstructured, seeds: &[Vec<u8>]) -> Result<Vec<u8>> {
    let text = if u.ratio(1, 2)? {
        mutate_seed(u, seeds, &["speed = ", "tint = ", "[", "]", "\"", "nan"])?
    } else {
        let mut s = String::new();
        for _ in 0..u.int_in_range(0..=6)? {
            let name = u.choose(&["speed", "tint", "shape", "spin", "count", "x"])?;
            let value = match u.int_in_range(0..=3)? {
                0 => number(u)?,
                1 => vector(u)?,
                2 => u
                    .choose(&["true", "\"box\"", "\"\"", "{}", "1979-05-27"])?
                    .to_string(),
                _ => random_text(u, 8)?,
            };
            s.push_str(&format!("{name} = {value}\n"));
        }
        s
    };
    Ok(text.into_bytes())
}

/// Any sidecar applies or is refused with a message, leaving every value
/// within its control's range and finite.
fn run_sidecar(input: &[u8]) -> std::result::Result<(), String> {
    let Ok(text) = text(input) else {
        return Ok(());
    };
    let mut set = sidecar_params();
    let _ = set.apply_toml(text);
    let _ = set.bytes();
    for (spec, value) in set.specs.iter().zip(&set.values) {
        if value.iter().any(|v| !v.is_finite()) {
            return Err(format!("{}: the value {value:?} is not finite", spec.name));
        }
        if spec.clamp(*value) != *value {
            return Err(format!(
                "{}: the value {value:?} is out of range",
                spec.name
            ));
        }
    }
    sidecar_round_trip(set)
}

// ------------------------------------------------------ multipass shaders

/// The Shadertoy JSON exports of the tests (written for this project).
fn shadertoy_json_seeds() -> Vec<Vec<u8>> {
    read_all(&files(Path::new("tests/shaders/multipass"), &["json"]))
}

/// What goes wrong in a JSON export: its syntax, the keys of passes and
/// inputs, ids and channels out of range.
fn make_shadertoy_json(u: &mut Unstructured, seeds: &[Vec<u8>]) -> Result<Vec<u8>> {
    let tokens = [
        "{",
        "}",
        "[",
        "]",
        "\"",
        ",",
        ":",
        "null",
        "-1",
        "4",
        "1e999",
        "\"channel\": ",
        "\"ctype\": \"buffer\"",
        "\"type\": \"image\"",
        "\"type\": \"buffer\"",
        "\"id\": 257",
        "\"id\": \"XsXGR8\"",
        "\"name\": \"Buffer C\"",
        "\"code\": \"\"",
        "\\n",
        "\\u0000",
    ];
    Ok(mutate_seed(u, seeds, &tokens)?.into_bytes())
}

/// A JSON export reads or is refused with an error that names the file;
/// what reads compiles, or its error names the file too.
fn run_shadertoy_json(input: &[u8]) -> std::result::Result<(), String> {
    let Ok(text) = text(input) else {
        return Ok(());
    };
    let path = Path::new("fuzz-dir/fuzz.json");
    let project = match multipass::json::parse(path, text) {
        Ok(project) => project,
        Err(e) if e.starts_with("fuzz-dir/fuzz.json: ") => return Ok(()),
        Err(e) => return Err(format!("the error does not name the file: {e}")),
    };
    check_bindings(&project)?;
    match multipass::compile_project(&project) {
        Err(e) if !e.file.starts_with("fuzz-dir/fuzz.json [") => Err(format!(
            "the compile error does not name the file's pass: {e}"
        )),
        _ => Ok(()),
    }
}

/// Every channel reads a buffer the project has.
fn check_bindings(project: &multipass::Project) -> std::result::Result<(), String> {
    for pass in &project.passes {
        for input in pass.channels.iter().flatten() {
            if let multipass::Input::Buffer(k) = input
                && project.pass(multipass::PassKind::Buffer(*k)).is_none()
            {
                return Err(format!("{} reads buffer {k}, which is missing", pass.name));
            }
        }
    }
    Ok(())
}

fn channels_toml_seeds() -> Vec<Vec<u8>> {
    read_all(&files(Path::new("tests/shaders/multipass"), &["toml"]))
}

fn make_channels_toml(u: &mut Unstructured, seeds: &[Vec<u8>]) -> Result<Vec<u8>> {
    let text = if u.ratio(1, 2)? {
        mutate_seed(
            u,
            seeds,
            &["[", "]", "\"", "=", "iChannel", "buffer_", "image", "\n"],
        )?
    } else {
        let mut s = String::new();
        for _ in 0..u.int_in_range(0..=4)? {
            let section = u.choose(&["image", "buffer_a", "buffer_d", "buffer_e", "", "common"])?;
            s.push_str(&format!("[{section}]\n"));
            for _ in 0..u.int_in_range(0..=4)? {
                let key = u.choose(&["iChannel0", "iChannel3", "iChannel4", "iChannel", "x"])?;
                let value = match u.int_in_range(0..=3)? {
                    0 => u
                        .choose(&["\"buffer_a\"", "\"buffer_c\"", "\"keyboard\"", "\"noise\""])?
                        .to_string(),
                    1 => number(u)?,
                    2 => format!("\"{}\"", random_text(u, 12)?.replace(['"', '\\'], "")),
                    _ => u.choose(&["{}", "[]", "true", "\"\""])?.to_string(),
                };
                s.push_str(&format!("{key} = {value}\n"));
            }
        }
        s
    };
    Ok(text.into_bytes())
}

/// `channels.toml` binds the channels of a folder with every pass, or is
/// refused with an error naming the file; what it binds is a channel the
/// folder can give.
fn run_channels_toml(input: &[u8]) -> std::result::Result<(), String> {
    let Ok(text) = text(input) else {
        return Ok(());
    };
    let mut passes: Vec<multipass::Pass> = multipass::PassKind::all()
        .into_iter()
        .map(|kind| multipass::Pass {
            kind,
            name: kind.stem(),
            code: multipass::Code::Text(String::new()),
            channels: Default::default(),
        })
        .collect();
    let dir = Path::new("fuzz-dir");
    match multipass::folder::bind(dir, "fuzz-dir/channels.toml", text, &mut passes) {
        Err(e) if !e.starts_with("fuzz-dir/channels.toml: ") => {
            Err(format!("the error does not name the file: {e}"))
        }
        _ => Ok(()),
    }
}

// --------------------------------------------------------------- includes

/// The files of a fuzzed folder of shaders, by index: the first is the
/// shader compiled, the others what it may include.
const FOLDER_FILES: [&str; 4] = ["main.frag", "lib/a.glsl", "lib/b.glsl", "c.glsl"];

/// The line that starts file `k` of [`FOLDER_FILES`] in a folder's input.
fn file_marker(k: usize) -> String {
    format!("//@file {k}\n")
}

/// What goes wrong with includes: files that are missing, not files, the
/// including file itself, one including the other (cycles), paths out of
/// the folder, empty and unterminated names.
const INCLUDE_TOKENS: [&str; 12] = [
    "#include \"lib/a.glsl\"\n",
    "#include \"b.glsl\"\n",
    "#include \"../c.glsl\"\n",
    "#include \"../main.frag\"\n",
    "#include \"main.frag\"\n",
    "#include \"missing.glsl\"\n",
    "#include \"lib\"\n",
    "#include \"/dev/zero\"\n",
    "#include \"\"\n",
    "#include \"lib/a.glsl\n",
    "//@file 1\n",
    "//@file 2\n",
];

/// A seed shader cut at random lines into the folder's files, each piece
/// included by the one before (so that, unmutated, the folder is the seed
/// again), then mutated with [`INCLUDE_TOKENS`].
fn make_include_folder(u: &mut Unstructured, seeds: &[Vec<u8>]) -> Result<Vec<u8>> {
    let lines: Vec<&str> = seed_text(u, seeds)?.split_inclusive('\n').collect();
    let pieces = u.int_in_range(1..=FOLDER_FILES.len())?;
    let mut cuts: Vec<usize> = (1..pieces)
        .map(|_| u.int_in_range(0..=lines.len()))
        .collect::<Result<_>>()?;
    cuts.sort_unstable();
    let mut folder = String::new();
    let mut start = 0;
    for (k, end) in cuts.into_iter().chain([lines.len()]).enumerate() {
        folder.push_str(&file_marker(k));
        folder.push_str(&lines[start..end].concat());
        if k + 1 < pieces {
            // Relative to this file's folder: lib/a.glsl and lib/b.glsl
            // are beside each other.
            let next = FOLDER_FILES[k + 1];
            let from_lib = FOLDER_FILES[k].starts_with("lib/");
            let path = match (from_lib, next.strip_prefix("lib/")) {
                (true, Some(name)) => name.to_string(),
                (true, None) => format!("../{next}"),
                (false, _) => next.to_string(),
            };
            folder.push_str(&format!("#include \"{path}\"\n"));
        }
        start = end;
    }
    Ok(mutate(u, &folder, &INCLUDE_TOKENS)?.into_bytes())
}

/// The folder's files from its input: text before the first marker, and
/// after a marker of file 0, belong to the shader compiled.
fn folder_files(text: &str) -> Vec<String> {
    let mut files = vec![String::new(); FOLDER_FILES.len()];
    let mut current = 0;
    for line in text.split_inclusive('\n') {
        match (0..FOLDER_FILES.len()).find(|&k| line == file_marker(k)) {
            Some(k) => current = k,
            None => files[current].push_str(line),
        }
    }
    files
}

/// A folder of shaders written for each input, reused (one per process).
static FOLDER: LazyLock<PathBuf> = LazyLock::new(|| {
    let dir = std::env::temp_dir().join(format!("raysandbox-fuzz-include-{}", std::process::id()));
    std::fs::create_dir_all(dir.join("lib")).expect("create the fuzzed folder");
    dir
});

/// The folder's shader compiles, or is refused with an error at a line of
/// one of the folder's files: the file that has the mistake, an included
/// one included, never the joined text's line.
fn run_include_folder(input: &[u8]) -> std::result::Result<(), String> {
    let Ok(text) = text(input) else {
        return Ok(());
    };
    let files = folder_files(text);
    for (name, content) in FOLDER_FILES.iter().zip(&files) {
        std::fs::write(FOLDER.join(name), content).map_err(|e| format!("{name}: {e}"))?;
    }
    let Err(e) = raysandbox::sandbox::compile_file(&FOLDER.join(FOLDER_FILES[0])) else {
        return Ok(());
    };
    let file = Path::new(&e.file)
        .canonicalize()
        .map_err(|_| format!("the error is not in a file of the folder: {e}"))?;
    let Some(k) = FOLDER_FILES
        .iter()
        .position(|name| FOLDER.join(name).canonicalize().is_ok_and(|p| p == file))
    else {
        return Err(format!("the error is not in a file of the folder: {e}"));
    };
    if !(1..=line_count(&files[k]).max(1) as u32).contains(&e.line) {
        return Err(format!(
            "the error's line is not in {}: {e}",
            FOLDER_FILES[k]
        ));
    }
    Ok(())
}
