//! The set-up scripts on a machine that lacks their optional tools:
//! `scripts/test --probe` (which also runs `scripts/web --probe`) is run with
//! a PATH from which one optional tool at a time, then all of them, have been
//! taken away. The probes must name what is missing and finish with status 0
//! under the scripts' `set -euo pipefail` (scripts/probe.sh), never end the
//! script with a missing command's status 127.

use std::collections::HashSet;
use std::os::unix::fs::symlink;
use std::path::{Path, PathBuf};
use std::process::Command;

/// Each optional tool, and what the probe's report must say without it.
const OPTIONAL: &[(&str, &str)] = &[
    ("wasm-opt", "wasm-opt: not installed, not used"),
    ("wasm-bindgen", "missing, would be installed"),
    ("rustup", "wasm32 target: "),
    ("chromium", "chromium"),
    ("Xvfb", "xvfb"),
    ("xdotool", "xdotool"),
    ("import", "imagemagick"),
    ("ldconfig", "Debian packages to install: "),
];

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// A folder of links to every command on this process's PATH except
/// `without` (the first of each name, as PATH would find it). scripts/web
/// also searches CARGO_HOME/bin, where `cargo install` puts wasm-bindgen:
/// CARGO_HOME points at an empty folder while the probe runs.
fn path_without(without: &[&str], dir: &Path) -> PathBuf {
    let bin = dir.join("bin");
    std::fs::create_dir_all(&bin).unwrap();
    let mut seen: HashSet<std::ffi::OsString> = without.iter().map(Into::into).collect();
    let path = std::env::var_os("PATH").expect("PATH is set");
    for folder in std::env::split_paths(&path) {
        let Ok(entries) = std::fs::read_dir(&folder) else {
            continue;
        };
        for entry in entries.flatten() {
            let name = entry.file_name();
            if seen.insert(name.clone()) {
                symlink(entry.path(), bin.join(&name)).unwrap();
            }
        }
    }
    bin
}

/// `scripts/test --probe` with PATH lacking `without`; its output. Fails the
/// test unless it exits with status 0.
fn probe(without: &[&str], no_vulkan_driver: bool) -> String {
    let dir = std::env::temp_dir().join(format!(
        "raysandbox-probe-{}-{}",
        std::process::id(),
        without.join("+")
    ));
    let _ = std::fs::remove_dir_all(&dir);
    let bin = path_without(without, &dir);
    let empty = dir.join("empty");
    std::fs::create_dir_all(&empty).unwrap();
    let mut command = Command::new(bin.join("bash"));
    command
        .arg(repo().join("scripts/test"))
        .arg("--probe")
        .env("PATH", &bin)
        .env("CARGO_HOME", &empty);
    if no_vulkan_driver {
        command.env("RAYSANDBOX_VULKAN_ICD_DIR", &empty);
    }
    let out = command.output().expect("run bash");
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        out.status.success(),
        "scripts/test --probe without {without:?} ended with {}:\n{text}",
        out.status
    );
    std::fs::remove_dir_all(&dir).unwrap();
    text
}

#[test]
fn each_optional_tool_missing_is_reported_not_fatal() {
    for &(tool, says) in OPTIONAL {
        let text = probe(&[tool], false);
        assert!(
            text.contains(says),
            "without {tool}, the probe should say {says:?}:\n{text}"
        );
    }
}

#[test]
fn every_optional_tool_missing_at_once_is_listed() {
    let tools: Vec<&str> = OPTIONAL.iter().map(|&(tool, _)| tool).collect();
    let text = probe(&tools, true);
    let line = text
        .lines()
        .find(|l| l.starts_with("Debian packages to install: "))
        .unwrap_or_else(|| panic!("no package line:\n{text}"));
    for package in [
        "mesa-vulkan-drivers",
        "xvfb",
        "xdotool",
        "imagemagick",
        "chromium",
    ] {
        assert!(line.contains(package), "{package} not in {line:?}");
    }
    assert!(text.contains("wasm-opt: not installed, not used"), "{text}");
    assert!(text.contains("wasm-bindgen"), "{text}");
}

#[test]
fn with_the_tools_present_the_probe_names_no_driver_it_has() {
    let text = probe(&[], false);
    let line = text
        .lines()
        .find(|l| l.starts_with("Debian packages to install: "))
        .unwrap_or_else(|| panic!("no package line:\n{text}"));
    let icd = Path::new("/usr/share/vulkan/icd.d");
    let has_lavapipe = std::fs::read_dir(icd).is_ok_and(|entries| {
        entries
            .flatten()
            .any(|e| e.file_name().to_string_lossy().starts_with("lvp_icd."))
    });
    assert_eq!(
        !line.contains("mesa-vulkan-drivers"),
        has_lavapipe,
        "the probe disagrees with {icd:?} about lavapipe: {line}"
    );
}
