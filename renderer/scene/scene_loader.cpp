#include "renderer/scene/scene_loader.h"
#include "renderer/scene/json_messages.h"

#include <fmt/format.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <iterator>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <utility>

#include "renderer/scene/gltf_import.h"
#include "renderer/scene/primitives.h"

namespace gib {

namespace {

using json = nlohmann::json;
using json_messages::ascii_line;
using json_messages::describe;
using json_messages::dump_safe;
using json_messages::pointer_token;


std::string join(std::initializer_list<std::string_view> names) {
  std::string out;
  for (std::string_view n : names) out += (out.empty() ? "" : ", ") + std::string(n);
  return out;
}

// Inclusive/exclusive numeric bounds with the words used in messages.
struct Range {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false, hi_open = false;
  bool contains(double x) const {
    return (lo_open ? x > lo : x >= lo) && (hi_open ? x < hi : x <= hi);
  }
  std::string text() const {
    // Bounds are printed as float so a bound taken from a float field reads "0.05", not
    // "0.05000000074505806".
    float l = static_cast<float>(lo), h = static_cast<float>(hi);
    bool has_lo = std::isfinite(lo), has_hi = std::isfinite(hi);
    if (has_lo && has_hi) return fmt::format("number in {}{}, {}{}", lo_open ? "(" : "[", l, h, hi_open ? ")" : "]");
    if (has_lo) return fmt::format("number {} {}", lo_open ? ">" : ">=", l);
    if (has_hi) return fmt::format("number {} {}", hi_open ? "<" : "<=", h);
    return "number";
  }
};
const Range kAny{};
const Range kNonNegative{0.0};
const Range kPositive{0.0, std::numeric_limits<double>::infinity(), true};
const Range kUnit{0.0, 1.0};

// A value in the document plus where it is; `v` is null when the key is absent.
struct Node {
  const json* v;
  std::string path;
  const std::string* source;

  bool present() const { return v != nullptr; }
  [[noreturn]] void fail(std::string_view expected, std::string_view got) const {
    throw SceneError(fmt::format("{}: {}: expected {}, got {}", *source, path.empty() ? "/" : path, expected, got));
  }
  [[noreturn]] void fail(std::string_view expected) const {
    fail(expected, present() ? describe(*v) : "missing key");
  }
  Node operator[](std::string_view key) const {  // only on objects
    auto it = v->find(key);
    return {it == v->end() ? nullptr : &*it, path + "/" + pointer_token(key), source};
  }
  Node operator[](size_t i) const { return {&(*v)[i], path + "/" + std::to_string(i), source}; }
};

// Every object is checked against its allowed keys so typos fail instead of being ignored.
void check_object(const Node& n, std::initializer_list<std::string_view> allowed) {
  if (!n.present() || !n.v->is_object()) n.fail("object");
  for (auto it = n.v->begin(); it != n.v->end(); ++it) {
    bool known = false;
    for (std::string_view a : allowed) known = known || a == it.key();
    if (!known) n[it.key()].fail("one of the keys " + join(allowed), "unknown key " + dump_safe(json(it.key())));
  }
}

void check_array(const Node& n, bool non_empty) {
  if (!n.present() || !n.v->is_array()) n.fail(non_empty ? "non-empty array" : "array");
  if (non_empty && n.v->empty()) n.fail("non-empty array");
}

double number_in(const Node& n, const Range& r, std::string_view what) {
  if (!n.present() || !n.v->is_number()) n.fail(std::string(what));
  double d = n.v->get<double>();
  // Values are stored as float: anything that overflows float is as bad as Inf.
  if (!std::isfinite(d) || !std::isfinite(static_cast<float>(d))) n.fail("finite " + std::string(what));
  if (!r.contains(d)) n.fail(std::string(what));
  return d;
}

// nullopt default means the key is required.
float get_float(const Node& n, const Range& r, std::optional<float> def) {
  if (!n.present() && def) return *def;
  return static_cast<float>(number_in(n, r, r.text()));
}

uint32_t get_uint(const Node& n, uint32_t lo, uint32_t hi, std::optional<uint32_t> def) {
  if (!n.present() && def) return *def;
  std::string what = fmt::format("integer in [{}, {}]", lo, hi);
  double d = number_in(n, Range{static_cast<double>(lo), static_cast<double>(hi)}, what);
  if (d != std::floor(d)) n.fail(what);
  return static_cast<uint32_t>(d);
}

bool get_bool(const Node& n, bool def) {
  if (!n.present()) return def;
  if (!n.v->is_boolean()) n.fail("true or false");
  return n.v->get<bool>();
}

template <int N>
std::array<float, N> get_floats(const Node& n, const Range& r, std::optional<std::array<float, N>> def) {
  if (!n.present() && def) return *def;
  std::string what = fmt::format("array of {} numbers", N);
  if (!n.present() || !n.v->is_array() || n.v->size() != N) n.fail(what);
  std::array<float, N> out{};
  for (int i = 0; i < N; ++i) out[i] = static_cast<float>(number_in(n[i], r, r.text()));
  return out;
}

Vec3 get_vec3(const Node& n, const Range& r, std::optional<Vec3> def) {
  auto a = get_floats<3>(n, r, def ? std::optional<std::array<float, 3>>({def->x, def->y, def->z}) : std::nullopt);
  return {a[0], a[1], a[2]};
}

Vec2 get_vec2(const Node& n, const Range& r, std::optional<Vec2> def) {
  auto a = get_floats<2>(n, r, def ? std::optional<std::array<float, 2>>({def->x, def->y}) : std::nullopt);
  return {a[0], a[1]};
}

Vec3 get_direction(const Node& n, std::optional<Vec3> def) {
  if (!n.present() && def) return *def;
  Vec3 d = get_vec3(n, kAny, std::nullopt);
  if (!(length(d) > 0) || !std::isfinite(length(d)))
    n.fail("non-zero direction vector", fmt::format("[{}, {}, {}]", d.x, d.y, d.z));
  return normalize(d);
}

std::string get_string(const Node& n, std::optional<std::string> def) {
  if (!n.present() && def) return *def;
  if (!n.present() || !n.v->is_string()) n.fail("string");
  return n.v->get<std::string>();
}

template <typename E>
E get_enum(const Node& n, std::initializer_list<std::pair<std::string_view, E>> names, std::optional<E> def) {
  if (!n.present() && def) return *def;
  std::string what = "one of";
  for (auto& [name, value] : names) what += fmt::format("{} \"{}\"", what.size() > 6 ? "," : "", name);
  if (!n.present() || !n.v->is_string()) n.fail(what);
  std::string s = n.v->get<std::string>();
  for (auto& [name, value] : names)
    if (name == s) return value;
  n.fail(what);
}

Material parse_material(const Node& n, const std::string& name) {
  check_object(n, {"albedo", "roughness", "metalness", "emissive", "translucency", "alpha", "alpha_cutoff",
                   "opacity", "texture", "albedo2", "texture_scale", "brdf", "sheen"});
  Material m;
  m.name = name;
  m.albedo = get_vec3(n["albedo"], kUnit, m.albedo);
  m.roughness = get_float(n["roughness"], kUnit, m.roughness);
  m.metalness = get_float(n["metalness"], kUnit, m.metalness);
  m.emissive = get_vec3(n["emissive"], kNonNegative, m.emissive);
  m.translucency = get_float(n["translucency"], kUnit, m.translucency);
  m.alpha = get_enum<AlphaKind>(n["alpha"],
                                {{"none", AlphaKind::none}, {"leaf_mask", AlphaKind::leaf_mask},
                                 {"checker_mask", AlphaKind::checker_mask}, {"opacity", AlphaKind::opacity}},
                                m.alpha);
  m.alpha_cutoff = get_float(n["alpha_cutoff"], kUnit, m.alpha_cutoff);
  m.opacity = get_float(n["opacity"], kUnit, m.opacity);
  m.texture = get_enum<TextureKind>(
      n["texture"],
      {{"none", TextureKind::none}, {"checker", TextureKind::checker}, {"value_noise", TextureKind::value_noise}},
      m.texture);
  m.albedo2 = get_vec3(n["albedo2"], kUnit, m.albedo2);
  m.texture_scale = get_float(n["texture_scale"], kPositive, m.texture_scale);
  m.brdf = get_enum<BrdfKind>(n["brdf"], {{"standard", BrdfKind::standard}, {"cloth", BrdfKind::cloth}, {"glossy", BrdfKind::glossy}}, m.brdf);
  Node sheen = n["sheen"];
  if (m.brdf == BrdfKind::cloth) {
    // The sheen lobe is the cloth class; a cloth without one is the standard BRDF by another name.
    m.sheen = get_float(sheen, Range{0.0, 1.0, true, false}, std::nullopt);
    // Cloth reflects only: the thin-translucency model is the standard class's.
    if (m.translucency > 0)
      n["translucency"].fail("0 for brdf \"cloth\" (cloth does not transmit)", describe(*n["translucency"].v));
  } else if (sheen.present()) {
    const char* kind = m.brdf == BrdfKind::glossy ? "no sheen for brdf \"glossy\" (sheen is the cloth class's lobe: set \"brdf\": \"cloth\")"
                                                  : "no sheen for brdf \"standard\" (sheen is the cloth class's lobe: set \"brdf\": \"cloth\")";
    sheen.fail(kind, describe(*sheen.v));
  }
  // The glossy class's base is opaque: the thin-translucency model is the standard class's.
  if (m.brdf == BrdfKind::glossy && m.translucency > 0)
    n["translucency"].fail("0 for brdf \"glossy\" (glossy does not transmit)", describe(*n["translucency"].v));
  return m;
}

Decal parse_decal(const Node& n, size_t index) {
  check_object(n, {"name", "position", "size", "rotate_deg", "albedo", "opacity", "shape"});
  Decal d;
  d.name = get_string(n["name"], "decal" + std::to_string(index));
  d.position = get_vec3(n["position"], kAny, std::nullopt);
  d.size = get_vec3(n["size"], kPositive, std::nullopt);
  d.rotation_deg = get_vec3(n["rotate_deg"], kAny, d.rotation_deg);
  d.albedo = get_vec3(n["albedo"], kUnit, std::nullopt);
  d.opacity = get_float(n["opacity"], kUnit, d.opacity);
  d.shape = get_enum<DecalShape>(n["shape"], {{"rect", DecalShape::rect}, {"disc", DecalShape::disc}}, d.shape);
  return d;
}

IndoorVolume parse_indoor_volume(const Node& n, size_t index) {
  check_object(n, {"name", "min", "max"});
  IndoorVolume v;
  v.name = get_string(n["name"], "indoor" + std::to_string(index));
  v.min = get_vec3(n["min"], kAny, std::nullopt);
  v.max = get_vec3(n["max"], kAny, std::nullopt);
  if (!(v.min.x < v.max.x && v.min.y < v.max.y && v.min.z < v.max.z))
    n["max"].fail("a corner above \"min\" on every axis",
                  fmt::format("[{}, {}, {}] with min [{}, {}, {}]", v.max.x, v.max.y, v.max.z, v.min.x, v.min.y, v.min.z));
  return v;
}

// A primitive description reduced to a canonical key (equal descriptions share one Mesh,
// whatever defaults were spelled out) and a builder.
struct Primitive {
  std::string key;
  Mesh (*build)(const Primitive&) = nullptr;
  Vec3 size3{1, 1, 1};
  Vec2 size2{1, 1};
  float radius = 0.5f, height = 1.0f, thickness = 0.02f;
  uint32_t segments = 32, count = 64, seed = 1;
  bool capped = true;
  bool solid = false;  // the object key "solid"'s default: thin_slab (a wall with a thickness)
  Facing facing = Facing::pos_y;
  Mesh mesh;         // type "mesh": the triangles as written
  std::string name;  // Mesh::name when the key is too long to read (mesh); empty: the key
};

constexpr uint32_t kMaxSegments = 4096;
constexpr uint32_t kMaxCards = 1000000;
constexpr size_t kMaxMeshVertices = 1u << 24;

Facing get_facing(const Node& n, Facing def) {
  return get_enum<Facing>(n,
                          {{"+x", Facing::pos_x}, {"-x", Facing::neg_x}, {"+y", Facing::pos_y},
                           {"-y", Facing::neg_y}, {"+z", Facing::pos_z}, {"-z", Facing::neg_z}},
                          def);
}

// An array with one element per mesh position (normals, uvs).
void check_per_vertex(const Node& n, size_t count, std::string_view what) {
  if (!n.v->is_array() || n.v->size() != count)
    n.fail(fmt::format("array of {} {} (one per position)", count, what));
}

// Explicit triangles, kept exactly as written: zero-area triangles (a repeated index, collinear
// vertices), duplicate vertices and zero-length or null (NaN) normals are valid input, which the
// degenerate-geometry case feeds to the renderer. Positions, normals and UVs must be finite
// numbers; null is the one way to write a non-finite (NaN) normal. Without normals every vertex
// gets a zero normal, which shading replaces by the face normal (flat shading).
Mesh parse_mesh(const Node& n) {
  check_object(n, {"type", "positions", "indices", "normals", "uvs"});
  Mesh m;
  Node pos = n["positions"];
  check_array(pos, true);
  if (pos.v->size() > kMaxMeshVertices)
    pos.fail(fmt::format("at most {} positions", kMaxMeshVertices), describe(*pos.v));
  for (size_t i = 0; i < pos.v->size(); ++i) m.positions.push_back(get_vec3(pos[i], kAny, std::nullopt));
  const uint32_t last = static_cast<uint32_t>(m.positions.size() - 1);

  Node idx = n["indices"];
  check_array(idx, true);
  for (size_t t = 0; t < idx.v->size(); ++t) {
    Node tri = idx[t];
    if (!tri.v->is_array() || tri.v->size() != 3) tri.fail("array of 3 vertex indices");
    for (size_t k = 0; k < 3; ++k) m.indices.push_back(get_uint(tri[k], 0, last, std::nullopt));
  }

  Node normals = n["normals"];
  if (normals.present()) {
    check_per_vertex(normals, m.positions.size(), "normals");
    for (size_t i = 0; i < normals.v->size(); ++i) {
      Node e = normals[i];
      if (e.v->is_null()) {
        const float nan = std::numeric_limits<float>::quiet_NaN();
        m.normals.push_back({nan, nan, nan});
        continue;
      }
      if (!e.v->is_array() || e.v->size() != 3) e.fail("array of 3 numbers or null");
      m.normals.push_back(get_vec3(e, kAny, std::nullopt));
    }
  }
  Node uvs = n["uvs"];
  if (uvs.present()) {
    check_per_vertex(uvs, m.positions.size(), "uvs");
    for (size_t i = 0; i < uvs.v->size(); ++i) m.uvs.push_back(get_vec2(uvs[i], kAny, std::nullopt));
  }
  return m;
}

Primitive parse_primitive(const Node& n) {
  if (!n.present() || !n.v->is_object()) n.fail("object");
  enum class Type { box, quad, sphere, cylinder, thin_slab, leaf_cards, mesh };
  Type type = get_enum<Type>(n["type"],
                             {{"box", Type::box}, {"quad", Type::quad}, {"sphere", Type::sphere},
                              {"cylinder", Type::cylinder}, {"thin_slab", Type::thin_slab},
                              {"leaf_cards", Type::leaf_cards}, {"mesh", Type::mesh}},
                             std::nullopt);
  Primitive p;
  switch (type) {
    case Type::box:
      check_object(n, {"type", "size"});
      p.size3 = get_vec3(n["size"], kPositive, p.size3);
      p.key = fmt::format("box size={},{},{}", p.size3.x, p.size3.y, p.size3.z);
      p.build = [](const Primitive& q) { return make_box(q.size3); };
      break;
    case Type::quad:
      check_object(n, {"type", "size", "facing"});
      p.size2 = get_vec2(n["size"], kPositive, p.size2);
      p.facing = get_facing(n["facing"], Facing::pos_y);
      p.key = fmt::format("quad size={},{} facing={}", p.size2.x, p.size2.y, facing_name(p.facing));
      p.build = [](const Primitive& q) { return make_quad(q.size2, q.facing); };
      break;
    case Type::sphere:
      check_object(n, {"type", "radius", "segments"});
      p.radius = get_float(n["radius"], kPositive, p.radius);
      p.segments = get_uint(n["segments"], 3, kMaxSegments, p.segments);
      p.key = fmt::format("sphere radius={} segments={}", p.radius, p.segments);
      p.build = [](const Primitive& q) { return make_sphere(q.radius, q.segments); };
      break;
    case Type::cylinder:
      check_object(n, {"type", "radius", "height", "segments", "capped"});
      p.radius = get_float(n["radius"], kPositive, p.radius);
      p.height = get_float(n["height"], kPositive, p.height);
      p.segments = get_uint(n["segments"], 3, kMaxSegments, p.segments);
      p.capped = get_bool(n["capped"], p.capped);
      p.key = fmt::format("cylinder radius={} height={} segments={} capped={}", p.radius, p.height, p.segments,
                          p.capped);
      p.build = [](const Primitive& q) { return make_cylinder(q.radius, q.height, q.segments, q.capped); };
      break;
    case Type::thin_slab:
      check_object(n, {"type", "size", "thickness", "facing"});
      p.size2 = get_vec2(n["size"], kPositive, p.size2);
      p.thickness = get_float(n["thickness"], kPositive, p.thickness);
      p.facing = get_facing(n["facing"], Facing::pos_z);
      p.key = fmt::format("thin_slab size={},{} thickness={} facing={}", p.size2.x, p.size2.y, p.thickness,
                          facing_name(p.facing));
      p.build = [](const Primitive& q) { return make_thin_slab(q.size2, q.thickness, q.facing); };
      p.solid = true;
      break;
    case Type::leaf_cards:
      check_object(n, {"type", "count", "region", "card_size", "seed"});
      p.count = get_uint(n["count"], 1, kMaxCards, p.count);
      p.size3 = get_vec3(n["region"], kPositive, p.size3);
      p.size2 = get_vec2(n["card_size"], kPositive, Vec2{0.1f, 0.1f});
      p.seed = get_uint(n["seed"], 0, std::numeric_limits<uint32_t>::max(), p.seed);
      p.key = fmt::format("leaf_cards count={} region={},{},{} card_size={},{} seed={}", p.count, p.size3.x,
                          p.size3.y, p.size3.z, p.size2.x, p.size2.y, p.seed);
      p.build = [](const Primitive& q) { return make_leaf_cards(q.count, q.size3, q.size2, q.seed); };
      break;
    case Type::mesh:
      p.mesh = parse_mesh(n);
      // The whole description is the key: identical meshes share one Mesh.
      p.key = "mesh " + dump_safe(*n.v);
      p.name = fmt::format("mesh positions={} triangles={}", p.mesh.positions.size(), p.mesh.indices.size() / 3);
      p.build = [](const Primitive& q) { return q.mesh; };
      break;
  }
  return p;
}

struct Trs {
  Vec3 t{0, 0, 0}, r{0, 0, 0}, s{1, 1, 1};
};

// Scale is any finite value: zero collapses an instance and negative mirrors it, both of
// which the degenerate-geometry stress cases need.
Trs parse_trs(const Node& n, const Trs& def) {
  Trs out;
  out.t = get_vec3(n["translate"], kAny, def.t);
  out.r = get_vec3(n["rotate_deg"], kAny, def.r);
  out.s = get_vec3(n["scale"], kAny, def.s);
  return out;
}

// Keys must be strictly increasing in time so interpolation can binary-search them.
float get_key_time(const Node& n, size_t index, float previous) {
  float t = get_float(n, kAny, std::nullopt);
  if (index > 0 && !(t > previous)) n.fail(fmt::format("time > {} (the previous key's)", previous), describe(*n.v));
  return t;
}

Instance parse_object(const Node& n, size_t index, const std::map<std::string, uint32_t>& material_index,
                      std::map<std::string, uint32_t>& mesh_index, std::vector<Mesh>& meshes) {
  check_object(n, {"type", "name", "primitive", "material", "transform", "animation", "removed_at", "solid"});
  Instance inst;
  inst.name = get_string(n["name"], "object" + std::to_string(index));

  Primitive prim = parse_primitive(n["primitive"]);
  auto [it, inserted] = mesh_index.try_emplace(prim.key, static_cast<uint32_t>(meshes.size()));
  if (inserted) {
    meshes.push_back(prim.build(prim));
    meshes.back().name = prim.name.empty() ? prim.key : prim.name;
  }
  inst.mesh = it->second;
  Node solid = n["solid"];
  inst.solid = get_bool(solid, prim.solid);
  if (inst.solid && !meshes[inst.mesh].closed)
    solid.fail("false: only a closed primitive (box, thin_slab, sphere, capped cylinder) can be solid", "true");

  Node mat = n["material"];
  std::string mat_name = get_string(mat, std::nullopt);
  auto m = material_index.find(mat_name);
  if (m == material_index.end()) {
    std::string names;
    for (auto& [name, i] : material_index) names += (names.empty() ? "" : ", ") + name;
    mat.fail("the name of a material (" + names + ")");
  }
  inst.material = m->second;

  Trs base;
  Node tr = n["transform"];
  if (tr.present()) {
    check_object(tr, {"translate", "rotate_deg", "scale"});
    base = parse_trs(tr, base);
  }
  inst.transform = Mat4::trs(base.t, base.r, base.s);

  Node anim = n["animation"];
  if (anim.present()) {
    check_array(anim, true);
    for (size_t k = 0; k < anim.v->size(); ++k) {
      Node key = anim[k];
      check_object(key, {"time", "translate", "rotate_deg", "scale"});
      Keyframe kf;
      kf.time = get_key_time(key["time"], k, k ? inst.animation.back().time : 0.0f);
      Trs trs = parse_trs(key, base);  // missing channels hold the static transform
      kf.translation = trs.t;
      kf.rotation_deg = trs.r;
      kf.scale = trs.s;
      inst.animation.push_back(kf);
    }
  }
  if (n["removed_at"].present()) inst.removed_at = get_float(n["removed_at"], kNonNegative, std::nullopt);
  return inst;
}

// What the "gltf" objects of one scene file share: where relative paths start, and whether the
// scene file sets the camera and the sun itself (then the glTF files' are not taken).
struct GltfObjects {
  std::filesystem::path base_dir;
  bool scene_camera = false, scene_sun = false;
  bool camera_taken = false;  // an earlier glTF object supplied the camera
};

enum class ObjectType { primitive, gltf };

ObjectType object_type(const Node& n) {
  if (!n.present() || !n.v->is_object()) n.fail("object");
  return get_enum<ObjectType>(n["type"], {{"primitive", ObjectType::primitive}, {"gltf", ObjectType::gltf}},
                              ObjectType::primitive);
}

// {"type": "gltf", "file": ..., "name", "transform"}: the file's default scene, placed by the
// transform (cases/scenes/README.md, "glTF objects"). Problems inside the file are SceneErrors
// naming the glTF file (gltf_import.h); the key's own problems name this scene file.
void import_gltf_object(const Node& n, size_t index, Scene& scene, GltfObjects& shared) {
  check_object(n, {"type", "name", "file", "transform"});
  const std::string name = get_string(n["name"], "object" + std::to_string(index));
  Node file = n["file"];
  const std::string rel = get_string(file, std::nullopt);
  const std::filesystem::path path = std::filesystem::path(rel).is_absolute() ? std::filesystem::path(rel) : shared.base_dir / rel;
  std::error_code ec;
  if (rel.empty() || !std::filesystem::is_regular_file(path, ec))
    file.fail("a .gltf or .glb file (relative to the scene file)",
              fmt::format("{} ({})", describe(*file.v), rel.empty() ? "empty" : "no such file: " + path.string()));
  Trs trs;
  Node tr = n["transform"];
  if (tr.present()) {
    check_object(tr, {"translate", "rotate_deg", "scale"});
    trs = parse_trs(tr, trs);
  }
  GltfImportOptions options;
  options.instance_prefix = name + "/";
  options.take_camera = !shared.scene_camera && !shared.camera_taken;
  options.take_sun = !shared.scene_sun;
  const GltfImportReport report = import_gltf(scene, path.string(), Mat4::trs(trs.t, trs.r, trs.s), options);
  shared.camera_taken = shared.camera_taken || report.camera;
  scene.imports.push_back(scene_import(report));
}

LocalLight parse_light(const Node& n) {
  if (!n.present() || !n.v->is_object()) n.fail("object");
  LocalLight l;
  l.kind = get_enum<LightKind>(n["type"], {{"point", LightKind::point}, {"spot", LightKind::spot}}, std::nullopt);
  if (l.kind == LightKind::point)
    check_object(n, {"type", "position", "intensity", "range"});
  else
    check_object(n, {"type", "position", "direction", "intensity", "range", "inner_cone_deg", "outer_cone_deg"});
  l.position = get_vec3(n["position"], kAny, std::nullopt);
  l.intensity = get_vec3(n["intensity"], kNonNegative, std::nullopt);
  l.range = get_float(n["range"], kPositive, l.range);
  if (l.kind == LightKind::spot) {
    l.direction = get_direction(n["direction"], std::nullopt);
    l.outer_cone_deg = get_float(n["outer_cone_deg"], Range{0.0, 90.0, true}, l.outer_cone_deg);
    Node inner = n["inner_cone_deg"];
    l.inner_cone_deg = get_float(inner, Range{0.0, 90.0}, std::fmin(l.inner_cone_deg, l.outer_cone_deg));
    if (l.inner_cone_deg > l.outer_cone_deg)
      inner.fail(fmt::format("number <= outer_cone_deg ({})", l.outer_cone_deg), describe(*inner.v));
  }
  return l;
}

Sun parse_sun(const Node& n) {
  check_object(n, {"enabled", "direction", "irradiance", "angular_radius_deg", "animation"});
  Sun s;
  s.enabled = get_bool(n["enabled"], true);
  s.direction = get_direction(n["direction"], std::nullopt);
  s.irradiance = get_vec3(n["irradiance"], kNonNegative, std::nullopt);
  s.angular_radius_deg = get_float(n["angular_radius_deg"], Range{0.0, 45.0}, s.angular_radius_deg);
  Node anim = n["animation"];
  if (anim.present()) {
    check_array(anim, true);
    for (size_t k = 0; k < anim.v->size(); ++k) {
      Node key = anim[k];
      check_object(key, {"time", "direction", "irradiance"});
      SunKey sk;
      sk.time = get_key_time(key["time"], k, k ? s.animation.back().time : 0.0f);
      sk.direction = get_direction(key["direction"], s.direction);
      sk.irradiance = get_vec3(key["irradiance"], kNonNegative, s.irradiance);
      // Between keys the direction turns along the shorter arc; opposite directions have none.
      if (k && dot(sk.direction, s.animation.back().direction) < -0.999f)
        key["direction"].fail("a direction less than 177 degrees from the previous key's (the sun turns along the shorter arc)",
                              fmt::format("[{}, {}, {}]", sk.direction.x, sk.direction.y, sk.direction.z));
      s.animation.push_back(sk);
    }
  }
  return s;
}

Sky parse_sky(const Node& n) {
  if (!n.present() || !n.v->is_object()) n.fail("object");
  Sky s;
  s.kind = get_enum<SkyKind>(n["type"],
                             {{"none", SkyKind::none}, {"constant", SkyKind::constant},
                              {"gradient", SkyKind::gradient}, {"analytic", SkyKind::analytic}},
                             std::nullopt);
  switch (s.kind) {
    case SkyKind::none: check_object(n, {"type"}); break;
    case SkyKind::constant:
      check_object(n, {"type", "radiance"});
      s.radiance = get_vec3(n["radiance"], kNonNegative, std::nullopt);
      break;
    case SkyKind::gradient:
      check_object(n, {"type", "radiance", "horizon", "ground"});
      s.radiance = get_vec3(n["radiance"], kNonNegative, std::nullopt);
      s.horizon = get_vec3(n["horizon"], kNonNegative, std::nullopt);
      s.ground = get_vec3(n["ground"], kNonNegative, Vec3{0, 0, 0});
      break;
    case SkyKind::analytic:
      check_object(n, {"type", "radiance", "horizon", "ground", "turbidity"});
      s.radiance = get_vec3(n["radiance"], kNonNegative, Vec3{1, 1, 1});
      s.horizon = get_vec3(n["horizon"], kNonNegative, Vec3{1, 1, 1});
      s.ground = get_vec3(n["ground"], kNonNegative, Vec3{0, 0, 0});
      s.turbidity = get_float(n["turbidity"], Range{1.0, 10.0}, s.turbidity);
      break;
  }
  return s;
}

void check_eye_target(const Node& target_node, Vec3 position, Vec3 target) {
  if (position == target)
    target_node.fail("target different from position",
                     fmt::format("[{}, {}, {}] (same as position)", target.x, target.y, target.z));
}

Camera parse_camera(const Node& n) {
  check_object(n, {"position", "target", "up", "fov_y_deg", "near", "far", "animation"});
  Camera c;
  const Range fov{0.0, 180.0, true, true};
  c.position = get_vec3(n["position"], kAny, c.position);
  c.target = get_vec3(n["target"], kAny, c.target);
  check_eye_target(n["target"], c.position, c.target);
  c.up = get_direction(n["up"], c.up);
  c.fov_y_deg = get_float(n["fov_y_deg"], fov, c.fov_y_deg);
  c.near_plane = get_float(n["near"], kPositive, c.near_plane);
  c.far_plane = get_float(n["far"], Range{c.near_plane, std::numeric_limits<double>::infinity(), true},
                          c.far_plane);
  Node anim = n["animation"];
  if (anim.present()) {
    check_array(anim, true);
    for (size_t k = 0; k < anim.v->size(); ++k) {
      Node key = anim[k];
      check_object(key, {"time", "position", "target", "fov_y_deg"});
      CameraKey ck;
      ck.time = get_key_time(key["time"], k, k ? c.animation.back().time : 0.0f);
      ck.position = get_vec3(key["position"], kAny, c.position);
      ck.target = get_vec3(key["target"], kAny, c.target);
      check_eye_target(key["target"].present() ? key["target"] : key["position"], ck.position, ck.target);
      ck.fov_y_deg = get_float(key["fov_y_deg"], fov, c.fov_y_deg);
      c.animation.push_back(ck);
    }
  }
  return c;
}

Scene parse_document(const json& doc, const std::string& source_name) {
  Node root{&doc, "", &source_name};
  check_object(root, {"materials", "objects", "lights", "decals", "indoor_volumes", "sun", "sky", "camera", "frame_time"});
  Scene scene;
  scene.source = source_name;

  Node objects = root["objects"];
  check_array(objects, true);
  // The library is needed only by primitive objects (each names a material); glTF objects bring
  // their files' materials.
  bool primitives = false;
  for (size_t i = 0; i < objects.v->size(); ++i) primitives = primitives || object_type(objects[i]) == ObjectType::primitive;
  Node mats = root["materials"];
  if ((primitives || mats.present()) && (!mats.present() || !mats.v->is_object() || mats.v->empty()))
    mats.fail("non-empty object of materials (primitive objects name one)");
  std::map<std::string, uint32_t> material_index;
  if (mats.present())
    for (auto it = mats.v->begin(); it != mats.v->end(); ++it) {
      if (it.key().empty()) mats[it.key()].fail("non-empty material name", "\"\"");
      material_index[it.key()] = static_cast<uint32_t>(scene.materials.size());
      scene.materials.push_back(parse_material(mats[it.key()], it.key()));
    }

  std::map<std::string, uint32_t> mesh_index;
  GltfObjects gltf{std::filesystem::path(source_name).parent_path(), root["camera"].present(), root["sun"].present()};
  for (size_t i = 0; i < objects.v->size(); ++i) {
    if (object_type(objects[i]) == ObjectType::gltf)
      import_gltf_object(objects[i], i, scene, gltf);
    else
      scene.instances.push_back(parse_object(objects[i], i, material_index, mesh_index, scene.meshes));
  }

  Node lights = root["lights"];
  if (lights.present()) {
    check_array(lights, false);
    for (size_t i = 0; i < lights.v->size(); ++i) scene.lights.push_back(parse_light(lights[i]));
  }
  Node decals = root["decals"];
  if (decals.present()) {
    check_array(decals, false);
    if (decals.v->size() > kMaxDecals)
      decals.fail(fmt::format("at most {} decals (the frame constants hold {})", kMaxDecals, kMaxDecals),
                  fmt::format("{} decals", decals.v->size()));
    for (size_t i = 0; i < decals.v->size(); ++i) scene.decals.push_back(parse_decal(decals[i], i));
  }
  Node indoor = root["indoor_volumes"];
  if (indoor.present()) {
    check_array(indoor, false);
    if (indoor.v->size() > kMaxIndoorVolumes)
      indoor.fail(fmt::format("at most {} indoor volumes (the frame constants hold {})", kMaxIndoorVolumes, kMaxIndoorVolumes),
                  fmt::format("{} volumes", indoor.v->size()));
    for (size_t i = 0; i < indoor.v->size(); ++i) scene.indoor_volumes.push_back(parse_indoor_volume(indoor[i], i));
  }
  if (root["sun"].present()) scene.sun = parse_sun(root["sun"]);
  if (root["sky"].present()) scene.sky = parse_sky(root["sky"]);
  if (root["camera"].present()) scene.camera = parse_camera(root["camera"]);
  scene.frame_time = get_float(root["frame_time"], kPositive, scene.frame_time);
  return scene;
}

std::string one_line(std::string s) {
  for (char& c : s)
    if (c == '\n' || c == '\r') c = ' ';
  return s;
}


}  // namespace

Scene parse_scene(const nlohmann::json& doc, const std::string& source_name) {
  try {
    return parse_document(doc, source_name);
  } catch (const json::exception& e) {
    // Every access is type-checked first; this is a safety net so a missed check still
    // reports the file instead of escaping as a library exception.
    throw SceneError(one_line(fmt::format("{}: expected a valid scene, got {}", source_name, e.what())));
  }
}

Scene load_scene(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw SceneError(fmt::format("{}: expected a scene file, got a directory", path));
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(fmt::format("{}: expected a readable file, got {}", path, std::strerror(errno)));
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw SceneError(fmt::format("{}: expected a readable file, got a read error", path));

  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::parse_error& e) {
    // nlohmann only knows the byte offset reliably; count lines ourselves.
    size_t end = std::min<size_t>(e.byte > 0 ? e.byte - 1 : 0, text.size());
    size_t line = 1, column = 1;
    for (size_t i = 0; i < end; ++i) {
      if (text[i] == '\n') { ++line; column = 1; } else { ++column; }
    }
    std::string why = e.what();
    if (auto colon = why.find(": "); colon != std::string::npos) why = why.substr(colon + 2);
    throw SceneError(ascii_line(fmt::format("{}: line {}, column {}: expected valid JSON, got {}", path, line, column, why)));
  } catch (const json::exception& e) {
    // e.g. a number literal that overflows double ("1e999"): no position is reported.
    std::string why = e.what();
    if (auto bracket = why.find("] "); bracket != std::string::npos) why = why.substr(bracket + 2);
    throw SceneError(ascii_line(fmt::format("{}: expected valid JSON, got {}", path, why)));
  }
  return parse_scene(doc, path);
}

}  // namespace gib
