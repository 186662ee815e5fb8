#include "renderer/scene/gltf_export.h"

#include <fmt/format.h>
#include <stb_image_write.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <numbers>
#include <utility>

#include "renderer/scene/scene_loader.h"

namespace gib {

namespace {

namespace tg = tinygltf;
constexpr double kDegToRad = std::numbers::pi / 180.0;

std::vector<double> column_major(const Mat4& m) {
  std::vector<double> out(16);
  for (int i = 0; i < 16; ++i) out[static_cast<size_t>(i)] = m.m[i / 4][i % 4];
  return out;
}

bool is_identity(const Mat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (m.m[c][r] != (c == r ? 1.0f : 0.0f)) return false;
  return true;
}

// A node frame at `position` whose +Z is `z`, +Y as close to `up` as possible (right-handed).
Mat4 frame(Vec3 position, Vec3 z, Vec3 up) {
  z = normalize(z);
  Vec3 x = cross(up, z);
  if (length(x) < 1e-6f) x = cross(std::fabs(z.y) < 0.9f ? Vec3{0, 1, 0} : Vec3{1, 0, 0}, z);
  x = normalize(x);
  const Vec3 y = cross(z, x);
  Mat4 m = Mat4::translation(position);
  for (int r = 0; r < 3; ++r) {
    m.m[0][r] = x[r];
    m.m[1][r] = y[r];
    m.m[2][r] = z[r];
  }
  return m;
}

// A colour-like vector as glTF writes it: a factor in [0, 1] per channel times one scalar.
// The division is done in double so the import's product in double rounds back to the float.
std::pair<std::vector<double>, double> split(Vec3 v) {
  const double peak = std::max({double(v.x), double(v.y), double(v.z)});
  if (peak <= 1.0) return {{v.x, v.y, v.z}, 1.0};
  return {{v.x / peak, v.y / peak, v.z / peak}, peak};
}

class Exporter {
 public:
  Exporter(const Scene& scene, float time, GltfExportReport& report) : s_(scene), time_(time), r_(report) {
    m_.asset.version = "2.0";
    m_.asset.generator = "gibench gltf_export";
    m_.buffers.resize(1);
    m_.scenes.resize(1);
    m_.defaultScene = 0;
  }

  tg::Model build(const std::string& path) {
    for (const Texture& t : s_.textures) add_texture(t);
    for (const Material& mat : s_.materials) add_material(mat);
    for (uint32_t i = 0; i < s_.instances.size(); ++i) add_instance(i, path);
    for (size_t i = 0; i < s_.lights.size(); ++i) add_light(s_.lights[i], i);
    const Sun sun = s_.sun_at(time_);
    if (sun.enabled) add_sun(sun);
    add_camera(s_.camera_at(time_));
    if (m_.buffers[0].data.empty()) m_.buffers.clear();
    if (uses_strength_) m_.extensionsUsed.push_back("KHR_materials_emissive_strength");
    if (s_.sky.kind != SkyKind::none) r_.lossy.push_back("sky: not part of glTF");
    if (!s_.decals.empty()) r_.lossy.push_back(fmt::format("{} decal(s) not exported", s_.decals.size()));
    if (!s_.indoor_volumes.empty()) r_.lossy.push_back(fmt::format("{} indoor volume(s) not exported", s_.indoor_volumes.size()));
    return std::move(m_);
  }

 private:
  // Level 0 as a PNG in a bufferView (lossless: the import rebuilds the same mips).
  void add_texture(const Texture& t) {
    if (t.mips.empty()) throw SceneError(t.name + ": expected a texture with its level 0, got none");
    std::vector<uint8_t> rgba(t.mips[0].size() * 4);
    for (size_t i = 0; i < t.mips[0].size(); ++i)
      for (int k = 0; k < 4; ++k) rgba[4 * i + size_t(k)] = uint8_t(t.mips[0][i] >> (8 * k));
    std::vector<uint8_t> png;
    auto sink = [](void* ctx, void* data, int size) {
      auto* out = static_cast<std::vector<uint8_t>*>(ctx);
      out->insert(out->end(), static_cast<uint8_t*>(data), static_cast<uint8_t*>(data) + size);
    };
    if (!stbi_write_png_to_func(sink, &png, int(t.width), int(t.height), 4, rgba.data(), int(t.width) * 4))
      throw SceneError(t.name + ": expected a texture stb_image_write can encode as PNG");
    tg::Image img;
    img.name = t.name;
    img.mimeType = "image/png";
    img.bufferView = add_view(png.data(), png.size(), 0);
    while (m_.buffers[0].data.size() % 4) m_.buffers[0].data.push_back(0);  // the next views stay 4-byte aligned
    m_.images.push_back(std::move(img));
    tg::Texture tex;
    tex.source = static_cast<int>(m_.images.size() - 1);
    m_.textures.push_back(std::move(tex));
  }

  void add_material(const Material& mat) {
    tg::Material g;
    g.name = mat.name;
    const Vec3 a = vmin(vmax(mat.albedo, {0, 0, 0}), {1, 1, 1});
    if (!(a == mat.albedo)) r_.lossy.push_back(mat.name + ": albedo clamped to [0, 1]");
    const bool texture_alpha = mat.alpha == AlphaKind::texture_mask || mat.alpha == AlphaKind::texture_opacity;
    const double alpha = mat.alpha == AlphaKind::opacity || texture_alpha ? mat.opacity : 1.0;
    g.pbrMetallicRoughness.baseColorFactor = {a.x, a.y, a.z, alpha};
    g.pbrMetallicRoughness.metallicFactor = mat.metalness;
    g.pbrMetallicRoughness.roughnessFactor = mat.roughness;
    auto [emissive, strength] = split(mat.emissive);
    g.emissiveFactor = emissive;
    if (strength != 1.0) {
      g.extensions["KHR_materials_emissive_strength"] =
          tg::Value(tg::Value::Object{{"emissiveStrength", tg::Value(strength)}});
      uses_strength_ = true;
    }
    g.doubleSided = true;  // nothing is culled here: every surface is seen from both sides
    switch (mat.alpha) {
      case AlphaKind::none: break;
      case AlphaKind::opacity:
      case AlphaKind::texture_opacity: g.alphaMode = "BLEND"; break;
      case AlphaKind::texture_mask:
        g.alphaMode = "MASK";
        g.alphaCutoff = mat.alpha_cutoff;
        break;
      case AlphaKind::leaf_mask:
      case AlphaKind::checker_mask:
        g.alphaMode = "MASK";
        g.alphaCutoff = mat.alpha_cutoff;
        r_.lossy.push_back(mat.name + ": procedural alpha mask written as MASK with alpha 1 (imports opaque)");
        break;
    }
    auto texture = [&](int32_t t) { return t >= 0 && size_t(t) < s_.textures.size() ? int(t) : -1; };
    g.pbrMetallicRoughness.baseColorTexture.index = texture(mat.base_color_texture);
    g.pbrMetallicRoughness.metallicRoughnessTexture.index = texture(mat.metallic_roughness_texture);
    g.emissiveTexture.index = texture(mat.emissive_texture);
    g.normalTexture.index = texture(mat.normal_texture);
    g.normalTexture.scale = mat.normal_scale;
    if (mat.texture != TextureKind::none && mat.texture != TextureKind::image) r_.lossy.push_back(mat.name + ": procedural texture (albedo2, texture_scale) not exported");
    if (mat.translucency > 0) r_.lossy.push_back(mat.name + ": translucency not exported");
    if (mat.brdf == BrdfKind::cloth) r_.lossy.push_back(mat.name + ": cloth BRDF (sheen) exported as standard");
    if (mat.brdf == BrdfKind::glossy) r_.lossy.push_back(mat.name + ": glossy BRDF exported as metallic-roughness (its Fresnel split differs)");
    m_.materials.push_back(std::move(g));
    ++r_.materials;
  }

  int add_view(const void* data, size_t bytes, int target) {
    std::vector<unsigned char>& bin = m_.buffers[0].data;
    tg::BufferView v;
    v.buffer = 0;
    v.byteOffset = bin.size();  // every element is 4-byte, so views stay 4-byte aligned
    v.byteLength = bytes;
    v.target = target;
    const auto* p = static_cast<const unsigned char*>(data);
    bin.insert(bin.end(), p, p + bytes);
    m_.bufferViews.push_back(std::move(v));
    return static_cast<int>(m_.bufferViews.size() - 1);
  }

  int add_accessor(const void* data, size_t count, int component, int type, size_t element, int target) {
    tg::Accessor a;
    a.bufferView = add_view(data, count * element, target);
    a.componentType = component;
    a.type = type;
    a.count = count;
    m_.accessors.push_back(std::move(a));
    return static_cast<int>(m_.accessors.size() - 1);
  }

  // The accessors of one Scene mesh, shared by every (mesh, material) pair that uses it.
  const std::map<std::string, int>& attributes(uint32_t mi, int& indices) {
    auto [it, inserted] = mesh_attributes_.try_emplace(mi);
    if (inserted) {
      const Mesh& mesh = s_.meshes[mi];
      const size_t n = mesh.positions.size();
      std::map<std::string, int>& attr = it->second.first;
      attr["POSITION"] = add_accessor(mesh.positions.data(), n, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, 12, TINYGLTF_TARGET_ARRAY_BUFFER);
      tg::Accessor& pos = m_.accessors.back();
      constexpr double inf = std::numeric_limits<double>::infinity();
      pos.minValues = {inf, inf, inf};
      pos.maxValues = {-inf, -inf, -inf};
      for (const Vec3& p : mesh.positions)
        for (int k = 0; k < 3; ++k) {
          pos.minValues[size_t(k)] = std::min(pos.minValues[size_t(k)], double(p[k]));
          pos.maxValues[size_t(k)] = std::max(pos.maxValues[size_t(k)], double(p[k]));
        }
      // Missing trailing normals / UVs read as zero in flatten(): pad them the same way.
      if (!mesh.normals.empty()) {
        std::vector<Vec3> normals = mesh.normals;
        normals.resize(n, Vec3{0, 0, 0});
        // Written as they are (the round trip is exact), though glTF asks for unit normals.
        const size_t off = static_cast<size_t>(std::count_if(normals.begin(), normals.end(), [](Vec3 v) {
          return !(std::fabs(length(v) - 1.0f) <= 5e-4f);
        }));
        if (off)
          r_.lossy.push_back(fmt::format("{}: {} normal(s) not of unit length or not finite, written as they are (glTF "
                                         "validators report them as errors)", mesh.name, off));
        attr["NORMAL"] = add_accessor(normals.data(), n, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, 12, TINYGLTF_TARGET_ARRAY_BUFFER);
      }
      if (!mesh.uvs.empty()) {
        std::vector<Vec2> uvs = mesh.uvs;
        uvs.resize(n, Vec2{0, 0});
        attr["TEXCOORD_0"] = add_accessor(uvs.data(), n, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC2, 8, TINYGLTF_TARGET_ARRAY_BUFFER);
      }
      it->second.second = add_accessor(mesh.indices.data(), mesh.indices.size(), TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT,
                                       TINYGLTF_TYPE_SCALAR, 4, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    }
    indices = it->second.second;
    return it->second.first;
  }

  int mesh_for(uint32_t mi, uint32_t material, const std::string& path) {
    auto [it, inserted] = gltf_meshes_.try_emplace({mi, material}, static_cast<int>(m_.meshes.size()));
    if (!inserted) return it->second;
    const Mesh& mesh = s_.meshes[mi];
    if (mesh.positions.empty() || mesh.indices.size() < 3 || mesh.indices.size() % 3)
      throw SceneError(fmt::format("{}: expected meshes of whole triangles to export, got mesh \"{}\" with {} indices", path,
                                   mesh.name, mesh.indices.size()));
    tg::Primitive prim;
    prim.attributes = attributes(mi, prim.indices);
    prim.material = static_cast<int>(material);
    prim.mode = TINYGLTF_MODE_TRIANGLES;
    tg::Mesh g;
    g.name = mesh.name;
    g.primitives.push_back(std::move(prim));
    m_.meshes.push_back(std::move(g));
    ++r_.meshes;
    return it->second;
  }

  int add_node(tg::Node node) {
    m_.nodes.push_back(std::move(node));
    const int index = static_cast<int>(m_.nodes.size() - 1);
    m_.scenes[0].nodes.push_back(index);
    ++r_.nodes;
    return index;
  }

  void add_instance(uint32_t i, const std::string& path) {
    const Instance& inst = s_.instances[i];
    if (inst.mesh >= s_.meshes.size() || inst.material >= s_.materials.size())
      throw SceneError(fmt::format("{}: expected instances with a valid mesh and material, got instance \"{}\"", path, inst.name));
    tg::Node node;
    node.name = inst.name;
    node.mesh = mesh_for(inst.mesh, inst.material, path);
    const Mat4 m = s_.instance_transform(i, time_);
    if (!is_identity(m)) node.matrix = column_major(m);
    if (!inst.animation.empty()) r_.lossy.push_back(inst.name + ": animation written as its transform at the export time");
    if (inst.removable()) r_.lossy.push_back(inst.name + ": removed_at written as its transform at the export time");
    if (inst.solid) {  // Instance::solid, read back by the importer (gltf_import_nodes.cpp)
      tg::Value::Object extras;
      extras["gibench_solid"] = tg::Value(true);
      node.extras = tg::Value(std::move(extras));
    }
    add_node(std::move(node));
  }

  int add_gltf_light(const std::string& type, Vec3 value, const std::string& name) {
    tg::Light l;
    l.name = name;
    l.type = type;
    auto [color, intensity] = split(value);
    l.color = color;
    l.intensity = intensity;
    m_.lights.push_back(std::move(l));
    return static_cast<int>(m_.lights.size() - 1);
  }

  static tg::Value light_ref(int index) { return tg::Value(tg::Value::Object{{"light", tg::Value(index)}}); }

  void add_light(const LocalLight& l, size_t i) {
    const std::string name = "light" + std::to_string(i);
    const int li = add_gltf_light(l.kind == LightKind::spot ? "spot" : "point", l.intensity, name);
    m_.lights[size_t(li)].range = l.range;
    tg::Node node;
    node.name = name;
    if (l.kind == LightKind::spot) {
      m_.lights[size_t(li)].spot.innerConeAngle = l.inner_cone_deg * kDegToRad;
      m_.lights[size_t(li)].spot.outerConeAngle = l.outer_cone_deg * kDegToRad;
      node.matrix = column_major(frame(l.position, -l.direction, {0, 1, 0}));  // glTF lights shine along -Z
    } else {
      node.translation = {l.position.x, l.position.y, l.position.z};
    }
    node.extensions["KHR_lights_punctual"] = light_ref(li);
    add_node(std::move(node));
    ++r_.lights;
  }

  void add_sun(const Sun& sun) {
    tg::Node node;
    node.name = "sun";
    node.matrix = column_major(frame({0, 0, 0}, sun.direction, {0, 1, 0}));  // +Z towards the sun
    node.extensions["KHR_lights_punctual"] = light_ref(add_gltf_light("directional", sun.irradiance, "sun"));
    add_node(std::move(node));
    r_.sun = true;
    if (!sun.animation.empty() || !s_.sun.animation.empty()) r_.lossy.push_back("sun: animation written as the sun at the export time");
    if (sun.angular_radius_deg != Sun{}.angular_radius_deg) r_.lossy.push_back("sun: angular radius not exported");
  }

  void add_camera(const Camera& c) {
    tg::Camera cam;
    cam.type = "perspective";
    cam.perspective.yfov = c.fov_y_deg * kDegToRad;
    cam.perspective.znear = c.near_plane;
    cam.perspective.zfar = c.far_plane;
    m_.cameras.push_back(std::move(cam));
    tg::Node node;
    node.name = "camera";
    node.camera = 0;
    node.matrix = column_major(frame(c.position, c.position - c.target, c.up));  // cameras look along -Z
    add_node(std::move(node));
    r_.camera = true;
    if (!s_.camera.animation.empty()) r_.lossy.push_back("camera: animation written as the camera at the export time");
  }

  const Scene& s_;
  float time_;
  GltfExportReport& r_;
  tg::Model m_;
  std::map<uint32_t, std::pair<std::map<std::string, int>, int>> mesh_attributes_;
  std::map<std::pair<uint32_t, uint32_t>, int> gltf_meshes_;
  bool uses_strength_ = false;
};

}  // namespace

GltfExportReport export_gltf(const Scene& scene, const std::string& path, float time) {
  GltfExportReport report;
  tg::Model model = Exporter(scene, time, report).build(path);
  const std::filesystem::path p(path);
  const bool binary = p.extension() == ".glb";
  if (!binary && !model.buffers.empty()) model.buffers[0].uri = p.stem().string() + ".bin";
  tg::TinyGLTF writer;
  auto fail = [&](const std::string& why) -> void {
    throw SceneError(fmt::format("{}: expected a writable glTF file, got {}", path, why));
  };
  errno = 0;
  try {
    if (binary) {  // written through our stream: tinygltf's .glb file writer reports no open failure
      std::ofstream out(path, std::ios::binary);
      if (!out) fail(std::strerror(errno));
      if (!writer.WriteGltfSceneToStream(&model, out, false, true)) fail("a serialisation failure");
      out.close();
      if (!out) fail("a write error");
    } else if (!writer.WriteGltfSceneToFile(&model, path, false, false, true, false)) {
      fail(errno ? std::strerror(errno) : "a write failure");
    }
  } catch (const SceneError&) {
    throw;
  } catch (const std::exception& e) {
    fail(e.what());
  }
  return report;
}

}  // namespace gib
