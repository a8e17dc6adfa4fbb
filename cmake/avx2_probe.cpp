// Exits 0 when the build machine runs AVX2 and FMA instructions (see core/core/CMakeLists.txt).
int main() { return (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) ? 0 : 1; }
