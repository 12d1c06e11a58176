//! The files that the shapes of the bundled scenes read (models), in the web page (docs/web.md,
//! "Scenes with mesh files"). The page has no file system: `scripts/web`
//! copies the files these scenes name into `dist/web/meshes/`, and the page
//! fetches each over http, once, before it parses a scene that names it.
//! The scene is then parsed from the fetched bytes
//! ([`Scene::from_toml_with_files`]), by the same parser as natively.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use crate::scene::{GivenFiles, Scene, bundled};

/// The files the bundled scenes' shapes read, as the scenes write them
/// (`../../meshes/bunny.obj`), each once; read from the scenes' texts once
/// (every debounced edit asks).
fn bundled_files() -> &'static BTreeSet<PathBuf> {
    static FILES: OnceLock<BTreeSet<PathBuf>> = OnceLock::new();
    FILES.get_or_init(|| {
        bundled::names_with_files()
            .into_iter()
            .flat_map(|name| Scene::files_named(bundled::text(name).unwrap_or_default()))
            .collect()
    })
}

/// Where the page serves `file` (as a scene writes it), relative to the
/// page's address: `meshes/NAME` for a file a bundled scene names,
/// `None` for any other file.
pub fn address(file: &Path) -> Option<String> {
    let name = file.file_name()?.to_str()?;
    bundled_files()
        .contains(file)
        .then(|| format!("meshes/{name}"))
}

/// The files the page fetched for shapes, and those it is fetching.
pub struct PageFiles {
    files: GivenFiles,
    fetching: BTreeSet<PathBuf>,
}

impl Default for PageFiles {
    fn default() -> Self {
        let bundled: Vec<String> = bundled_files()
            .iter()
            .map(|f| f.display().to_string())
            .collect();
        let missing = format!(
            "the page cannot read this file: in the page, a file a shape reads must be one of \
             the bundled models ({}) or a model dropped on the page; a shape may also be \
             written inline in the scene",
            bundled.join(", ")
        );
        PageFiles {
            files: GivenFiles::new(&missing),
            fetching: BTreeSet::new(),
        }
    }
}

impl PageFiles {
    /// The files fetched so far, to parse scenes with.
    pub fn files(&self) -> &GivenFiles {
        &self.files
    }

    /// The files `text`'s shapes name that the page serves and has not
    /// fetched yet: what to wait for before the text is parsed. (A file it
    /// does not serve is reported by the parse, at its line.)
    pub fn missing(&self, text: &str) -> Vec<PathBuf> {
        let mut named = BTreeSet::new();
        let mut files = Scene::files_named(text);
        files.retain(|f| address(f).is_some() && !self.files.has(f) && named.insert(f.clone()));
        files
    }

    /// Of `files`, those not being fetched already, now marked as being
    /// fetched.
    pub fn start_fetching(&mut self, files: &[PathBuf]) -> Vec<PathBuf> {
        files
            .iter()
            .filter(|f| self.fetching.insert(f.to_path_buf()))
            .cloned()
            .collect()
    }

    /// A fetch finished: its bytes are kept; after a failure (`None`) a
    /// later scene naming the file fetches it again.
    pub fn fetched(&mut self, file: &Path, bytes: Option<Vec<u8>>) {
        self.fetching.remove(file);
        if let Some(bytes) = bytes {
            self.files.insert(file.to_path_buf(), bytes);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `scripts/web` copies `assets/meshes/NAME` to `dist/web/meshes/NAME`
    /// for each file the bundled mesh scenes name: each address the page
    /// fetches is such a file.
    #[test]
    fn the_page_serves_each_model_of_the_bundled_mesh_scenes_by_its_name() {
        let folder = Path::new(env!("CARGO_MANIFEST_DIR")).join(bundled::SCENES_WITH_FILES_FOLDER);
        let files = bundled_files();
        assert_eq!(files.len(), 3, "{files:?}");
        for file in files {
            let address = address(file).expect("served");
            let on_disk = folder.join(file);
            assert!(on_disk.is_file(), "{}", on_disk.display());
            assert!(on_disk.starts_with(folder.join("../../meshes")));
            let name = on_disk.file_name().unwrap().to_str().unwrap();
            assert_eq!(address, format!("meshes/{name}"));
        }
        assert_eq!(
            address(Path::new("bunny.obj")),
            None,
            "only as the scenes write it"
        );
        assert_eq!(address(Path::new("/home/me/model.ply")), None);
    }

    /// `scripts/web` picks the files to copy with `sed` on lines written
    /// exactly `file = "../../meshes/NAME"`: every file the scenes' TOML
    /// names must be written so, or the page would fetch a file never
    /// copied.
    #[test]
    fn scripts_web_finds_every_model_the_bundled_mesh_scenes_name() {
        let by_line: BTreeSet<PathBuf> = bundled::names_with_files()
            .into_iter()
            .flat_map(|name| bundled::text(name).unwrap_or_default().lines())
            .filter_map(|line| {
                let name = line.strip_prefix("file = \"../../meshes/")?;
                Some(PathBuf::from(format!(
                    "../../meshes/{}",
                    name.strip_suffix('"')?
                )))
            })
            .collect();
        assert_eq!(&by_line, bundled_files());
    }

    #[test]
    fn a_scene_waits_for_the_served_files_it_names_until_they_are_fetched() {
        let mut meshes = PageFiles::default();
        let text = bundled::text("glass_bunny").unwrap();
        let bunny = PathBuf::from("../../meshes/bunny.obj");
        let only_bunny = vec![bunny.clone()];
        assert_eq!(meshes.missing(text), only_bunny);
        let twice = "[camera]\nfrom = [0, 1, 5]\nto = [0, 0, 0]\n\
                     [[meshes]]\nfile = \"../../meshes/bunny.obj\"\n\
                     [[meshes]]\nfile = \"../../meshes/teapot.obj\"\n\
                     [[meshes]]\nfile = \"../../meshes/bunny.obj\"\n";
        let teapot = PathBuf::from("../../meshes/teapot.obj");
        assert_eq!(
            meshes.missing(twice),
            [bunny.clone(), teapot],
            "each file once, in order"
        );
        assert_eq!(meshes.start_fetching(&only_bunny), only_bunny);
        assert!(
            meshes.start_fetching(&only_bunny).is_empty(),
            "fetched once"
        );
        meshes.fetched(&bunny, None);
        assert_eq!(meshes.missing(text), only_bunny, "a failed fetch");
        assert_eq!(
            meshes.start_fetching(&only_bunny),
            only_bunny,
            "tried again"
        );
        let bytes =
            std::fs::read(Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/meshes/bunny.obj"))
                .unwrap();
        meshes.fetched(&bunny, Some(bytes));
        assert!(meshes.missing(text).is_empty());
        let scene = Scene::from_toml_with_files(text, None, meshes.files()).unwrap();
        assert!(!scene.meshes[0].geometry.0.triangles.is_empty());
    }

    #[test]
    fn a_file_the_page_does_not_serve_is_reported_at_its_line_with_what_the_page_reads() {
        let meshes = PageFiles::default();
        let text =
            "[camera]\nfrom = [0, 1, 5]\nto = [0, 0, 0]\n[[meshes]]\nfile = \"my_model.obj\"\n";
        assert!(meshes.missing(text).is_empty(), "nothing to fetch");
        let e = Scene::from_toml_with_files(text, None, meshes.files()).unwrap_err();
        assert_eq!(e.line, Some(5));
        let message = e.to_string();
        for part in [
            "my_model.obj: the page cannot read this file",
            "../../meshes/bunny.obj",
            "dropped on the page",
            "inline",
        ] {
            assert!(message.contains(part), "{part:?} in {message}");
        }
    }
}
