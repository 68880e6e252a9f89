#pragma once
// Window tests run under xvfb-run. Without it a window test skips on a
// developer's machine, but fails under CI (CI=true), which scripts/setup.sh
// provides with Xvfb: a missing install step must not pass as skipped tests.
#include <cstdlib>
#include <string>

#include <gtest/gtest.h>

namespace igi::test {

inline bool have_xvfb() { return std::system("command -v xvfb-run >/dev/null 2>&1") == 0; }
inline bool under_ci() {
  const char* ci = std::getenv("CI");
  return ci && std::string(ci) == "true";
}

}  // namespace igi::test

#define IGI_NEED_XVFB()                                                                       \
  do {                                                                                        \
    if (::igi::test::have_xvfb()) break;                                                      \
    if (::igi::test::under_ci()) FAIL() << "xvfb-run not installed (scripts/setup.sh installs xvfb)"; \
    GTEST_SKIP() << "xvfb-run not installed";                                                 \
  } while (0)
