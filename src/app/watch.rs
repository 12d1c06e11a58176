//! Watching the shader folder, the scene file and the mesh files it reads
//! for edits made in another program (the class's own editor, a modeller's
//! export), debounced so that one save that an
//! editor performs as several writes gives one reload.

use std::path::{Path, PathBuf};
use std::time::Duration;

use notify_debouncer_mini::notify::event::{AccessKind, AccessMode, Event, EventKind};
use notify_debouncer_mini::notify::{
    self, EventHandler, RecommendedWatcher, RecursiveMode, Watcher, WatcherKind,
};
use notify_debouncer_mini::{Config, DebounceEventResult, Debouncer, new_debouncer_opt};

/// What changed on disk.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Change {
    Shaders,
    SceneFile,
    /// One of the files the shapes read, as it was given to [`watch`].
    ShapeFile(PathBuf),
}

/// Quiet time after the last write before a change is reported.
const DEBOUNCE: Duration = Duration::from_millis(150);

/// Keeps the watch alive; dropping it stops watching.
pub struct Watch {
    _debouncer: Debouncer<ChangeWatcher>,
}

/// The platform's watcher, without the events of a file being opened or
/// read: the viewer reads the files it watches when they change, and on
/// Linux each read would be reported as a new change and start the reload
/// again, for ever.
pub struct ChangeWatcher(RecommendedWatcher);

/// Whether `event` only says that a file was opened or read, not written.
fn is_read_only(event: &Event) -> bool {
    matches!(
        event.kind,
        EventKind::Access(
            AccessKind::Read | AccessKind::Open(_) | AccessKind::Close(AccessMode::Read)
        )
    )
}

impl Watcher for ChangeWatcher {
    fn new<F: EventHandler>(mut handler: F, config: notify::Config) -> notify::Result<Self> {
        let filtered = move |event: notify::Result<Event>| {
            if !event.as_ref().is_ok_and(is_read_only) {
                handler.handle_event(event);
            }
        };
        RecommendedWatcher::new(filtered, config).map(ChangeWatcher)
    }

    fn watch(&mut self, path: &Path, mode: RecursiveMode) -> notify::Result<()> {
        self.0.watch(path, mode)
    }

    fn unwatch(&mut self, path: &Path) -> notify::Result<()> {
        self.0.unwatch(path)
    }

    fn kind() -> WatcherKind {
        RecommendedWatcher::kind()
    }
}

/// Starts watching `shader_dir` (its `.wgsl` files and those of its `shapes/`
/// folder, one per shape kind), `scene_file` and `shape_files` (the files
/// its shapes read), calling
/// `notify` from the watcher's thread for every debounced change. Folders are
/// watched rather than files, because editors often save by writing a new
/// file and renaming it over the old one, which ends a watch on the file.
pub fn watch(
    shader_dir: Option<&Path>,
    scene_file: Option<&Path>,
    shape_files: &[PathBuf],
    notify: impl Fn(Change) + Send + 'static,
) -> Result<Watch, String> {
    let shader_dir = shader_dir.map(canonical);
    let scene_file = scene_file.map(canonical);
    let shape_dir = shader_dir.as_ref().map(|d| d.join("shapes"));
    let shape_files: Vec<(PathBuf, PathBuf)> = shape_files
        .iter()
        .map(|given| (canonical(given), given.clone()))
        .collect();
    let (dirs, classify) = {
        let mut dirs: Vec<PathBuf> = shader_dir.iter().cloned().collect();
        dirs.extend(shape_dir.iter().filter(|d| d.is_dir()).cloned());
        let files = scene_file.iter().chain(shape_files.iter().map(|(c, _)| c));
        for parent in files.filter_map(|f| f.parent()) {
            if parent.is_dir() && !dirs.iter().any(|d| d == parent) {
                dirs.push(parent.to_path_buf());
            }
        }
        let classify = move |path: &Path| -> Option<Change> {
            let path = canonical(path);
            if scene_file.as_deref() == Some(path.as_path()) {
                return Some(Change::SceneFile);
            }
            if let Some((_, given)) = shape_files.iter().find(|(c, _)| *c == path) {
                return Some(Change::ShapeFile(given.clone()));
            }
            let in_shader_dir = path.parent().is_some_and(|p| {
                shader_dir.as_deref() == Some(p) || shape_dir.as_deref() == Some(p)
            });
            (in_shader_dir && path.extension().is_some_and(|e| e == "wgsl"))
                .then_some(Change::Shaders)
        };
        (dirs, classify)
    };
    let config = Config::default().with_timeout(DEBOUNCE);
    let handler = move |result: DebounceEventResult| match result {
        Ok(events) => {
            let mut changes: Vec<Change> = Vec::new();
            for change in events.iter().filter_map(|e| classify(&e.path)) {
                if !changes.contains(&change) {
                    changes.push(change);
                }
            }
            for change in changes {
                notify(change);
            }
        }
        Err(e) => log::warn!("file watch: {e}"),
    };
    let mut debouncer = new_debouncer_opt::<_, ChangeWatcher>(config, handler)
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
    fn next_change(rx: &mpsc::Receiver<Change>, previous: Option<&Change>) -> Option<Change> {
        loop {
            let change = rx.recv_timeout(Duration::from_secs(5)).ok()?;
            if Some(&change) != previous {
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
        let _watch = watch(Some(&shaders), Some(&scene), &[], move |c| {
            tx.send(c).unwrap()
        })
        .unwrap();
        std::thread::sleep(Duration::from_millis(200));

        std::fs::write(shaders.join("main.wgsl"), "b").unwrap();
        assert_eq!(next_change(&rx, None), Some(Change::Shaders));
        std::fs::write(&scene, "b").unwrap();
        assert_eq!(
            next_change(&rx, Some(&Change::Shaders)),
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
        // What the viewer does on a change: it reads the files again.
        assert_eq!(std::fs::read_to_string(&scene).unwrap(), "b");
        assert_eq!(
            std::fs::read_to_string(shaders.join("main.wgsl")).unwrap(),
            "b"
        );
        assert!(
            rx.recv_timeout(Duration::from_millis(600)).is_err(),
            "reading a watched file is not a change"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn reports_a_mesh_file_by_the_path_it_was_given() {
        let dir =
            std::env::temp_dir().join(format!("raysandbox-watch-mesh-{}", std::process::id()));
        let models = dir.join("models");
        std::fs::create_dir_all(&models).unwrap();
        let mesh = models.join("tri.obj");
        std::fs::write(&mesh, "a").unwrap();
        // As a scene names it: through its own folder.
        let given = dir.join("scenes/../models/tri.obj");
        std::fs::create_dir_all(dir.join("scenes")).unwrap();
        let (tx, rx) = mpsc::channel();
        let _watch = watch(None, None, std::slice::from_ref(&given), move |c| {
            tx.send(c).unwrap()
        })
        .unwrap();
        std::thread::sleep(Duration::from_millis(200));
        std::fs::write(models.join("other.obj"), "x").unwrap();
        std::fs::write(&mesh, "b").unwrap();
        assert_eq!(next_change(&rx, None), Some(Change::ShapeFile(given)));
        while rx.recv_timeout(Duration::from_millis(500)).is_ok() {}
        std::fs::write(models.join("other.obj"), "y").unwrap();
        assert!(
            rx.recv_timeout(Duration::from_millis(600)).is_err(),
            "other files of the folder are ignored"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
