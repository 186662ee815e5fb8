// Goldens: goldens/<case>/reference[.<aov>].exr (path traced) and
// goldens/<case>/<technique>.<preset>[.<device class>].exr (approved outputs), described by
// goldens/<case>/golden.json. Writes are atomic (temporary file + rename); a replaced file
// moves to goldens/<case>/history/ first, so a bad update can be undone by moving it back.
#pragma once
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>

#include "renderer/image/float_image.h"

namespace gib {

class Gpu;
struct Case;
struct CaseRender;

struct GoldenError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// "lavapipe" (CPU), "nvidia", "amd", "intel" or "other": goldens may differ per class.
std::string device_class(const std::string& driver_name, const std::string& device_name);

class GoldenStore {
 public:
  GoldenStore(std::string root, std::string case_name);
  // A store in <root>/<case>/<sub> (the GPU tier's goldens, a reference cache entry).
  GoldenStore(std::string root, std::string case_name, const std::string& sub);
  // New files are written as half-float EXR (float when a finite value would not fit in
  // half): the GPU tier's committed goldens. Readers take either.
  void set_write_half(bool on) { write_half_ = on; }
  const std::string& dir() const { return dir_; }
  // File stems: "reference", "reference.direct", "reference.direct.f010" (the reference of
  // frame 10 of an animated case), "direct.medium".
  static std::string reference_stem(const std::string& aov, const std::string& default_aov, uint32_t frame = 0);
  static std::string technique_stem(const std::string& technique, const std::string& preset);
  // The golden to compare with on `device_class`: "<stem>.<class>.exr" if present, else
  // "<stem>.exr". Empty when neither exists.
  std::string find(const std::string& stem, const std::string& device_class) const;
  // A golden or reference of this store with its record: GoldenError naming the file when it
  // is corrupt, and naming golden.json when the file's record is missing or incomplete
  // (record_of). *half (if given): stored as half floats.
  FloatImage read(const std::string& path, bool* half = nullptr) const;
  // The image alone, its record not asked for: what update-goldens reads of the file it
  // replaces, which may be one whose record was lost.
  FloatImage read_without_record(const std::string& path) const;
  // The entry golden.json keeps for `file_name` under "files": what the runs read about the
  // file besides its pixels. A path-traced reference (reference[.<aov>][.fNNN].exr) records its
  // "aov", "spp" and "device" (and its noise floor once measured, which the 3x rule reads); an
  // approved output (<technique>.<preset>[.<class>].exr) its "technique", "preset" and "device".
  // GoldenError, one line naming golden.json, the file, what is expected and how to restore or
  // re-approve it, when golden.json, the entry or one of those fields is missing.
  nlohmann::json record_of(const std::string& file_name) const;
  // True for a path-traced reference's file name (reference_stem + ".exr"), false for an
  // approved output's (technique_stem, "reference.<preset>" included).
  static bool is_reference_file(const std::string& file_name);
  // Writes atomically; moves an existing file to history/<stem>.<utc timestamp>.exr and
  // returns that history path ("" when nothing was replaced).
  std::string write(const std::string& stem, const std::string& device_class, const FloatImage& image);
  // golden.json: {"files": {"<file name>": {...metadata}}, "noise_floor": {...}}
  nlohmann::json metadata() const;  // {} when absent
  void write_metadata(const nlohmann::json& j);  // atomic
  // The CI device class (lavapipe) and "" own the plain name; other classes get a suffix.
  // Path-traced references are written with "" (one file for every device: a converged
  // reference is the truth, whichever device rendered it).
  std::string file_name(const std::string& stem, const std::string& device_class) const;

 private:
  std::string root_, case_, sub_, dir_;
  bool write_half_ = false;
};

// The reference noise floor: FLIP (the case's flip_mode and ppd) between the reference rendered
// with reference_seed and with reference_seed + 1000, at c.reference_spp (callers pass a copy of
// the case with the spp they render at), at the last evaluation frame for per-frame references.
// Measured on every AOV the reference produces; "flip" is the case's output AOV. Returns
// {"flip", "aov", "aovs": {aov: flip}, "spp", "seeds", "device_class", "device", "driver",
// "date"[, "at_frame"]}. `first`: the reference_seed render already made (update-goldens), or
// null to render both here (run --noise-floor).
// `progress` (may be empty) sees the frames of each render it makes.
nlohmann::json measure_noise_floor(Gpu& gpu, const Case& c, const CaseRender* first = nullptr,
                                   const std::function<void(uint32_t, uint32_t)>& progress = {});
// Stores a measured floor in golden.json: the top-level "noise_floor" (what the check below
// reads) and, on every path-traced reference file's entry (one with an "aov"), "noise_floor"
// {"flip" (of that file's AOV), "aov", "spp", "seeds"}.
void record_noise_floor(nlohmann::json& meta, const nlohmann::json& floor);
// The spp golden.json records for the case's committed reference (output AOV; the last frame's
// for per-frame references): the truth about the committed file. c.reference_spp when absent
// (c.reference_spp is the default for re-rendering only).
uint32_t recorded_reference_spp(const Case& c, const nlohmann::json& meta);

// A committed reference is converged when two seeds differ by at most this FLIP at the case's size.
inline constexpr double kReferenceNoiseFloorMax = 0.01;
// A bound tighter than 3x the reference's own noise measures the reference, not the technique.
inline constexpr double kNoiseFloorFactor = 3.0;
// Throws CaseError (one line naming the case file, the run, the threshold and 3 x the floor)
// when a run's whole-image "flip" max against the reference is below kNoiseFloorFactor x the
// noise floor recorded in `meta` (golden.json) for the AOV that run compares with. No floor
// recorded (or none for that AOV): no check. `where` names golden.json in the message.
void check_noise_floor_bounds(const Case& c, const nlohmann::json& meta, const std::string& where);

std::string utc_now_iso();
std::string renderer_revision();  // git revision the binary was built from
std::string fnv1a_hex(const std::string& text);

}  // namespace gib
