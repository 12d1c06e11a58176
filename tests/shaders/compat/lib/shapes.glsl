// Part of tests/shaders/compat/include_library.frag, included twice.
float inside_box(vec2 st) {
    return step(-1.0, st.x) * step(st.x, 2.0);
}
