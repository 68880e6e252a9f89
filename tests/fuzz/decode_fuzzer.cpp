// libFuzzer target for the two wire decoders, protocol::decode and the display
// link's display::decode (built with -DIGI_FUZZ=ON; scripts/fuzz.sh).
#include "fuzz/harness.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  igi::fuzz::fail_unless_handled("igi-fuzz-decode", igi::fuzz::check_decode({data, size}));
  return igi::fuzz::fail_unless_handled("igi-fuzz-decode", igi::fuzz::check_display_decode({data, size}));
}
