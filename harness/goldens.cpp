#include "harness/goldens.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <optional>
#include <unistd.h>
#include <vector>

#include "harness/case.h"
#include "harness/case_render.h"
#include "harness/image_io.h"
#include "metrics/flip.h"
#include "renderer/techniques/aov.h"
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

GoldenStore::GoldenStore(std::string root, std::string case_name, const std::string& sub)
    : root_(std::move(root)), case_(std::move(case_name)), sub_(sub), dir_((fs::path(root_) / case_ / sub).string()) {}

std::string GoldenStore::reference_stem(const std::string& aov, const std::string& default_aov, uint32_t frame) {
  std::string stem = aov.empty() || aov == default_aov ? "reference" : "reference." + aov;
  return frame ? fmt::format("{}.f{:03}", stem, frame) : stem;
}

std::string GoldenStore::technique_stem(const std::string& technique, const std::string& preset) {
  return technique + "." + preset;
}

// The CI device class (lavapipe) and "" (references) own the plain name; other classes get a suffix.
std::string GoldenStore::file_name(const std::string& stem, const std::string& cls) const {
  return cls.empty() || cls == "lavapipe" ? stem + ".exr" : stem + "." + cls + ".exr";
}

std::string GoldenStore::find(const std::string& stem, const std::string& cls) const {
  for (auto name : {file_name(stem, cls), stem + ".exr"}) {
    fs::path p = fs::path(dir_) / name;
    if (fs::exists(p)) return p.string();
  }
  return "";
}

namespace {

FloatImage read_golden_image(const std::string& path, bool* half) {
  try {
    return read_image(path, half);
  } catch (const std::exception& e) {
    throw GoldenError(fmt::format("{}: expected a readable EXR golden, got: {}", path, e.what()));
  }
}

}  // namespace

FloatImage GoldenStore::read(const std::string& path, bool* half) const {
  FloatImage image = read_golden_image(path, half);
  record_of(fs::path(path).filename().string());
  return image;
}

FloatImage GoldenStore::read_without_record(const std::string& path) const { return read_golden_image(path, nullptr); }

bool GoldenStore::is_reference_file(const std::string& file) {
  std::vector<std::string> parts;
  for (size_t at = 0;;) {
    const size_t dot = file.find('.', at);
    parts.push_back(file.substr(at, dot == std::string::npos ? std::string::npos : dot - at));
    if (dot == std::string::npos) break;
    at = dot + 1;
  }
  if (parts.size() < 2 || parts.front() != "reference" || parts.back() != "exr") return false;
  size_t i = 1;
  const size_t last = parts.size() - 1;  // "exr"
  if (i < last && std::find(kContractAovs.begin(), kContractAovs.end(), parts[i]) != kContractAovs.end()) ++i;
  auto is_frame = [](const std::string& p) {
    return p.size() > 1 && p[0] == 'f' && std::all_of(p.begin() + 1, p.end(), [](char c) { return c >= '0' && c <= '9'; });
  };
  if (i < last && is_frame(parts[i])) ++i;
  return i == last;
}

nlohmann::json GoldenStore::record_of(const std::string& file) const {
  const bool reference = is_reference_file(file);
  const std::string where = (fs::path(dir_) / "golden.json").string();
  // How to get the record back: golden.json is committed (restore it), or the file is approved
  // again, which writes both; a reference cache entry is rendered again.
  std::string fix;
  if (!sub_.empty() && sub_ != "gpu") {
    fix = fmt::format("render the entry again with: gibench references --case {} --refresh", case_);
  } else if (reference) {
    fix = fmt::format("restore it from git or re-approve with: gibench update-goldens --case {} --reference "
                      "--only-reference --noise-floor --reason \"...\"",
                      case_);
  } else {
    std::string technique = file.substr(0, file.find('.'));
    technique = technique.substr(0, technique.find('+'));
    fix = fmt::format("restore it from git or re-approve with: gibench update-goldens --case {} --technique {}{} "
                      "--reason \"...\"",
                      case_, technique, sub_ == "gpu" ? " --tier gpu" : "");
  }
  const char* fields = reference ? "aov, spp, device" : "technique, preset, device";
  auto error = [&](const std::string& pointer, const std::string& got) {
    return GoldenError(fmt::format("{}: {}expected the record of {} ({}), got {}; {}", where,
                                   pointer.empty() ? "" : pointer + ": ", file, fields, got, fix));
  };
  if (!fs::exists(where)) throw error("", "no file");
  const nlohmann::json meta = metadata();
  const std::string pointer = "/files/" + file;
  if (!meta.is_object() || !meta.contains("files") || !meta["files"].is_object() || !meta["files"].contains(file))
    throw error(pointer, "no entry");
  const nlohmann::json& rec = meta["files"][file];
  if (!rec.is_object()) throw error(pointer, rec.dump());
  for (const char* f : reference ? std::vector<const char*>{"aov", "spp", "device"}
                                 : std::vector<const char*>{"technique", "preset", "device"}) {
    const bool ok = std::string(f) == "spp" ? rec.contains(f) && rec[f].is_number_unsigned() && rec[f].get<uint64_t>() > 0
                                            : rec.contains(f) && rec[f].is_string() && !rec[f].get<std::string>().empty();
    if (!ok) throw error(pointer + "/" + f, rec.contains(f) ? rec[f].dump() : "none");
  }
  return rec;
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
  write_exr(staged.string(), image, write_half_ && fits_half(image));
  try {
    if (fs::exists(target)) {
      fs::create_directories(fs::path(dir_) / "history");
      std::string stamp = utc_now_iso();
      for (auto& c : stamp) if (c == ':') c = '-';
      fs::path hist = fs::path(dir_) / "history" / (target.stem().string() + "." + stamp + ".exr");
      fs::copy_file(target, hist, fs::copy_options::overwrite_existing);
      moved = hist.string();
    }
    fs::rename(staged, target);
  } catch (...) {  // the old golden stays; the staged file goes
    std::error_code ec;
    fs::remove(staged, ec);
    throw;
  }
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
  std::string text = j.dump(2) + "\n";  // before the temporary exists: a bad value leaves nothing behind
  {
    std::ofstream out(tmp);
    out << text;
    out.close();
    if (!out) {
      std::error_code ec;
      fs::remove(tmp, ec);
      throw GoldenError(fmt::format("{}: write failed", tmp.string()));
    }
  }
  fs::rename(tmp, p);
}

nlohmann::json measure_noise_floor(Gpu& gpu, const Case& c, const CaseRender* first,
                                   const std::function<void(uint32_t, uint32_t)>& progress) {
  uint32_t at = per_frame_references(c) ? evaluation_frames(c).back() : 0;
  std::optional<CaseRender> a;
  if (!first) first = &a.emplace(render_reference(gpu, c, 0, at, progress));
  CaseRender b = render_reference(gpu, c, 1000, at, progress);
  FlipOptions fo;
  fo.ppd = c.ppd;
  fo.mode = c.flip_mode == "ldr" ? FlipOptions::Mode::ldr : FlipOptions::Mode::hdr;
  // An AOV that is black in both renders (e.g. indirect_diffuse of a scene with nothing to
  // bounce from) has no noise: floor 0 (HDR-FLIP has no exposure range for an all-black image).
  auto black = [](const FloatImage& img) {
    for (uint32_t y = 0; y < img.height; ++y)
      for (uint32_t x = 0; x < img.width; ++x)
        for (uint32_t ch = 0; ch < std::min(3u, img.channels); ++ch)
          if (img.at(x, y, ch) != 0.0f) return false;
    return true;
  };
  nlohmann::json aovs = nlohmann::json::object();
  for (auto& [aov, img] : first->aovs)
    aovs[aov] = black(img) && black(b.aovs.at(aov)) ? 0.0 : flip(img, b.aovs.at(aov), fo).mean;
  const DeviceInfo& d = gpu.info();
  nlohmann::json floor = {{"flip", aovs.contains(c.output) ? aovs[c.output].get<double>() : flip(first->image, b.image, fo).mean},
                          {"aov", c.output},
                          {"aovs", aovs},
                          {"spp", first->spp},
                          {"seeds", {c.reference_seed, c.reference_seed + 1000}},
                          {"device_class", device_class(d.driver_name, d.name)},
                          {"device", d.name},
                          {"driver", d.driver_name + " " + d.driver_info},
                          {"date", utc_now_iso()}};
  if (at) floor["at_frame"] = at;
  return floor;
}

namespace {
// The floor of `aov`: its own entry in "aovs", else "flip" when measured on that AOV (a floor
// without "aov" was measured on the case's output). Null when none describes `aov`.
std::optional<double> floor_of(const nlohmann::json& floor, const std::string& aov, const std::string& output) {
  if (floor.contains("aovs") && floor["aovs"].contains(aov)) return floor["aovs"][aov].get<double>();
  if (floor.value("aov", output) == aov && floor.contains("flip")) return floor["flip"].get<double>();
  return std::nullopt;
}
}  // namespace

void record_noise_floor(nlohmann::json& meta, const nlohmann::json& floor) {
  meta["noise_floor"] = floor;
  if (!meta.contains("files")) return;
  for (auto& [name, rec] : meta["files"].items()) {
    if (!rec.contains("aov")) continue;  // an approved technique output, not a reference
    std::string aov = rec["aov"];
    std::optional<double> f = floor_of(floor, aov, floor.value("aov", std::string()));
    if (!f) continue;
    rec["noise_floor"] = {{"flip", *f}, {"aov", aov}, {"spp", floor["spp"]}, {"seeds", floor["seeds"]}};
    if (floor.contains("at_frame")) rec["noise_floor"]["at_frame"] = floor["at_frame"];
  }
}

uint32_t recorded_reference_spp(const Case& c, const nlohmann::json& meta) {
  uint32_t at = per_frame_references(c) ? evaluation_frames(c).back() : 0;
  std::string name = GoldenStore::reference_stem(c.output, c.output, at) + ".exr";
  if (meta.contains("files") && meta["files"].contains(name) && meta["files"][name].contains("spp"))
    return meta["files"][name]["spp"].get<uint32_t>();
  return c.reference_spp;
}

void check_noise_floor_bounds(const Case& c, const nlohmann::json& meta, const std::string& where) {
  if (!meta.contains("noise_floor")) return;
  const nlohmann::json& floor = meta["noise_floor"];
  for (auto& run : c.techniques) {
    std::string aov = run.compare_aov.empty() ? c.output : run.compare_aov;
    std::optional<double> f = floor_of(floor, aov, c.output);
    if (!f) continue;
    // The floor is a whole-image mean: ROI bounds are not held to it.
    for (auto& t : run.thresholds) {
      if (t.metric != "flip" || t.against != "reference" || !t.roi.empty() || !t.max) continue;
      double bound = kNoiseFloorFactor * *f;
      if (*t.max >= bound * (1 - 1e-9)) continue;  // exactly 3x passes, whatever the rounding
      throw CaseError(fmt::format(
          "{}: run {} ({}): flip vs reference max {:.4g} is below 3 x the reference noise floor = 3 x {:.4g} = {:.4g} "
          "({} AOV, {} spp, {}): a bound tighter than 3x the reference's own noise measures the reference, not "
          "the technique",
          c.file, run.technique, fmt::join(run.presets, ", "), *t.max, *f, bound, aov,
          floor.contains("spp") ? floor["spp"].dump() : "?", where));
    }
  }
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
