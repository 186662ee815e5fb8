#include "renderer/scene/gltf_schema.h"

#include <fmt/format.h>

#include <array>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "renderer/scene/json_messages.h"

namespace gib::gltf {

namespace {

using json = nlohmann::json;

constexpr std::string_view kDraco = "KHR_draco_mesh_compression";
constexpr std::array<std::string_view, 2> kSupported = {"KHR_lights_punctual", "KHR_materials_emissive_strength"};

// ---------------------------------------------------------------- the table

enum class Kind { string, boolean, number, integer, index, object, objects, numbers, indices, strings, index_map, index_maps };

struct Prop {
  std::string_view name;
  Kind kind;
  std::string_view target = {};             // index kinds: the root array indexed ("nodes")
  const std::vector<Prop>* props = nullptr;  // object kinds: the object's (each element's) properties
  int64_t lo = 0;                            // integer: minimum; numbers: length (0: any); objects: minimum count
  int64_t hi = std::numeric_limits<int64_t>::max();  // integer: maximum
  bool required = false;
};
using Props = std::vector<Prop>;

Prop req(Prop p) {
  p.required = true;
  return p;
}
Prop str(std::string_view n) { return {n, Kind::string}; }
Prop boolean(std::string_view n) { return {n, Kind::boolean}; }
Prop num(std::string_view n) { return {n, Kind::number}; }
Prop integer(std::string_view n, int64_t lo, int64_t hi = std::numeric_limits<int64_t>::max()) {
  return {n, Kind::integer, {}, nullptr, lo, hi};
}
Prop numbers(std::string_view n, int64_t length) { return {n, Kind::numbers, {}, nullptr, length}; }
Prop index(std::string_view n, std::string_view target) { return {n, Kind::index, target}; }
Prop indices(std::string_view n, std::string_view target) { return {n, Kind::indices, target}; }
Prop index_map(std::string_view n, std::string_view target) { return {n, Kind::index_map, target}; }
Prop index_maps(std::string_view n, std::string_view target) { return {n, Kind::index_maps, target}; }
Prop object(std::string_view n, const Props& p) { return {n, Kind::object, {}, &p}; }
Prop objects(std::string_view n, const Props& p, int64_t min_count = 0) { return {n, Kind::objects, {}, &p, min_count}; }
Prop strings(std::string_view n) { return {n, Kind::strings}; }

// glTF 2.0's core schema (the JSON Schema files of the specification), as far as types,
// required properties, integer minimums, fixed array lengths and index targets go.
const Props& root_props() {
  static const Props texture_info = {req(index("index", "textures")), integer("texCoord", 0)};
  static const Props normal_info = {req(index("index", "textures")), integer("texCoord", 0), num("scale")};
  static const Props occlusion_info = {req(index("index", "textures")), integer("texCoord", 0), num("strength")};
  static const Props pbr = {numbers("baseColorFactor", 4), object("baseColorTexture", texture_info), num("metallicFactor"),
                            num("roughnessFactor"), object("metallicRoughnessTexture", texture_info)};
  static const Props material = {str("name"), object("pbrMetallicRoughness", pbr), object("normalTexture", normal_info),
                                 object("occlusionTexture", occlusion_info), object("emissiveTexture", texture_info),
                                 numbers("emissiveFactor", 3), str("alphaMode"), num("alphaCutoff"), boolean("doubleSided")};
  static const Props primitive = {req(index_map("attributes", "accessors")), index("indices", "accessors"),
                                  index("material", "materials"), integer("mode", 0, 6), index_maps("targets", "accessors")};
  static const Props mesh = {str("name"), req(objects("primitives", primitive, 1)), numbers("weights", 0)};
  static const Props node = {str("name"), index("camera", "cameras"), indices("children", "nodes"), index("skin", "skins"),
                             numbers("matrix", 16), index("mesh", "meshes"), numbers("rotation", 4), numbers("scale", 3),
                             numbers("translation", 3), numbers("weights", 0)};
  static const Props scene = {str("name"), indices("nodes", "nodes")};
  static const Props sparse_indices = {req(index("bufferView", "bufferViews")), integer("byteOffset", 0),
                                       req(integer("componentType", 0))};
  static const Props sparse_values = {req(index("bufferView", "bufferViews")), integer("byteOffset", 0)};
  static const Props sparse = {req(integer("count", 1)), req(object("indices", sparse_indices)), req(object("values", sparse_values))};
  static const Props accessor = {str("name"), index("bufferView", "bufferViews"), integer("byteOffset", 0),
                                 req(integer("componentType", 0)), boolean("normalized"), req(integer("count", 1)),
                                 req(str("type")), numbers("max", 0), numbers("min", 0), object("sparse", sparse)};
  static const Props buffer_view = {str("name"), req(index("buffer", "buffers")), integer("byteOffset", 0),
                                    req(integer("byteLength", 1)), integer("byteStride", 4, 252), integer("target", 0)};
  static const Props buffer = {str("name"), str("uri"), req(integer("byteLength", 1))};
  static const Props texture = {str("name"), index("sampler", "samplers"), index("source", "images")};
  static const Props image = {str("name"), str("uri"), str("mimeType"), index("bufferView", "bufferViews")};
  static const Props sampler = {str("name"), integer("magFilter", 0), integer("minFilter", 0), integer("wrapS", 0),
                                integer("wrapT", 0)};
  static const Props perspective = {num("aspectRatio"), req(num("yfov")), num("zfar"), req(num("znear"))};
  static const Props orthographic = {req(num("xmag")), req(num("ymag")), req(num("zfar")), req(num("znear"))};
  static const Props camera = {str("name"), req(str("type")), object("perspective", perspective),
                               object("orthographic", orthographic)};
  static const Props skin = {str("name"), index("inverseBindMatrices", "accessors"), index("skeleton", "nodes"),
                             req(indices("joints", "nodes"))};
  static const Props channel_target = {index("node", "nodes"), req(str("path"))};
  static const Props channel = {req(integer("sampler", 0)), req(object("target", channel_target))};
  static const Props animation_sampler = {req(index("input", "accessors")), str("interpolation"), req(index("output", "accessors"))};
  static const Props animation = {str("name"), req(objects("channels", channel, 1)), req(objects("samplers", animation_sampler, 1))};
  static const Props asset = {req(str("version")), str("minVersion"), str("generator"), str("copyright")};
  static const Props root = {
      req(object("asset", asset)), index("scene", "scenes"), objects("scenes", scene), objects("nodes", node),
      objects("meshes", mesh), objects("accessors", accessor), objects("bufferViews", buffer_view), objects("buffers", buffer),
      objects("materials", material), objects("textures", texture), objects("images", image), objects("samplers", sampler),
      objects("cameras", camera), objects("skins", skin), objects("animations", animation), strings("extensionsUsed"),
      strings("extensionsRequired")};
  return root;
}

// What one element of a root array is called in messages ("mesh index in [0, 1]").
std::string_view singular(std::string_view array) {
  static const std::pair<std::string_view, std::string_view> names[] = {
      {"accessors", "accessor"}, {"animations", "animation"}, {"buffers", "buffer"}, {"bufferViews", "bufferView"},
      {"cameras", "camera"},     {"images", "image"},         {"materials", "material"}, {"meshes", "mesh"},
      {"nodes", "node"},         {"samplers", "sampler"},     {"scenes", "scene"},     {"skins", "skin"},
      {"textures", "texture"}};
  for (const auto& [plural, one] : names)
    if (plural == array) return one;
  return array;
}

// ---------------------------------------------------------------- the walk

class Checker {
 public:
  Checker(const json& doc, const Where& w) : doc_(doc), w_(w) {}

  void object(const json& v, const std::string& p, const Props& props) const {
    if (!v.is_object()) w_.fail(p, "object", json_messages::describe(v));
    if (v.contains("extensions") && !v["extensions"].is_object())
      w_.fail(p + "/extensions", "object", json_messages::describe(v["extensions"]));
    for (const Prop& prop : props) {
      const std::string key(prop.name), pp = p + "/" + key;
      if (!v.contains(key)) {
        if (prop.required) w_.fail(pp, expected(prop), "missing key");
        continue;
      }
      value(v[key], pp, prop);
    }
  }

 private:
  std::string expected(const Prop& prop) const {
    switch (prop.kind) {
      case Kind::string: return "string";
      case Kind::boolean: return "boolean";
      case Kind::number: return "number";
      case Kind::integer:
        return prop.hi == std::numeric_limits<int64_t>::max() ? fmt::format("integer >= {}", prop.lo)
                                                                : fmt::format("integer in [{}, {}]", prop.lo, prop.hi);
      case Kind::index: return index_range(prop.target);
      case Kind::object: return "object";
      case Kind::objects: return prop.lo > 0 ? "non-empty array of objects" : "array of objects";
      case Kind::numbers: return prop.lo > 0 ? fmt::format("array of {} numbers", prop.lo) : "array of numbers";
      case Kind::indices: return fmt::format("array of {} indices", singular(prop.target));
      case Kind::strings: return "array of strings";
      case Kind::index_map: return fmt::format("object of {} indices", singular(prop.target));
      case Kind::index_maps: return fmt::format("array of objects of {} indices", singular(prop.target));
    }
    return "";
  }

  std::string index_range(std::string_view target) const {
    const size_t n = count(target);
    return n ? fmt::format("{} index in [0, {}]", singular(target), n - 1)
             : fmt::format("{} index (the file has no {})", singular(target), target);
  }

  size_t count(std::string_view target) const {
    const std::string key(target);
    return doc_.contains(key) && doc_[key].is_array() ? doc_[key].size() : 0;
  }

  void index(const json& v, const std::string& p, std::string_view target) const {
    const size_t n = count(target);
    const bool ok = (v.is_number_unsigned() && v.get<uint64_t>() < n) ||
                    (v.is_number_integer() && v.get<int64_t>() >= 0 && static_cast<uint64_t>(v.get<int64_t>()) < n);
    if (!ok) w_.fail(p, index_range(target), json_messages::describe(v));
  }

  void integer(const json& v, const std::string& p, const Prop& prop) const {
    const bool ok = v.is_number_unsigned() ? v.get<uint64_t>() >= static_cast<uint64_t>(prop.lo) &&
                                                 v.get<uint64_t>() <= static_cast<uint64_t>(prop.hi)
                                           : v.is_number_integer() && v.get<int64_t>() >= prop.lo && v.get<int64_t>() <= prop.hi;
    if (!ok) w_.fail(p, expected(prop), json_messages::describe(v));
  }

  // An array whose elements each pass `element` (given the element and its pointer).
  template <class F>
  void array(const json& v, const std::string& p, const Prop& prop, F&& element) const {
    if (!v.is_array() || (prop.kind == Kind::objects && v.size() < static_cast<size_t>(prop.lo)) ||
        (prop.kind == Kind::numbers && prop.lo > 0 && v.size() != static_cast<size_t>(prop.lo)))
      w_.fail(p, expected(prop), json_messages::describe(v));
    for (size_t i = 0; i < v.size(); ++i) element(v[i], p + "/" + std::to_string(i));
  }

  void index_map(const json& v, const std::string& p, std::string_view target) const {
    if (!v.is_object()) w_.fail(p, fmt::format("object of {} indices", singular(target)), json_messages::describe(v));
    for (auto it = v.begin(); it != v.end(); ++it) index(it.value(), p + "/" + json_messages::pointer_token(it.key()), target);
  }

  void value(const json& v, const std::string& p, const Prop& prop) const {
    auto type = [&](bool ok) {
      if (!ok) w_.fail(p, expected(prop), json_messages::describe(v));
    };
    switch (prop.kind) {
      case Kind::string: return type(v.is_string());
      case Kind::boolean: return type(v.is_boolean());
      case Kind::number: return type(v.is_number());
      case Kind::integer: return integer(v, p, prop);
      case Kind::index: return index(v, p, prop.target);
      case Kind::object: return object(v, p, *prop.props);
      case Kind::index_map: return index_map(v, p, prop.target);
      case Kind::objects: return array(v, p, prop, [&](const json& e, const std::string& ep) { object(e, ep, *prop.props); });
      case Kind::index_maps:
        return array(v, p, prop, [&](const json& e, const std::string& ep) { index_map(e, ep, prop.target); });
      case Kind::indices: return array(v, p, prop, [&](const json& e, const std::string& ep) { index(e, ep, prop.target); });
      case Kind::numbers:
        return array(v, p, prop, [&](const json& e, const std::string& ep) {
          if (!e.is_number()) w_.fail(ep, "number", json_messages::describe(e));
        });
      case Kind::strings:
        return array(v, p, prop, [&](const json& e, const std::string& ep) {
          if (!e.is_string()) w_.fail(ep, "string", json_messages::describe(e));
        });
    }
  }

  const json& doc_;
  const Where& w_;
};

std::string quoted(const std::string& s) { return json_messages::describe(json(s)); }

}  // namespace

bool supported_extension(std::string_view name) {
  for (std::string_view s : kSupported)
    if (s == name) return true;
  return false;
}

void check_schema(const json& doc, const Where& where) { Checker(doc, where).object(doc, "", root_props()); }

void check_extensions(const json& doc, const Where& where) {
  if (doc.contains("extensionsRequired"))
    for (size_t i = 0; i < doc["extensionsRequired"].size(); ++i) {
      const std::string name = doc["extensionsRequired"][i].get<std::string>();
      if (!supported_extension(name))
        where.fail(fmt::format("/extensionsRequired/{}", i),
                   fmt::format("a required extension gibench supports ({}, {})", kSupported[0], kSupported[1]),
                   quoted(name) + (name == kDraco ? " (Draco-compressed meshes are not supported)" : ""));
    }
  // KHR_draco_mesh_compression used but not required: a primitive must still carry its
  // uncompressed data, which the import reads (the accessors the schema checked have a bufferView).
  if (!doc.contains("meshes")) return;
  const json& meshes = doc["meshes"];
  for (size_t i = 0; i < meshes.size(); ++i)
    for (size_t j = 0; j < meshes[i]["primitives"].size(); ++j) {
      const json& pr = meshes[i]["primitives"][j];
      if (!pr.contains("extensions") || !pr["extensions"].contains(std::string(kDraco))) continue;
      std::vector<uint64_t> used;
      for (const auto& [name, a] : pr["attributes"].items()) used.push_back(a.get<uint64_t>());
      if (pr.contains("indices")) used.push_back(pr["indices"].get<uint64_t>());
      for (uint64_t a : used)
        if (!doc["accessors"][a].contains("bufferView"))
          where.fail(fmt::format("/meshes/{}/primitives/{}/extensions/{}", i, j, kDraco),
                     fmt::format("uncompressed vertex data beside it ({} is not supported)", kDraco),
                     fmt::format("/accessors/{} without a bufferView (its data only in Draco form)", a));
    }
}

}  // namespace gib::gltf
