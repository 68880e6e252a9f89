#include "scene/gltf_animation.h"

#include <cmath>
#include <string>

#include <tiny_gltf.h>

#include "scene/gltf_accessors.h"

namespace igi {
namespace {

class AnimationReader {
 public:
  AnimationReader(const tinygltf::Model& model, GltfDiagnostics& diag) : model_(model), diag_(diag) {}

  void read(size_t index, std::vector<AnimationChannel>& out);

 private:
  AnimationChannel read_channel(const tinygltf::Animation& animation, const tinygltf::AnimationChannel& channel,
                                const std::string& name, const std::string& animation_name);
  std::vector<double> read_times(int accessor, const std::string& role);

  const tinygltf::Model& model_;
  GltfDiagnostics& diag_;
};

void AnimationReader::read(size_t index, std::vector<AnimationChannel>& out) {
  const tinygltf::Animation& animation = model_.animations[index];
  const std::string animation_name = gltf_element("animations", index);
  for (size_t c = 0; c < animation.channels.size(); ++c) {
    const tinygltf::AnimationChannel& channel = animation.channels[c];
    const std::string name = animation_name + "." + gltf_element("channels", c);
    if (channel.target_path == "weights") {
      diag_.warn_once("morph targets", "morph targets ignored: meshes keep their base shape (animated by " + name + ")");
      continue;
    }
    if (channel.target_node < 0) continue;  // glTF: no target node means an extension's target
    out.push_back(read_channel(animation, channel, name, animation_name));
  }
}

AnimationChannel AnimationReader::read_channel(const tinygltf::Animation& animation,
                                               const tinygltf::AnimationChannel& channel, const std::string& name,
                                               const std::string& animation_name) {
  AnimationChannel out;
  if (size_t(channel.target_node) >= model_.nodes.size())
    diag_.fail(name, "target node " + std::to_string(channel.target_node) + " does not exist (the file has " +
                         std::to_string(model_.nodes.size()) + ")");
  out.node = uint32_t(channel.target_node);
  int components = 3;
  if (channel.target_path == "translation") out.path = AnimationPath::Translation;
  else if (channel.target_path == "rotation") out.path = AnimationPath::Rotation, components = 4;
  else if (channel.target_path == "scale") out.path = AnimationPath::Scale;
  else diag_.fail(name, "target path '" + channel.target_path + "', expected translation, rotation, scale or weights");
  if (channel.sampler < 0 || size_t(channel.sampler) >= animation.samplers.size())
    diag_.fail(name, "sampler " + std::to_string(channel.sampler) + " does not exist (the animation has " +
                         std::to_string(animation.samplers.size()) + ")");
  const tinygltf::AnimationSampler& sampler = animation.samplers[size_t(channel.sampler)];
  const std::string sampler_name = animation_name + "." + gltf_element("samplers", size_t(channel.sampler));
  if (sampler.interpolation.empty() || sampler.interpolation == "LINEAR") out.interpolation = Interpolation::Linear;
  else if (sampler.interpolation == "STEP") out.interpolation = Interpolation::Step;
  else if (sampler.interpolation == "CUBICSPLINE") out.interpolation = Interpolation::CubicSpline;
  else diag_.fail(sampler_name, "interpolation '" + sampler.interpolation + "', expected LINEAR, STEP or CUBICSPLINE");

  out.times = read_times(sampler.input, "input of " + sampler_name);
  const std::vector<float> values =
      read_float_elements(model_, sampler.output, components, "output of " + sampler_name, diag_);
  const size_t per_key = out.interpolation == Interpolation::CubicSpline ? 3 : 1;
  const size_t elements = values.size() / size_t(components);
  if (elements != per_key * out.times.size())
    diag_.fail(sampler_name, "output has " + std::to_string(elements) + " elements for " +
                                 std::to_string(out.times.size()) + " key times, expected " +
                                 std::to_string(per_key * out.times.size()) +
                                 (per_key == 3 ? " (CUBICSPLINE: in-tangent, value, out-tangent per key)" : ""));
  out.values.resize(elements);
  for (size_t i = 0; i < elements; ++i) {
    const float* v = &values[i * size_t(components)];
    out.values[i] = components == 4 ? glm::dvec4(v[0], v[1], v[2], v[3]) : glm::dvec4(v[0], v[1], v[2], 0.0);
  }
  if (out.path == AnimationPath::Rotation)
    for (size_t key = 0; key < out.times.size(); ++key)
      if (glm::length(out.values[per_key * key + (per_key == 3 ? 1 : 0)]) == 0.0)
        diag_.fail(sampler_name, "rotation key " + std::to_string(key) + " is the zero quaternion");
  return out;
}

std::vector<double> AnimationReader::read_times(int accessor, const std::string& role) {
  const std::vector<float> keys = read_float_elements(model_, accessor, 1, role, diag_);
  const std::string name = gltf_element("accessors", size_t(accessor)) + " (" + role + ")";
  if (keys.empty()) diag_.fail(name, "no key times");
  std::vector<double> times(keys.begin(), keys.end());
  for (size_t i = 0; i < times.size(); ++i) {
    if (times[i] < 0.0) diag_.fail(name, "key time " + std::to_string(i) + " is negative (" + std::to_string(times[i]) + ")");
    if (i > 0 && !(times[i] > times[i - 1]))
      diag_.fail(name, "key time " + std::to_string(i) + " (" + std::to_string(times[i]) +
                           ") does not increase from the one before (" + std::to_string(times[i - 1]) + ")");
  }
  return times;
}

}  // namespace

std::vector<AnimationChannel> read_gltf_animations(const tinygltf::Model& model, GltfDiagnostics& diag) {
  std::vector<AnimationChannel> channels;
  AnimationReader reader(model, diag);
  for (size_t i = 0; i < model.animations.size(); ++i) reader.read(i, channels);
  return channels;
}

}  // namespace igi
