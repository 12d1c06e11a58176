//! Views: ways of looking inside the tracer in place of the shaded picture
//! (docs/views.md). A view is a pipeline constant (`VIEW` in
//! `shaders/views.wgsl`): the shaded pipeline compiles its counters as dead
//! code. It is how the picture is looked at, not part of the scene, so it is
//! never saved with it.

use crate::scene::NamedOption;

crate::named_option! {
    /// What the picture shows. The numbers are `VIEW_*` in
    /// `shaders/views.wgsl`.
    pub enum View {
        /// The Whitted picture.
        #[default]
        Shaded = "shaded",
        /// The shading normal of the first hit as a colour.
        Normals = "normals",
        /// The geometric normal of the first hit as a colour.
        Geometric = "geometric",
        /// The distance from the eye to the first hit.
        Depth = "depth",
        /// A false colour per shape.
        Id = "id",
        /// A triangle's barycentric weights; a sphere's u, v.
        Barycentric = "barycentric",
        /// BVH nodes visited by the camera ray.
        Nodes = "nodes",
        /// Shape and triangle tests of the camera ray.
        Tests = "tests",
        /// BVH nodes visited by all the rays of the pixel.
        NodesAll = "nodes-all",
        /// Shape and triangle tests of all the rays of the pixel.
        TestsAll = "tests-all",
        /// Sphere-tracing, marching and root-finding steps of all the rays.
        Steps = "steps",
        /// The deepest level of the pixel's ray tree (0: the camera ray).
        Bounces = "bounces",
        /// Shadow rays cast by the pixel's ray tree.
        ShadowRays = "shadow-rays",
        /// How far the GPU's picture is from the f64 reference's, in 8-bit
        /// levels (`reference::ErrorImage`).
        Error = "error",
        /// The same as FLIP per pixel, once the reference is at every
        /// pixel (natively only: `nv-flip` is C++).
        ErrorFlip = "error-flip",
    }
}

impl View {
    /// The next view, after the last the first: what the cycling key does.
    pub fn next(self) -> View {
        View::ALL[(self as usize + 1) % View::ALL.len()]
    }

    /// Whether the view compares the GPU with the f64 reference.
    pub fn is_error(self) -> bool {
        matches!(self, View::Error | View::ErrorFlip)
    }

    /// The view the GPU traces: both error views trace the radiance at
    /// pixel centres, and differ only in what the CPU makes of it.
    pub fn traced(self) -> View {
        if self.is_error() { View::Error } else { self }
    }

    /// Whether the view is a number per pixel shown as a heat map with a
    /// colour bar (and so needs [`range`]).
    pub fn scalar(self) -> bool {
        !matches!(
            self,
            View::Shaded | View::Normals | View::Geometric | View::Id | View::Barycentric
        )
    }

    /// What a colour means, for the status line: for a scalar view with
    /// the colour bar, e.g. `nodes: BVH nodes visited by the camera ray,
    /// 0 (blue) … 60 (red), largest 93`.
    pub fn legend(self, bar: Option<ColourBar>) -> String {
        let what = match self {
            View::Shaded => "the Whitted picture",
            View::Normals => "shading normal, x y z as red green blue (-1 dark, +1 bright)",
            View::Geometric => "geometric normal, x y z as red green blue (-1 dark, +1 bright)",
            View::Depth => "distance from the eye to the first hit",
            View::Id => "one colour per shape; the selected one is outlined",
            View::Barycentric => {
                "triangle weights as red green blue; a sphere's u, v as red, green"
            }
            View::Nodes => "BVH nodes visited by the camera ray",
            View::Tests => "shape and triangle tests of the camera ray",
            View::NodesAll => "BVH nodes visited by all rays of the pixel",
            View::TestsAll => "shape and triangle tests of all rays of the pixel",
            View::Steps => "sphere-tracing and root-finding steps of all rays",
            View::Bounces => "deepest level of the ray tree (0: the camera ray)",
            View::ShadowRays => "shadow rays cast",
            View::Error => "|GPU - f64 reference| in 8-bit sRGB levels, largest of r g b",
            View::ErrorFlip => {
                "FLIP of the GPU's picture against the f64 reference's (0: alike, 1: most \
                 different) once the reference is at every pixel, |GPU - f64| in levels before"
            }
        };
        match bar {
            Some(bar) if self.scalar() => {
                let [lo, hi] = bar.range;
                let mut text = format!(
                    "{}: {what}, {} (blue) … {} (red)",
                    self.name(),
                    number(lo),
                    number(hi)
                );
                if bar.largest > hi {
                    text += &format!(", largest {}", number(bar.largest));
                }
                text
            }
            _ => format!("{}: {what}", self.name()),
        }
    }
}

/// A colour bar's end as people read it: counts as integers, distances
/// with four significant digits.
fn number(x: f32) -> String {
    if x == x.round() && x.abs() < 1e7 {
        format!("{x:.0}")
    } else {
        format!("{x:.4}")
    }
}

/// The colour bar of a scalar view.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ColourBar {
    /// The quantities shown blue and red (`view_range` in the globals).
    pub range: [f32; 2],
    /// The largest quantity; above `range[1]`, it shows red too.
    pub largest: f32,
}

/// Which share of the pixels the colour bar spans: the rest, above it,
/// shows red. A few outliers (a ground plane's horizon in the depth view,
/// the one pixel that grazes a mesh in the cost view) would otherwise put
/// every other pixel in the blue end.
const BAR_QUANTILE: f64 = 0.98;

/// The colour bar of a scalar view from the raw quantities read back from
/// the GPU (four floats per pixel, `OffscreenRenderer::read_sums`), over
/// the pixels where the quantity means something (a hit; any pixel for the
/// counters): from the smallest to the [`BAR_QUANTILE`] quantile. `None`
/// where no pixel has one; a range of one value is widened to one unit
/// above it, so that value shows blue.
pub fn colour_bar(quantities: &[f32]) -> Option<ColourBar> {
    let mut values: Vec<f32> = quantities
        .chunks_exact(4)
        .filter(|q| q[3] > 0.0 && q[0].is_finite())
        .map(|q| q[0])
        .collect();
    let lo = values.iter().copied().reduce(f32::min)?;
    let largest = values.iter().copied().reduce(f32::max)?;
    let at = ((values.len() - 1) as f64 * BAR_QUANTILE).round() as usize;
    let hi = *values.select_nth_unstable_by(at, f32::total_cmp).1;
    Some(ColourBar {
        range: [lo, if hi > lo { hi } else { lo + 1.0 }],
        largest,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_and_cycling_visits_every_view() {
        for v in View::ALL {
            assert_eq!(View::from_name(v.name()), Ok(v));
        }
        let mut v = View::Shaded;
        let mut seen = Vec::new();
        for _ in 0..View::ALL.len() {
            seen.push(v);
            v = v.next();
        }
        assert_eq!(v, View::Shaded);
        assert_eq!(seen, View::ALL);
    }

    #[test]
    fn the_range_skips_pixels_without_a_quantity() {
        let q = [3.0, 0.0, 0.0, 1.0, 99.0, 0.0, 0.0, 0.0, 7.5, 0.0, 0.0, 1.0];
        let bar = |range, largest| Some(ColourBar { range, largest });
        assert_eq!(colour_bar(&q), bar([3.0, 7.5], 7.5));
        assert_eq!(colour_bar(&[0.0, 0.0, 0.0, 0.0]), None);
        assert_eq!(colour_bar(&[2.0, 0.0, 0.0, 1.0]), bar([2.0, 3.0], 2.0));
        assert_eq!(
            View::Nodes.legend(bar([0.0, 212.0], 212.0)),
            "nodes: BVH nodes visited by the camera ray, 0 (blue) … 212 (red)"
        );
    }

    #[test]
    fn outliers_beyond_the_quantile_show_red_and_are_named() {
        // 99 pixels at 1..=99 and one at 1000: the bar ends at the 98 %
        // quantile, the largest is said.
        let q: Vec<f32> = (1..=99)
            .map(|i| i as f32)
            .chain([1000.0])
            .flat_map(|x| [x, 0.0, 0.0, 1.0])
            .collect();
        let b = colour_bar(&q).unwrap();
        assert_eq!(
            b,
            ColourBar {
                range: [1.0, 98.0],
                largest: 1000.0
            }
        );
        assert_eq!(
            View::Steps.legend(Some(b)),
            "steps: sphere-tracing and root-finding steps of all rays, 1 (blue) … 98 (red), largest 1000"
        );
    }
}
