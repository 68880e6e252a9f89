#pragma once
// Resampling candidates by weight without trading places: candidate c, of
// weight w_c among candidates of total W, is expected to be drawn
// e_c = n w_c / W times, and is drawn floor(e_c) times plus once more when its
// own uniform number u_c falls below frac(e_c) (randomised rounding). Each
// draw carries value v_c / e_c, so the kept set estimates sum_c v_c without
// bias, whatever the other candidates drew.
//
// Why not systematic resampling (one offset, draws at (u + m) W / n): there a
// candidate's count depends on the weights of all candidates before it, so
// when a moving camera nudges the weights, draws slide along the list and
// VPLs trade places all over the set (bidirectional IR flickered 1.35x plain
// igi in rooms-4 that way, 1.11x with rounding; README, "Bidirectional IR").
// Here a nudge changes only the candidates whose u_c lies near frac(e_c). The
// number of draws varies around n (it is exact when every e_c is whole).
#include <cmath>

namespace igi::importance {

inline int rounded_draws(double expected, double u) {
  const double whole = std::floor(expected);
  return int(whole) + (u < expected - whole ? 1 : 0);
}

// Candidate c's number in group g of G: frac(u_c + g / G). Each is uniform on
// [0, 1) when u_c is, so every group alone is an unbiased resampling; over the
// G groups a candidate's numbers are stratified, so the groups together draw
// it close to G e_c times.
inline double group_offset(double u, int g, int groups) {
  const double v = u + double(g) / double(groups);
  return v >= 1.0 ? v - 1.0 : v;
}

}  // namespace igi::importance
