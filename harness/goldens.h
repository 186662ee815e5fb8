// Goldens: goldens/<case>/reference[.<aov>].exr (path traced) and
// goldens/<case>/<technique>.<preset>[.<device class>].exr (approved outputs), described by
// goldens/<case>/golden.json. Writes are atomic (temporary file + rename); a replaced file
// moves to goldens/<case>/history/ first, so a bad update can be undone by moving it back.
#pragma once
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>

#include "renderer/image/float_image.h"

namespace gib {

struct GoldenError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// "lavapipe" (CPU), "nvidia", "amd", "intel" or "other": goldens may differ per class.
std::string device_class(const std::string& driver_name, const std::string& device_name);

class GoldenStore {
 public:
  GoldenStore(std::string root, std::string case_name);
  const std::string& dir() const { return dir_; }
  // File stems: "reference", "reference.direct", "reference.direct.f010" (the reference of
  // frame 10 of an animated case), "direct.medium".
  static std::string reference_stem(const std::string& aov, const std::string& default_aov, uint32_t frame = 0);
  static std::string technique_stem(const std::string& technique, const std::string& preset);
  // The golden to compare with on `device_class`: "<stem>.<class>.exr" if present, else
  // "<stem>.exr". Empty when neither exists.
  std::string find(const std::string& stem, const std::string& device_class) const;
  FloatImage read(const std::string& path) const;  // GoldenError naming the file when corrupt
  // Writes atomically; moves an existing file to history/<stem>.<utc timestamp>.exr and
  // returns that history path ("" when nothing was replaced).
  std::string write(const std::string& stem, const std::string& device_class, const FloatImage& image);
  // golden.json: {"files": {"<file name>": {...metadata}}, "noise_floor": {...}}
  nlohmann::json metadata() const;  // {} when absent
  void write_metadata(const nlohmann::json& j);  // atomic
  std::string file_name(const std::string& stem, const std::string& device_class) const;

 private:
  std::string root_, case_, dir_;
};

std::string utc_now_iso();
std::string renderer_revision();  // git revision the binary was built from
std::string fnv1a_hex(const std::string& text);

}  // namespace gib
