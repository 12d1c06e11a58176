//! The egui frame: side panel, status line, overlays, dialogs, shortcuts, and
//! the mouse over the image. It edits the scene and reports what the app must
//! do; it never touches the GPU, the window or files itself.

use egui::{Key, KeyboardShortcut, Modifiers, PointerButton, Sense};

use super::document::Document;
use super::help::Help;
use super::panel::{self, PanelAction, PanelState, ViewSettings};
use super::ray_tree::PixelTree;
use super::status::MessageAge;
use super::{camera_model, controls, help, layout, overlay, status};
use crate::gpu::View;
use crate::scene::{Camera, Scene};
use crate::shader_params::ParamSet;

/// UI state that is not part of the scene.
pub struct Editor {
    pub panel: PanelState,
    pub view: ViewSettings,
    pub show_panel: bool,
    /// The scene panel's width in points: where it opens (330, or what the
    /// page kept from the last visit, docs/web.md), then as the user
    /// dragged it, after each frame.
    pub panel_width: f32,
    pub show_help: bool,
    /// The last shader error (file:line:column and source line); cleared
    /// when the shaders compile again.
    pub shader_error: Option<String>,
    /// The last error reading the scene file after an external edit.
    pub scene_error: Option<String>,
    /// Why the GPU refused the scene (a buffer beyond its limits): the last
    /// scene that fitted is drawn.
    pub gpu_error: Option<String>,
    /// An external edit of the file, waiting for the user's decision because
    /// the panel holds unsaved edits.
    pub pending_reload: Option<(Scene, String)>,
    /// The quit dialog is open (unsaved changes).
    pub confirm_quit: bool,
    /// A short message for the status line ("Saved to ..."), until it is
    /// old.
    pub message: Option<String>,
    message_age: MessageAge,
    /// The pixel's ray tree shown in the panel and drawn over the picture
    /// (docs/ray-tree.md); Esc or "Clear" forgets it.
    pub ray_tree: Option<PixelTree>,
    /// The pixels whose camera rays the camera model draws: each pixel
    /// asked for a ray tree, the newest last, at most
    /// `camera_model::MAX_PIXELS`; Esc or "Clear" forgets them with the tree.
    pub pixels: Vec<(u32, u32)>,
    /// The observer's camera while `C` shows the scene's camera from
    /// outside (docs/ray-tree.md, "The camera model"); not saved.
    pub observer: Option<Camera>,
}

impl Default for Editor {
    fn default() -> Self {
        Editor {
            panel: PanelState::default(),
            view: ViewSettings::default(),
            show_panel: true,
            panel_width: 330.0,
            show_help: false,
            shader_error: None,
            scene_error: None,
            gpu_error: None,
            pending_reload: None,
            confirm_quit: false,
            message: None,
            message_age: MessageAge::default(),
            ray_tree: None,
            pixels: Vec::new(),
            observer: None,
        }
    }
}

pub use super::status::Status;

/// What the app must do after this frame.
#[derive(Debug)]
pub enum Command {
    Panel(PanelAction),
    ToggleFullscreen,
    LeaveFullscreen,
    /// Quit, asking first if there are unsaved changes.
    Quit,
    /// Quit now, unsaved changes or not.
    QuitNow,
    SaveAndQuit,
    /// Take the pending external version of the scene file.
    AcceptReload,
    /// Keep the unsaved edits over the pending external version.
    KeepEdits,
    /// A value in "Shader parameters" changed: rebuild the pipelines.
    ShaderParamsChanged,
    /// Put a link to the scene on the clipboard (the page's "Copy link").
    CopyLink,
}

/// What the program around the panel offers: files (the window program),
/// or a menu and links (the web page, which has no files).
pub struct Host<'a> {
    /// The bundled scenes, offered in the panel's "File" section beside
    /// Save and Open; `None` hides that section.
    pub files: Option<&'a [&'static str]>,
    /// The menu at the top of the panel, in the order shown; empty: no menu.
    pub menu: &'a [MenuItem],
    /// A "Copy link" button at the top of the panel.
    pub copy_link: bool,
    /// What the help window (F1) says.
    pub help: &'a Help,
}

/// One entry of the panel's menu: `label` under the menu `group`.
#[derive(Debug, Clone)]
pub struct MenuItem {
    pub group: &'static str,
    pub label: &'static str,
    pub action: PanelAction,
}

impl MenuItem {
    /// The bundled scenes, under "Scenes": those that need no file, then
    /// those whose shapes read files (the web page fetches them).
    pub fn bundled_scenes() -> Vec<MenuItem> {
        use crate::scene::bundled;
        [bundled::names(), bundled::names_with_files()]
            .concat()
            .into_iter()
            .map(|name| MenuItem {
                group: "Scenes",
                label: name,
                action: PanelAction::OpenBundled(name),
            })
            .collect()
    }

    /// The example shaders of the sandbox, under "Shaders".
    pub fn example_shaders() -> Vec<MenuItem> {
        crate::sandbox::bundled::SHADERS
            .iter()
            .map(|(name, _)| MenuItem {
                group: "Shaders",
                label: name,
                action: PanelAction::OpenExampleShader(name),
            })
            .collect()
    }
}

/// Mouse input over the image (not over the panel or a window), in physical
/// pixels of the window.
#[derive(Debug, Default, Clone, Copy)]
pub struct ViewInput {
    pub orbit: (f64, f64),
    pub pan: (f64, f64),
    /// Wheel notches, positive = towards the target.
    pub zoom: f64,
    pub click: Option<(f64, f64)>,
    pub double_click: Option<(f64, f64)>,
    /// Shift+click, or `T` with the mouse over the picture: that pixel's
    /// ray tree (docs/ray-tree.md).
    pub ray_tree: Option<(f64, f64)>,
    /// A camera drag is in progress (render at the interaction scale).
    pub dragging: bool,
    /// A widget of the panel is being dragged (a slider: Julia's c, a
    /// light, ...): the scene changes every frame, so render at the
    /// interaction scale too, and refine once it is let go.
    pub widget_dragging: bool,
}

/// Builds the whole UI for one frame.
pub fn draw(
    ui: &mut egui::Ui,
    doc: &mut Document,
    editor: &mut Editor,
    shader_params: &mut ParamSet,
    status: &Status,
    host: &Host,
) -> (Vec<Command>, ViewInput) {
    let mut commands = shortcuts(ui, editor, &doc.scene.camera);
    if editor.show_panel {
        let (title, path) = (doc.short_label(), doc.label());
        let panel = egui::Panel::left("scene panel")
            .resizable(true)
            .default_size(editor.panel_width)
            .show(ui, |ui| {
                // The panel keeps its width (`panel_width`, or as the user
                // dragged it), not that of its widest row, which changes
                // with the selection.
                ui.set_min_width(ui.available_width());
                menu_bar(ui, host, &mut commands);
                egui::ScrollArea::vertical().show(ui, |ui| {
                    if let Some(tree) = &editor.ray_tree
                        && panel::ray_tree_section(ui, tree)
                    {
                        editor.ray_tree = None;
                        editor.pixels.clear();
                    }
                    let actions = panel::show(
                        ui,
                        &mut doc.scene,
                        &mut editor.view,
                        &mut editor.panel,
                        host.files,
                        &title,
                        &path,
                    );
                    commands.extend(actions.into_iter().map(Command::Panel));
                    if !shader_params.is_empty() {
                        shader_params_section(ui, shader_params, &mut commands);
                    }
                    layout::note(ui.ctx(), "panel-content", ui.min_rect());
                });
            });
        layout::note(ui.ctx(), "panel", panel.response.rect);
        editor.panel_width = panel.response.rect.width();
        // Hiding the panel (H) leaves the picture alone, for a projector.
        editor.message_age.expire(ui.ctx(), &mut editor.message);
        let message = editor.message.as_deref();
        let max_samples = editor.view.max_samples;
        // What a colour means in a view inside the tracer (docs/views.md).
        let legend = (editor.view.shown != View::Shaded).then(|| {
            let legend = editor.view.shown.legend(editor.view.colour_bar);
            match &editor.view.progress {
                Some(progress) => format!("{legend}; {progress}"),
                None => legend,
            }
        });
        let status = egui::Panel::bottom("status").show(ui, |ui| {
            status::show(ui, status, max_samples, legend.as_deref(), message)
        });
        layout::note(ui.ctx(), "status", status.response.rect);
    }
    let view = egui::CentralPanel::no_frame().show(ui, view_input);
    layout::note(ui.ctx(), "view", view.response.rect);
    let mut input = view.inner;
    input.widget_dragging = !input.dragging && ui.ctx().dragged_id().is_some();
    overlays(ui.ctx(), editor, &mut commands);
    help::window(ui.ctx(), &mut editor.show_help, host.help);
    (commands, input)
}

/// Room left under a drop-down menu's list, in points: its frame, and the
/// menu bar above it (a list that fits below the bar drops down from it).
const MENU_MARGIN: f32 = 40.0;

/// The least height of a menu's list: a few entries, even in a window too
/// short for them below the menu bar.
const MENU_MIN_HEIGHT: f32 = 60.0;

/// The menu at the top of the panel: one drop-down per group, in the
/// order of the entries, and "Copy link".
fn menu_bar(ui: &mut egui::Ui, host: &Host, commands: &mut Vec<Command>) {
    if host.menu.is_empty() && !host.copy_link {
        return;
    }
    egui::MenuBar::new().ui(ui, |ui| {
        let mut groups: Vec<&str> = host.menu.iter().map(|item| item.group).collect();
        groups.dedup();
        for group in groups {
            let menu = ui.menu_button(group, |ui| {
                // A list taller than the room below scrolls, rather than
                // covering the menu bar (a small page or window).
                let room = (ui.ctx().content_rect().bottom() - ui.cursor().top() - MENU_MARGIN)
                    .max(MENU_MIN_HEIGHT);
                egui::ScrollArea::vertical()
                    .max_height(room)
                    .show(ui, |ui| {
                        for item in host.menu.iter().filter(|item| item.group == group) {
                            let entry = ui.button(item.label);
                            let name = format!("item:{group}/{}", item.label);
                            layout::note(ui.ctx(), &name, entry.rect);
                            if entry.clicked() {
                                commands.push(Command::Panel(item.action.clone()));
                            }
                        }
                    });
            });
            layout::note(ui.ctx(), &format!("menu:{group}"), menu.response.rect);
        }
        if host.copy_link
            && ui
                .button("Copy link")
                .on_hover_text("A link that opens this scene, camera included")
                .clicked()
        {
            commands.push(Command::CopyLink);
        }
    });
    ui.separator();
}

/// The annotated constants of the shader folder, with the sandbox's
/// controls. A change rebuilds the pipelines (a new shader variant).
fn shader_params_section(ui: &mut egui::Ui, params: &mut ParamSet, commands: &mut Vec<Command>) {
    egui::CollapsingHeader::new(egui::RichText::new("Shader parameters").strong())
        .default_open(true)
        .show(ui, |ui| {
            ui.weak("annotated constants of the shader files (docs/sandbox.md)");
            let mut changed = controls::params_ui(ui, params);
            if ui
                .button("Reset")
                .on_hover_text("the values in the files")
                .clicked()
            {
                params.reset();
                changed = true;
            }
            if changed {
                commands.push(Command::ShaderParamsChanged);
            }
        });
}

/// Keys work only while no text field has the keyboard.
fn shortcuts(ui: &mut egui::Ui, editor: &mut Editor, camera: &Camera) -> Vec<Command> {
    let mut commands = Vec::new();
    if ui.ctx().egui_wants_keyboard_input() {
        return commands;
    }
    ui.input_mut(|i| {
        if i.consume_shortcut(&KeyboardShortcut::new(Modifiers::COMMAND, Key::S)) {
            commands.push(Command::Panel(PanelAction::Save));
        }
        if i.consume_shortcut(&KeyboardShortcut::new(Modifiers::COMMAND, Key::Q)) {
            commands.push(Command::Quit);
        }
        let plain = |i: &mut egui::InputState, key| i.consume_key(Modifiers::NONE, key);
        if plain(i, Key::H) {
            editor.show_panel = !editor.show_panel;
        }
        if plain(i, Key::F1) {
            editor.show_help = !editor.show_help;
        }
        if plain(i, Key::R) {
            commands.push(Command::Panel(PanelAction::ResetCamera));
        }
        if plain(i, Key::P) {
            commands.push(Command::Panel(PanelAction::Screenshot));
        }
        if plain(i, Key::V) {
            editor.view.shown = editor.view.shown.next();
        }
        if plain(i, Key::C) {
            editor.observer = match editor.observer {
                Some(_) => None,
                None => Some(camera_model::observer_for(camera)),
            };
        }
        if plain(i, Key::F11) {
            commands.push(Command::ToggleFullscreen);
        }
        // Esc forgets a ray tree and the selected pixels first, a second
        // Esc leaves fullscreen.
        if plain(i, Key::Escape) {
            let selected = editor.ray_tree.take().is_some() || !editor.pixels.is_empty();
            editor.pixels.clear();
            if !selected {
                commands.push(Command::LeaveFullscreen);
            }
        }
    });
    commands
}

/// The mouse over the image: egui gives the panel and windows priority, so a
/// drag that starts on a slider never reaches the camera.
fn view_input(ui: &mut egui::Ui) -> ViewInput {
    let response = ui.allocate_rect(ui.max_rect(), Sense::click_and_drag());
    let ppp = f64::from(ui.ctx().pixels_per_point());
    let physical = |p: egui::Pos2| (f64::from(p.x) * ppp, f64::from(p.y) * ppp);
    let mut input = ViewInput::default();
    let delta = response.drag_delta();
    let delta = (f64::from(delta.x) * ppp, f64::from(delta.y) * ppp);
    if response.dragged_by(PointerButton::Primary) {
        input.orbit = delta;
        input.dragging = true;
    } else if response.dragged_by(PointerButton::Secondary)
        || response.dragged_by(PointerButton::Middle)
    {
        input.pan = delta;
        input.dragging = true;
    }
    if response.hovered() {
        let scroll = ui.input(|i| i.smooth_scroll_delta.y);
        input.zoom = f64::from(scroll) / 50.0;
    }
    let pointer = response.interact_pointer_pos().map(physical);
    let shift = ui.input(|i| i.modifiers.shift);
    if response.double_clicked() {
        input.double_click = pointer;
    } else if response.clicked() && shift {
        input.ray_tree = pointer;
    } else if response.clicked() {
        input.click = pointer;
    }
    let over = response.hover_pos().map(physical);
    if over.is_some()
        && !ui.ctx().egui_wants_keyboard_input()
        && ui.input_mut(|i| i.consume_key(Modifiers::NONE, Key::T))
    {
        input.ray_tree = over;
    }
    input
}

/// An error in a window above the status line, until the user closes it or
/// the cause is gone (`error` set to `None`); reported in the layout as
/// `name`.
fn closable_error(ctx: &egui::Context, title: &str, name: &str, error: &mut Option<String>) {
    let Some(text) = error else { return };
    let mut open = true;
    let window = egui::Window::new(title)
        .open(&mut open)
        .anchor(egui::Align2::CENTER_BOTTOM, [0.0, -40.0])
        .show(ctx, |ui| {
            ui.label(
                egui::RichText::new(text.as_str())
                    .monospace()
                    .color(egui::Color32::LIGHT_RED),
            );
            ui.is_sizing_pass()
        });
    layout::note_window(ctx, name, window);
    if !open {
        *error = None;
    }
}

fn overlays(ctx: &egui::Context, editor: &mut Editor, commands: &mut Vec<Command>) {
    if let Some(error) = &editor.shader_error {
        overlay::error_window(
            ctx,
            "Shader error: the last good shader keeps running",
            error,
            egui::Align2::CENTER_TOP,
        );
    }
    closable_error(
        ctx,
        "Scene file error: the current scene is kept",
        "scene-error",
        &mut editor.scene_error,
    );
    closable_error(
        ctx,
        "The GPU cannot draw this scene: the last one that fitted is shown",
        "gpu-error",
        &mut editor.gpu_error,
    );
    if editor.pending_reload.is_some() {
        let question = "You have unsaved edits. Replace them with the file's new content?";
        let answers = ["Reload from disk", "Keep my edits"];
        let heading = "The scene file changed on disk";
        match ask(ctx, "reload dialog", heading, question, &answers) {
            Some(0) => commands.push(Command::AcceptReload),
            Some(_) => commands.push(Command::KeepEdits),
            None => {}
        }
    }
    if editor.confirm_quit {
        let answers = ["Save and quit", "Quit without saving", "Cancel"];
        let question = "Save the scene before quitting?";
        match ask(ctx, "quit dialog", "Unsaved changes", question, &answers) {
            Some(0) => commands.push(Command::SaveAndQuit),
            Some(1) => commands.push(Command::QuitNow),
            Some(_) => editor.confirm_quit = false,
            None => {}
        }
    }
}

/// A modal dialog that asks `question` under `heading` with a button per
/// answer, side by side: the number of the answer clicked this frame.
fn ask(
    ctx: &egui::Context,
    id: &str,
    heading: &str,
    question: &str,
    answers: &[&str],
) -> Option<usize> {
    let mut clicked = None;
    egui::Modal::new(egui::Id::unique(id)).show(ctx, |ui| {
        ui.heading(heading);
        ui.label(question);
        ui.horizontal(|ui| {
            for (i, answer) in answers.iter().enumerate() {
                if ui.button(*answer).clicked() {
                    clicked = Some(i);
                }
            }
        });
    });
    clicked
}
