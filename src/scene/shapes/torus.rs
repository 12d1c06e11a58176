//! `[[tori]]`: a torus (docs/scene-format.md, "Implicit surfaces").

use glam::DVec3;
use serde::{Deserialize, Serialize};

use super::{Choices, Context, NoSettings, Placement, Shape};
use crate::scene::NamedOption;
use crate::scene::key_path::KeyPath;
use crate::scene::validate::{Check, Issue, POSITIVE, number};

/// The tube of radius `minor_radius` around the circle of radius
/// `major_radius` about the local y axis.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Torus {
    pub major_radius: f64,
    pub minor_radius: f64,
}

crate::named_option! {
    /// How the GPU solves a torus's quartic (docs/implementation.md,
    /// "Torus"): the same root in exact arithmetic, different cost in f32.
    /// The f64 reference always bisects to full precision.
    pub enum TorusMethod {
        /// The slope's zeros and the root by bisection on monotone pieces.
        Bisection = "bisection",
        /// The slope's zeros in closed form (a depressed cubic), the root by
        /// Newton steps kept inside its bracket.
        #[default]
        Newton = "newton",
        /// The quartic's roots in closed form (Descartes' factorisation by
        /// the largest root of its resolvent cubic), the first polished by
        /// one Newton step: straight-line code, no loop, but a grazing ray
        /// can gain or lose its double root to rounding.
        ClosedForm = "closed-form",
    }
}

impl Choices for Torus {
    /// How the GPU solves the quartic; the scene file does not choose it
    /// (the reference always brackets).
    type Options = TorusMethod;
    type Settings = NoSettings;

    const FLAG: Option<(&'static str, &'static str)> = Some((
        "torus",
        "How the GPU solves a torus's quartic: bisection, newton (the slope's zeros in \
         closed form, Newton steps kept inside the bracket), or closed-form (the quartic's \
         own roots in closed form, one Newton step). Default: newton",
    ));

    fn options_named(name: &str) -> Result<TorusMethod, String> {
        TorusMethod::from_name(name)
    }
}

impl Shape for Torus {
    fn validate(&mut self, path: &KeyPath, _context: &Context) -> Check {
        number(&path.key("major_radius"), self.major_radius, &POSITIVE)?;
        number(&path.key("minor_radius"), self.minor_radius, &POSITIVE)?;
        if self.minor_radius >= self.major_radius {
            return Err(Issue::new(
                &path.key("minor_radius"),
                format!(
                    "must be < major_radius ({}), got {}",
                    self.major_radius, self.minor_radius
                ),
            ));
        }
        Ok(())
    }

    type Placement = Placement;

    fn bounds(&self, placement: &Placement) -> [DVec3; 2] {
        let (big, r) = (self.major_radius + self.minor_radius, self.minor_radius);
        placement.bounds([DVec3::new(-big, -r, -big), DVec3::new(big, r, big)])
    }
}
