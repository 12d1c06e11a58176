//! The help window (F1): the keys and notes of the program it is shown in,
//! the window program's ([`WINDOW`], README.md, "The viewer") or the web
//! page's (its own, docs/web.md, "What the page does"), and the UI scale.

use super::layout;

/// What the help window lists.
pub struct Help {
    /// Keys or mouse input, and what they do, in groups.
    pub keys: &'static [&'static [(&'static str, &'static str)]],
    /// Sentences under the keys.
    pub notes: &'static [&'static str],
}

/// The mouse over the picture, the same in both programs.
pub const MOUSE: &[(&str, &str)] = &[
    ("Left drag", "orbit around the target"),
    ("Right / middle drag", "pan"),
    ("Wheel", "zoom (dolly towards the target)"),
    ("Click / double-click", "select an object / orbit around it"),
    (
        "Shift+click / T",
        "that pixel's ray tree (the one under the mouse for T): panel and 3D rays; \
         adds the pixel to those whose camera rays C shows (up to 8)",
    ),
];

/// The window program's help.
pub const WINDOW: Help = Help {
    keys: &[
        MOUSE,
        &[
            ("H", "show or hide the panel and status line"),
            ("R / P", "reset camera / screenshot"),
            (
                "V",
                "next view: shaded, normals, geometric, depth, id, barycentric, nodes, tests, \
                 steps, bounces, shadow rays, error...",
            ),
            (
                "C",
                "the camera model: an observer's view of the scene's camera and the \
                 selected pixels' rays",
            ),
            ("Ctrl+S", "save the scene"),
            (
                "Ctrl+plus / minus / 0",
                "UI scale: larger / smaller / as it was",
            ),
            (
                "F11 / Esc",
                "fullscreen / clear the ray tree and pixels, then leave fullscreen",
            ),
            ("F1 / Ctrl+Q", "this help / quit"),
        ],
    ],
    notes: &[
        "Edit the WGSL files in shaders/ (or --shaders DIR) in any editor: they reload on save.",
        "Edit the scene file in any editor: it reloads on save.",
        "Annotated constants in the shader files get controls under \"Shader parameters\" \
         (docs/sandbox.md).",
    ],
};

/// The smallest and largest UI scale.
pub const SCALES: std::ops::RangeInclusive<f32> = 0.5..=3.0;

/// The help window, while `open`; its slider sets egui's zoom factor (the
/// UI scale, which Ctrl+plus and minus change too).
pub fn window(ctx: &egui::Context, open: &mut bool, help: &Help) {
    let shown = egui::Window::new("Help")
        .open(open)
        .collapsible(false)
        .show(ctx, |ui| {
            egui::Grid::new("shortcuts").striped(true).show(ui, |ui| {
                for (keys, what) in help.keys.iter().copied().flatten() {
                    ui.strong(*keys);
                    ui.label(*what);
                    ui.end_row();
                }
            });
            ui.separator();
            for note in help.notes {
                ui.label(*note);
            }
            ui.separator();
            let mut zoom = ctx.zoom_factor();
            let slider = egui::Slider::new(&mut zoom, SCALES).text("UI scale");
            // Applied when let go: the window grows under the pointer.
            let response = ui.add(slider);
            if response.drag_stopped() || (response.changed() && !response.dragged()) {
                ctx.set_zoom_factor(zoom);
            }
            layout::note(ctx, "help-scale", response.rect);
            ui.is_sizing_pass()
        });
    layout::note_window(ctx, "help", shown);
}
