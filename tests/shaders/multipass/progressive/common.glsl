// Common code, joined before every pass (docs/sandbox.md, "Multipass").

// hash() and random(): the bundled path tracer's random numbers.
#include "../../../../assets/shaders/pathtracer/random.glsl"
