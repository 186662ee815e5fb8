// Fuzzing the glTF import: thousands of mutants of small valid files (byte flips, truncations,
// JSON field replacements and removals, BIN chunk corruption), bounded in count and time. Every
// outcome must be a successful import whose scene flattens, or one SceneError line naming the
// file: nothing else escapes, nothing crashes (CI also runs it under ASan: see
// cases/scenes/README.md, "glTF objects").
#include <gtest/gtest.h>

#include <chrono>
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

#include "renderer/scene/gltf_import.h"
#include "renderer/scene/scene.h"
#include "renderer/scene/scene_loader.h"
#include "tests/gltf_test_content.h"
#include "tests/temp_dir.h"

namespace gib {
namespace {

using json = nlohmann::json;
using Clock = std::chrono::steady_clock;

struct Tally {
  size_t imported = 0, rejected = 0, escaped = 0;
};

void try_import(const std::vector<uint8_t>& bytes, const std::string& name, const std::string& base, Tally& t) {
  try {
    Scene s;
    import_gltf_bytes(s, bytes, name, base, Mat4::trs({1, 2, 3}, {10, 20, 30}, {1, 2, 1}));
    flatten(s, 0.0f);  // an accepted file must give valid indices and references
    ++t.imported;
  } catch (const SceneError& e) {
    ++t.rejected;
    const std::string msg = e.what();
    if (msg.rfind(name + ": ", 0) != 0 || msg.find("expected ") == std::string::npos || msg.find('\n') != std::string::npos) {
      ++t.escaped;
      ADD_FAILURE() << "malformed message: " << msg;
    }
  } catch (const std::exception& e) {
    ++t.escaped;
    ADD_FAILURE() << name << ": escaped as " << e.what();
  }
}

// Leaves and containers of a document, as JSON pointers: the places a mutation can hit.
std::vector<json::json_pointer> pointers(const json& doc) {
  std::vector<json::json_pointer> out;
  const json flat = doc.flatten();
  for (auto it = flat.begin(); it != flat.end(); ++it)
    for (json::json_pointer p(it.key()); !p.empty(); p = p.parent_pointer()) out.push_back(p);
  return out;
}

json mutate_json(const json& doc, const std::vector<json::json_pointer>& places, std::mt19937& rng) {
  static const json values[] = {nullptr, true, -1, 0, 1, 2, 3, 4, 7, 255, 65535, 4294967295u, 4294967296u, 1e9, -1e9, 1e39,
                                0.5, "x", "TRIANGLES", json::array(), json::object(), json::array({0, 0, 0}), "KHR_x"};
  json out = doc;
  const int edits = 1 + static_cast<int>(rng() % 3);
  for (int e = 0; e < edits; ++e) {
    const json::json_pointer& p = places[rng() % places.size()];
    if (!out.contains(p)) continue;
    if (rng() % 4 == 0) {  // remove the key or element
      json& parent = out[p.parent_pointer()];
      if (parent.is_object()) parent.erase(p.back());
      else if (parent.is_array()) parent.erase(static_cast<size_t>(std::stoul(p.back())));
    } else {
      out[p] = values[rng() % std::size(values)];
    }
  }
  return out;
}

std::vector<uint8_t> flip_bytes(std::vector<uint8_t> bytes, std::mt19937& rng, size_t from = 0) {
  const int flips = 1 + static_cast<int>(rng() % 8);
  for (int k = 0; k < flips && bytes.size() > from; ++k) {
    const size_t at = from + rng() % (bytes.size() - from);
    bytes[at] = rng() % 2 ? static_cast<uint8_t>(rng()) : static_cast<uint8_t>(bytes[at] ^ (1u << (rng() % 8)));
  }
  return bytes;
}

size_t env_number(const char* name, size_t fallback) {
  const char* v = std::getenv(name);
  return v && *v ? static_cast<size_t>(std::strtoull(v, nullptr, 10)) : fallback;
}

TEST(GltfFuzz, MutantsImportOrFailWithOneLine) {
  // 5 kinds x 2000 mutants or 20 s, whichever comes first; GIB_GLTF_FUZZ_SEED and
  // GIB_GLTF_FUZZ_COUNT (mutants per kind) make longer or different runs.
  const size_t per_kind = env_number("GIB_GLTF_FUZZ_COUNT", 2000);
  const auto budget = std::chrono::seconds(env_number("GIB_GLTF_FUZZ_SECONDS", 20));
  const Clock::time_point start = Clock::now();
  std::mt19937 rng(static_cast<uint32_t>(env_number("GIB_GLTF_FUZZ_SEED", 18)));
  test::TempDir dir;
  const test::GltfContent seed = test::rich_content();
  const std::vector<uint8_t> glb = test::to_glb(seed);
  dir.write("rich.bin", std::string(seed.bin.begin(), seed.bin.end()));
  const std::vector<uint8_t> gltf = test::to_gltf(seed, "rich.bin");   // external buffer
  const std::vector<uint8_t> embedded = test::to_gltf(seed);           // data URI buffer
  const size_t bin_start = glb.size() - seed.bin.size();
  const std::vector<json::json_pointer> places = pointers(seed.doc);

  Tally kinds[5];
  const char* names[5] = {"glb byte flips", "glb truncations", "glb JSON fields", "glb BIN bytes", "gltf bytes/fields"};
  size_t total = 0;
  for (size_t i = 0; i < per_kind && Clock::now() - start < budget; ++i) {
    try_import(flip_bytes(glb, rng), "m.glb", dir.str(), kinds[0]);
    std::vector<uint8_t> cut(glb.begin(), glb.begin() + static_cast<std::ptrdiff_t>(rng() % glb.size()));
    try_import(cut, "m.glb", dir.str(), kinds[1]);
    test::GltfContent mutant = seed;
    mutant.doc = mutate_json(seed.doc, places, rng);
    try_import(test::to_glb(mutant), "m.glb", dir.str(), kinds[2]);
    try_import(flip_bytes(glb, rng, bin_start), "m.glb", dir.str(), kinds[3]);
    switch (rng() % 3) {
      case 0: try_import(flip_bytes(gltf, rng), "m.gltf", dir.str(), kinds[4]); break;
      case 1: try_import(test::to_gltf(mutant, "rich.bin"), "m.gltf", dir.str(), kinds[4]); break;
      default: try_import(flip_bytes(embedded, rng), "m.gltf", dir.str(), kinds[4]); break;
    }
    total += 5;
  }
  size_t escaped = 0;
  for (int k = 0; k < 5; ++k) {
    std::printf("[ GltfFuzz ] %-18s %5zu imported %5zu rejected %zu escaped\n", names[k], kinds[k].imported, kinds[k].rejected,
                kinds[k].escaped);
    escaped += kinds[k].escaped;
  }
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  std::printf("[ GltfFuzz ] %zu mutants in %.1f s, %zu escaped\n", total, seconds, escaped);
  RecordProperty("mutants", static_cast<int>(total));
  EXPECT_EQ(escaped, 0u);
  EXPECT_GE(total, std::min<size_t>(1000, 5 * per_kind)) << "the time budget cut the run short";
  EXPECT_GT(kinds[2].imported, 0u);  // some field mutations are harmless
  EXPECT_GT(kinds[2].rejected, 0u);
}

}  // namespace
}  // namespace gib
