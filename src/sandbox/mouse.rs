//! The mouse as the sandbox's shaders see it (docs/sandbox.md, "The values
//! every shader gets"): Shadertoy's `iMouse`, GLSL Sandbox's `mouse` and its
//! pan-and-zoom surface. Kept apart from any window, so the native window
//! and the page share it.

use super::clock::Tick;
use super::uniforms::FrameUniforms;

/// The mouse as Shadertoy reports it, in canvas pixels with y up.
#[derive(Debug, Default, Clone, Copy, PartialEq)]
pub struct Mouse {
    /// Position while a button is held (kept after release).
    pub position: [f32; 2],
    /// Where the button went down.
    pub click: [f32; 2],
    pub down: bool,
    /// The button went down since the last drawn frame.
    pub just_clicked: bool,
    /// The pointer over the image, in [0, 1]², y up (no click needed).
    pub uv: [f32; 2],
    pub surface: Surface,
}

/// GLSL Sandbox's surface: the part of the plane the image shows, for
/// `surfacePosition` and `surfaceSize`. The wheel zooms about the pointer,
/// a right drag pans, as on glslsandbox.com.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Surface {
    pub center: [f32; 2],
    pub height: f32,
}

impl Default for Surface {
    fn default() -> Self {
        Surface {
            center: [0.0; 2],
            height: 1.0,
        }
    }
}

impl Surface {
    /// Zooms by `factor` (< 1 zooms in) keeping the plane's point under the
    /// pointer (`uv`, in [0, 1]²) where it is; `aspect` is width / height.
    pub fn zoom(&mut self, factor: f32, uv: [f32; 2], aspect: f32) {
        let offset = [(uv[0] - 0.5) * aspect, uv[1] - 0.5];
        for (c, o) in self.center.iter_mut().zip(offset) {
            *c += o * self.height * (1.0 - factor);
        }
        self.height = (self.height * factor).clamp(1e-6, 1e6);
    }

    /// Moves the plane with the pointer, which moved by `delta_uv`.
    pub fn pan(&mut self, delta_uv: [f32; 2], aspect: f32) {
        self.center[0] -= delta_uv[0] * aspect * self.height;
        self.center[1] -= delta_uv[1] * self.height;
    }
}

impl Mouse {
    /// Shadertoy's `iMouse`: z > 0 while down, w > 0 only in the click's frame.
    pub fn shadertoy(&self) -> [f32; 4] {
        let z = if self.down {
            self.click[0]
        } else {
            -self.click[0]
        };
        let w = if self.just_clicked {
            self.click[1]
        } else {
            -self.click[1]
        };
        [self.position[0], self.position[1], z, w]
    }
}

impl Mouse {
    /// The uniforms of a frame of `size` pixels drawn live at `tick`, with
    /// the mouse as it is now and the date of the system clock.
    pub fn frame_uniforms(&self, tick: &Tick, size: (u32, u32)) -> FrameUniforms {
        FrameUniforms {
            mouse: self.shadertoy(),
            time_delta: tick.delta as f32,
            frame_rate: tick.rate as f32,
            surface_height: self.surface.height,
            mouse_uv: self.uv,
            surface_center: self.surface.center,
            ..FrameUniforms::at(tick.time, tick.frame, size)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mouse_follows_the_shadertoy_convention() {
        let mut mouse = Mouse {
            position: [10.0, 20.0],
            click: [10.0, 20.0],
            down: true,
            just_clicked: true,
            uv: [0.0; 2],
            surface: Surface::default(),
        };
        assert_eq!(
            mouse.shadertoy(),
            [10.0, 20.0, 10.0, 20.0],
            "the click's frame"
        );
        mouse.just_clicked = false;
        mouse.position = [30.0, 40.0];
        assert_eq!(
            mouse.shadertoy(),
            [30.0, 40.0, 10.0, -20.0],
            "held: z > 0, w < 0"
        );
        mouse.down = false;
        assert_eq!(mouse.shadertoy(), [30.0, 40.0, -10.0, -20.0], "released");
    }

    #[test]
    fn the_surface_zooms_about_the_pointer_and_pans_with_it() {
        let mut surface = Surface::default();
        // The plane's point under the pointer at uv (0.75, 0.5), aspect 2.
        let under = |s: &Surface| s.center[0] + (0.75 - 0.5) * 2.0 * s.height;
        let before = under(&surface);
        surface.zoom(0.5, [0.75, 0.5], 2.0);
        assert_eq!(surface.height, 0.5);
        assert!((under(&surface) - before).abs() < 1e-6, "{surface:?}");
        let mut panned = Surface::default();
        panned.pan([0.25, -0.5], 2.0);
        assert_eq!(panned.center, [-0.5, 0.5], "the plane follows the pointer");
    }
}
