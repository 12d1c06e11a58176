//! The f64 hit test of every shape kind, one file each (the kinds of
//! `scene::shapes`): the shape in the form the test reads, its robust
//! routine and the lecture's naive one. [`Shapes`] holds a prepared scene's
//! shapes, kind by kind, from the registry `for_each_shape_kind!`.

pub mod cube;
pub mod implicit;
pub mod julia;
pub mod mesh;
pub mod placement;
pub mod plane;
pub mod sphere;
pub mod torus;

use std::fmt::Debug;

use super::ReferenceOptions;
use super::hit::Hit;
use super::ray::Ray;
use crate::scene::{self, Instance, Scene, Shape, ShapeId};

/// A scene shape kind made ready for the tracer.
pub trait Prepare: Shape {
    /// The shape as its hit test reads it (matrices computed once, ...).
    type Traced: Trace;

    fn prepare(shape: &Instance<Self>) -> Self::Traced;

    /// What the barycentric view shows at `hit` (docs/views.md): a
    /// triangle's weights, which its hit carries; zeros unless the kind
    /// says otherwise (a sphere's texture coordinates).
    fn view_coordinates(hit: &Hit) -> [f64; 3] {
        hit.barycentric.unwrap_or([0.0; 3])
    }
}

/// The hit test of one prepared shape.
pub trait Trace: Debug + Clone {
    /// The hit with `0 < t < t_max`: the robust routine
    /// (docs/implementation.md) or, with `options.robust = false`, the
    /// lecture's; a mesh's triangles by its test in `options.kinds`.
    fn hit(&self, ray: &Ray, t_max: f64, options: &ReferenceOptions) -> Option<Hit>;

    /// Whether the hit depends on `options.pixel_angle`, which a render
    /// then sets for its image height (a Julia set whose epsilon grows with
    /// the pixel footprint).
    fn uses_pixel_angle(&self) -> bool {
        false
    }
}

/// A hit test of one kind: the shape, the ray, `t_max`.
pub type HitTest<S> = fn(&S, &Ray, f64) -> Option<Hit>;

/// `robust` or, with `options.robust = false`, the lecture's `naive` test
/// (docs/implementation.md, "The naive variant"), for the kinds that have
/// both.
pub fn robust_or_naive<S>(
    options: &ReferenceOptions,
    robust: HitTest<S>,
    naive: HitTest<S>,
) -> HitTest<S> {
    if options.robust { robust } else { naive }
}

/// `Trace` for a prepared shape `$traced` whose hit is `$robust(shape, ray,
/// t_max)`: in both variants, or with the lecture's `$naive` for
/// `options.robust = false` ([`robust_or_naive`]).
macro_rules! traced_by {
    ($traced:ty: $robust:path) => {
        $crate::reference::shapes::traced_by!($traced: $robust, $robust);
    };
    ($traced:ty: $robust:path, $naive:path) => {
        impl $crate::reference::shapes::Trace for $traced {
            fn hit(
                &self,
                ray: &$crate::reference::ray::Ray,
                t_max: f64,
                options: &$crate::reference::ReferenceOptions,
            ) -> Option<$crate::reference::hit::Hit> {
                $crate::reference::shapes::robust_or_naive(options, $robust, $naive)(self, ray, t_max)
            }
        }
    };
}
pub(crate) use traced_by;

/// A prepared shape and the slot of its material in
/// `PreparedScene::materials`, kept beside it for every kind alike.
#[derive(Debug, Clone)]
pub struct Prepared<T> {
    pub traced: T,
    pub material: usize,
}

macro_rules! prepared_shapes {
    ($($kind:ident: $field:ident),* $(,)?) => {
        /// Every shape of a scene, prepared, kind by kind.
        #[derive(Debug, Clone)]
        pub struct Shapes {
            $($field: Vec<Prepared<<scene::$kind as Prepare>::Traced>>,)*
        }

        impl Shapes {
            /// Prepares every shape of a validated scene (a material name
            /// that validation would have rejected falls back to the default).
            pub fn new(scene: &Scene) -> Self {
                Shapes {
                    $($field: scene.$field.iter().map(|s| Prepared {
                        traced: scene::$kind::prepare(s),
                        material: scene.material_slot(s.material.as_deref()) as usize,
                    }).collect(),)*
                }
            }

            /// The hit of shape `id` with `0 < t < t_max`.
            pub fn hit(&self, id: ShapeId, ray: &Ray, t_max: f64, options: &ReferenceOptions) -> Option<Hit> {
                match id {
                    $(ShapeId::$kind(i) => self.$field[i].traced.hit(ray, t_max, options),)*
                }
            }

            /// Whether any shape's hit depends on `options.pixel_angle`.
            pub fn use_pixel_angle(&self) -> bool {
                false $(|| self.$field.iter().any(|p| p.traced.uses_pixel_angle()))*
            }

            /// What the barycentric view shows at `hit` of shape `id`
            /// ([`Prepare::view_coordinates`]).
            pub fn view_coordinates(id: ShapeId, hit: &Hit) -> [f64; 3] {
                match id {
                    $(ShapeId::$kind(_) => <scene::$kind as Prepare>::view_coordinates(hit),)*
                }
            }

            /// The material slot of shape `id`.
            pub fn material(&self, id: ShapeId) -> usize {
                match id {
                    $(ShapeId::$kind(i) => self.$field[i].material,)*
                }
            }
        }

        /// Prepares `shape` once, on the caller's thread, and drops it:
        /// what the kind derives from its data and shares between copies
        /// (a mesh's BVH, in its cache) is then made before the shape
        /// joins a scene, so a large model read on a thread of its own
        /// does not stall the window when it is added.
        pub fn prepare_ahead(shape: &scene::NewShape) {
            match shape {
                $(scene::NewShape::$kind(s) => {
                    let instance = Instance::new((**s).clone(), Default::default());
                    scene::$kind::prepare(&instance);
                })*
            }
        }
    };
}
crate::scene::for_each_shape_kind!(prepared_shapes);

/// What the tests of the kinds' hit tests share.
#[cfg(test)]
pub mod test_rays {
    use glam::DVec3;

    use super::Ray;

    /// The ray from `o` along `d` (normalised).
    pub fn ray(o: [f64; 3], d: [f64; 3]) -> Ray {
        Ray::new(DVec3::from(o), DVec3::from(d))
    }

    /// Equal to 1e-12.
    pub fn close(a: DVec3, b: DVec3) -> bool {
        (a - b).length() < 1e-12
    }
}
