// expect: pass 0 255 0
// glslViewer's textures: u_tex0 and u_tex1 with their sizes
// (u_tex0Resolution; the built-in noise is 256 pixels square), declared
// out of order, and a texture of another name taking the next free channel.
#ifdef GL_ES
precision mediump float;
#endif

uniform sampler2D u_tex1;
uniform sampler2D u_tex0;
uniform sampler2D u_extra;
uniform vec2 u_tex0Resolution;
uniform vec2 u_tex1Resolution;
uniform vec2 u_resolution;

void main() {
    vec2 st = gl_FragCoord.xy / u_resolution;
    vec4 a = texture2D(u_tex0, st) + texture2D(u_tex1, st) + texture2D(u_extra, st);
    bool ok = u_tex0Resolution == vec2(256.0) && u_tex1Resolution == vec2(256.0)
        && a.a > 0.0;
    gl_FragColor = ok ? vec4(0.0, 1.0, 0.0, 1.0) : vec4(1.0, 0.0, 0.0, 1.0);
}
