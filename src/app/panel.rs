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

mod edit;
mod shapes;
mod view_menu;
mod widgets;

use std::path::PathBuf;

use super::layout;
use crate::gpu::{ColourBar, DEFAULT_MAX_SAMPLES, DEFAULT_MIN_WEIGHT, MIN_SCALE, View};
use crate::scene::{Camera, Light, Material, Mesh, RenderSettings, Scene, ShapeId, ShapeKind};
use egui::{
    Button, CollapsingHeader, ComboBox, Grid, Key, RichText, Slider, SliderClamping, TextEdit, Ui,
};

use widgets::{COORDINATES, MIN_POSITIVE, VALUE_LIMIT, color_row, number, slider, vec3_row};

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
}

/// The frame budget while the view moves: 100 ms, ten frames a second,
/// where a dragged slider still feels live (docs/performance.md).
pub const DEFAULT_FRAME_BUDGET_MS: f32 = 100.0;

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
    /// The text of the "Add mesh file" path field.
    mesh_path: String,
    /// Why the last mesh file could not be read (file and line), shown
    /// under the shapes until a mesh file reads well.
    pub mesh_error: Option<String>,
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
    /// Ask for a mesh file in the system's file dialog.
    PickMeshFile,
    /// Add the mesh in this file (OBJ or PLY), typed by the user.
    AddMeshFile(PathBuf),
}

/// Adds `mesh` (read from a file) in front of the camera and selects it.
pub fn add_mesh(scene: &mut Scene, state: &mut PanelState, mesh: Mesh) {
    state.selection = Some(edit::add_mesh(scene, mesh));
    state.mesh_error = None;
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
    mesh_error_row(ui, state);
    let held = selected_shape_section(ui, scene, state, scale);
    shapes::settle(scene, held);
    actions
}

/// A top-level collapsing section.
fn section(ui: &mut Ui, title: &str, open: bool, add_contents: impl FnOnce(&mut Ui)) {
    CollapsingHeader::new(title)
        .default_open(open)
        .show(ui, add_contents);
}

/// A label in the first column of a grid, with the explanation on hover.
fn field(ui: &mut Ui, name: &str, tooltip: &str) {
    ui.label(name).on_hover_text(tooltip);
}

/// A text field for a path with its button; Enter in the field also clicks.
/// Returns the trimmed path when clicked.
fn path_row(ui: &mut Ui, button: &str, hint: &str, text: &mut String) -> Option<PathBuf> {
    ui.horizontal(|ui| {
        let path = text.trim();
        let clicked = ui
            .add_enabled(!path.is_empty(), Button::new(button))
            .clicked();
        let field = ui.add(
            TextEdit::singleline(text)
                .hint_text(hint)
                .desired_width(ui.available_width()),
        );
        let entered = field.lost_focus() && ui.input(|i| i.key_pressed(Key::Enter));
        let path = text.trim();
        ((clicked || entered) && !path.is_empty()).then(|| PathBuf::from(path))
    })
    .inner
}

fn file_section(
    ui: &mut Ui,
    state: &mut PanelState,
    bundled: &[&'static str],
    actions: &mut Vec<PanelAction>,
) {
    ui.horizontal(|ui| {
        if ui
            .button("Save (Ctrl+S)")
            .on_hover_text("Write the scene to its file")
            .clicked()
        {
            actions.push(PanelAction::Save);
        }
        if ui
            .button("Screenshot (P)")
            .on_hover_text("Save the current image as a PNG")
            .clicked()
        {
            actions.push(PanelAction::Screenshot);
        }
    });
    if let Some(path) = path_row(ui, "Save as", "new/scene.toml", &mut state.save_as_path) {
        actions.push(PanelAction::SaveAs(path));
    }
    if let Some(path) = path_row(ui, "Open", "scenes/file.toml", &mut state.open_path) {
        actions.push(PanelAction::Open(path));
    }
    if !bundled.is_empty() {
        ui.horizontal_wrapped(|ui| {
            ui.label("Examples:");
            for &name in bundled {
                if ui
                    .button(name)
                    .on_hover_text("Switch to this bundled scene")
                    .clicked()
                {
                    actions.push(PanelAction::OpenBundled(name));
                }
            }
        });
    }
}

/// Camera fields. An edit that would make `from == to` or `up == 0` (which
/// leave the camera without a view direction) is ignored.
fn camera_section(ui: &mut Ui, camera: &mut Camera, scale: f64, actions: &mut Vec<PanelAction>) {
    let speed = 0.005 * scale;
    Grid::new("camera").num_columns(2).show(ui, |ui| {
        field(ui, "from", "Eye position e (x, y, z)");
        let mut from = camera.from;
        if vec3_row(ui, &mut from, speed, COORDINATES).changed
            && (from - camera.to).try_normalize().is_some()
        {
            camera.from = from;
        }
        ui.end_row();

        field(ui, "to", "The point looked at; must differ from `from`");
        let mut to = camera.to;
        if vec3_row(ui, &mut to, speed, COORDINATES).changed
            && (camera.from - to).try_normalize().is_some()
        {
            camera.to = to;
        }
        ui.end_row();

        field(
            ui,
            "up",
            "Which way is up in the image (any non-zero length; \
             replaced by an axis if parallel to the view)",
        );
        let mut up = camera.up;
        if vec3_row(ui, &mut up, 0.01, COORDINATES).changed && up.try_normalize().is_some() {
            camera.up = up;
        }
        ui.end_row();

        field(ui, "fov", "Vertical field of view");
        let fov = ui.add(
            Slider::new(&mut camera.fov, 1.0..=179.0)
                .clamping(SliderClamping::Edits)
                .suffix("°"),
        );
        layout::note(ui.ctx(), "camera-fov", fov.rect);
        ui.end_row();

        field(
            ui,
            "aperture",
            "Lens radius: 0 is a pinhole (all sharp); larger blurs what is \
             not at the focus distance (needs several samples)",
        );
        ui.add(number(&mut camera.aperture, 0.1 * speed, 0.0..=VALUE_LIMIT));
        ui.end_row();

        field(ui, "focus", "Distance from the eye to the plane in focus");
        focus_row(ui, camera, speed);
        ui.end_row();
    });
    if ui
        .button("Reset camera")
        .on_hover_text("Back to the camera of the scene file")
        .clicked()
    {
        actions.push(PanelAction::ResetCamera);
    }
}

/// "auto" is `focus_distance = None`: the distance to `to`, following the
/// camera as it moves. Unticking it starts from that same distance.
fn focus_row(ui: &mut Ui, camera: &mut Camera, speed: f64) {
    ui.horizontal(|ui| {
        let mut auto = camera.focus_distance.is_none();
        if ui.checkbox(&mut auto, "auto (|from - to|)").changed() {
            camera.focus_distance = (!auto).then(|| {
                camera
                    .focus_distance()
                    .clamp(MIN_POSITIVE, widgets::COORDINATE_LIMIT)
            });
        }
        if let Some(distance) = &mut camera.focus_distance {
            ui.add(number(
                distance,
                speed,
                MIN_POSITIVE..=widgets::COORDINATE_LIMIT,
            ));
        }
    });
}

fn render_section(ui: &mut Ui, render: &mut RenderSettings, view: &mut ViewSettings) {
    Grid::new("render").num_columns(2).show(ui, |ui| {
        view_menu::lecture_switches(ui, render);
        field(
            ui,
            "max depth",
            "Deepest secondary ray: 0 = primary rays only (no reflections, no refraction)",
        );
        ui.add(Slider::new(&mut render.max_depth, 0..=16));
        ui.end_row();

        field(
            ui,
            "min weight",
            "Secondary rays whose weight falls below this are not traced (0 = all up to max depth)",
        );
        slider(ui, &mut render.min_weight, 0.0..=1.0, 0.0..=1.0, true);
        ui.end_row();

        field(ui, "background", "Radiance of rays that hit nothing");
        color_row(ui, &mut render.background);
        ui.end_row();

        field(
            ui,
            "ambient",
            "Light that reaches everywhere: ambient * albedo * kd",
        );
        color_row(ui, &mut render.ambient);
        ui.end_row();

        field(
            ui,
            "exposure",
            "Multiplies the radiance before clamping to [0, 1]",
        );
        slider(
            ui,
            &mut render.exposure,
            0.01..=100.0,
            MIN_POSITIVE..=VALUE_LIMIT,
            true,
        );
        ui.end_row();
    });
    ui.separator();
    ui.label("Viewer (not saved in the file)");
    Grid::new("view").num_columns(2).show(ui, |ui| {
        view_menu::view_row(ui, &mut view.shown);
        field(
            ui,
            "samples",
            "Progressive refinement stops after this many samples per pixel",
        );
        ui.add(Slider::new(&mut view.max_samples, 1..=1024).logarithmic(true));
        ui.end_row();

        field(
            ui,
            "moving scale",
            "Resolution while the camera moves or a slider is dragged: lower keeps it \
             smooth. With a frame budget, where the first moving frame starts",
        );
        ui.add(Slider::new(&mut view.interaction_scale, MIN_SCALE..=1.0));
        ui.end_row();

        field(
            ui,
            "frame budget",
            "While moving, pick the scale from the last frame's time so that a frame \
             takes about this long (ms)",
        );
        ui.horizontal(|ui| {
            ui.checkbox(&mut view.adaptive_scale, "");
            ui.add_enabled(
                view.adaptive_scale,
                Slider::new(&mut view.frame_budget_ms, 10.0..=1000.0)
                    .logarithmic(true)
                    .suffix(" ms"),
            );
        });
        ui.end_row();

        field(
            ui,
            "last moving frame",
            "Trace time and resolution scale of the last frame drawn while moving",
        );
        ui.label(view.moving_frame.map_or("-".to_string(), |f| {
            format!(
                "{:.1} ms at scale {:.2}",
                f.time.as_secs_f64() * 1e3,
                f.scale
            )
        }));
        ui.end_row();

        field(
            ui,
            "min weight",
            "While viewing, skip secondary rays weaker than this (the file's min_weight is kept)",
        );
        ui.add(Slider::new(&mut view.min_weight, 0.0..=0.1).logarithmic(true));
        ui.end_row();
    });
}

fn lights_section(ui: &mut Ui, scene: &mut Scene, scale: f64) {
    let mut remove = None;
    for (i, light) in scene.lights.iter_mut().enumerate() {
        ui.push_id(("light", i), |ui| {
            ui.horizontal(|ui| {
                ui.strong(format!("Light {i}"));
                if ui.small_button("Remove").clicked() {
                    remove = Some(i);
                }
            });
            light_grid(ui, light, scale);
        });
        ui.separator();
    }
    if let Some(i) = remove.filter(|&i| i < scene.lights.len()) {
        scene.lights.remove(i);
    }
    if scene.lights.is_empty() {
        ui.weak("No lights: only the ambient term lights the scene.");
    }
    if ui
        .button("Add light")
        .on_hover_text("A white light above the target")
        .clicked()
    {
        edit::add_light(scene);
    }
}

fn light_grid(ui: &mut Ui, light: &mut Light, scale: f64) {
    Grid::new("light").num_columns(2).show(ui, |ui| {
        field(ui, "position", "A point light (x, y, z)");
        vec3_row(ui, &mut light.position, 0.005 * scale, COORDINATES);
        ui.end_row();

        field(ui, "colour", "Light colour (linear RGB)");
        color_row(ui, &mut light.color);
        ui.end_row();

        field(
            ui,
            "intensity",
            "Multiplies the colour; lights do not fall off with distance",
        );
        slider(
            ui,
            &mut light.intensity,
            0.0..=2.0,
            0.0..=VALUE_LIMIT,
            false,
        );
        ui.end_row();
    });
}

/// What a material's buttons asked for, applied after the list is drawn
/// (the list borrows the materials).
enum MaterialOp {
    StartRename(String),
    CancelRename,
    Rename(String, String),
    Remove(String),
}

fn materials_section(ui: &mut Ui, scene: &mut Scene, state: &mut PanelState, scale: f64) {
    let users: Vec<usize> = scene
        .materials
        .keys()
        .map(|name| edit::material_users(scene, name))
        .collect();
    let mut op = None;
    for ((name, material), users) in scene.materials.iter_mut().zip(users) {
        CollapsingHeader::new(name.as_str())
            .id_salt(("material", name.as_str()))
            .show(ui, |ui| {
                let rename = state.rename.as_mut().filter(|r| r.material == *name);
                if let Some(new_op) = material_buttons(ui, name, users, rename) {
                    op = Some(new_op);
                }
                material_grid(ui, material, scale);
            });
    }
    match op {
        Some(MaterialOp::StartRename(name)) => {
            state.rename = Some(Rename {
                text: name.clone(),
                material: name,
                error: None,
                focus: true,
            });
        }
        Some(MaterialOp::CancelRename) => state.rename = None,
        Some(MaterialOp::Rename(old, new)) => match edit::rename_material(scene, &old, &new) {
            Ok(()) => state.rename = None,
            Err(message) => {
                if let Some(rename) = &mut state.rename {
                    rename.error = Some(message);
                }
            }
        },
        Some(MaterialOp::Remove(name)) => {
            edit::remove_material(scene, &name);
            state.rename = state.rename.take().filter(|r| r.material != name);
        }
        None => {}
    }
    if ui
        .button("Add material")
        .on_hover_text("A new material with the default values")
        .clicked()
    {
        edit::add_material(scene);
    }
}

/// Rename and Remove, or the rename field while a rename is typed.
fn material_buttons(
    ui: &mut Ui,
    name: &str,
    users: usize,
    rename: Option<&mut Rename>,
) -> Option<MaterialOp> {
    let Some(rename) = rename else {
        return ui
            .horizontal(|ui| {
                if ui.small_button("Rename").clicked() {
                    return Some(MaterialOp::StartRename(name.to_owned()));
                }
                let remove = ui.small_button("Remove").on_hover_text(format!(
                    "{users} shape(s) use it; they will get the default material"
                ));
                remove
                    .clicked()
                    .then(|| MaterialOp::Remove(name.to_owned()))
            })
            .inner;
    };
    let op = ui
        .horizontal(|ui| {
            let field = ui.add(TextEdit::singleline(&mut rename.text).desired_width(120.0));
            if std::mem::take(&mut rename.focus) {
                field.request_focus();
            }
            let entered = field.lost_focus() && ui.input(|i| i.key_pressed(Key::Enter));
            if ui.small_button("OK").clicked() || entered {
                Some(MaterialOp::Rename(name.to_owned(), rename.text.clone()))
            } else if ui.small_button("Cancel").clicked() {
                Some(MaterialOp::CancelRename)
            } else {
                None
            }
        })
        .inner;
    if let Some(error) = &rename.error {
        ui.colored_label(ui.visuals().error_fg_color, error);
    }
    op
}

/// The fields of docs/rendering-model.md, "Materials". Weights show a 0..1 slider but take larger
/// typed values: the rendering model only asks for >= 0.
fn material_grid(ui: &mut Ui, m: &mut Material, scale: f64) {
    Grid::new("material").num_columns(2).show(ui, |ui| {
        field(ui, "colour", "Albedo; also tints light passing through (linear RGB)");
        color_row(ui, &mut m.color);
        ui.end_row();

        let weights = [
            ("diffuse", "kd: Lambert (matte) weight, also of the ambient light", &mut m.diffuse),
            ("specular", "ks: weight of the white Blinn-Phong highlight", &mut m.specular),
            ("mirror", "kr: perfect mirror weight (untinted)", &mut m.mirror),
            (
                "transparency",
                "kt: weight of the glass part; Fresnel splits it into reflected and refracted light",
                &mut m.transparency,
            ),
        ];
        for (name, tooltip, value) in weights {
            field(ui, name, tooltip);
            slider(ui, value, 0.0..=1.0, 0.0..=VALUE_LIMIT, false);
            ui.end_row();
        }

        field(
            ui,
            "shininess",
            "Blinn-Phong exponent: larger gives a smaller, sharper highlight",
        );
        slider(ui, &mut m.shininess, 1.0..=10000.0, MIN_POSITIVE..=VALUE_LIMIT, true);
        ui.end_row();

        field(
            ui,
            "ior",
            "Index of refraction of the inside: 1 air (no bending), 1.33 water, 1.5 glass, 2.42 diamond",
        );
        slider(ui, &mut m.ior, 1.0..=3.0, MIN_POSITIVE..=100.0, false);
        ui.end_row();

        checker_rows(ui, m, scale);
    });
}

fn checker_rows(ui: &mut Ui, m: &mut Material, scale: f64) {
    field(
        ui,
        "checker",
        "A 3D checkerboard: the colour above on even cells, the checker colour on odd ones",
    );
    let mut on = m.checker.is_some();
    if ui.checkbox(&mut on, "").changed() {
        m.checker = on.then(|| edit::default_checker(scale));
    }
    ui.end_row();
    if let Some(checker) = &mut m.checker {
        field(ui, "  colour", "Colour of the odd cells (linear RGB)");
        color_row(ui, &mut checker.color);
        ui.end_row();

        field(ui, "  size", "Edge length of a cell");
        ui.add(number(
            &mut checker.size,
            0.002 * scale,
            MIN_POSITIVE..=VALUE_LIMIT,
        ));
        ui.end_row();
    }
}

fn shapes_section(
    ui: &mut Ui,
    scene: &mut Scene,
    state: &mut PanelState,
    actions: &mut Vec<PanelAction>,
) {
    ui.horizontal_wrapped(|ui| {
        for &kind in ShapeKind::ALL {
            let label = format!("Add {}", kind.name().to_lowercase());
            if ui.button(label).clicked() {
                state.selection = Some(edit::add_shape(scene, kind));
            }
        }
    })
    .response
    .on_hover_text("A new shape near the target, selected for editing");
    mesh_file_rows(ui, state, actions);
    for id in edit::shape_ids(scene) {
        let selected = state.selection == Some(id);
        if ui
            .selectable_label(selected, edit::shape_label(scene, id))
            .clicked()
        {
            // Picked in this list, which is in view: no need to scroll.
            state.selection = Some(id);
            state.shown_selection = Some(id);
        }
    }
    if scene.shape_count() == 0 {
        ui.weak("No shapes yet.");
    }
}

/// "Add mesh file": the system's file dialog, or a typed path; and why the
/// last mesh file could not be read.
fn mesh_file_rows(ui: &mut Ui, state: &mut PanelState, actions: &mut Vec<PanelAction>) {
    if ui
        .button("Add mesh from file…")
        .on_hover_text("An OBJ or PLY file, placed at the target (or drop the file on the window)")
        .clicked()
    {
        actions.push(PanelAction::PickMeshFile);
    }
    if let Some(path) = path_row(ui, "Add file", "models/bunny.obj", &mut state.mesh_path) {
        actions.push(PanelAction::AddMeshFile(path));
    }
}

/// Why the last mesh file could not be read, outside the (folded) Shapes
/// section so that it is seen; the scene keeps what it showed.
fn mesh_error_row(ui: &mut Ui, state: &mut PanelState) {
    let Some(error) = &state.mesh_error else {
        return;
    };
    let mut dismiss = false;
    ui.horizontal_wrapped(|ui| {
        ui.colored_label(ui.visuals().error_fg_color, format!("Mesh file: {error}"));
        dismiss = ui.small_button("OK").clicked();
    });
    if dismiss {
        state.mesh_error = None;
    }
}

/// The editor of the selected shape. Returns the shape if an edit holds one
/// of its values (a plane's normal being dragged), so that it is made
/// canonical only once the edit is done.
fn selected_shape_section(
    ui: &mut Ui,
    scene: &mut Scene,
    state: &mut PanelState,
    scale: f64,
) -> Option<ShapeId> {
    let reveal = state.selection.is_some() && state.selection != state.shown_selection;
    state.shown_selection = state.selection;
    let title = match state.selection {
        Some(id) => format!("Selected: {}", edit::shape_label(scene, id)),
        None => "Selected shape".to_owned(),
    };
    let response = CollapsingHeader::new(title)
        .id_salt("selected shape")
        .default_open(true)
        .open(reveal.then_some(true))
        .show(ui, |ui| {
            let Some(id) = state.selection else {
                ui.weak("Click a shape in the view or in the Shapes list.");
                return None;
            };
            let held = Grid::new("shape")
                .num_columns(2)
                .show(ui, |ui| shapes::edit(ui, scene, id, scale))
                .inner;
            material_combo(ui, scene, id);
            ui.horizontal(|ui| {
                if ui
                    .button("Duplicate")
                    .on_hover_text("Copy it beside itself and select the copy")
                    .clicked()
                {
                    edit::duplicate_selected(scene, &mut state.selection);
                }
                if ui.button("Remove").clicked() {
                    edit::remove_shape(scene, id, &mut state.selection);
                }
            });
            held.then_some(id)
        });
    if reveal {
        response
            .header_response
            .scroll_to_me(Some(egui::Align::TOP));
    }
    response.body_returned.flatten()
}

/// The shape's material: the default one or any named material.
fn material_combo(ui: &mut Ui, scene: &mut Scene, id: ShapeId) {
    let names: Vec<String> = scene.materials.keys().cloned().collect();
    let Some(slot) = edit::shape_material_mut(scene, id) else {
        return;
    };
    ui.horizontal(|ui| {
        ui.label("material")
            .on_hover_text("Shapes without a material use the default one");
        ComboBox::from_id_salt("shape material")
            .selected_text(slot.as_deref().unwrap_or("(default)"))
            .show_ui(ui, |ui| {
                ui.selectable_value(slot, None, "(default)");
                for name in names {
                    let label = name.clone();
                    ui.selectable_value(slot, Some(name), label);
                }
            });
    });
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

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
