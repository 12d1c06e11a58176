//! The per-frame values every sandbox shader can read (time, mouse,
//! resolution, date, ...): one 80-byte uniform block, the same bytes for the
//! WGSL struct `u` and for the GLSL blocks of both GLSL styles.

// std's SystemTime panics in the browser; web-time's is std's natively.
use web_time::{SystemTime, UNIX_EPOCH};

/// The uniform block at `@group(0) @binding(0)`. Field order and padding
/// follow WGSL's uniform layout (and GLSL's std140, which agrees here); a
/// test checks the offsets naga computes for every style against these.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct FrameUniforms {
    /// Render size in pixels (Shadertoy's `iResolution.xy`).
    pub resolution: [f32; 2],
    /// Pixel aspect ratio, 1 (Shadertoy's `iResolution.z`).
    pub pixel_aspect: f32,
    /// Seconds since the clock started (or was restarted).
    pub time: f32,
    /// Shadertoy's `iMouse`, in render pixels with y up: xy = position while
    /// a button is held (kept after release), zw = where it was pressed;
    /// z > 0 while the button is down, w > 0 only in the frame of the click.
    pub mouse: [f32; 4],
    /// Year, month (0 = January, as in Shadertoy), day of the month, seconds
    /// since midnight; UTC.
    pub date: [f32; 4],
    /// Seconds since the previous frame.
    pub time_delta: f32,
    /// Frames drawn since the clock started, from 0.
    pub frame: u32,
    /// Frames per second, averaged over the last frames.
    pub frame_rate: f32,
    /// GLSL Sandbox's surface (`surfacePosition`, `surfaceSize`): the height
    /// of the part of the plane the image shows, 1 until the wheel zooms.
    pub surface_height: f32,
    /// The pointer position in [0, 1]², y up, following the pointer without
    /// a click (GLSL Sandbox's `mouse`).
    pub mouse_uv: [f32; 2],
    /// The point of the plane at the image's centre, (0, 0) until a right
    /// drag pans.
    pub surface_center: [f32; 2],
}

/// Size of [`FrameUniforms`] in bytes.
pub const FRAME_UNIFORMS_SIZE: u64 = std::mem::size_of::<FrameUniforms>() as u64;

impl FrameUniforms {
    /// The values for one frame at `time` seconds, frame number `frame`, of
    /// a `size` image, with the mouse at rest in the lower left corner.
    pub fn at(time: f64, frame: u32, size: (u32, u32)) -> Self {
        FrameUniforms {
            resolution: [size.0 as f32, size.1 as f32],
            pixel_aspect: 1.0,
            time: time as f32,
            mouse: [0.0; 4],
            date: date_now(),
            time_delta: 1.0 / 60.0,
            frame,
            frame_rate: 60.0,
            surface_height: 1.0,
            mouse_uv: [0.0; 2],
            surface_center: [0.0; 2],
        }
    }
}

/// The WGSL declaration of [`FrameUniforms`] (part of the WGSL prelude).
pub const WGSL_STRUCT: &str = "\
struct Uniforms {
    resolution: vec2<f32>,   // render size in pixels
    pixel_aspect: f32,       // 1.0
    time: f32,               // seconds since the clock started
    mouse: vec4<f32>,        // Shadertoy's iMouse: xy drag position, zw click position (pixels, y up)
    date: vec4<f32>,         // year, month (0-based), day, seconds since midnight (UTC)
    time_delta: f32,         // seconds since the previous frame
    frame: u32,              // frames since the clock started
    frame_rate: f32,         // frames per second
    surface_height: f32,     // GLSL Sandbox's surface: height of the plane shown (1, the wheel zooms)
    mouse_uv: vec2<f32>,     // pointer position in [0, 1], y up (GLSL Sandbox's `mouse`)
    surface_center: vec2<f32>, // GLSL Sandbox's surface: the plane's point at the centre (right drag pans)
}
";

/// The current date for `date`, from the system clock (UTC).
pub fn date_now() -> [f32; 4] {
    let since_epoch = SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .unwrap_or_default()
        .as_secs_f64();
    date_from_unix(since_epoch)
}

/// Year, 0-based month, day and seconds since midnight of a Unix time (UTC).
pub fn date_from_unix(seconds: f64) -> [f32; 4] {
    let days = (seconds / 86400.0).floor();
    let (y, m, d) = civil_from_days(days as i64);
    [
        y as f32,
        (m - 1) as f32,
        d as f32,
        (seconds - days * 86400.0) as f32,
    ]
}

/// Howard Hinnant's `civil_from_days`: days since 1970-01-01 to
/// (year, month 1..=12, day 1..=31) in the proleptic Gregorian calendar.
fn civil_from_days(days: i64) -> (i64, u32, u32) {
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z.rem_euclid(146_097);
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = (doy - (153 * mp + 2) / 5 + 1) as u32;
    let m = if mp < 10 { mp + 3 } else { mp - 9 } as u32;
    let y = yoe + era * 400 + i64::from(m <= 2);
    (y, m, d)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn layout_is_80_bytes() {
        assert_eq!(FRAME_UNIFORMS_SIZE, 80);
        assert_eq!(std::mem::offset_of!(FrameUniforms, mouse), 16);
        assert_eq!(std::mem::offset_of!(FrameUniforms, frame), 52);
        assert_eq!(std::mem::offset_of!(FrameUniforms, mouse_uv), 64);
    }

    #[test]
    fn dates() {
        assert_eq!(date_from_unix(0.0), [1970.0, 0.0, 1.0, 0.0]);
        // 2024-02-29 12:00:30 UTC
        assert_eq!(
            date_from_unix(1_709_208_030.0),
            [2024.0, 1.0, 29.0, 43_230.0]
        );
        // 2000-03-01 00:00:00 UTC
        assert_eq!(date_from_unix(951_868_800.0), [2000.0, 2.0, 1.0, 0.0]);
    }
}
