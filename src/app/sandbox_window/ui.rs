//! The sandbox window's egui frame: the panel (clock, render scale,
//! parameters, channels), the keys, the mouse over the image, the help.

use super::{Actions, PanelState, SHORTCUTS, SandboxApp};
use crate::app::controls::ClockAction;
use crate::app::layout::Layout;
use crate::app::{controls, layout, overlay};
use crate::gpu::Timing;
use crate::sandbox::Session;
use crate::sandbox::channels::CHANNELS;
use crate::sandbox::clock::Tick;
use crate::sandbox::mouse::Mouse;
use egui::{Key, KeyboardShortcut, Modifiers, RichText, Sense};
use std::path::PathBuf;
use std::time::{Duration, Instant};

impl SandboxApp {
    /// Runs the egui frame.
    pub(super) fn run_ui(&mut self) -> (Actions, egui::FullOutput) {
        let gfx = self.gfx.as_mut().expect("drawing needs graphics");
        let mut actions = Actions::default();
        let window_size = (gfx.config.width, gfx.config.height);
        let canvas_size = gfx.canvas.size();
        let now = Instant::now();
        let tick = self.last_tick.unwrap_or(Tick {
            time: self.clock.time(now),
            delta: 0.0,
            frame: 0,
            rate: 0.0,
        });
        let timing = match gfx.timer {
            Some(_) => Timing::GpuTimestamps,
            None => Timing::SubmitToDone,
        };
        let paused = self.clock.is_paused();
        let status = status_text(canvas_size, self.gpu_time, paused, tick.rate);
        let adapter = gfx.gpu.adapter.get_info().name;
        let style = match &self.multi {
            Some(multi) => multi.describe(),
            None => self
                .session
                .style()
                .map_or("not compiled yet", |s| s.describe())
                .to_string(),
        };
        let session = &mut self.session;
        let panel = &mut self.panel;
        let mouse = &mut self.mouse;
        let scale = self.scale;
        let warning = shown_warning(self.warning.as_deref(), &self.source_warnings);
        let channel_paths = &mut self.channels.paths;
        let file = self.options.file.file_name().map_or_else(
            || self.options.file.display().to_string(),
            |n| n.to_string_lossy().into_owned(),
        );
        let mut drawn = Layout::default();
        let output = gfx.egui.run(&gfx.window, |ui| {
            shortcuts(ui, panel, &mut actions);
            if panel.show {
                let shown = egui::Window::new(format!("raysandbox: {file}"))
                    .id(egui::Id::unique("sandbox panel"))
                    .default_pos([10.0, 10.0])
                    .default_width(280.0)
                    .resizable(true)
                    .show(ui.ctx(), |ui| {
                        ui.weak(&style);
                        ui.separator();
                        if let Some(a) = controls::clock_controls(ui, paused, &tick) {
                            actions.clock = Some(a);
                        }
                        scale_row(ui, scale, &mut actions);
                        ui.label(RichText::new(&status).monospace())
                            .on_hover_text(format!(
                                "time of the shader's pass, {}\nadapter: {adapter}",
                                timing.describe()
                            ));
                        if !session.params.is_empty() {
                            params_rows(ui, session, &mut actions);
                        }
                        ui.separator();
                        egui::CollapsingHeader::new("Channels")
                            .default_open(false)
                            .show(ui, |ui| {
                                if let Some(a) = channels_ui(ui, channel_paths) {
                                    actions.channel = Some(a);
                                }
                            });
                        if let Some(message) = &panel.message {
                            ui.separator();
                            ui.label(message);
                        }
                        ui.weak("F1: help   H: hide this panel");
                        ui.is_sizing_pass()
                    });
                layout::note_window(ui.ctx(), "panel", shown);
            }
            egui::CentralPanel::no_frame().show(ui, |ui| {
                actions.mouse_changed = view_input(ui, mouse, window_size, canvas_size);
            });
            if let Some(error) = &session.error {
                overlay::error_window(
                    ui.ctx(),
                    "Shader error: the last good shader keeps running",
                    &error.to_string(),
                    egui::Align2::CENTER_BOTTOM,
                );
            }
            if let Some(warning) = &warning {
                overlay::warning(ui.ctx(), warning, egui::Align2::CENTER_TOP);
            }
            if panel.help {
                help_window(ui.ctx(), &mut panel.help);
            }
            drawn = layout::take(ui.ctx());
        });
        if let Some(line) = self.layout.changed(drawn) {
            self.events.event(&line);
        }
        (actions, output)
    }
}

/// The panel's status line: render size, the shader's GPU time, and the
/// frame rate while the clock runs.
fn status_text(size: (u32, u32), gpu_time: Option<Duration>, paused: bool, rate: f64) -> String {
    let gpu = gpu_time.map_or("-".to_string(), |t| {
        format!("{:.1} ms GPU", t.as_secs_f64() * 1e3)
    });
    let fps = if paused {
        String::new()
    } else {
        format!("{rate:.0} fps")
    };
    format!("{} x {}   {gpu}   {fps}", size.0, size.1)
}

/// The render scale's slider.
fn scale_row(ui: &mut egui::Ui, scale: f32, actions: &mut Actions) {
    ui.horizontal(|ui| {
        let mut s = scale;
        ui.label("render scale");
        if ui
            .add(egui::Slider::new(&mut s, 0.25..=1.0).step_by(0.05))
            .on_hover_text("fraction of the window resolution the shader renders at")
            .changed()
        {
            actions.scale = Some(s);
        }
    });
}

/// The shader's parameters and the buttons that reset, save and load them.
fn params_rows(ui: &mut egui::Ui, session: &mut Session, actions: &mut Actions) {
    ui.separator();
    ui.strong("Parameters");
    egui::ScrollArea::vertical()
        .max_height(ui.ctx().content_rect().height() * 0.6)
        .show(ui, |ui| {
            actions.params_changed |= controls::params_ui(ui, &mut session.params);
        });
    ui.horizontal(|ui| {
        let sidecar = session.sidecar().display().to_string();
        if ui
            .button("Reset")
            .on_hover_text("the defaults of the source")
            .clicked()
        {
            actions.reset_params = true;
        }
        if ui
            .button("Save")
            .on_hover_text(format!("to {sidecar} (Ctrl+S)"))
            .clicked()
        {
            actions.save_params = true;
        }
        if ui
            .button("Load")
            .on_hover_text(format!("from {sidecar}"))
            .clicked()
        {
            actions.load_params = true;
        }
    });
}

/// Keys work only while no text field has the keyboard.
pub(super) fn shortcuts(ui: &mut egui::Ui, panel: &mut PanelState, actions: &mut Actions) {
    if ui.ctx().egui_wants_keyboard_input() {
        return;
    }
    ui.input_mut(|i| {
        if i.consume_shortcut(&KeyboardShortcut::new(Modifiers::COMMAND, Key::S)) {
            actions.save_params = true;
        }
        if i.consume_shortcut(&KeyboardShortcut::new(Modifiers::COMMAND, Key::Q)) {
            actions.quit = true;
        }
        let mut plain = |key| i.consume_key(Modifiers::NONE, key);
        if plain(Key::Space) {
            actions.clock = Some(ClockAction::Toggle);
        }
        if plain(Key::R) {
            actions.clock = Some(ClockAction::Restart);
        }
        if plain(Key::ArrowRight) {
            actions.clock = Some(ClockAction::Step);
        }
        if plain(Key::P) {
            actions.screenshot = true;
        }
        if plain(Key::H) {
            panel.show = !panel.show;
        }
        if plain(Key::F1) {
            panel.help = !panel.help;
        }
        if plain(Key::F11) {
            actions.toggle_fullscreen = true;
        }
        if plain(Key::Escape) {
            actions.leave_fullscreen = true;
        }
    });
}

/// The pointer over the image (not over the panel or an overlay), as
/// Shadertoy's and GLSL Sandbox's mouse uniforms. True when they changed.
pub(super) fn view_input(
    ui: &mut egui::Ui,
    mouse: &mut Mouse,
    window: (u32, u32),
    canvas: (u32, u32),
) -> bool {
    let before = *mouse;
    let response = ui.allocate_rect(ui.max_rect(), Sense::click_and_drag());
    let ppp = ui.ctx().pixels_per_point();
    let to_canvas = |p: egui::Pos2| {
        let x = p.x * ppp * canvas.0 as f32 / window.0.max(1) as f32;
        let y = (window.1 as f32 - p.y * ppp) * canvas.1 as f32 / window.1.max(1) as f32;
        [x, y]
    };
    if let Some(p) = response.hover_pos() {
        let [x, y] = to_canvas(p);
        let uv = [x / canvas.0.max(1) as f32, y / canvas.1.max(1) as f32];
        mouse.uv = uv;
    }
    let down = response.is_pointer_button_down_on();
    if let Some(p) = response.interact_pointer_pos().filter(|_| down) {
        let position = to_canvas(p);
        if !mouse.down {
            mouse.click = position;
            mouse.just_clicked = true;
        }
        mouse.position = position;
    }
    mouse.down = down;
    let aspect = canvas.0.max(1) as f32 / canvas.1.max(1) as f32;
    if response.hovered() {
        let scroll = ui.input(|i| i.smooth_scroll_delta.y);
        if scroll != 0.0 {
            mouse.surface.zoom(0.998_f32.powf(scroll), mouse.uv, aspect);
        }
    }
    if response.dragged_by(egui::PointerButton::Secondary) {
        let delta = response.drag_delta() * ppp;
        let delta_uv = [
            delta.x / window.0.max(1) as f32,
            -delta.y / window.1.max(1) as f32,
        ];
        mouse.surface.pan(delta_uv, aspect);
    }
    *mouse != before
}

/// A row per channel: the image's path, Load, and Clear (back to the
/// noise). Returns what was asked for.
pub(super) fn channels_ui(
    ui: &mut egui::Ui,
    paths: &mut [String; CHANNELS],
) -> Option<(usize, Option<PathBuf>)> {
    let mut asked = None;
    for (k, path) in paths.iter_mut().enumerate() {
        ui.horizontal(|ui| {
            ui.label(format!("iChannel{k}"));
            let edit = ui.add(
                egui::TextEdit::singleline(path)
                    .hint_text("noise (path to an image)")
                    .desired_width(150.0),
            );
            let entered = edit.lost_focus() && ui.input(|i| i.key_pressed(Key::Enter));
            if (ui.button("Load").clicked() || entered) && !path.trim().is_empty() {
                asked = Some((k, Some(PathBuf::from(path.trim()))));
            }
            if ui
                .button("Clear")
                .on_hover_text("back to the built-in noise")
                .clicked()
            {
                path.clear();
                asked = Some((k, None));
            }
        });
    }
    asked
}

pub(super) fn help_window(ctx: &egui::Context, open: &mut bool) {
    egui::Window::new("Help")
        .open(open)
        .collapsible(false)
        .show(ctx, |ui| {
            egui::Grid::new("sandbox shortcuts")
                .striped(true)
                .show(ui, |ui| {
                    for (keys, what) in SHORTCUTS {
                        ui.strong(keys);
                        ui.label(what);
                        ui.end_row();
                    }
                });
            ui.separator();
            ui.label("Edit the shader file in any editor: it reloads on every save.");
            ui.label("Annotate parameters in a comment: // @slider(0, 1), @color, @checkbox, @select(a, b), @log(1e-3, 1).");
            ui.label("docs/sandbox.md lists the uniforms and the preludes.");
        });
}

/// The warning at the top of the window: what the output check found, and
/// the warnings of the shader's source.
pub(super) fn shown_warning(output: Option<&str>, source: &[String]) -> Option<String> {
    let lines: Vec<&str> = output
        .into_iter()
        .chain(source.iter().map(String::as_str))
        .collect();
    (!lines.is_empty()).then(|| lines.join("\n"))
}
