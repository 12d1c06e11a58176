//! Watching the shader folder and the scene file for edits made in another
//! program (the class's own editor), debounced so that one save that an
//! editor performs as several writes gives one reload.

use std::path::{Path, PathBuf};
use std::time::Duration;

use notify_debouncer_mini::notify::RecursiveMode;
use notify_debouncer_mini::{DebounceEventResult, Debouncer, new_debouncer};

/// What changed on disk.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Change {
    Shaders,
    SceneFile,
}

/// Quiet time after the last write before a change is reported.
const DEBOUNCE: Duration = Duration::from_millis(150);

/// Keeps the watch alive; dropping it stops watching.
pub struct Watch {
    _debouncer: Debouncer<notify_debouncer_mini::notify::RecommendedWatcher>,
}

/// Starts watching `shader_dir` (its `.wgsl` files and those of its `shapes/`
/// folder, one per shape kind) and `scene_file`, calling
/// `notify` from the watcher's thread for every debounced change. Folders are
/// watched rather than files, because editors often save by writing a new
/// file and renaming it over the old one, which ends a watch on the file.
pub fn watch(
    shader_dir: Option<&Path>,
    scene_file: Option<&Path>,
    notify: impl Fn(Change) + Send + 'static,
) -> Result<Watch, String> {
    let shader_dir = shader_dir.map(canonical);
    let scene_file = scene_file.map(canonical);
    let shape_dir = shader_dir.as_ref().map(|d| d.join("shapes"));
    let (dirs, classify) = {
        let mut dirs: Vec<PathBuf> = shader_dir.iter().cloned().collect();
        dirs.extend(shape_dir.iter().filter(|d| d.is_dir()).cloned());
        if let Some(parent) = scene_file.as_deref().and_then(Path::parent)
            && !dirs.iter().any(|d| d == parent)
        {
            dirs.push(parent.to_path_buf());
        }
        let classify = move |path: &Path| -> Option<Change> {
            let path = canonical(path);
            if scene_file.as_deref() == Some(path.as_path()) {
                return Some(Change::SceneFile);
            }
            let in_shader_dir = path.parent().is_some_and(|p| {
                shader_dir.as_deref() == Some(p) || shape_dir.as_deref() == Some(p)
            });
            (in_shader_dir && path.extension().is_some_and(|e| e == "wgsl"))
                .then_some(Change::Shaders)
        };
        (dirs, classify)
    };
    let mut debouncer = new_debouncer(DEBOUNCE, move |result: DebounceEventResult| match result {
        Ok(events) => {
            let mut changes: Vec<Change> =
                events.iter().filter_map(|e| classify(&e.path)).collect();
            changes.dedup();
            changes.sort_by_key(|c| *c as u8);
            changes.dedup();
            for change in changes {
                notify(change);
            }
        }
        Err(e) => log::warn!("file watch: {e}"),
    })
    .map_err(|e| format!("cannot watch files: {e}"))?;
    for dir in &dirs {
        debouncer
            .watcher()
            .watch(dir, RecursiveMode::NonRecursive)
            .map_err(|e| format!("cannot watch {}: {e}", dir.display()))?;
    }
    Ok(Watch {
        _debouncer: debouncer,
    })
}

/// Watches one file (the sandbox's shader), calling `notify` for every
/// debounced change of it. Its folder is watched, as for the scene file.
pub fn watch_file(file: &Path, notify: impl Fn() + Send + 'static) -> Result<Watch, String> {
    watch(None, Some(file), move |_| notify())
}

/// The absolute path, resolved through links where the file exists (events
/// report absolute paths; the user may have typed a relative one).
fn canonical(path: &Path) -> PathBuf {
    if let Ok(p) = path.canonicalize() {
        return p;
    }
    // A file being replaced may not exist at this instant: resolve its folder.
    match (path.parent(), path.file_name()) {
        (Some(dir), Some(name)) => {
            let dir = if dir.as_os_str().is_empty() {
                Path::new(".")
            } else {
                dir
            };
            dir.canonicalize()
                .map_or_else(|_| path.to_path_buf(), |d| d.join(name))
        }
        _ => path.to_path_buf(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::mpsc;

    /// The next change that is not a repeat of `previous`: one write can
    /// reach the watcher as several events, which a loaded machine may
    /// debounce into separate reports.
    fn next_change(rx: &mpsc::Receiver<Change>, previous: Option<Change>) -> Option<Change> {
        loop {
            let change = rx.recv_timeout(Duration::from_secs(5)).ok()?;
            if Some(change) != previous {
                return Some(change);
            }
        }
    }

    #[test]
    fn reports_shader_and_scene_edits_and_nothing_else() {
        let dir = std::env::temp_dir().join(format!("raysandbox-watch-{}", std::process::id()));
        let shaders = dir.join("shaders");
        std::fs::create_dir_all(&shaders).unwrap();
        let scene = dir.join("scene.toml");
        std::fs::write(&scene, "a").unwrap();
        std::fs::write(shaders.join("main.wgsl"), "a").unwrap();
        let (tx, rx) = mpsc::channel();
        let _watch = watch(Some(&shaders), Some(&scene), move |c| tx.send(c).unwrap()).unwrap();
        std::thread::sleep(Duration::from_millis(200));

        std::fs::write(shaders.join("main.wgsl"), "b").unwrap();
        assert_eq!(next_change(&rx, None), Some(Change::Shaders));
        std::fs::write(&scene, "b").unwrap();
        assert_eq!(
            next_change(&rx, Some(Change::Shaders)),
            Some(Change::SceneFile)
        );
        // Let late repeats of the scene write arrive before the quiet check.
        while rx.recv_timeout(Duration::from_millis(500)).is_ok() {}
        std::fs::write(dir.join("other.toml"), "x").unwrap();
        std::fs::write(shaders.join("notes.txt"), "x").unwrap();
        assert!(
            rx.recv_timeout(Duration::from_millis(600)).is_err(),
            "unrelated files are ignored"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
