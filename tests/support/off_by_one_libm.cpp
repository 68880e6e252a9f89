// A maths library 1 ulp off: LD_PRELOAD it into one process and its sinf,
// cosf and sincosf round up where the real ones do not (a machine with
// another glibc, which no version check sees). The master's VPL sets then
// differ from its workers' (Security.AMasterWithAnotherMathsLibrary...).
// No <cmath>: its declarations would clash with these definitions.
#include <dlfcn.h>

extern "C" float nextafterf(float from, float to);

namespace {
template <typename F>
F real(const char* name) {
  return reinterpret_cast<F>(dlsym(RTLD_NEXT, name));
}
constexpr float kUp = 1e30f;
}  // namespace

extern "C" {

float sinf(float x) {
  static auto f = real<float (*)(float)>("sinf");
  return nextafterf(f(x), kUp);
}

float cosf(float x) {
  static auto f = real<float (*)(float)>("cosf");
  return nextafterf(f(x), kUp);
}

void sincosf(float x, float* s, float* c) {
  static auto f = real<void (*)(float, float*, float*)>("sincosf");
  f(x, s, c);
  *s = nextafterf(*s, kUp);
  *c = nextafterf(*c, kUp);
}

}  // extern "C"
