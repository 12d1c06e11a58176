//! Where the window's parts were drawn, told to scripts and tests as an
//! event line (`layout panel=0,0,330,410 status=0,410,800,40 ...`, in
//! physical pixels: x, y, width, height). A test that drives the window
//! finds what to click or drag from this, not from fixed pixels, which move
//! with the fonts, the window's size or the length of a file's path.

use std::collections::BTreeMap;

/// The parts noted in one frame, by name.
#[derive(Clone, Default, PartialEq)]
pub struct Layout(BTreeMap<String, [i32; 4]>);

impl Layout {
    /// The event line's text: `name=x,y,w,h` for each part, by name.
    pub fn describe(&self) -> String {
        let parts: Vec<String> = self
            .0
            .iter()
            .map(|(name, [x, y, w, h])| format!("{name}={x},{y},{w},{h}"))
            .collect();
        format!("layout {}", parts.join(" "))
    }
}

fn id() -> egui::Id {
    egui::Id::unique("raysandbox layout")
}

/// Notes that `name` was drawn at `rect` (in points) this frame. A part
/// noted twice keeps its last place (egui may run a frame's UI twice).
/// Spaces in the name become `_`, to keep the event line's form.
pub fn note(ctx: &egui::Context, name: &str, rect: egui::Rect) {
    let ppp = ctx.pixels_per_point();
    let min = (rect.min.to_vec2() * ppp).round();
    let size = (rect.size() * ppp).round();
    let place = [min.x, min.y, size.x, size.y].map(|v| v as i32);
    ctx.data_mut(|data| {
        data.get_temp_mut_or_default::<Layout>(id())
            .0
            .insert(name.replace(' ', "_"), place);
    });
}

/// Notes where a window was shown, given what its contents returned:
/// whether that was egui's sizing pass, in which a new window is laid out
/// invisibly at a provisional place (that place is not noted).
pub fn note_window(
    ctx: &egui::Context,
    name: &str,
    shown: Option<egui::InnerResponse<Option<bool>>>,
) {
    if let Some(shown) = shown
        && shown.inner == Some(false)
    {
        note(ctx, name, shown.response.rect);
    }
}

/// The parts noted since the last call.
pub fn take(ctx: &egui::Context) -> Layout {
    ctx.data_mut(|data| data.remove_temp::<Layout>(id()))
        .unwrap_or_default()
}

/// Tells the layout when it differs from the last one told.
#[derive(Default)]
pub struct LayoutReport {
    last: Layout,
}

impl LayoutReport {
    /// The event line for `layout`, when it changed since the last (the
    /// line is written only then, not every frame).
    pub fn changed(&mut self, layout: Layout) -> Option<String> {
        if layout == self.last {
            return None;
        }
        let line = layout.describe();
        self.last = layout;
        Some(line)
    }
}
