//! A user's implicit surface as `shaders/shapes/implicit.wgsl` reads it,
//! and the scene's distinct functions (`scene::implicit::functions`) as
//! generated WGSL ([`functions_part`], the kind's `PackShape::generated`).

use bytemuck::Zeroable;

use super::{Frame, PackShape, f32x3, packed_struct, placement};
use crate::scene::{self, Instance, Scene};

packed_struct! {
    pub struct Implicit for scene::Implicit, "../../../shaders/shapes/implicit.wgsl", placed {
        pub bounds_min: [f32; 3],
        /// Index into the scene's [`scene::implicit::functions`].
        pub function: u32,
        pub bounds_max: [f32; 3],
        pub steps: u32,
        pub material: u32,
    }
}

/// Name of the part that holds the implicit surfaces' functions.
const FUNCTIONS: &str = "(generated) implicit functions";

/// The scene's functions of x, y, z as WGSL (`src/expr`): `implicit_<i>`
/// and its dual twin per function, and the two functions
/// `shaders/shapes/implicit.wgsl` calls, which pick one by index. A function
/// that does not parse (a scene that failed validation never gets here)
/// becomes the constant 1: no surface.
fn functions_part(functions: &[String]) -> (String, String) {
    let mut text = String::from(
        "// The scene's implicit functions, written by raysandbox (src/gpu/shapes/implicit.rs).\n",
    );
    let mut values = String::new();
    let mut gradients = String::new();
    for (i, source) in functions.iter().enumerate() {
        let f = crate::expr::Function::parse(source)
            .unwrap_or_else(|_| crate::expr::Function::parse("1").expect("a constant parses"));
        text += &f.to_wgsl(&format!("implicit_{i}"));
        values += &format!("        case {i}u: {{ return implicit_{i}(p); }}\n");
        gradients += &format!("        case {i}u: {{ return implicit_{i}_dual(p).yzw; }}\n");
    }
    text += &format!(
        "\n/// f(p) of the scene's function number `function`.\n\
         fn implicit_value(function: u32, p: vec3<f32>) -> f32 {{\n\
         \x20   switch function {{\n{values}\
         \x20       default: {{ return 1.0; }}\n\
         \x20   }}\n\
         }}\n\n\
         /// grad f(p), exact (dual numbers).\n\
         fn implicit_gradient(function: u32, p: vec3<f32>) -> vec3<f32> {{\n\
         \x20   switch function {{\n{gradients}\
         \x20       default: {{ return vec3(0.0); }}\n\
         \x20   }}\n\
         }}\n"
    );
    (FUNCTIONS.to_string(), text)
}

impl PackShape for scene::Implicit {
    const OCCLUDES: bool = true;

    fn generated(functions: &Vec<String>) -> Option<(String, String)> {
        Some(functions_part(functions))
    }

    fn pack(
        scene: &Scene,
        frame: &Frame,
        i: &Instance<scene::Implicit>,
        material: u32,
    ) -> Implicit {
        let (center, scale, rotation) = placement::pack(frame, &i.placement);
        let function = scene::implicit::functions(scene)
            .iter()
            .position(|f| *f == i.f)
            .expect("every implicit's function is in the set") as u32;
        Implicit {
            center,
            scale,
            rotation,
            bounds_min: f32x3(i.bounds[0]),
            function,
            bounds_max: f32x3(i.bounds[1]),
            steps: i.steps,
            material,
            ..Zeroable::zeroed()
        }
    }
}
