// expect: pass 128 64 255
// Globals of a GLSL Sandbox shader: one initialised by a function call,
// several in one declaration (one with a value), a bool, set by main and
// by a helper and read by another; `void main( void )`.
#ifdef GL_ES
precision mediump float;
#endif
uniform float time;
uniform vec2 resolution;
vec3 axis = normalize(vec3(0.0, 3.0, 4.0));
float red, green = 0.25, blue;
bool doubled = true;
float scaled(float x) { return doubled ? x * 2.0 : x; }
void set_blue() { blue = time; }
void main( void ) {
    red = axis.y - 0.1;
    set_blue();
    gl_FragColor = vec4(red, scaled(green) * 0.5, blue, 1.0);
}
