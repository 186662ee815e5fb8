// Internal to the glTF import: the class that turns a loaded, not yet trusted tinygltf::Model
// into Scene content. gltf_import.cpp holds the asset, material, mesh and texture checks;
// gltf_import_nodes.cpp the node tree, instances, lights and camera.
#pragma once
#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <numbers>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "renderer/scene/gltf_import.h"
#include "renderer/scene/gltf_model.h"
#include "renderer/scene/json_messages.h"

namespace gib::gltf {

namespace tg = tinygltf;

// Units. glTF lights are photometric (point and spot: candela = lm/sr; directional: lux =
// lm/m^2); the scene's are radiometric (LocalLight::intensity in W/sr, Sun::irradiance in W/m^2)
// in linear RGB, with no luminous efficacy model. The import maps them one to one:
// colour x intensity [cd] -> W/sr, colour x intensity [lx] -> W/m^2, and emissiveFactor x
// KHR_materials_emissive_strength -> Material::emissive. A 683 lm/W factor would only be right
// for 555 nm light; one to one keeps the ratios between a file's lights, sun and emissive
// surfaces as its author set them, and makes export -> import exact.
inline constexpr double kPi = std::numbers::pi;
inline constexpr double kInf = std::numeric_limits<double>::infinity();

inline std::string quoted(const std::string& s) { return json_messages::describe(nlohmann::json(s)); }
inline bool finite(Vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// A TRIANGLE_STRIP (5) or TRIANGLE_FAN (6) vertex sequence as a triangle list, the winding
// glTF gives each triangle kept.
std::vector<uint32_t> triangle_list(const std::vector<uint32_t>& sequence, int mode);

class Importer {
 public:
  Importer(Scene& scene, const tg::Model& m, const Where& w, const GltfImportOptions& opt, const ImageLog& images,
           GltfImportReport& report)
      : scene_(scene), m_(m), w_(w), opt_(opt), images_(images), report_(report) {}
  void run(const Mat4& transform);  // everything, in the file's order; throws SceneError

 private:
  // gltf_import.cpp
  void check_asset();
  Vec3 factors3(const std::vector<double>& v, const std::string& p, double hi);
  Material convert_material(size_t i);
  static GltfMaterialInfo info_of(const tg::Material& g);
  uint32_t add_material(Material mat, GltfMaterialInfo info);
  uint32_t material_for(int index, const std::string& ref);
  uint32_t mesh_for(size_t mi, size_t pj);
  void load_textures();
  const ImageLog::Entry& image_bytes(size_t ii, ImageLog::Entry& scratch, const uint8_t*& data, size_t& size);
  int32_t texture_for(int index, const std::string& ref, bool srgb);
  // gltf_import_nodes.cpp
  static Mat4 trs_matrix(Vec3 t, const double q[4], Vec3 s);
  Mat4 local_matrix(const tg::Node& n, const std::string& np);
  void visit_scene(const Mat4& transform);
  void add_instances(size_t ni, const std::string& np, const Mat4& world);
  Vec3 axis(const Mat4& world, Vec3 local, const std::string& np, const char* what);
  Vec3 origin(const Mat4& world, const std::string& np, const char* what);
  void add_camera(const tg::Node& n, const std::string& np, const Mat4& world);
  void add_light(const tg::Value& ext, const std::string& np, const Mat4& world);

  Scene& scene_;
  const tg::Model& m_;
  const Where& w_;
  const GltfImportOptions& opt_;
  const ImageLog& images_;
  GltfImportReport& report_;
  std::set<std::string> names_;                             // every material name in the scene
  std::map<std::string, int> suffixes_;                     // the next "#k" to try per name
  std::map<std::pair<size_t, size_t>, uint32_t> meshes_;    // (glTF mesh, primitive) -> Scene mesh
  std::set<std::string> ignored_attributes_;
  std::set<std::pair<size_t, size_t>> skipped_;             // (glTF mesh, primitive) of points or lines
  int64_t default_material_ = -1;
  std::map<std::pair<size_t, bool>, int32_t> textures_;  // (glTF image, sRGB) -> Scene texture
  uint32_t ignored_suns_ = 0;
};

}  // namespace gib::gltf
