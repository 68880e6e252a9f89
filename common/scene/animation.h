#pragma once
// What moves in a scene, and how to put it where it is at a given time.
//
// A scene keeps its triangles in world space (scene.h). The parts that move
// (the meshes of glTF nodes that are animated or below an animated node, and
// the scene's area lights, which the window can move) are listed here with
// their object-space vertices; pose_scene() rewrites just those vertices,
// their normals and the punctual lights, so posing costs what moves, never
// the static geometry. Posing uses the loader's own arithmetic
// (node_transform.h): a scene posed at time t equals, bit for bit, the same
// scene loaded from a file whose nodes stand where the animation puts them.
//
// Everything here is a pure function of the scene and the pose, so every
// worker poses identically from what the frame setup carries.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene/node_transform.h"
#include "scene/scene.h"
#include "scene/scene_pose.h"

namespace igi {

enum class AnimationPath : uint8_t { Translation, Rotation, Scale };
enum class Interpolation : uint8_t { Linear, Step, CubicSpline };

// One glTF animation channel with its sampler.
struct AnimationChannel {
  uint32_t node = 0;  // index into SceneAnimation::nodes
  AnimationPath path = AnimationPath::Translation;
  Interpolation interpolation = Interpolation::Linear;
  std::vector<double> times;  // strictly increasing, at least one
  // One value per key; three for CUBICSPLINE (in-tangent, value, out-tangent).
  // Translation and scale use xyz; rotation is a quaternion (x, y, z, w).
  std::vector<glm::dvec4> values;

  // The sampled value at `time`, held constant outside the key times.
  glm::dvec4 sample(double time) const;
};

// A glTF node that moves: animated itself, or below one that is.
struct PoseNode {
  std::string name;             // "nodes[3]", for messages
  int parent = -1;              // index into SceneAnimation::nodes; -1: parent_world is fixed
  glm::dmat4 parent_world{1.0};  // the static ancestors' transform (parent == -1)
  NodeTrs rest;                 // the node's own translation, rotation and scale
  std::optional<glm::dmat4> matrix;  // instead of rest, for a node given by matrix (never animated)
};

// Triangles that move together: one primitive of a moving node's mesh, or
// the light group (every emissive triangle no node moves), which only
// ScenePose::light_offset moves. A part's vertices belong to it alone.
struct DynamicPart {
  int node = -1;                        // index into SceneAnimation::nodes; -1: the light group
  std::vector<uint32_t> triangles;      // indices into Scene::triangles
  std::vector<glm::uvec3> rest_triangles;  // their vertex indices as loaded
  bool rest_flip = false;               // whether the loaded winding was mirrored
  std::vector<uint32_t> vertices;       // indices into Scene::positions (and normals)
  std::vector<glm::vec3> object_positions;  // one per vertex (world positions for the light group)
  std::vector<glm::vec3> object_normals;    // one per vertex, or empty (no normals, or flat)
  bool flat = false;                    // normals are each triangle's geometric normal
};

struct SceneAnimation {
  std::vector<PoseNode> nodes;  // parents before children
  std::vector<AnimationChannel> channels;
  std::vector<DynamicPart> parts;
  std::vector<PunctualLight> rest_lights;  // Scene::lights as loaded
  std::vector<int> light_node;             // per light: index into nodes, or -1 (static)
  int camera_node = -1;                    // the scene camera's node (index into nodes), or -1: it stays
  double duration = 0.0;                   // the last key time of any channel

  bool animated() const { return !channels.empty(); }
  // Every moving node's own translation, rotation and scale at `time`.
  std::vector<NodeTrs> locals(double time) const;
  // Every moving node's world transform at `time`.
  std::vector<glm::dmat4> world(double time) const;
  // The scene camera at `time` (`rest` is the camera as loaded, whose field
  // of view it keeps): where its node stands then, by the loader's
  // arithmetic; `rest` where the pose collapses the view between key times.
  Camera camera(double time, const Camera& rest) const;
  // The first time at which a moving part's bounds, a light or the camera
  // reach beyond +-max_coordinate (or are not finite), or the camera's view
  // collapses; none when every time checked keeps them within. Checked at
  // every key time and, where a CUBICSPLINE channel can overshoot its keys,
  // at the times between keys where a component of its curve turns.
  struct OutOfRange {
    double time;
    bool key;                             // a key time, or a time between keys
    const char* what;                     // "a moving part or light", "the camera", or why the view collapses
    std::optional<glm::dvec3> position;   // the point beyond range; none when the view collapses
  };
  std::optional<OutOfRange> check_extent(double max_coordinate) const;
};

// The camera a frame at `time` starts from: the scene's camera where its
// node stands then, or the automatic camera of a scene without one.
Camera scene_camera(const Scene& scene, double time);

// Makes `camera` the scene's camera, which no animation moves from then on
// (a camera the user gave, such as a bookmark file).
void place_camera(Scene& scene, const Camera& camera);

// Puts the scene's parts and lights where `pose` says. Touches only what
// moves. A scene without an animation and without area lights is left as is.
void pose_scene(Scene& scene, const ScenePose& pose);

// Makes the emissive triangles that no node moves one part (the light group),
// copying any vertex they share with other triangles so the group moves
// alone. Creates the scene's SceneAnimation if it has none. Idempotent.
void group_area_lights(Scene& scene);

// Makes triangles [first_triangle, end) one moving node, following
// `channels` (their `node` is set here), as a procedural scene animates a
// part: their vertices must be theirs alone, and stand at rest in world space.
void animate_triangles(Scene& scene, uint32_t first_triangle, std::vector<AnimationChannel> channels);

// The pose a master asks for at frame `index` of a run: `start` plus `step`
// per frame; with `loop`, wrapped into [0, duration) of the animation.
double scene_time(double start, double step, uint64_t index, bool loop, double duration);

}  // namespace igi
