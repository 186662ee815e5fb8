#include "harness/goldens.h"

#include <fmt/format.h>

#include <chrono>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "harness/image_io.h"
#include "revision.h"

namespace fs = std::filesystem;

namespace gib {

std::string device_class(const std::string& driver, const std::string& name) {
  auto has = [](const std::string& s, const char* sub) {
    std::string l = s;
    for (auto& c : l) c = char(std::tolower(c));
    return l.find(sub) != std::string::npos;
  };
  if (has(driver, "llvmpipe") || has(name, "llvmpipe")) return "lavapipe";
  if (has(driver, "nvidia") || has(name, "nvidia")) return "nvidia";
  if (has(driver, "radv") || has(driver, "amd") || has(name, "amd") || has(name, "radeon")) return "amd";
  if (has(driver, "intel") || has(name, "intel")) return "intel";
  return "other";
}

GoldenStore::GoldenStore(std::string root, std::string case_name)
    : root_(std::move(root)), case_(std::move(case_name)), dir_((fs::path(root_) / case_).string()) {}

std::string GoldenStore::reference_stem(const std::string& aov, const std::string& default_aov, uint32_t frame) {
  std::string stem = aov.empty() || aov == default_aov ? "reference" : "reference." + aov;
  return frame ? fmt::format("{}.f{:03}", stem, frame) : stem;
}

std::string GoldenStore::technique_stem(const std::string& technique, const std::string& preset) {
  return technique + "." + preset;
}

// The CI device class (lavapipe) owns the plain name; other classes get a suffix.
std::string GoldenStore::file_name(const std::string& stem, const std::string& cls) const {
  return cls == "lavapipe" ? stem + ".exr" : stem + "." + cls + ".exr";
}

std::string GoldenStore::find(const std::string& stem, const std::string& cls) const {
  for (auto name : {file_name(stem, cls), stem + ".exr"}) {
    fs::path p = fs::path(dir_) / name;
    if (fs::exists(p)) return p.string();
  }
  return "";
}

FloatImage GoldenStore::read(const std::string& path) const {
  try {
    return read_image(path);
  } catch (const std::exception& e) {
    throw GoldenError(fmt::format("{}: expected a readable EXR golden, got: {}", path, e.what()));
  }
}

std::string utc_now_iso() {
  std::time_t t = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}

std::string GoldenStore::write(const std::string& stem, const std::string& cls, const FloatImage& image) {
  fs::create_directories(dir_);
  fs::path target = fs::path(dir_) / file_name(stem, cls);
  std::string moved;
  // Write the new file first (atomically, under a temporary name inside write_exr), then
  // move the old one to history, then rename the new into place: at no point is the golden
  // missing or partial.
  fs::path staged = fs::path(dir_) / fmt::format(".staged.{}.{}.exr", getpid(), stem);
  write_exr(staged.string(), image);
  if (fs::exists(target)) {
    fs::create_directories(fs::path(dir_) / "history");
    std::string stamp = utc_now_iso();
    for (auto& c : stamp) if (c == ':') c = '-';
    fs::path hist = fs::path(dir_) / "history" / (target.stem().string() + "." + stamp + ".exr");
    fs::copy_file(target, hist, fs::copy_options::overwrite_existing);
    moved = hist.string();
  }
  fs::rename(staged, target);
  return moved;
}

nlohmann::json GoldenStore::metadata() const {
  fs::path p = fs::path(dir_) / "golden.json";
  if (!fs::exists(p)) return nlohmann::json::object();
  std::ifstream in(p);
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw GoldenError(fmt::format("{}: expected valid JSON, got: {}", p.string(), e.what()));
  }
}

void GoldenStore::write_metadata(const nlohmann::json& j) {
  fs::create_directories(dir_);
  fs::path p = fs::path(dir_) / "golden.json";
  fs::path tmp = fs::path(dir_) / fmt::format(".golden.json.tmp{}", getpid());
  {
    std::ofstream out(tmp);
    out << j.dump(2) << "\n";
    if (!out) throw GoldenError(fmt::format("{}: write failed", tmp.string()));
  }
  fs::rename(tmp, p);
}

std::string renderer_revision() { return GIB_REVISION; }

std::string fnv1a_hex(const std::string& text) {
  uint64_t h = 1469598103934665603ull;
  for (unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return fmt::format("{:016x}", h);
}

}  // namespace gib
