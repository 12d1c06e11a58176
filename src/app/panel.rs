//! The scene editor: the contents of the viewer's left panel.
//!
//! The panel edits the [`Scene`] in place and keeps no copy of it: the app
//! sees a change by comparing the scene with its own copy, and re-renders.
//! Whatever the user clicks or types, the scene stays one the rendering model accepts
//! (positive radii, `from != to`, unit plane normals once an edit is done,
//! materials that exist), so the renderers never see an invalid value.
//! Anything beyond the scene (files, the GPU, the window) is left to the app
//! as a [`PanelAction`].
//!
//! The rules behind the buttons live in [`edit`], as plain functions with
//! tests; this file only lays out widgets.

mod camera;
mod edit;
mod file;
mod lights;
mod materials;
mod ray_tree;
mod render;
mod shape_list;
mod shapes;
mod view_menu;
mod widgets;

use std::path::PathBuf;

use super::layout;
use crate::gpu::{
    ColourBar, DEFAULT_FRAME_BUDGET_MS, DEFAULT_MAX_SAMPLES, DEFAULT_MIN_WEIGHT, View,
};
use crate::scene::{NewShape, Scene, ShapeId};
use egui::{CollapsingHeader, RichText, Ui};

use camera::camera_section;
use file::file_section;
use lights::lights_section;
use materials::materials_section;
pub use ray_tree::ray_tree_section;
use render::render_section;
use shape_list::{file_error_row, selected_shape_section, shapes_section};

/// Viewer settings edited in the panel that are not part of the scene file.
#[derive(Debug, Clone, PartialEq)]
pub struct ViewSettings {
    /// Progressive refinement stops after this many samples per pixel
    /// (1..=1024).
    pub max_samples: u32,
    /// Resolution scale while the view moves (MIN_SCALE..=1.0): the camera
    /// dragged or a slider held. Fewer pixels keep it smooth on a weak GPU.
    /// With a frame budget, the scale of the first moving frame.
    pub interaction_scale: f32,
    /// Pick the moving scale from the last frame's time so that frames take
    /// about `frame_budget_ms` (gpu/interaction.rs).
    pub adaptive_scale: bool,
    /// Trace time per moving frame aimed at, in milliseconds (10..=1000).
    pub frame_budget_ms: f32,
    /// The last moving frame: its trace time and scale (shown, not edited).
    pub moving_frame: Option<MovingFrame>,
    /// While viewing, secondary rays weaker than this are skipped even if
    /// the file's `min_weight` is lower (the file keeps its value). The
    /// default leaves no visible difference: docs/performance.md.
    pub min_weight: f64,
    /// What the picture shows (docs/views.md): the View menu, `V`.
    pub shown: View,
    /// The colour bar of a scalar view, fitted to the traced image (shown,
    /// not edited).
    pub colour_bar: Option<ColourBar>,
    /// What the view still waits for, after its legend in the status line
    /// (the error view's reference, docs/views.md).
    pub progress: Option<String>,
}

/// A frame drawn while the view moved.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MovingFrame {
    /// GPU time of the trace (what the scale controls).
    pub time: std::time::Duration,
    /// The whole redraw: UI, scene upload, trace, outline, present.
    pub wall: std::time::Duration,
    pub scale: f32,
}

impl Default for ViewSettings {
    fn default() -> Self {
        Self {
            max_samples: DEFAULT_MAX_SAMPLES,
            interaction_scale: 0.5,
            adaptive_scale: true,
            frame_budget_ms: DEFAULT_FRAME_BUDGET_MS,
            moving_frame: None,
            min_weight: DEFAULT_MIN_WEIGHT,
            shown: View::Shaded,
            colour_bar: None,
            progress: None,
        }
    }
}

/// UI state that lives across frames.
#[derive(Debug, Default)]
pub struct PanelState {
    /// The shape being edited; the app sets it too (a click in the view).
    pub selection: Option<ShapeId>,
    /// The selection the editor last showed. A selection that differs was
    /// made elsewhere (in the view, or by Add and Duplicate): the editor opens
    /// and scrolls into view.
    shown_selection: Option<ShapeId>,
    /// The rename in progress, if any.
    rename: Option<Rename>,
    /// The text of the "Save as" path field.
    save_as_path: String,
    /// The text of the "Open" path field.
    open_path: String,
    /// The text of the "Add file" path field (a file a shape is made
    /// from).
    shape_path: String,
    /// Why the last file a shape reads could not be read (file and line),
    /// shown under the shapes until one reads well.
    pub file_error: Option<String>,
}

/// A material rename being typed, with the reason the last attempt failed.
#[derive(Debug)]
struct Rename {
    material: String,
    text: String,
    error: Option<String>,
    /// The field has not been shown yet: give it the keyboard focus, so the
    /// new name can be typed at once.
    focus: bool,
}

/// Something the app must do (the panel itself never touches files, GPU or
/// window).
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum PanelAction {
    /// Write the scene to its file.
    Save,
    /// Write the scene to this path, typed by the user.
    SaveAs(PathBuf),
    /// Load the scene at this path, typed by the user.
    Open(PathBuf),
    /// Switch to the bundled example scene of this name.
    OpenBundled(&'static str),
    /// Open the example shader of this file name (`assets/shaders/`) in the
    /// page's shader editor (the web page's menu only).
    OpenExampleShader(&'static str),
    /// Put the camera back where the scene file has it.
    ResetCamera,
    /// Save the current image.
    Screenshot,
    /// Ask for a file a shape is made from in the system's file dialog.
    PickShapeFile,
    /// Add the shape made from this file (a mesh's OBJ or PLY), typed by
    /// the user or dropped on the window.
    AddShapeFile(PathBuf),
}

/// Adds `shape` (read from a file) in front of the camera
/// ([`Scene::add_in_view`]) and selects it.
pub fn add_in_view(scene: &mut Scene, state: &mut PanelState, shape: NewShape) {
    state.selection = Some(scene.add_in_view(shape));
    state.file_error = None;
}

/// Draws the panel's contents into `ui` (the app has already created a left
/// side panel with a scroll area) and edits `scene`/`view`/`state` in place.
/// Returns the actions clicked this frame.
///
/// `files` names the bundled example scenes offered beside Save and Open
/// (`None`: no "File" section, where there are no files: the web page);
/// `file_label` is the current file's name (or "(built-in whitted scene)")
/// and whether it has unsaved changes, `file_path` its whole path, shown
/// on hover.
pub fn show(
    ui: &mut Ui,
    scene: &mut Scene,
    view: &mut ViewSettings,
    state: &mut PanelState,
    files: Option<&[&'static str]>,
    file_label: &str,
    file_path: &str,
) -> Vec<PanelAction> {
    state.selection = edit::checked_selection(scene, state.selection);
    // Drag speeds and new shapes' sizes follow the scene's scale, so the
    // panel feels the same in millimetres and in kilometres.
    let scale = scene.view_scale();
    let mut actions = Vec::new();

    let title = ui
        .label(RichText::new(file_label).strong())
        .on_hover_text(file_path);
    layout::note(ui.ctx(), "title", title.rect);
    if let Some(bundled) = files {
        section(ui, "File", false, |ui| {
            file_section(ui, state, bundled, &mut actions);
        });
    }
    section(ui, "Camera", true, |ui| {
        camera_section(ui, &mut scene.camera, scale, &mut actions);
    });
    section(ui, "Render", false, |ui| {
        render_section(ui, &mut scene.render, view);
    });
    section(ui, "Lights", false, |ui| lights_section(ui, scene, scale));
    section(ui, "Materials", false, |ui| {
        materials_section(ui, scene, state, scale);
    });
    section(ui, "Shapes", false, |ui| {
        shapes_section(ui, scene, state, &mut actions);
    });
    file_error_row(ui, state);
    let held = selected_shape_section(ui, scene, state, scale);
    shapes::settle(scene, held);
    actions
}

/// A top-level collapsing section.
/// A section of the panel, folded unless `open`; its header is a part of
/// the layout the window tells (`section:Shapes`).
fn section(ui: &mut Ui, title: &str, open: bool, add_contents: impl FnOnce(&mut Ui)) {
    let shown = CollapsingHeader::new(title)
        .default_open(open)
        .show(ui, add_contents);
    layout::note(
        ui.ctx(),
        &format!("section:{title}"),
        shown.header_response.rect,
    );
}

/// A label in the first column of a grid, with the explanation on hover.
fn field(ui: &mut Ui, name: &str, tooltip: &str) {
    ui.label(name).on_hover_text(tooltip);
}

#[cfg(test)]
mod tests {
    use egui::Key;
    use glam::DVec3;

    use super::materials::material_grid;
    use super::shape_list::material_combo;
    use crate::gpu::MIN_SCALE;

    use super::*;

    /// A scene with values outside the sliders' ranges (legal in a file), a
    /// checker, a box and over-bright colours: just drawing it must not
    /// change it, or the app would flag every loaded file as edited.
    fn scene() -> Scene {
        let text = r#"
            [render]
            background = [2, 0.5, 0.25]
            exposure = 0.001
            min_weight = 0.5
            [camera]
            from = [0, 1.5, 6]
            to = [0, 1, 0]
            fov = 0.5
            focus_distance = 4
            [[lights]]
            position = [5, 8, 5]
            color = [3, 1, 1]
            intensity = 50
            [materials.glass]
            transparency = 1.5
            shininess = 20000
            ior = 0.5
            [materials.floor]
            color = [0.1, 0.2, 0.3]
            checker = { color = [0.15, 0.15, 0.15], size = 1e-7 }
            [[spheres]]
            center = [0, 1, 0]
            radius = 1e-7
            material = "glass"
            [[planes]]
            point = [0, 0, 0]
            normal = [0, 0.6, 0.8]
            material = "floor"
            [[cubes]]
            center = [2e10, 0.5, 0]
            size = [1, 2, 3]
            rotation = [0, 720, 0]
        "#;
        Scene::from_toml_str(text, None).unwrap()
    }

    /// Runs `draw` for a few frames in a headless egui.
    fn frames(mut draw: impl FnMut(&mut Ui)) {
        let ctx = egui::Context::default();
        ctx.set_fonts(egui::FontDefinitions::empty());
        for _ in 0..3 {
            ctx.run_ui(egui::RawInput::default(), &mut draw)
                .drop_without_applying_deltas();
        }
    }

    #[test]
    fn drawing_every_field_changes_nothing() {
        let original = scene();
        let mut scene = original.clone();
        let mut view = ViewSettings::default();
        let mut state = PanelState::default();
        let ids: Vec<ShapeId> = edit::shape_ids(&scene).collect();
        frames(|ui| {
            let mut actions = Vec::new();
            camera_section(ui, &mut scene.camera, 6.0, &mut actions);
            render_section(ui, &mut scene.render, &mut view);
            lights_section(ui, &mut scene, 6.0);
            for (i, material) in scene.materials.values_mut().enumerate() {
                ui.push_id(i, |ui| material_grid(ui, material, 6.0));
            }
            for &id in &ids {
                ui.push_id(id, |ui| {
                    assert!(!shapes::edit(ui, &mut scene, id, 6.0));
                    material_combo(ui, &mut scene, id);
                });
            }
            file_section(ui, &mut state, &["whitted", "cornell"], &mut actions);
            assert!(actions.is_empty());
        });
        assert_eq!(scene, original);
        assert_eq!(view, ViewSettings::default());
    }

    #[test]
    fn show_draws_each_selection_and_clears_a_stale_one() {
        let original = scene();
        let mut scene = original.clone();
        let mut view = ViewSettings::default();
        let mut state = PanelState::default();
        let selections = [
            Some(ShapeId::Sphere(0)),
            Some(ShapeId::Plane(0)),
            Some(ShapeId::Cube(0)),
            None,
        ];
        for selection in selections {
            state.selection = selection;
            frames(|ui| {
                let actions = show(
                    ui,
                    &mut scene,
                    &mut view,
                    &mut state,
                    Some(&["whitted"]),
                    "x.toml",
                    "/some/folder/x.toml",
                );
                assert!(actions.is_empty());
            });
            assert_eq!(state.selection, selection);
            assert_eq!(state.shown_selection, selection);
        }
        assert_eq!(scene, original);
        // The app swapped in a scene with fewer shapes: no index past the end.
        state.selection = Some(ShapeId::Cube(3));
        frames(|ui| {
            show(
                ui,
                &mut scene,
                &mut view,
                &mut state,
                Some(&[]),
                "x.toml",
                "/some/folder/x.toml",
            );
        });
        assert_eq!(state.selection, None);
    }

    /// A small deterministic generator for the monkey test (xorshift64).
    struct Monkey(u64);

    impl Monkey {
        fn below(&mut self, n: u64) -> u64 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            self.0 % n.max(1)
        }

        /// A point inside `area`.
        fn pos(&mut self, area: egui::Rect) -> egui::Pos2 {
            let x = area.left() + self.below(area.width() as u64) as f32;
            let y = area.top() + self.below(area.height() as u64) as f32;
            egui::pos2(x, y)
        }

        /// One gesture over `area`, as the input events of consecutive frames.
        fn gesture(&mut self, area: egui::Rect) -> Vec<Vec<egui::Event>> {
            let button = |pos, pressed| egui::Event::PointerButton {
                pos,
                button: egui::PointerButton::Primary,
                pressed,
                modifiers: egui::Modifiers::NONE,
            };
            let a = self.pos(area);
            let b = a + egui::vec2(self.below(200) as f32 - 100.0, 0.0);
            match self.below(3) {
                0 => vec![
                    vec![egui::Event::PointerMoved(a), button(a, true)],
                    vec![button(a, false)],
                ],
                1 => vec![
                    vec![egui::Event::PointerMoved(a), button(a, true)],
                    vec![egui::Event::PointerMoved(a.lerp(b, 0.5))],
                    vec![egui::Event::PointerMoved(b)],
                    vec![button(b, false)],
                ],
                _ => {
                    let texts = ["0", "-1", "nan", "-inf", "1e400", "1e-320", "x", " "];
                    let text = texts[self.below(texts.len() as u64) as usize];
                    let enter = egui::Event::Key {
                        key: Key::Enter,
                        physical_key: None,
                        pressed: true,
                        repeat: false,
                        modifiers: egui::Modifiers::NONE,
                    };
                    vec![vec![egui::Event::Text(text.to_owned())], vec![enter]]
                }
            }
        }
    }

    /// Random clicks, drags and typing (including "nan" and "inf") over the
    /// panel as it is laid out: nothing panics, the selection stays in range
    /// and the scene always saves and loads back.
    #[test]
    fn random_input_keeps_the_scene_valid() {
        let ctx = egui::Context::default();
        let screen = egui::Rect::from_min_size(egui::Pos2::ZERO, egui::vec2(400.0, 4000.0));
        let mut scene = scene();
        let mut view = ViewSettings::default();
        let mut state = PanelState::default();
        let mut monkey = Monkey(0x9E37_79B9_7F4A_7C15);
        let mut content = screen;
        let mut time = 0.0;
        for _ in 0..1000 {
            for events in monkey.gesture(content) {
                time += 0.25;
                let input = egui::RawInput {
                    screen_rect: Some(screen),
                    time: Some(time),
                    events,
                    ..Default::default()
                };
                let bundled = ["whitted", "cornell"];
                ctx.run_ui(input, |ui| {
                    show(
                        ui,
                        &mut scene,
                        &mut view,
                        &mut state,
                        Some(&bundled),
                        "x.toml",
                        "/some/folder/x.toml",
                    );
                    content = ui.min_rect();
                })
                .drop_without_applying_deltas();
                if let Err(e) = Scene::from_toml_str(&scene.to_toml_string(), None) {
                    panic!("{e}\n{}", scene.to_toml_string());
                }
                let selection = edit::checked_selection(&scene, state.selection);
                assert_eq!(selection, state.selection);
                assert!((1..=1024).contains(&view.max_samples));
                assert!((MIN_SCALE..=1.0).contains(&view.interaction_scale));
                assert!((10.0..=1000.0).contains(&view.frame_budget_ms));
                assert!((0.0..=0.1).contains(&view.min_weight));
            }
        }
    }

    #[test]
    fn view_defaults_are_in_range() {
        let view = ViewSettings::default();
        assert_eq!((view.max_samples, view.interaction_scale), (64, 0.5));
        assert!(view.adaptive_scale);
        assert_eq!(view.frame_budget_ms, DEFAULT_FRAME_BUDGET_MS);
        assert_eq!(view.min_weight, DEFAULT_MIN_WEIGHT);
    }

    #[test]
    fn a_plane_normal_left_unnormalised_is_fixed_by_the_next_frame() {
        let mut scene = scene();
        scene.planes[0].normal = DVec3::new(0.0, 0.0, 2.0);
        let mut state = PanelState {
            selection: Some(ShapeId::Plane(0)),
            ..PanelState::default()
        };
        frames(|ui| {
            show(
                ui,
                &mut scene,
                &mut ViewSettings::default(),
                &mut state,
                None,
                "",
                "",
            );
        });
        assert_eq!(scene.planes[0].normal, DVec3::Z);
    }
}
