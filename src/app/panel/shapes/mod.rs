//! The editor of every shape kind, one file each (the kinds of
//! `scene::shapes`): where a new shape goes, where its duplicate goes, and
//! its rows in the "Selected" grid. The functions below visit every kind
//! through the registry `for_each_shape_kind!`, so a kind without an
//! editor does not compile.

mod cube;
mod implicit;
mod julia;
mod mesh;
mod placement;
mod plane;
mod sphere;
mod torus;

use egui::Ui;
use glam::DVec3;

use super::widgets::{MIN_POSITIVE, VALUE_LIMIT, number, vec3_row};
use crate::scene::{self, AxisScale, Instance, Scene, Shape, ShapeId, ShapeKind};
use placement::EditPlacement;

/// Where new shapes go and how big they are: from the view, so that a new
/// shape appears in sight and at the size of the scene. (Not a shape's
/// `scene::Placement`, which says where one shape is.)
pub(super) struct InView {
    /// The camera target.
    pub target: DVec3,
    /// The view's right and up directions, unit length.
    pub right: DVec3,
    pub up: DVec3,
    /// The scene scale (`Scene::view_scale`).
    pub scale: f64,
}

/// The panel's view of one shape kind. Its placement has rows of its own
/// ([`EditPlacement`]), shown after the kind's.
pub(super) trait EditShape: Shape<Placement: EditPlacement> {
    /// A new shape near the target ("Add <kind>").
    fn new_near(at: &InView) -> Instance<Self>;

    /// How far "Duplicate" moves the copy of `shape` so that both stay
    /// visible.
    fn beside(shape: &Instance<Self>, at: &InView) -> DVec3;

    /// The rows of its own keys in the editor grid (a `Grid` of two
    /// columns). Returns true while a value is being dragged or typed that
    /// [`EditShape::settle`] must leave alone until the edit is done.
    fn edit(&mut self, ui: &mut Ui, scale: f64) -> bool;

    /// Makes values canonical again once no edit holds them (a plane's
    /// normal becomes unit length, as the renderers expect).
    fn settle(&mut self) {}

    /// The rows of the kind's own keys in `[render]` ([`Choices::Settings`])
    /// in the Render section's grid; none for a kind without any.
    fn edit_settings(_ui: &mut Ui, _settings: &mut Self::Settings) {}
}

macro_rules! editors {
    ($($kind:ident: $field:ident),* $(,)?) => {
        /// Appends a new shape of `kind`; returns its id.
        pub(super) fn add(scene: &mut Scene, kind: ShapeKind, at: &InView) -> ShapeId {
            match kind {
                $(ShapeKind::$kind => {
                    scene.$field.push(<scene::$kind as EditShape>::new_near(at));
                    ShapeId::$kind(scene.$field.len() - 1)
                })*
            }
        }

        /// Appends a copy of shape `id` beside it; returns the copy's id,
        /// `None` if there is no such shape.
        pub(super) fn duplicate(scene: &mut Scene, id: ShapeId, at: &InView) -> Option<ShapeId> {
            match id {
                $(ShapeId::$kind(i) => {
                    let shape = scene.$field.get(i)?;
                    let mut copy = shape.clone();
                    copy.translate(<scene::$kind as EditShape>::beside(shape, at));
                    scene.$field.push(copy);
                    Some(ShapeId::$kind(scene.$field.len() - 1))
                })*
            }
        }

        /// The editor rows of shape `id`; true while an edit holds a value
        /// (see [`EditShape::edit`]).
        pub(super) fn edit(ui: &mut Ui, scene: &mut Scene, id: ShapeId, scale: f64) -> bool {
            match id {
                $(ShapeId::$kind(i) => scene.$field.get_mut(i).is_some_and(|s| edit_instance(ui, s, scale)),)*
            }
        }

        /// Every kind's rows in the Render section's grid
        /// ([`EditShape::edit_settings`]), in registry order.
        pub(super) fn settings_rows(ui: &mut Ui, render: &mut scene::Render) {
            $(<scene::$kind as EditShape>::edit_settings(ui, &mut render.$field);)*
        }

        /// [`EditShape::settle`] on every shape but `held`.
        pub(super) fn settle(scene: &mut Scene, held: Option<ShapeId>) {
            $(for (i, shape) in scene.$field.iter_mut().enumerate() {
                if held != Some(ShapeId::$kind(i)) {
                    shape.shape.settle();
                }
            })*
        }
    };
}
crate::scene::for_each_shape_kind!(editors);

/// The kind's rows, then its placement's; true while an edit holds a value.
fn edit_instance<K: EditShape>(ui: &mut Ui, shape: &mut Instance<K>, scale: f64) -> bool {
    let held = shape.shape.edit(ui, scale);
    shape.placement.rows(ui, scale);
    held
}

/// One length or three (a cube's size, a mesh's scale), with a toggle
/// between the two forms.
pub(super) fn size_row(ui: &mut Ui, size: &mut AxisScale, speed: f64) {
    ui.vertical(|ui| {
        let mut per_axis = matches!(size, AxisScale::PerAxis(_));
        if ui.checkbox(&mut per_axis, "per axis").changed() {
            *size = cube::toggle_per_axis(*size);
        }
        match size {
            AxisScale::Uniform(s) => {
                ui.add(number(s, speed, MIN_POSITIVE..=VALUE_LIMIT));
            }
            AxisScale::PerAxis(edges) => {
                vec3_row(ui, edges, speed, MIN_POSITIVE..=VALUE_LIMIT);
            }
        }
    });
}
