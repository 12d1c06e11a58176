// expect: pass 0 255 0
// glslViewer's and The Book of Shaders' uniforms (u_time, u_resolution,
// u_mouse in pixels, u_frame, u_delta, u_date): green where each has the
// value of a headless frame at time 1 (mouse at 0), red otherwise.
#ifdef GL_ES
precision mediump float;
#endif

uniform vec2 u_resolution;
uniform vec2 u_mouse;
uniform float u_time;
uniform float u_delta;
uniform int u_frame;
uniform vec4 u_date;

void main() {
    vec2 st = gl_FragCoord.xy / u_resolution.xy;
    bool ok = u_resolution == vec2(32.0, 18.0) && u_time == 1.0 && u_frame == 0
        && abs(u_delta - 1.0 / 60.0) < 1e-6 && u_mouse == vec2(0.0)
        && u_date.x >= 2024.0 && st.x < 1.0 && st.y < 1.0;
    gl_FragColor = ok ? vec4(0.0, 1.0, 0.0, 1.0) : vec4(1.0, 0.0, 0.0, 1.0);
}
