#pragma once
// The accuracy suite: small, deterministic scenes, each built to show where a
// many-light method fails. All in metres, all exportable as glTF
// (igi-render --scene NAME --export-gltf F.gltf) so any renderer reads the
// same scene. Every builder returns triangles grouped by material with
// vertices in first-use order, which is how the glTF writer stores them: a
// written scene loads back with the same triangle and vertex order.
//
//   corner  closed 4 x 2.5 x 4 m room, one spot light aimed into a floor
//           corner: everything the camera sees away from the spot is
//           indirect light from VPLs crowded into that corner (clamping
//           darkens it).
//   rooms-N N x N rooms of 4 x 4 x 2.5 m joined by doorways, one ceiling
//           light each; the camera sees a few rooms, most light is occluded.
//   corridor  a 4 x 4 m room (the camera's) joined by a corridor with a bend
//           to a second room with the only light: no light can be seen from
//           the camera's room, whose light has bounced at least once in the
//           corridor (light paths seldom get there). Through the door the
//           camera also sees the bend, lit straight along the second leg.
//   glossy  the Cornell box with a GGX metal floor (alpha 0.04): VPLs show as
//           spikes; glossy-rough: alpha 0.3, where they blur.
//   large   the Cornell box without its blocks and a 3 x 3 grid of bumpy
//           spheres, about 1.05 M triangles.
//   glass   the Cornell box with a mirror tall block and, for the short one, a
//           glass sphere hung so its caustic focuses on the floor in view:
//           light that reaches a diffuse surface through mirrors and glass
//           (caustics, common/photons/), and glass seen from the camera.
//   courtyard  open ground of 16 x 16 m with two blocks and a metal ball, and
//           no light of its own but a sky (constant 1, 1, 1 unless
//           --environment names another, or an HDR map): what a glTF file
//           without lights is, lit the way such files are.
//   sunroom  a 4 x 2.5 x 4 m room on open ground, closed but for one window
//           of 1 x 0.8 m, lit by a sun through it: a few percent of the
//           plain rule's sun paths enter (light paths that find the view,
//           importance/view_guide.h).
//   tilted-light  closed 4 x 3 x 4 m room lit by a small one-sided quad
//           tilted towards a corner: the walls beside it see the light at
//           grazing angles (area-light sampling far from the normal).
//   glossy-medium  the tilted-light room with a medium-rough metal floor
//           (GGX alpha 0.25, just above --glossy-threshold, so VPLs shade
//           it): a glossy lobe beside a small, bright emitter near a corner.
#include <string>

#include "scene/scene.h"

namespace igi {

inline constexpr int kMaxRooms = 10;

Scene make_corner_scene();
Scene make_courtyard_scene();
Scene make_sunroom_scene();
Scene make_tilted_light_scene();
Scene make_glossy_medium_scene();
// 1 <= n <= kMaxRooms; throws SceneError otherwise.
Scene make_rooms_scene(int n);
inline constexpr float kCorridorLamp = 100.0f;  // the lamp's radiance (red channel), W/(m^2 sr)
Scene make_corridor_scene();
// alpha: GGX roughness parameter of the floor (roughness^2).
Scene make_glossy_cornell(float alpha = 0.04f, const std::string& name = "glossy");
// At least `triangles` triangles in the spheres (the box adds 20).
Scene make_large_scene(int triangles = 1'050'000);
// The Cornell box with a mirror tall block and a glass sphere (ior 1.5) of
// radius 9 cm in place of the short block, at 1.5 radii above the floor:
// the ball lens focuses the ceiling light onto the floor, where the camera
// sees the caustic past the sphere. About 4,000 triangles, with
// smooth shading normals on the sphere (and face normals elsewhere).
Scene make_glass_cornell();

// The room of suite scene `name` (as named on the command line) holding
// point p, for counting the VPLs that land in rooms the camera sees: the
// 4 x 4 m cells of rooms-N (i N + j); in "corridor" 0 for the camera's room,
// 1 for the corridor, 2 for the lamp's room; 0 in scenes of one room.
int suite_room(const std::string& name, glm::vec3 p);

// The room count named by "rooms" (4) or "rooms-N"; 0 when `name` is neither
// or N is outside 1..kMaxRooms.
int parse_rooms_name(const std::string& name);

// Stable-sorts triangles by material and renumbers vertices in first-use
// order, dropping unused ones: the order the glTF writer stores.
void group_by_material(Scene& scene);

}  // namespace igi
