#pragma once
// This machine's memory, and bytes as a memory message writes them: what every
// method's memory check (methods/memory_check.h, lightcuts/lightcuts_settings.h,
// photons/caustic_settings.h) shares.
#include <cstdint>
#include <string>

namespace igi {

// "1.5 GiB": bytes for a memory message.
std::string gib(double bytes);

// This machine's physical memory; 0 when unknown.
uint64_t machine_memory_bytes();

}  // namespace igi
