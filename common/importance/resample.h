#pragma once
// Systematic resampling (stratified with one offset): n draws from entries of
// weight w_c (total W) at the positions (u + m) W / n, m = 0 .. n-1. Entry c is
// drawn n w_c / W times on average (exactly that, rounded down or up), so
// giving each draw the value v_c W / (n w_c) estimates sum_c v_c without bias
// for a uniform u, with less variance than n independent draws.
#include <cstdint>
#include <span>
#include <vector>

namespace igi::importance {

// counts[c] = how often entry c is drawn; weights must be >= 0 with a positive sum; u in [0, 1).
void systematic_counts(std::span<const double> weights, int n, double u, std::vector<int>& counts);

// The offset of group g of G: frac(u + g / G). Each is uniform on [0, 1) when u
// is, so every group alone is an unbiased resampling; together the G groups'
// positions are one systematic resampling of all their draws.
inline double group_offset(double u, int g, int groups) {
  const double v = u + double(g) / double(groups);
  return v >= 1.0 ? v - 1.0 : v;
}

}  // namespace igi::importance
