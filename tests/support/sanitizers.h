#pragma once
// Whether this build runs under a sanitizer (scripts/test-sanitizers.sh), which
// slows everything 2-15x. The few tests that bound a latency widen their slack
// by kSlowdown there; what they check stays the same.
#if defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
#define IGI_TEST_SANITIZED 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define IGI_TEST_SANITIZED 1
#endif

namespace igi::test {

#ifdef IGI_TEST_SANITIZED
inline constexpr double kSlowdown = 5.0;
#else
inline constexpr double kSlowdown = 1.0;
#endif

}  // namespace igi::test
