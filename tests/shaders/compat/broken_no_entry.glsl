// expect: error 2:31: error: neither `void main()`
float f(float x) { return x; }
