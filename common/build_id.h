#pragma once
// Identifies a build, so master and workers that would compute different
// floats refuse each other (the handshake compares it whole): the source
// tree as `git describe --always --dirty` saw it at the last build (not at
// configure: a pull and a rebuild give a new id), the compiler, Embree's
// version and the ISA its kernels are pinned to (IGI_EMBREE_ISA, scene/accel.cpp).
// Defined in a file generated at build time (scripts/build_id.cmake).
namespace igi {
const char* build_id();
}  // namespace igi
