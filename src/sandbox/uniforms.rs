//! The per-frame values every sandbox shader can read (time, mouse,
//! resolution, date, ...): one 80-byte uniform block, the same bytes for the
//! WGSL struct `u` and for the GLSL blocks of both GLSL styles.

use std::fmt::Write as _;

// std's SystemTime panics in the browser; web-time's is std's natively.
use web_time::{SystemTime, UNIX_EPOCH};

/// One member of the frame uniform block, as the table of
/// [`frame_uniforms!`] declares it: the Rust field, the WGSL member and the
/// GLSL members of both GLSL styles come from this one row.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct UniformField {
    /// The Rust field's and the WGSL member's name.
    pub name: &'static str,
    /// The WGSL type.
    pub wgsl: &'static str,
    /// The GLSL type in the GLSL Sandbox and glslViewer blocks.
    pub glsl: &'static str,
    /// The member in the GLSL Sandbox and glslViewer blocks: the style's
    /// conventional name for this slot where the user declared it, else
    /// `rsb_` and the slot.
    pub slot: &'static str,
    /// The member of Shadertoy's block (GLSL type, name), or `None` where
    /// the field is the tail of the member before it (`iResolution.z`).
    pub shadertoy: Option<(&'static str, &'static str)>,
    /// What the value is, for the comment of the WGSL declaration.
    pub doc: &'static str,
    /// Byte offset of the Rust field, which every declaration must match.
    pub offset: usize,
}

/// Declares the `#[repr(C)]` frame uniform struct and its table
/// ([`FrameUniforms::FIELDS`]) from one list, so the Rust struct, the WGSL
/// struct ([`wgsl_struct`]) and the GLSL blocks cannot disagree on a name,
/// a type or the order.
macro_rules! frame_uniforms {
    (
        $(#[$meta:meta])*
        pub struct $name:ident {
            $(
                #[doc = $doc:literal]
                $(#[doc = $more:literal])*
                $field:ident: $rust:ty =>
                    wgsl $wgsl:literal, glsl $glsl:literal $slot:literal, shadertoy $shadertoy:expr,
            )*
        }
    ) => {
        $(#[$meta])*
        pub struct $name {
            $(
                #[doc = $doc]
                $(#[doc = $more])*
                pub $field: $rust,
            )*
        }

        impl $name {
            /// The members in order, one row each.
            pub const FIELDS: &'static [UniformField] = &[$(UniformField {
                name: stringify!($field),
                wgsl: $wgsl,
                glsl: $glsl,
                slot: $slot,
                shadertoy: $shadertoy,
                doc: concat!($doc $(, $more)*),
                offset: std::mem::offset_of!($name, $field),
            }),*];
        }
    };
}

frame_uniforms! {
    /// The uniform block at `@group(0) @binding(0)`. Field order and padding
    /// follow WGSL's uniform layout (and GLSL's std140, which agrees here); a
    /// test checks the offsets naga computes for every style against these.
    #[repr(C)]
    #[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
    pub struct FrameUniforms {
        /// Render size in pixels (Shadertoy's `iResolution.xy`).
        resolution: [f32; 2] =>
            wgsl "vec2<f32>", glsl "vec2" "resolution", shadertoy Some(("vec3", "iResolution")),
        /// Pixel aspect ratio, 1 (Shadertoy's `iResolution.z`).
        pixel_aspect: f32 =>
            wgsl "f32", glsl "float" "pixel_aspect", shadertoy None,
        /// Seconds since the clock started (or was restarted).
        time: f32 =>
            wgsl "f32", glsl "float" "time", shadertoy Some(("float", "iTime")),
        /// Shadertoy's `iMouse`, in render pixels with y up: xy = position while
        /// a button is held (kept after release), zw = where it was pressed;
        /// z > 0 while the button is down, w > 0 only in the frame of the click.
        mouse: [f32; 4] =>
            wgsl "vec4<f32>", glsl "vec4" "mouse_px", shadertoy Some(("vec4", "iMouse")),
        /// Year, month (0 = January, as in Shadertoy), day of the month, seconds
        /// since midnight; UTC.
        date: [f32; 4] =>
            wgsl "vec4<f32>", glsl "vec4" "date", shadertoy Some(("vec4", "iDate")),
        /// Seconds since the previous frame.
        time_delta: f32 =>
            wgsl "f32", glsl "float" "time_delta", shadertoy Some(("float", "iTimeDelta")),
        /// Frames drawn since the clock started, from 0.
        frame: u32 =>
            wgsl "u32", glsl "int" "frame", shadertoy Some(("int", "iFrame")),
        /// Frames per second, averaged over the last frames.
        frame_rate: f32 =>
            wgsl "f32", glsl "float" "frame_rate", shadertoy Some(("float", "iFrameRate")),
        /// GLSL Sandbox's surface (`surfacePosition`, `surfaceSize`): the height
        /// of the part of the plane the image shows, 1 until the wheel zooms.
        surface_height: f32 =>
            wgsl "f32", glsl "float" "surface_height",
            shadertoy Some(("float", "rsb_surface_height")),
        /// The pointer position in [0, 1]², y up, following the pointer without
        /// a click (GLSL Sandbox's `mouse`).
        mouse_uv: [f32; 2] =>
            wgsl "vec2<f32>", glsl "vec2" "mouse", shadertoy Some(("vec2", "rsb_mouse_uv")),
        /// The point of the plane at the image's centre, (0, 0) until a right
        /// drag pans.
        surface_center: [f32; 2] =>
            wgsl "vec2<f32>", glsl "vec2" "surface_center",
            shadertoy Some(("vec2", "rsb_surface_center")),
    }
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

/// The WGSL declaration of [`FrameUniforms`] (part of the WGSL prelude),
/// from [`FrameUniforms::FIELDS`].
pub fn wgsl_struct() -> String {
    let mut text = String::from("struct Uniforms {\n");
    for f in FrameUniforms::FIELDS {
        let _ = writeln!(text, "    {}: {}, // {}", f.name, f.wgsl, f.doc.trim());
    }
    text.push_str("}\n");
    text
}

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
    fn the_wgsl_struct_has_the_offsets_of_the_rust_struct() {
        let text = format!(
            "{}@group(0) @binding(0) var<uniform> u: Uniforms;\n",
            wgsl_struct()
        );
        let module = naga::front::wgsl::parse_str(&text).unwrap_or_else(|e| panic!("{e}"));
        let ty = module
            .types
            .iter()
            .find(|(_, t)| t.name.as_deref() == Some("Uniforms"))
            .expect("the struct");
        let naga::TypeInner::Struct { members, span } = &ty.1.inner else {
            panic!("a struct");
        };
        assert_eq!(u64::from(*span), FRAME_UNIFORMS_SIZE);
        let found: Vec<(&str, usize)> = members
            .iter()
            .map(|m| (m.name.as_deref().unwrap(), m.offset as usize))
            .collect();
        let expected: Vec<(&str, usize)> = FrameUniforms::FIELDS
            .iter()
            .map(|f| (f.name, f.offset))
            .collect();
        assert_eq!(found, expected);
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
