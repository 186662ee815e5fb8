#include "renderer/scene/gltf_model.h"

#include <fmt/format.h>
#include <stb_image.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <exception>
#include <limits>
#include <nlohmann/json.hpp>

#include "renderer/scene/gltf_import.h"
#include "renderer/scene/gltf_schema.h"
#include "renderer/scene/json_messages.h"
#include "renderer/scene/scene_loader.h"

namespace gib::gltf {

namespace {

static_assert(std::endian::native == std::endian::little, "glTF buffers are little-endian; reads memcpy them");

// Deeper JSON than this is refused before tinygltf sees it: its extras/extensions parser
// recurses once per level, so a file of nested brackets could otherwise exhaust the stack.
constexpr int kMaxJsonDepth = 256;

// tinygltf's messages are multi-line and some quote nlohmann's exception names; one line of
// printable ASCII goes into the SceneError.
std::string one_line(std::string s) {
  for (size_t pos; (pos = s.find("[json.exception.")) != std::string::npos;) {
    size_t end = s.find("] ", pos);
    if (end == std::string::npos) break;
    s.erase(pos, end + 2 - pos);
  }
  std::string out;
  for (char c : s) {
    if (c == '\n' || c == '\r') {
      if (!out.empty() && out.back() != ' ') out += "; ";
    } else {
      out += c;
    }
  }
  while (!out.empty() && (out.back() == ' ' || out.back() == ';')) out.pop_back();
  if (out.size() > 400) out = out.substr(0, 397) + "...";
  return json_messages::ascii_line(out.empty() ? std::string("no message from the parser") : out);
}

void check_nesting(const uint8_t* text, size_t size, const Where& where) {
  int depth = 0;
  bool in_string = false, escaped = false;
  for (size_t i = 0; i < size; ++i) {
    const char c = static_cast<char>(text[i]);
    if (in_string) {
      if (escaped) escaped = false;
      else if (c == '\\') escaped = true;
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxJsonDepth)
        where.fail_file(fmt::format("JSON nested at most {} levels deep", kMaxJsonDepth),
                        fmt::format("deeper nesting at byte {}", i));
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
}

uint32_t read_u32(const uint8_t* p) {
  uint32_t v;
  std::memcpy(&v, p, 4);
  return v;
}

// The .glb container's header, checked before tinygltf reads it so a truncated or padded file
// says what is wrong with it.
void check_glb_header(const std::vector<uint8_t>& b, const Where& where) {
  if (b.size() < 20) where.fail_file("a .glb of at least 20 bytes (file and JSON chunk headers)", fmt::format("{} bytes", b.size()));
  const uint32_t version = read_u32(b.data() + 4), length = read_u32(b.data() + 8);
  const uint32_t json_length = read_u32(b.data() + 12), json_type = read_u32(b.data() + 16);
  if (version != 2) where.fail_file("a .glb of container version 2", fmt::format("version {}", version));
  if (length != b.size())
    where.fail_file(fmt::format("the {} bytes the .glb header gives", length),
                    fmt::format("{} bytes{}", b.size(), b.size() < length ? " (a truncated file)" : ""));
  if (json_type != 0x4E4F534Au) where.fail_file("a .glb whose first chunk is JSON", fmt::format("chunk type 0x{:08x}", json_type));
  if (uint64_t{json_length} + 20 > b.size())
    where.fail_file(fmt::format("a JSON chunk inside the file ({} bytes after the headers)", b.size() - 20),
                    fmt::format("a chunk of {} bytes", json_length));
}

// tinygltf reports a missing external buffer as "File not found : <uri>"; the buffer's pointer
// is found in the document so the message says which one.
void explain_missing_buffer(const std::string& err, const uint8_t* text, size_t size, const Where& where) {
  static const std::string tag = "File not found : ";
  const size_t at = err.find(tag);
  if (at == std::string::npos) return;
  std::string uri = err.substr(at + tag.size());
  uri = uri.substr(0, uri.find('\n'));
  const nlohmann::json doc = nlohmann::json::parse(text, text + size, nullptr, false);
  if (!doc.is_object() || !doc.contains("buffers") || !doc["buffers"].is_array()) return;
  for (size_t i = 0; i < doc["buffers"].size(); ++i) {
    const nlohmann::json& b = doc["buffers"][i];
    if (b.is_object() && b.contains("uri") && b["uri"].is_string() && b["uri"].get<std::string>() == uri)
      where.fail(fmt::format("/buffers/{}/uri", i), "a readable buffer file (relative to the glTF file)",
                 json_messages::describe(nlohmann::json(uri)) + " (not found)");
  }
}

// tinygltf's image callback. URI images arrive as their file's bytes and are inspected here;
// bufferView images arrive as a pointer tinygltf computed without checking the view's range,
// so those bytes are not touched (the import checks the range, then inspects them).
bool on_image(tinygltf::Image* image, const int index, std::string*, std::string*, int, int,
              const unsigned char* bytes, int size, void* user) {
  if (image->bufferView >= 0) return true;
  auto* log = static_cast<ImageLog*>(user);
  ImageLog::Entry& e = log->by_uri[index];
  e = inspect_image(bytes, size > 0 ? static_cast<size_t>(size) : 0);
  if (e.decodable) e.bytes.assign(bytes, bytes + size);
  return true;
}

int component_size(int component_type) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_INT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;
  }
}

int type_components(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    case TINYGLTF_TYPE_MAT2: return 4;
    case TINYGLTF_TYPE_MAT3: return 9;
    case TINYGLTF_TYPE_MAT4: return 16;
    default: return 0;
  }
}

}  // namespace

void Where::fail(std::string_view pointer, std::string_view expected, std::string_view got) const {
  throw SceneError(json_messages::ascii_line(
      fmt::format("{}: {}: expected {}, got {}", file, pointer.empty() ? "/" : pointer, expected, got)));
}

void Where::fail_file(std::string_view expected, std::string_view got) const {
  throw SceneError(json_messages::ascii_line(fmt::format("{}: expected {}, got {}", file, expected, got)));
}

size_t Where::index(std::string_view pointer, int i, size_t count, std::string_view what) const {
  if (i < 0 || static_cast<size_t>(i) >= count) {
    if (count == 0) fail(pointer, fmt::format("{} index (the file has no {}s)", what, what), std::to_string(i));
    fail(pointer, fmt::format("{} index in [0, {}]", what, count - 1), std::to_string(i));
  }
  return static_cast<size_t>(i);
}

float Where::number(std::string_view pointer, double v, double lo, double hi) const {
  if (!std::isfinite(v) || !std::isfinite(static_cast<float>(v)))
    fail(pointer, "a finite number that fits a float", fmt::format("{}", v));
  if (v < lo || v > hi) {
    std::string range = std::isinf(hi) ? fmt::format("number >= {}", lo) : fmt::format("number in [{}, {}]", lo, hi);
    fail(pointer, range, fmt::format("{}", v));
  }
  return static_cast<float>(v);
}

ImageLog::Entry inspect_image(const unsigned char* bytes, size_t size) {
  ImageLog::Entry e;
  if (bytes == nullptr || size == 0) {
    e.reason = "no bytes";
    return e;
  }
  if (size > static_cast<size_t>(std::numeric_limits<int>::max())) {
    e.reason = "an image of 2 GiB or more";
    return e;
  }
  int w = 0, h = 0, c = 0;
  e.decodable = stbi_info_from_memory(bytes, static_cast<int>(size), &w, &h, &c) != 0;
  if (e.decodable) {
    e.width = w;
    e.height = h;
    e.channels = c;
  } else {
    const char* why = stbi_failure_reason();
    e.reason = why ? why : "an unknown format";
  }
  return e;
}

tinygltf::Model load_model(const std::vector<uint8_t>& bytes, const Where& where, const std::string& base_dir,
                           ImageLog& images) {
  if (bytes.empty()) where.fail_file("a glTF 2.0 file", "an empty file");
  if (bytes.size() >= std::numeric_limits<unsigned>::max())
    where.fail_file("a file smaller than 4 GiB", fmt::format("{} bytes", bytes.size()));
  const bool glb = bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
  if (glb) check_glb_header(bytes, where);
  const uint8_t* text = glb ? bytes.data() + 20 : bytes.data();
  const size_t text_size = glb ? read_u32(bytes.data() + 12) : bytes.size();
  check_nesting(text, text_size, where);
  // The schema's types, required properties and indices, on the JSON as written (tinygltf
  // would skip or default what it does not understand); JSON that does not parse is left to
  // tinygltf's message.
  const nlohmann::json doc = nlohmann::json::parse(text, text + text_size, nullptr, false);
  if (!doc.is_discarded()) {
    check_schema(doc, where);
    check_extensions(doc, where);
  }

  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(&on_image, &images);
  tinygltf::Model model;
  std::string err, warn;
  bool ok = false;
  try {
    const auto size = static_cast<unsigned>(bytes.size());
    ok = glb ? loader.LoadBinaryFromMemory(&model, &err, &warn, bytes.data(), size, base_dir)
             : loader.LoadASCIIFromString(&model, &err, &warn, reinterpret_cast<const char*>(bytes.data()), size,
                                          base_dir);
  } catch (const std::exception& e) {  // nlohmann's parse errors, std::bad_alloc
    err = e.what();
    ok = false;
  }
  if (!ok) explain_missing_buffer(err, text, text_size, where);
  if (!ok)
    where.fail_file(glb ? "a valid binary glTF 2.0 (.glb) file" : "a valid glTF 2.0 JSON file",
                    one_line(err.empty() ? warn : err));
  return model;
}

const uint8_t* buffer_view_bytes(const tinygltf::Model& m, size_t view, const Where& where) {
  const tinygltf::BufferView& v = m.bufferViews[view];
  const std::string p = "/bufferViews/" + std::to_string(view);
  const size_t b = where.index(p + "/buffer", v.buffer, m.buffers.size(), "buffer");
  const size_t size = m.buffers[b].data.size();
  if (v.byteLength < 1) where.fail(p + "/byteLength", "integer >= 1", std::to_string(v.byteLength));
  if (v.byteOffset > size || v.byteLength > size - v.byteOffset)
    where.fail(p, fmt::format("a byte range inside buffer {} ({} bytes)", b, size),
               fmt::format("byteOffset {} and byteLength {}", v.byteOffset, v.byteLength));
  return m.buffers[b].data.data() + v.byteOffset;
}

AccessorData accessor(const tinygltf::Model& m, int index, const Where& where, const std::string& ref, int type,
                      std::initializer_list<int> component_types, std::string_view what) {
  const size_t i = where.index(ref, index, m.accessors.size(), "accessor");
  const tinygltf::Accessor& a = m.accessors[i];
  AccessorData d;
  d.pointer = "/accessors/" + std::to_string(i);
  const std::string& p = d.pointer;
  if (a.sparse.isSparse)
    where.fail(p + "/sparse", "an accessor without \"sparse\" (sparse accessors are not supported)", "a sparse accessor");
  if (a.type != type) where.fail(p + "/type", fmt::format("\"{}\" for {}", type_name(type), what), type_name(a.type));
  bool allowed = false;
  std::string names;
  for (int c : component_types) {
    allowed = allowed || c == a.componentType;
    names += (names.empty() ? "" : " or ") + component_type_name(c);
  }
  if (!allowed)
    where.fail(p + "/componentType", fmt::format("{} for {}", names, what), component_type_name(a.componentType));
  // glTF 2.0 gives no upper bound; this one keeps a corrupt count from becoming an allocation.
  if (a.count < 1 || a.count > kGltfMaxAccessorCount)
    where.fail(p + "/count", fmt::format("integer in [1, {}]", kGltfMaxAccessorCount), std::to_string(a.count));
  d.count = a.count;
  d.component_type = a.componentType;
  d.components = type_components(type);
  d.normalized = a.normalized;
  const size_t element = static_cast<size_t>(component_size(a.componentType)) * static_cast<size_t>(d.components);
  // Without a bufferView every element is zero, which only sparse accessors (refused above)
  // make useful; refusing it also keeps a tiny file from asking for gigabytes of zeros.
  if (a.bufferView == -1)
    where.fail(p + "/bufferView", "a bufferView (accessors of zeros without one are not supported)", "none");
  const size_t vi = where.index(p + "/bufferView", a.bufferView, m.bufferViews.size(), "bufferView");
  const tinygltf::BufferView& view = m.bufferViews[vi];
  const uint8_t* bytes = buffer_view_bytes(m, vi, where);
  d.stride = view.byteStride ? view.byteStride : element;
  if (view.byteStride && (view.byteStride < element || view.byteStride > 252 || view.byteStride % 4))
    where.fail("/bufferViews/" + std::to_string(vi) + "/byteStride",
               fmt::format("a multiple of 4 in [{}, 252] (for {}, {}-byte elements)", std::max<size_t>(4, element),
                           p, element),
               std::to_string(view.byteStride));
  // count <= 2^26 and stride <= 252, so the span cannot overflow 64 bits.
  const uint64_t span = static_cast<uint64_t>(d.stride) * (d.count - 1) + element;
  if (a.byteOffset > view.byteLength || span > view.byteLength - a.byteOffset)
    where.fail(p, fmt::format("elements inside bufferView {} ({} bytes)", vi, view.byteLength),
               fmt::format("{} elements of {} bytes every {} bytes from byteOffset {} ({} bytes)", d.count, element,
                           d.stride, a.byteOffset, span));
  d.data = bytes + a.byteOffset;
  return d;
}

float AccessorData::get(size_t element, int component) const {
  const uint8_t* p = data + element * stride + static_cast<size_t>(component * component_size(component_type));
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
      float f;
      std::memcpy(&f, p, 4);
      return f;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return normalized ? p[0] / 255.0f : p[0];
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      const float v = static_cast<int8_t>(p[0]);
      return normalized ? std::fmax(v / 127.0f, -1.0f) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      uint16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? v / 65535.0f : v;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      int16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? std::fmax(v / 32767.0f, -1.0f) : v;
    }
    default: return static_cast<float>(get_uint(element));
  }
}

uint32_t AccessorData::get_uint(size_t element) const {
  const uint8_t* p = data + element * stride;
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return p[0];
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      uint16_t v;
      std::memcpy(&v, p, 2);
      return v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return read_u32(p);
    default: return 0;
  }
}

std::vector<Vec3> read_vec3(const AccessorData& a, bool require_finite, const Where& where) {
  std::vector<Vec3> out(a.count);
  for (size_t i = 0; i < a.count; ++i) {
    Vec3 v{a.get(i, 0), a.get(i, 1), a.get(i, 2)};
    if (require_finite && !(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z)))
      where.fail(a.pointer, "finite values", fmt::format("[{}, {}, {}] at element {}", v.x, v.y, v.z, i));
    out[i] = v;
  }
  return out;
}

std::vector<Vec2> read_vec2(const AccessorData& a, const Where& where) {
  std::vector<Vec2> out(a.count);
  for (size_t i = 0; i < a.count; ++i) {
    Vec2 v{a.get(i, 0), a.get(i, 1)};
    if (!(std::isfinite(v.x) && std::isfinite(v.y)))
      where.fail(a.pointer, "finite values", fmt::format("[{}, {}] at element {}", v.x, v.y, i));
    out[i] = v;
  }
  return out;
}

std::vector<uint32_t> read_indices(const AccessorData& a, size_t vertex_count, const Where& where,
                                   const std::string& ref) {
  std::vector<uint32_t> out(a.count);
  for (size_t i = 0; i < a.count; ++i) {
    const uint32_t v = a.get_uint(i);
    if (v >= vertex_count)
      where.fail(ref, fmt::format("vertex indices below {} (the POSITION count)", vertex_count),
                 fmt::format("{} at element {} of {}", v, i, a.pointer));
    out[i] = v;
  }
  return out;
}

std::string component_type_name(int t) {
  switch (t) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: return "BYTE (5120)";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return "UNSIGNED_BYTE (5121)";
    case TINYGLTF_COMPONENT_TYPE_SHORT: return "SHORT (5122)";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return "UNSIGNED_SHORT (5123)";
    case TINYGLTF_COMPONENT_TYPE_INT: return "INT (5124)";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return "UNSIGNED_INT (5125)";
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return "FLOAT (5126)";
    default: return std::to_string(t);
  }
}

std::string type_name(int t) {
  switch (t) {
    case TINYGLTF_TYPE_SCALAR: return "SCALAR";
    case TINYGLTF_TYPE_VEC2: return "VEC2";
    case TINYGLTF_TYPE_VEC3: return "VEC3";
    case TINYGLTF_TYPE_VEC4: return "VEC4";
    case TINYGLTF_TYPE_MAT2: return "MAT2";
    case TINYGLTF_TYPE_MAT3: return "MAT3";
    case TINYGLTF_TYPE_MAT4: return "MAT4";
    default: return "an unknown type";
  }
}

}  // namespace gib::gltf
