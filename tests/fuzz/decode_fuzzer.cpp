// libFuzzer target for protocol::decode (built with -DIGI_FUZZ=ON; scripts/fuzz.sh).
#include <cstdio>
#include <cstdlib>

#include "fuzz/harness.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string failure = igi::fuzz::check_decode({data, size});
  if (!failure.empty()) {
    std::fprintf(stderr, "igi-fuzz-decode: %s\n", failure.c_str());
    std::abort();  // libFuzzer keeps the input as a crash
  }
  return 0;
}
