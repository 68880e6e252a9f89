// OBJ scenes with their MTL materials (scene/obj_loader.h): the mapping onto
// the four material models, errors that name the file and what is wrong, and
// the .glb every reader of the scene loads alike.
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "image/image.h"
#include "scene/gltf_loader.h"
#include "scene/gltf_pack.h"
#include "scene/load_scene.h"
#include "scene/obj_loader.h"
#include "support/image_compare.h"

namespace igi {
namespace {

namespace fs = std::filesystem;

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = test::output_path("obj/" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// A quad in z = 0 facing +z (two triangles), with texture coordinates, in material `material`.
std::string quad_obj(const std::string& mtllib, const std::vector<std::string>& materials) {
  std::string obj = mtllib.empty() ? "" : "mtllib " + mtllib + "\n";
  for (size_t i = 0; i < materials.size(); ++i) {
    const float x = 2.0f * float(i);
    obj += "v " + std::to_string(x) + " 0 0\nv " + std::to_string(x + 1) + " 0 0\nv " + std::to_string(x + 1) +
           " 1 0\nv " + std::to_string(x) + " 1 0\n";
  }
  obj += "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\n";
  for (size_t i = 0; i < materials.size(); ++i) {
    const int v = int(4 * i) + 1;
    obj += "usemtl " + materials[i] + "\nf " + std::to_string(v) + "/1/1 " + std::to_string(v + 1) + "/2/1 " +
           std::to_string(v + 2) + "/3/1 " + std::to_string(v + 3) + "/4/1\n";
  }
  return obj;
}

const char* kMaterials = R"(newmtl wall
Kd 0.5 0.6 0.7
Ka 0.1 0.1 0.1
newmtl lamp
Kd 0 0 0
Ke 10 9 8
newmtl metal
Kd 0.05 0.05 0.05
Ks 0.9 0.8 0.7
Ns 198
newmtl mirror
Ks 1 1 1
Ns 100000000
newmtl glass
Tf 0.9 1 0.95
Ni 1.33
d 0.2
newmtl textured
Kd 1 1 1
map_Kd checker.png
map_bump bumps.png
Pr 0.4
)";

Scene load(const fs::path& path, std::vector<std::string>* warnings = nullptr) {
  SceneMessages messages;
  Scene scene = load_scene(path.string(), {}, &messages);
  if (warnings) *warnings = messages.warnings;
  return scene;
}

size_t said(const std::vector<std::string>& lines, const std::string& text) {
  return size_t(std::count_if(lines.begin(), lines.end(), [&](const std::string& l) { return l.find(text) != std::string::npos; }));
}

TEST(ObjLoader, MaterialsMapOntoTheFourModelsAsTheReadmeSays) {
  const fs::path dir = fresh_dir("materials");
  Image checker(2, 2);
  checker.at(0, 0) = checker.at(1, 1) = glm::vec3(1.0f);  // linear 1 and 0: exact through sRGB 8-bit
  write_image(checker, (dir / "checker.png").string());
  std::ofstream(dir / "room.mtl") << kMaterials;
  std::ofstream(dir / "room.obj") << quad_obj("room.mtl", {"wall", "lamp", "metal", "mirror", "glass", "textured"});
  std::vector<std::string> warnings;
  const Scene scene = load(dir / "room.obj", &warnings);
  ASSERT_EQ(scene.triangles.size(), 12u);
  ASSERT_EQ(scene.materials.size(), 6u);
  const Material& wall = scene.materials[scene.triangle_material[0]];
  EXPECT_EQ(wall.type, MaterialType::Diffuse);
  EXPECT_EQ(wall.base_color, glm::vec3(0.5f, 0.6f, 0.7f));
  const Material& lamp = scene.materials[scene.triangle_material[2]];
  EXPECT_EQ(lamp.emission, glm::vec3(10.0f, 9.0f, 8.0f)) << "Ke: radiance, as written";
  const Material& metal = scene.materials[scene.triangle_material[4]];
  EXPECT_EQ(metal.type, MaterialType::Conductor);
  EXPECT_NEAR(metal.alpha, 0.1f, 1e-5f) << "sqrt(2 / (Ns + 2))";
  EXPECT_EQ(metal.base_color, glm::vec3(0.9f, 0.8f, 0.7f));
  EXPECT_EQ(scene.materials[scene.triangle_material[6]].type, MaterialType::Mirror);
  const Material& glass = scene.materials[scene.triangle_material[8]];
  EXPECT_EQ(glass.type, MaterialType::Glass);
  EXPECT_FLOAT_EQ(glass.ior, 1.33f);
  EXPECT_EQ(glass.base_color, glm::vec3(0.9f, 1.0f, 0.95f));
  const Material& textured = scene.materials[scene.triangle_material[10]];
  ASSERT_GE(textured.base_color_texture, 0);
  const Texture& texture = scene.textures[size_t(textured.base_color_texture)];
  ASSERT_EQ(texture.width, 2);
  EXPECT_EQ(texture.texels[0], glm::vec4(1, 1, 1, 1));
  EXPECT_EQ(texture.texels[1], glm::vec4(0, 0, 0, 1));
  // OBJ's v grows up, glTF's down: the corner at vt (0, 0) is uv (0, 1).
  EXPECT_EQ(scene.uvs[scene.triangles[10][0]], glm::vec2(0.0f, 1.0f));
  EXPECT_EQ(scene.normals[scene.triangles[10][0]], glm::vec3(0, 0, 1));
  for (const char* feature : {"Ka", "bump map", "Pr (the PBR extension)", "d (dissolve)", "Kd beside a brighter Ks"})
    EXPECT_EQ(said(warnings, feature), 1u) << feature << " not reported once";
  EXPECT_EQ(said(warnings, "room.obj"), warnings.size()) << "every line names the file";
}

// The lamps' Ke lights it: no supplied sun. Faces with no material are white.
TEST(ObjLoader, FacesWithoutAMaterialAreWhiteAndKeIsTheLight) {
  const fs::path dir = fresh_dir("no-material");
  std::ofstream(dir / "lamp.mtl") << "newmtl lamp\nKe 5 5 5\n";
  std::ofstream(dir / "plain.obj") << "mtllib lamp.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nusemtl lamp\nf 1 3 4\n";
  const Scene scene = load(dir / "plain.obj");
  EXPECT_TRUE(scene.lights.empty()) << "lit by its emitter, no sun supplied";
  ASSERT_EQ(scene.materials.size(), 2u);
  const Material& plain = scene.materials[1];  // after the file's own
  EXPECT_EQ(plain.name, "default");
  EXPECT_EQ(plain.type, MaterialType::Diffuse);
  EXPECT_EQ(plain.base_color, glm::vec3(0.8f));
  EXPECT_TRUE(scene.normals.empty() && scene.uvs.empty()) << "none in the file: none made up";
}

// Bad input: an error naming the file and what is wrong, nothing read from outside the OBJ's folder.
TEST(ObjLoader, BrokenFilesAreErrorsNamingTheFileAndTheFault) {
  const fs::path dir = fresh_dir("broken");
  fs::create_directories(dir / "scene");
  std::ofstream(dir / "outside.mtl") << "newmtl x\nKd 1 1 1\n";
  std::ofstream(dir / "scene" / "escape.obj") << "mtllib ../outside.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  std::ofstream(dir / "scene" / "far.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n";
  std::ofstream(dir / "scene" / "tex.mtl") << "newmtl t\nmap_Kd ../checker.png\n";
  std::ofstream(dir / "scene" / "tex.obj") << "mtllib tex.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl t\nf 1 2 3\n";
  std::ofstream(dir / "scene" / "notex.mtl") << "newmtl t\nmap_Kd missing.png\n";
  std::ofstream(dir / "scene" / "notex.obj") << "mtllib notex.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl t\nf 1 2 3\n";
  std::ofstream(dir / "scene" / "empty.obj") << "# nothing\n";
  write_image(Image(2, 2), (dir / "checker.png").string());
  const std::pair<const char*, std::vector<std::string>> cases[] = {
      {"escape.obj", {"escape.obj", "mtllib ../outside.mtl", "outside the scene's folder"}},
      {"far.obj", {"far.obj", "face 0", "vertex 9 of 3"}},
      {"tex.obj", {"tex.obj", "map_Kd ../checker.png", "outside the scene's folder"}},
      {"notex.obj", {"notex.obj", "map_Kd missing.png", "missing"}},
      {"empty.obj", {"empty.obj", "no geometry"}},
      {"none.obj", {"none.obj", "no such file"}}};
  for (const auto& [file, fragments] : cases) {
    try {
      load(dir / "scene" / file);
      ADD_FAILURE() << file << " loaded";
    } catch (const SceneError& e) {
      for (const std::string& fragment : fragments)
        EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << "'" << fragment << "' missing in: " << e.what();
    }
  }
}

// The master sends workers the .glb the OBJ becomes; loaded from those bytes
// it is the scene igi-render loads from the OBJ, float for float.
TEST(ObjLoader, WorkersGetTheSceneTheMasterLoads) {
  const fs::path dir = fresh_dir("workers");
  Image checker(4, 4);
  checker.at(1, 2) = glm::vec3(0.3f, 0.5f, 0.7f);
  write_image(checker, (dir / "checker.png").string());
  std::ofstream(dir / "room.mtl") << kMaterials;
  std::ofstream(dir / "room.obj") << quad_obj("room.mtl", {"wall", "lamp", "metal", "glass", "textured"});
  const Scene direct = load(dir / "room.obj");
  const SceneFile file = scene_file_for_workers((dir / "room.obj").string());
  EXPECT_EQ(file.name, "room.glb");
  EXPECT_TRUE(file.packed);
  const Scene sent = load_gltf_memory(file.bytes, file.name).scene;
  EXPECT_EQ(sent.name, direct.name);
  EXPECT_EQ(sent.positions, direct.positions);
  EXPECT_EQ(sent.normals, direct.normals);
  EXPECT_EQ(sent.uvs, direct.uvs);
  EXPECT_EQ(sent.triangles, direct.triangles);
  ASSERT_EQ(sent.materials.size(), direct.materials.size());
  for (size_t i = 0; i < sent.materials.size(); ++i) {
    EXPECT_EQ(sent.materials[i].base_color, direct.materials[i].base_color) << i;
    EXPECT_EQ(sent.materials[i].alpha, direct.materials[i].alpha) << i;
    EXPECT_EQ(sent.materials[i].emission, direct.materials[i].emission) << i;
  }
  ASSERT_EQ(sent.textures.size(), 1u);
  EXPECT_EQ(sent.textures[0].texels, direct.textures[0].texels);
  EXPECT_EQ(scene_file_for_workers((dir / "room.obj").string()).bytes, file.bytes) << "the same bytes every time";
}

}  // namespace
}  // namespace igi
