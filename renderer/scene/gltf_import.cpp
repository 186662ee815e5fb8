#include "renderer/scene/gltf_import.h"

#include <fmt/format.h>

#include <array>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>

#include "renderer/scene/gltf_importer.h"
#include "renderer/scene/gltf_schema.h"
#include "renderer/scene/scene_loader.h"

namespace gib {

namespace gltf {

namespace {

constexpr size_t kMaxPrimitiveVertices = size_t{1} << 24;  // as the JSON mesh primitive

std::string topology(int mode) {
  static const char* names[] = {"POINTS", "LINES", "LINE_LOOP", "LINE_STRIP", "TRIANGLES", "TRIANGLE_STRIP", "TRIANGLE_FAN"};
  return mode >= 0 && mode <= 6 ? names[mode] : std::to_string(mode);
}

}  // namespace

// glTF 2.0, "Primitive topologies": strip triangle i is (v_i, v_{i+1+i%2}, v_{i+2-i%2}), so
// every triangle keeps the first one's winding; fan triangle i is (v_{i+1}, v_{i+2}, v_0).
std::vector<uint32_t> triangle_list(const std::vector<uint32_t>& v, int mode) {
  std::vector<uint32_t> out;
  if (v.size() < 3) return out;
  out.reserve(3 * (v.size() - 2));
  for (size_t i = 0; i + 2 < v.size(); ++i) {
    const std::array<uint32_t, 3> t = mode == TINYGLTF_MODE_TRIANGLE_FAN ? std::array{v[i + 1], v[i + 2], v[0]}
                                      : i % 2                           ? std::array{v[i], v[i + 2], v[i + 1]}
                                                                        : std::array{v[i], v[i + 1], v[i + 2]};
    out.insert(out.end(), t.begin(), t.end());
  }
  return out;
}

void Importer::run(const Mat4& transform) {
  check_asset();
  for (const Material& mat : scene_.materials) names_.insert(mat.name);
  report_.first_material = static_cast<uint32_t>(scene_.materials.size());
  report_.first_mesh = static_cast<uint32_t>(scene_.meshes.size());
  report_.first_instance = static_cast<uint32_t>(scene_.instances.size());
  for (size_t i = 0; i < m_.materials.size(); ++i) add_material(convert_material(i), info_of(m_.materials[i]));
  visit_scene(transform);
  load_textures();
  if (ignored_suns_) report_.notes.push_back(fmt::format("{} directional light(s) ignored: the scene sets its sun", ignored_suns_));
  for (const std::string& a : ignored_attributes_) report_.notes.push_back("attribute " + a + " ignored");
  for (const auto& [mi, pj] : skipped_)
    report_.notes.push_back(fmt::format("/meshes/{}/primitives/{}: {} skipped (points and lines cannot be shaded)", mi, pj,
                                        topology(m_.meshes[mi].primitives[pj].mode)));
}

void Importer::check_asset() {
  const tg::Asset& a = m_.asset;
  if (a.version.rfind("2.", 0) != 0) w_.fail("/asset/version", "\"2.0\" (glTF 2)", quoted(a.version));
  if (!a.minVersion.empty() && a.minVersion != "2.0") w_.fail("/asset/minVersion", "\"2.0\" or none", quoted(a.minVersion));
  // extensionsRequired was checked on the JSON (check_extensions).
  for (const std::string& e : m_.extensionsUsed)
    if (!supported_extension(e)) report_.notes.push_back("extension " + e + " (optional) ignored");
  if (!m_.skins.empty()) report_.notes.push_back(fmt::format("{} skin(s) ignored: meshes stay in bind pose", m_.skins.size()));
  if (!m_.animations.empty()) report_.notes.push_back(fmt::format("{} animation(s) ignored", m_.animations.size()));
}

Vec3 Importer::factors3(const std::vector<double>& v, const std::string& p, double hi) {
  if (v.size() != 3) w_.fail(p, "array of 3 numbers", fmt::format("array of {} numbers", v.size()));
  return {w_.number(p + "/0", v[0], 0, hi), w_.number(p + "/1", v[1], 0, hi), w_.number(p + "/2", v[2], 0, hi)};
}

Material Importer::convert_material(size_t i) {
  const tg::Material& g = m_.materials[i];
  const std::string p = "/materials/" + std::to_string(i), pp = p + "/pbrMetallicRoughness";
  Material mat;
  mat.name = g.name.empty() ? "material" + std::to_string(i) : g.name;
  const std::vector<double>& bc = g.pbrMetallicRoughness.baseColorFactor;
  if (bc.size() != 4) w_.fail(pp + "/baseColorFactor", "array of 4 numbers", fmt::format("array of {} numbers", bc.size()));
  std::vector<double> base(bc.begin(), bc.end() - 1);
  mat.albedo = factors3(base, pp + "/baseColorFactor", 1);
  const float alpha = w_.number(pp + "/baseColorFactor/3", bc[3], 0, 1);
  mat.metalness = w_.number(pp + "/metallicFactor", g.pbrMetallicRoughness.metallicFactor, 0, 1);
  mat.roughness = w_.number(pp + "/roughnessFactor", g.pbrMetallicRoughness.roughnessFactor, 0, 1);

  double strength = 1.0;
  if (auto it = g.extensions.find("KHR_materials_emissive_strength"); it != g.extensions.end()) {
    const std::string ep = p + "/extensions/KHR_materials_emissive_strength";
    if (!it->second.IsObject()) w_.fail(ep, "object", "a non-object");
    if (it->second.Has("emissiveStrength")) {
      const tg::Value& s = it->second.Get("emissiveStrength");
      if (!s.IsNumber()) w_.fail(ep + "/emissiveStrength", "number >= 0", "a non-number");
      strength = w_.number(ep + "/emissiveStrength", s.GetNumberAsDouble(), 0, kInf);
    }
  }
  const std::vector<double> ef = g.emissiveFactor.empty() ? std::vector<double>(3, 0.0) : g.emissiveFactor;
  factors3(ef, p + "/emissiveFactor", 1);
  // The product in double, rounded once: an exported factor/strength pair comes back exact.
  for (int k = 0; k < 3; ++k)
    mat.emissive[k] = w_.number(fmt::format("{}/emissiveFactor/{}", p, k), ef[k] * strength, 0, kInf);

  if (g.alphaMode == "MASK") {
    // Without texture sampling the mask is the constant base colour alpha: covered (alpha >=
    // cutoff) is opaque, uncovered is invisible (stochastic opacity 0).
    mat.alpha_cutoff = w_.number(p + "/alphaCutoff", g.alphaCutoff, 0, kInf);
    if (alpha < mat.alpha_cutoff) {
      mat.alpha = AlphaKind::opacity;
      mat.opacity = 0.0f;
    }
  } else if (g.alphaMode == "BLEND") {
    mat.alpha = AlphaKind::opacity;  // blending becomes stochastic coverage
    mat.opacity = alpha;
  } else if (g.alphaMode != "OPAQUE") {
    w_.fail(p + "/alphaMode", "one of \"OPAQUE\", \"MASK\", \"BLEND\"", quoted(g.alphaMode));
  }
  return mat;
}

GltfMaterialInfo Importer::info_of(const tg::Material& g) {
  GltfMaterialInfo info;
  info.double_sided = g.doubleSided;
  info.textures.base_color = g.pbrMetallicRoughness.baseColorTexture.index;
  info.textures.metallic_roughness = g.pbrMetallicRoughness.metallicRoughnessTexture.index;
  info.textures.emissive = g.emissiveTexture.index;
  info.textures.normal = g.normalTexture.index;
  info.textures.occlusion = g.occlusionTexture.index;
  return info;
}

uint32_t Importer::add_material(Material mat, GltfMaterialInfo info) {
  const std::string base = opt_.material_prefix + mat.name;
  std::string name = base;
  for (int& k = suffixes_.try_emplace(base, 2).first->second; names_.count(name); ++k) name = fmt::format("{}#{}", base, k);
  names_.insert(name);
  mat.name = name;
  info.scene_material = static_cast<uint32_t>(scene_.materials.size());
  scene_.materials.push_back(std::move(mat));
  report_.materials.push_back(info);
  ++report_.material_count;
  return info.scene_material;
}

// glTF's default material (a primitive without one): base colour 1, metallic 1, roughness 1.
uint32_t Importer::material_for(int index, const std::string& ref) {
  if (index != -1) return report_.first_material + static_cast<uint32_t>(w_.index(ref, index, m_.materials.size(), "material"));
  if (default_material_ < 0) {
    Material d;
    d.name = "default";
    d.albedo = {1, 1, 1};
    d.metalness = d.roughness = 1.0f;
    default_material_ = add_material(d, {});
  }
  return static_cast<uint32_t>(default_material_);
}

uint32_t Importer::mesh_for(size_t mi, size_t pj) {
  auto [it, inserted] = meshes_.try_emplace({mi, pj}, static_cast<uint32_t>(scene_.meshes.size()));
  if (!inserted) return it->second;
  const tg::Primitive& pr = m_.meshes[mi].primitives[pj];
  const std::string pp = fmt::format("/meshes/{}/primitives/{}", mi, pj), ap = pp + "/attributes/";
  // TRIANGLES, TRIANGLE_STRIP or TRIANGLE_FAN here: the schema bounds the mode to [0, 6] and
  // add_instances skips points and lines.
  auto attribute = [&](const char* name) {
    auto a = pr.attributes.find(name);
    return a == pr.attributes.end() ? std::nullopt : std::optional<int>(a->second);
  };
  const std::optional<int> position = attribute("POSITION");
  if (!position) w_.fail(pp + "/attributes", "a POSITION attribute", "none");
  Mesh mesh;
  const AccessorData pa =
      accessor(m_, *position, w_, ap + "POSITION", TINYGLTF_TYPE_VEC3, {TINYGLTF_COMPONENT_TYPE_FLOAT}, "POSITION");
  if (pa.count > kMaxPrimitiveVertices)
    w_.fail(pa.pointer + "/count", fmt::format("at most {} vertices in a primitive", kMaxPrimitiveVertices), std::to_string(pa.count));
  mesh.positions = read_vec3(pa, true, w_);
  const size_t n = pa.count;
  auto same_count = [&](const AccessorData& a, const std::string& ref) {
    if (a.count != n) w_.fail(ref, fmt::format("an accessor of {} elements (the POSITION count)", n), fmt::format("{} elements in {}", a.count, a.pointer));
  };
  if (const std::optional<int> normal = attribute("NORMAL")) {
    const AccessorData na =
        accessor(m_, *normal, w_, ap + "NORMAL", TINYGLTF_TYPE_VEC3, {TINYGLTF_COMPONENT_TYPE_FLOAT}, "NORMAL");
    same_count(na, ap + "NORMAL");
    mesh.normals = read_vec3(na, false, w_);  // non-finite normals pass on, as the JSON mesh's null
  }  // else none: zero normals, which shading replaces by the face normal (glTF's flat normals)
  if (const std::optional<int> uv = attribute("TEXCOORD_0")) {
    const AccessorData ta = accessor(
        m_, *uv, w_, ap + "TEXCOORD_0", TINYGLTF_TYPE_VEC2,
        {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT}, "TEXCOORD_0");
    if (ta.component_type != TINYGLTF_COMPONENT_TYPE_FLOAT && !ta.normalized)
      w_.fail(ta.pointer + "/normalized", "true for an integer TEXCOORD_0", "false");
    same_count(ta, ap + "TEXCOORD_0");
    mesh.uvs = read_vec2(ta, w_);
  }
  for (const auto& [name, index] : pr.attributes)
    if (name != "POSITION" && name != "NORMAL" && name != "TEXCOORD_0") ignored_attributes_.insert(name);
  // The vertex sequence (indices, or the vertices in order), then its triangles.
  const bool list = pr.mode == TINYGLTF_MODE_TRIANGLES;
  const std::string needs = list ? "a multiple of 3" : "at least 3";
  if (pr.indices != -1) {
    const AccessorData ia = accessor(
        m_, pr.indices, w_, pp + "/indices", TINYGLTF_TYPE_SCALAR,
        {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT}, "indices");
    if (list ? ia.count % 3 != 0 : ia.count < 3)
      w_.fail(pp + "/indices", fmt::format("{} indices ({})", needs, topology(pr.mode)), fmt::format("{} in {}", ia.count, ia.pointer));
    mesh.indices = read_indices(ia, n, w_, pp + "/indices");
  } else {
    if (list ? n % 3 != 0 : n < 3)
      w_.fail(ap + "POSITION", fmt::format("{} vertices ({} without indices)", needs, topology(pr.mode)), std::to_string(n));
    mesh.indices.resize(n);
    for (size_t i = 0; i < n; ++i) mesh.indices[i] = static_cast<uint32_t>(i);
  }
  if (!list) mesh.indices = triangle_list(mesh.indices, pr.mode);
  if (!pr.targets.empty()) report_.notes.push_back(fmt::format("{}: morph targets ignored", pp));
  const std::string& mesh_name = m_.meshes[mi].name;
  mesh.name = opt_.instance_prefix + (mesh_name.empty() ? "mesh" + std::to_string(mi) : mesh_name) +
              (m_.meshes[mi].primitives.size() > 1 ? "/" + std::to_string(pj) : "");
  scene_.meshes.push_back(std::move(mesh));
  ++report_.mesh_count;
  return it->second;
}

// The textures materials reference: base colour, emissive, metallic-roughness and normal images
// are decoded into Scene::textures (once per image and colour space); occlusion images must
// exist and decode but are not sampled.
void Importer::load_textures() {
  report_.first_texture = static_cast<uint32_t>(scene_.textures.size());
  size_t unsampled = 0;
  for (size_t i = 0; i < m_.materials.size(); ++i) {
    const tg::Material& g = m_.materials[i];
    const GltfTextureRefs& t = report_.materials[i].textures;
    const std::string p = "/materials/" + std::to_string(i), pp = p + "/pbrMetallicRoughness";
    Material& mat = scene_.materials[report_.materials[i].scene_material];
    mat.base_color_texture = texture_for(t.base_color, pp + "/baseColorTexture/index", true);
    mat.emissive_texture = texture_for(t.emissive, p + "/emissiveTexture/index", true);
    mat.metallic_roughness_texture = texture_for(t.metallic_roughness, pp + "/metallicRoughnessTexture/index", false);
    mat.normal_texture = texture_for(t.normal, p + "/normalTexture/index", false);
    mat.normal_scale = static_cast<float>(g.normalTexture.scale);
    if (!std::isfinite(mat.normal_scale))
      w_.fail(p + "/normalTexture/scale", "a finite number", fmt::format("{}", g.normalTexture.scale));
    if (t.occlusion != -1) {
      texture_for(t.occlusion, p + "/occlusionTexture/index", false);  // checked (and decoded) like the others
      ++unsampled;
    }
    for (const auto& [index, coord, ref] :
         {std::tuple{g.pbrMetallicRoughness.baseColorTexture.index, g.pbrMetallicRoughness.baseColorTexture.texCoord,
                     pp + "/baseColorTexture"},
          std::tuple{g.emissiveTexture.index, g.emissiveTexture.texCoord, p + "/emissiveTexture"},
          std::tuple{g.pbrMetallicRoughness.metallicRoughnessTexture.index,
                     g.pbrMetallicRoughness.metallicRoughnessTexture.texCoord, pp + "/metallicRoughnessTexture"},
          std::tuple{g.normalTexture.index, g.normalTexture.texCoord, p + "/normalTexture"}})
      if (index != -1 && coord != 0)
        report_.notes.push_back(ref + ": TEXCOORD_" + std::to_string(coord) + " read as TEXCOORD_0");
    if (mat.base_color_texture < 0) continue;
    mat.texture = TextureKind::image;
    const float alpha = static_cast<float>(g.pbrMetallicRoughness.baseColorFactor[3]);  // checked
    if (g.alphaMode == "MASK") {
      mat.alpha = AlphaKind::texture_mask;
      mat.opacity = alpha;
    } else if (g.alphaMode == "BLEND") {
      mat.alpha = AlphaKind::texture_opacity;
      mat.opacity = alpha;
    }
  }
  // Textures the scene will not use, the trailing ones of an unreferenced material, stay (they
  // cost memory only).
  if (unsampled) report_.notes.push_back(fmt::format("{} occlusion texture reference(s) not sampled", unsampled));
  report_.texture_count = static_cast<uint32_t>(scene_.textures.size()) - report_.first_texture;
  for (size_t i = report_.first_texture; i < scene_.textures.size(); ++i) report_.texture_bytes += scene_.textures[i].bytes();
}

// The bytes of image ii (a checked bufferView, or its URI file's).
const ImageLog::Entry& Importer::image_bytes(size_t ii, ImageLog::Entry& scratch, const uint8_t*& data, size_t& size) {
  const tg::Image& img = m_.images[ii];
  const std::string ip = "/images/" + std::to_string(ii);
  if (img.bufferView != -1) {
    const size_t vi = w_.index(ip + "/bufferView", img.bufferView, m_.bufferViews.size(), "bufferView");
    data = buffer_view_bytes(m_, vi, w_);
    size = m_.bufferViews[vi].byteLength;
    scratch = inspect_image(data, size);
    return scratch;
  }
  auto it = images_.by_uri.find(static_cast<int>(ii));
  if (it == images_.by_uri.end())
    w_.fail(ip + "/uri", "a readable image file (relative to the glTF file)", quoted(img.uri));
  data = it->second.bytes.data();
  size = it->second.bytes.size();
  return it->second;
}

int32_t Importer::texture_for(int index, const std::string& ref, bool srgb) {
  if (index == -1) return -1;
  const size_t ti = w_.index(ref, index, m_.textures.size(), "texture");
  const std::string sp = fmt::format("/textures/{}/source", ti);
  if (m_.textures[ti].source == -1) w_.fail(sp, "an image index (no supported extension supplies one)", "none");
  const size_t ii = w_.index(sp, m_.textures[ti].source, m_.images.size(), "image");
  if (auto it = textures_.find({ii, srgb}); it != textures_.end()) return it->second;
  if (const int si = m_.textures[ti].sampler; si >= 0 && static_cast<size_t>(si) < m_.samplers.size()) {
    const tg::Sampler& s = m_.samplers[static_cast<size_t>(si)];
    if (s.wrapS != TINYGLTF_TEXTURE_WRAP_REPEAT || s.wrapT != TINYGLTF_TEXTURE_WRAP_REPEAT)
      report_.notes.push_back(fmt::format("/samplers/{}: wrap modes other than REPEAT sampled as REPEAT", si));
  }
  const std::string ip = "/images/" + std::to_string(ii);
  ImageLog::Entry scratch;
  const uint8_t* data = nullptr;
  size_t size = 0;
  const ImageLog::Entry& e = image_bytes(ii, scratch, data, size);
  if (!e.decodable) w_.fail(ip, "an image stb_image can decode (PNG, JPEG, BMP, TGA, ...)", e.reason);
  if (scene_.textures.size() >= kTextureMaxCount)
    w_.fail(ip, fmt::format("at most {} textures in a scene", kTextureMaxCount), "one more");
  const DecodedImage d = decode_image(data, size);
  if (!d.ok) w_.fail(ip, fmt::format("an image stb_image can decode, at most {} texels a side", kTextureMaxSize), d.reason);
  Texture t = make_texture(w_.file + ": " + ip, d.width, d.height, d.rgba.data(), srgb);
  const uint64_t bytes = t.bytes() + textures_bytes(scene_.textures);
  if (bytes > kTextureMaxBytes)
    w_.fail(ip, fmt::format("at most {} MiB of textures and mips in a scene", kTextureMaxBytes >> 20),
            fmt::format("{} bytes with this one", bytes));
  scene_.textures.push_back(std::move(t));
  const int32_t id = static_cast<int32_t>(scene_.textures.size() - 1);
  textures_[{ii, srgb}] = id;
  return id;
}

}  // namespace gltf

GltfImportReport import_gltf_bytes(Scene& scene, const std::vector<uint8_t>& bytes, const std::string& name,
                                   const std::string& base_dir, const Mat4& transform, const GltfImportOptions& options) {
  const gltf::Where w{name};
  GltfImportOptions opt = options;
  const std::string stem = std::filesystem::path(name).stem().string() + "/";
  if (opt.material_prefix.empty()) opt.material_prefix = stem;
  if (opt.instance_prefix.empty()) opt.instance_prefix = stem;
  GltfImportReport report;
  report.path = name;
  // Nothing of a failed import stays in the scene.
  const size_t materials = scene.materials.size(), meshes = scene.meshes.size(), instances = scene.instances.size(),
               lights = scene.lights.size(), textures = scene.textures.size();
  const Sun sun = scene.sun;
  const Camera camera = scene.camera;
  auto roll_back = [&] {
    scene.materials.resize(materials);
    scene.meshes.resize(meshes);
    scene.instances.resize(instances);
    scene.lights.resize(lights);
    scene.textures.resize(textures);
    scene.sun = sun;
    scene.camera = camera;
  };
  try {
    gltf::ImageLog images;
    const tinygltf::Model model = gltf::load_model(bytes, w, base_dir, images);
    gltf::Importer(scene, model, w, opt, images, report).run(transform);
  } catch (const SceneError&) {
    roll_back();
    throw;
  } catch (const std::exception& e) {  // std::bad_alloc and the like: still one line naming the file
    roll_back();
    w.fail_file("a glTF file that can be imported", json_messages::ascii_line(e.what()));
  }
  return report;
}

SceneImport scene_import(const GltfImportReport& r) {
  SceneImport out;
  out.file = r.path;
  out.read = fmt::format("{} meshes, {} instances ({} triangles, {} vertices), {} materials, {} textures ({:.1f} KiB with mips), {} lights{}{}",
                         r.mesh_count, r.instance_count, r.triangles, r.vertices, r.material_count, r.texture_count,
                         r.texture_bytes / 1024.0, r.lights, r.camera ? ", the camera" : "", r.sun ? ", the sun" : "");
  out.ignored = r.notes;
  return out;
}

GltfImportReport import_gltf(Scene& scene, const std::string& path, const Mat4& transform, const GltfImportOptions& options) {
  const gltf::Where w{path};
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) w.fail_file("a glTF file", "a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in) w.fail_file("a readable file", std::strerror(errno));
  std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) w.fail_file("a readable file", "a read error");
  std::string base = std::filesystem::path(path).parent_path().string();
  return import_gltf_bytes(scene, bytes, path, base.empty() ? "." : base, transform, options);
}

}  // namespace gib
