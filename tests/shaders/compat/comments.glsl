// expect: pass 128 128 128
/* A block comment holding what the rewrites look for: uniform float speed;
   texture2D(iChannel0, uv), mat2(v), float f(const in float);
   void main() { gl_FragColor = vec4(1.0); }, 1e39, precision highp float;
   and the GLSL 4.50 words sample, input, filter, buffer, common. */
// uniform sampler2D iChannel3;  #version 300 es  out vec4 color;
void mainImage(out vec4 c, in vec2 p) {
    c = vec4(0.5); // texture2D(iChannel0, p) in a line comment
    /* vec3 gone = texture(iChannel0, p).rgb; */ c.a = 1.0;
}
