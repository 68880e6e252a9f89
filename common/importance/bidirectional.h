#pragma once
// Bidirectional instant radiosity (after Segovia, Iehl, Mitanchey and
// Péroche, EGSR 2006): VPLs where the camera needs them.
//
// Light paths alone put VPLs where light goes: in a building lit through a
// corridor almost none land in the rooms the camera sees. Per set k:
//  1. Candidates, half from each side:
//     - standard: the VPLs of the set's M light paths (as without --bidir,
//       lights chosen by power or by light importance);
//     - reverse: R camera paths (importance/camera_points.h) reach x_i, turn
//       by a cosine-distributed direction and end at y_i; a diffuse y_i
//       becomes a VPL whose light is gathered from the set's standard VPLs
//       and the exact point, spot and directional lights.
//  2. Both estimate the same light leaving y towards a receiver, so each
//     path receiver <- y <- z (z: the light path's vertex before y) is
//     weighted by the balance heuristic between the two ways y was found:
//       standard:  p_L(y | z), the density with which z's light path
//                  continues to y (BSDF sampling at z times its Russian
//                  roulette; for a punctual light M P(light) times its
//                  emission density, since the gather takes it exactly);
//       reverse:   p_R(y) = sum_i p(y | x_i), the density with which the R
//                  camera paths reach y (each cosine-distributed from x_i,
//                  with visibility): R samples of a deterministic mixture.
//     A standard VPL's flux is scaled by p_L / (p_L + p_R); a reverse VPL
//     gathers each z with weight p_R / (p_L + p_R) and carries flux
//     E(y) / p_R(y). The weights of each path sum to one, so the candidates
//     together are an unbiased estimate of the set's light (as unbiased as
//     the clamped VPLs are; Area VPLs on the emitters weigh 1: reverse VPLs
//     gather reflected light only). Reverse VPLs sit on diffuse surfaces
//     only; elsewhere p_R = 0 and the standard VPLs weigh 1.
//  3. Resampling: each candidate c's contribution to the image is estimated
//     at the set's R camera points x_i (one shadow ray each, the same rays
//     that give p_R): w_c = estimate + a floor (kResampleFloor of the mean, so
//     no candidate is impossible). K draws (--bidir K) are expected: c is
//     drawn about e_c = K w_c / W times, rounded up or down by a number of
//     its own (importance/resample.h), and a candidate drawn n times is one
//     VPL of flux n / e_c times its own: each kept VPL's power divided by its
//     expected number of draws, so the kept set is still unbiased.
//  4. Anti-aliasing groups: group g of G expects K_g of the K draws and
//     rounds with the candidate's number shifted by g / G, so each group
//     alone is an unbiased resampling of the whole set's candidates (its
//     flux divided by G, as a group of light paths holds 1 / G of the set),
//     and over the groups a candidate's draws are stratified.
// Each set uses only its own light and camera paths, so the sets stay
// independent estimates, as the interleaving and the filter assume.
// Everything is a pure function of scene, settings, camera, image size and
// frame seed: every worker builds the same sets.
//
// Cost: per set (C + R) R shadow rays for the estimates and densities and
// R (C + punctual lights) for the gathers, C being the standard candidates
// (about 3 M), in begin_frame, one task per set on threads of its own
// (importance/parallel.h).
#include "core/frame.h"
#include "core/method.h"
#include "core/vpl.h"
#include "vpl/vpl_generator.h"

namespace igi::importance {

inline constexpr float kResampleFloor = 0.1f;

// `light_paths.selection` chooses the lights of the standard candidates
// (nullptr: by power); its `vertices` must be null (this fills its own).
// `rays` counts the camera paths, estimates and gathers.
VplSets generate_bidirectional(const SceneContext& context, const RenderSettings& settings, const FrameSetup& frame,
                               const LightPathOptions& light_paths, RayCounts& rays);

// Area density with which a light path leaving VPL `z` (reached as `from`
// says) continues to the point y with normal n_y: the direction density at z
// times its Russian roulette and |cos_y| / r^2. 0 when the path cannot go on
// (its last bounce) or z is not a diffuse, glossy or area vertex.
float continuation_density(const Scene& scene, const Vpl& z, const LightVertex& from, glm::vec3 y, glm::vec3 n_y,
                           int max_depth);
// Area density with which a light path leaving punctual light `light` (a
// Vpl of core/direct_lights.h) first reaches y; directional lights leave a
// disc of the scene's radius.
float punctual_density(const Scene& scene, const Vpl& light, float scene_radius, glm::vec3 y, glm::vec3 n_y);

}  // namespace igi::importance
