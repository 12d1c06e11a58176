// Common code, joined before every pass (docs/sandbox.md, "Multipass").

// A 32-bit integer hash (Chris Wellons' lowbias32): every output bit
// depends on every input bit.
uint hash(uint x) {
    x ^= x >> 16u;
    x *= 0x7feb352du;
    x ^= x >> 15u;
    x *= 0x846ca68bu;
    x ^= x >> 16u;
    return x;
}

// A uniform random number in [0, 1), advancing the state.
float random(inout uint state) {
    state = hash(state);
    return float(state >> 8u) / 16777216.0;
}
