// libFuzzer target for protocol::decode (built with -DIGI_FUZZ=ON; scripts/fuzz.sh).
#include "fuzz/harness.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return igi::fuzz::fail_unless_handled("igi-fuzz-decode", igi::fuzz::check_decode({data, size}));
}
