// expect: error error: neither `void main()`
float f(float x) { return x; }
