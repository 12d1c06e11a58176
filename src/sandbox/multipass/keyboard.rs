//! Shadertoy's keyboard texture: 256 x 3 texels, one column per JavaScript
//! key code (65 = A, 37 to 40 the arrows, 32 space); row 0 is 1 while the
//! key is down, row 1 only in the frame the key went down, row 2 flips at
//! every press. Shaders read it with `texelFetch(iChannel1, ivec2(KEY, 0), 0).x`.
//! The native window and the web page both feed it winit's key events.

use wgpu::util::DeviceExt;
use winit::event::{ElementState, KeyEvent};
use winit::keyboard::{KeyCode, PhysicalKey};

/// Key codes 0 to 255.
pub const KEYS: usize = 256;

/// The keys' state, written to the texture before each frame.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Keyboard {
    down: [bool; KEYS],
    pressed: [bool; KEYS],
    toggled: [bool; KEYS],
}

impl Default for Keyboard {
    fn default() -> Self {
        Keyboard {
            down: [false; KEYS],
            pressed: [false; KEYS],
            toggled: [false; KEYS],
        }
    }
}

impl Keyboard {
    /// The key with JavaScript code `code` went down (a repeat while it is
    /// held is no new press).
    pub fn press(&mut self, code: u8) {
        let k = usize::from(code);
        if !self.down[k] {
            self.pressed[k] = true;
            self.toggled[k] = !self.toggled[k];
        }
        self.down[k] = true;
    }

    pub fn release(&mut self, code: u8) {
        self.down[usize::from(code)] = false;
    }

    /// A key event of the window or the page's canvas, by the key's
    /// position (`KeyA` whatever the layout types), as Shadertoy's page reads
    /// `keyCode`; keys without a code here are ignored.
    pub fn key(&mut self, event: &KeyEvent) {
        let PhysicalKey::Code(code) = event.physical_key else {
            return;
        };
        let Some(js) = js_key_code(code) else { return };
        match event.state {
            ElementState::Pressed => self.press(js),
            ElementState::Released => self.release(js),
        }
    }

    /// After a frame was drawn: "pressed this frame" is over.
    pub fn frame_drawn(&mut self) {
        self.pressed = [false; KEYS];
    }

    /// The texture's bytes, row 0 first.
    pub fn bytes(&self) -> Vec<u8> {
        [&self.down, &self.pressed, &self.toggled]
            .iter()
            .flat_map(|row| row.iter().map(|&on| if on { 255 } else { 0 }))
            .collect()
    }

    /// A texture holding [`bytes`](Self::bytes) (one byte per texel).
    pub fn texture(&self, device: &wgpu::Device, queue: &wgpu::Queue) -> wgpu::Texture {
        device.create_texture_with_data(
            queue,
            &wgpu::TextureDescriptor {
                label: Some("sandbox keyboard"),
                size: wgpu::Extent3d {
                    width: KEYS as u32,
                    height: 3,
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format: wgpu::TextureFormat::R8Unorm,
                usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
                view_formats: &[],
            },
            wgpu::util::TextureDataOrder::LayerMajor,
            &self.bytes(),
        )
    }

    /// Writes the state into a texture made by [`texture`](Self::texture).
    pub fn write(&self, queue: &wgpu::Queue, texture: &wgpu::Texture) {
        queue.write_texture(
            texture.as_image_copy(),
            &self.bytes(),
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(KEYS as u32),
                rows_per_image: Some(3),
            },
            texture.size(),
        );
    }
}

/// The JavaScript `keyCode` of a key, as Shadertoy's keyboard texture
/// indexes it: letters 65 to 90, digits 48 to 57, the arrows 37 to 40,
/// space 32, and the common controls.
fn js_key_code(code: KeyCode) -> Option<u8> {
    use KeyCode::*;
    let letters = [
        KeyA, KeyB, KeyC, KeyD, KeyE, KeyF, KeyG, KeyH, KeyI, KeyJ, KeyK, KeyL, KeyM, KeyN, KeyO,
        KeyP, KeyQ, KeyR, KeyS, KeyT, KeyU, KeyV, KeyW, KeyX, KeyY, KeyZ,
    ];
    if let Some(k) = letters.iter().position(|&c| c == code) {
        return Some(65 + k as u8);
    }
    let digits = [
        Digit0, Digit1, Digit2, Digit3, Digit4, Digit5, Digit6, Digit7, Digit8, Digit9,
    ];
    if let Some(k) = digits.iter().position(|&c| c == code) {
        return Some(48 + k as u8);
    }
    let functions = [F1, F2, F3, F4, F5, F6, F7, F8, F9, F10, F11, F12];
    if let Some(k) = functions.iter().position(|&c| c == code) {
        return Some(112 + k as u8);
    }
    Some(match code {
        Backspace => 8,
        Tab => 9,
        Enter | NumpadEnter => 13,
        ShiftLeft | ShiftRight => 16,
        ControlLeft | ControlRight => 17,
        AltLeft | AltRight => 18,
        Escape => 27,
        Space => 32,
        PageUp => 33,
        PageDown => 34,
        End => 35,
        Home => 36,
        ArrowLeft => 37,
        ArrowUp => 38,
        ArrowRight => 39,
        ArrowDown => 40,
        Delete => 46,
        _ => return None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_are_down_pressed_and_toggled() {
        let mut k = Keyboard::default();
        k.press(65);
        let b = k.bytes();
        assert_eq!((b[65], b[KEYS + 65], b[2 * KEYS + 65]), (255, 255, 255));
        k.frame_drawn();
        k.press(65); // held: a repeat
        let b = k.bytes();
        assert_eq!((b[65], b[KEYS + 65], b[2 * KEYS + 65]), (255, 0, 255));
        k.release(65);
        k.press(65);
        k.frame_drawn();
        let b = k.bytes();
        assert_eq!((b[65], b[KEYS + 65], b[2 * KEYS + 65]), (255, 0, 0));
        assert_eq!(b.len(), 3 * KEYS);
    }

    #[test]
    fn keys_get_javascript_codes() {
        assert_eq!(js_key_code(KeyCode::KeyA), Some(65));
        assert_eq!(js_key_code(KeyCode::KeyZ), Some(90));
        assert_eq!(js_key_code(KeyCode::Digit7), Some(55));
        assert_eq!(js_key_code(KeyCode::ArrowLeft), Some(37));
        assert_eq!(js_key_code(KeyCode::F12), Some(123));
        assert_eq!(js_key_code(KeyCode::CapsLock), None);
    }
}
