//! Shared by the integration tests: the GPU, the tally of tests that used
//! it, and where the scenes are.
//! Each test binary compiles this module and uses only part of it.
#![allow(dead_code)]

pub mod browser;
pub mod xwindow;

use std::path::{Path, PathBuf};

use raysandbox::gpu::{DataAccess, Gpu, data_texture_count};

/// A folder in which every GPU or window test leaves one file named after
/// itself; `scripts/test` sets it and counts the files, so a run that tested
/// nothing on the GPU cannot look like a green one.
pub const TALLY_DIR: &str = "RAYSANDBOX_TEST_TALLY";

/// How to get what the GPU and window tests need.
pub const INSTALL_HINT: &str = "install lavapipe (Mesa's Vulkan driver on the CPU) and the Vulkan \
     loader with `sudo apt-get install mesa-vulkan-drivers libvulkan1`, or run scripts/test, \
     which installs them (and Xvfb, xdotool, ImageMagick for the window tests)";

/// The GPU device. Without an adapter the test fails with a message saying
/// how to install one: a GPU test never passes untested.
pub fn gpu() -> Gpu {
    match Gpu::headless() {
        Ok(gpu) => {
            eprintln!("adapter: {}", gpu.describe());
            record("gpu");
            gpu
        }
        Err(e) => {
            panic!("this test needs a GPU adapter and found none: {e}\nTo run it, {INSTALL_HINT}.")
        }
    }
}

/// Both ways the tracer reads its data textures ([`DataAccess`]): `gpu`,
/// which binds them as storage textures (lavapipe has enough of them; the
/// test fails where it has not), and a device from the same adapter with
/// WebGPU's default limit of storage textures, which samples them.
pub fn both_data_accesses(gpu: &Gpu) -> [(Gpu, &'static str); 2] {
    assert_eq!(
        DataAccess::for_device(&gpu.device),
        DataAccess::Storage,
        "this test reads the data textures both ways: it needs a device that binds {} \
         storage textures per shader stage, as lavapipe does",
        data_texture_count()
    );
    let sampled = pollster::block_on(Gpu::request_with_limits(
        gpu.instance.clone(),
        gpu.adapter.clone(),
        |limits| {
            limits.max_storage_textures_per_shader_stage =
                wgpu::Limits::default().max_storage_textures_per_shader_stage
        },
    ))
    .expect("a device with WebGPU's default storage textures");
    assert_eq!(DataAccess::for_device(&sampled.device), DataAccess::Sampled);
    [(gpu.clone(), "storage"), (sampled, "sampled")]
}

/// For the tests that run the `raysandbox` binary, which makes its own
/// device: fails the test, saying how to install an adapter, when there is
/// none, rather than letting the binary's own error stand for it.
pub fn require_gpu() {
    gpu();
}

/// Leaves the file `KIND-BINARY-TEST` in the [`TALLY_DIR`] folder, if there
/// is one: one file per test however often it asks for the GPU. libtest
/// names each test's thread after the test.
pub fn record(kind: &str) {
    let Some(dir) = std::env::var_os(TALLY_DIR) else {
        return;
    };
    let thread = std::thread::current();
    let test = thread.name().unwrap_or("main").replace("::", "-");
    let file = Path::new(&dir).join(format!("{kind}-{}-{test}", env!("CARGO_CRATE_NAME")));
    std::fs::create_dir_all(&dir)
        .and_then(|()| std::fs::write(&file, ""))
        .unwrap_or_else(|e| panic!("{TALLY_DIR}: {}: {e}", file.display()));
}

/// The project's folder of bundled scenes.
pub fn scenes_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/scenes")
}

/// Every `*.toml` directly in `dir`, sorted by name.
pub fn toml_files(dir: &Path) -> Vec<PathBuf> {
    files_in(dir, |extension| extension == "toml")
}

/// The shader files of a suite folder, sorted (its `.md` notes left out).
pub fn shader_files(dir: &Path) -> Vec<PathBuf> {
    files_in(dir, |extension| extension != "md")
}

/// Every file at `path` or below it, at any depth, sorted by path.
pub fn files_below(path: &Path) -> Vec<PathBuf> {
    if path.is_file() {
        return vec![path.to_path_buf()];
    }
    let mut entries: Vec<PathBuf> = std::fs::read_dir(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .map(|entry| entry.expect("directory entry").path())
        .collect();
    entries.sort();
    entries
        .iter()
        .flat_map(|entry| files_below(entry))
        .collect()
}

/// The files of `dir` (not below it) whose extension `keep` accepts, sorted.
fn files_in(dir: &Path, keep: impl Fn(&std::ffi::OsStr) -> bool) -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|entry| entry.expect("directory entry").path())
        .filter(|p| p.extension().is_some_and(&keep))
        .collect();
    files.sort();
    files
}

/// Copies a folder with its subfolders (the shader folder has `shapes/`).
pub fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for entry in std::fs::read_dir(from).unwrap() {
        let path = entry.unwrap().path();
        let target = to.join(path.file_name().unwrap());
        if path.is_dir() {
            copy_dir(&path, &target);
        } else {
            std::fs::copy(&path, &target).unwrap();
        }
    }
}

/// `/proc/loadavg`, to print beside a measured time: the test machine's 2
/// cores are shared with other jobs.
pub fn load_average() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .unwrap_or_default()
        .trim()
        .to_string()
}

/// A fresh folder for one test's files, `raysandbox-PREFIX-NAME-PID` in the
/// system's temporary folder.
pub fn temp_dir(prefix: &str, name: &str) -> PathBuf {
    let dir =
        std::env::temp_dir().join(format!("raysandbox-{prefix}-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Writes `text` to `dir/name` and returns the path.
pub fn write_file(dir: &Path, name: &str, text: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

/// What the shader fuzzers (tests/sandbox_fuzz.rs, tests/fuzz) insert:
/// brackets, keywords and constructs that real shaders and the program's
/// rewrites care about.
pub const SHADER_MISTAKES: [&str; 24] = [
    "(",
    ")",
    "{",
    "}",
    ";",
    ",",
    "inout ",
    "out ",
    "#if 0\n",
    "#endif\n",
    "#define X\n",
    "while(true)",
    "/*",
    "*/",
    "sampler2D ",
    "texture2D(",
    "1e39",
    "mat2(",
    "dot(",
    "uniform ",
    "precision ",
    "void main()",
    "mainImage(",
    "[",
];

/// Runs the raysandbox binary with `args`, its output captured.
pub fn raysandbox(args: &[&str]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_raysandbox"))
        .args(args)
        .output()
        .expect("run raysandbox")
}
