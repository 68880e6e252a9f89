#pragma once
// The run-time libraries a render's floats depend on beyond the build itself:
// the C library's maths (sinf, expf, ... are looked up at run time, so a
// machine with another glibc computes other VPL sets from the same binary)
// and Embree's version. Workers say them in their Hello; the master names
// them when its VPL sets and its workers' differ.
#include <string>

namespace igi {

// "glibc 2.36, Embree 3.13.5".
std::string runtime_libraries();

}  // namespace igi
