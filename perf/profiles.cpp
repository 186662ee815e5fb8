#include "perf/profiles.h"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <unistd.h>

#include "perf/project_files.h"

namespace gib::perf {
namespace {

using ojson = nlohmann::ordered_json;

std::string read_text(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw PerfError(fmt::format("{}: cannot open (expected a JSON file)", path));
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

ojson parse_json(const std::string& text, const std::string& file) {
  try {
    return ojson::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw PerfError(fmt::format("{}: expected valid JSON, got a parse error: {}", file, e.what()));
  }
}

std::string got(const ojson& v) {
  std::string s = v.dump();
  if (s.size() > 40) s = s.substr(0, 37) + "...";
  return fmt::format("{} {}", v.type_name(), s);
}

const ojson& member(const ojson& obj, const std::string& key, const std::string& file, const std::string& ptr,
                    const char* expected) {
  if (!obj.is_object()) throw PerfError(fmt::format("{}: {}: expected an object, got {}", file, ptr, got(obj)));
  auto it = obj.find(key);
  if (it == obj.end()) throw PerfError(fmt::format("{}: {}/{}: expected {}, got nothing (missing)", file, ptr, key, expected));
  return *it;
}

double positive(const ojson& obj, const std::string& key, const std::string& file, const std::string& ptr) {
  const ojson& v = member(obj, key, file, ptr, "a positive number");
  if (!v.is_number() || !(v.get<double>() > 0))
    throw PerfError(fmt::format("{}: {}/{}: expected a positive number, got {}", file, ptr, key, got(v)));
  return v.get<double>();
}

std::pair<uint32_t, uint32_t> resolution(const ojson& obj, const std::string& file, const std::string& ptr) {
  const ojson& r = member(obj, "resolution", file, ptr, "[width, height]");
  if (!r.is_array() || r.size() != 2 || !r[0].is_number_unsigned() || !r[1].is_number_unsigned() ||
      r[0].get<uint64_t>() == 0 || r[1].get<uint64_t>() == 0 || r[0].get<uint64_t>() > 65536 ||
      r[1].get<uint64_t>() > 65536)
    throw PerfError(fmt::format("{}: {}/resolution: expected [width, height] of positive integers, got {}", file, ptr, got(r)));
  return {r[0].get<uint32_t>(), r[1].get<uint32_t>()};
}

}  // namespace

std::vector<ConsoleProfile> parse_profiles(const std::string& text, const std::string& file) {
  ojson j = parse_json(text, file);
  const ojson& profiles = member(j, "profiles", file, "", "an object of profiles");
  if (!profiles.is_object() || profiles.empty())
    throw PerfError(fmt::format("{}: /profiles: expected a non-empty object, got {}", file, got(profiles)));
  std::vector<ConsoleProfile> out;
  for (auto& [name, p] : profiles.items()) {
    std::string ptr = "/profiles/" + name;
    ConsoleProfile c;
    c.name = name;
    if (!p.is_object()) throw PerfError(fmt::format("{}: {}: expected an object, got {}", file, ptr, got(p)));
    c.label = p.value("label", name);
    c.fp32_tflops = positive(p, "fp32_tflops", file, ptr);
    c.bandwidth_gbs = positive(p, "bandwidth_gbs", file, ptr);
    if (p.contains("rops")) {  // fill rate = ROPs x clock; the clock must be given with them
      const ojson& r = p["rops"];
      if (!r.is_number_unsigned() || r.get<uint64_t>() == 0)
        throw PerfError(fmt::format("{}: {}/rops: expected a positive integer, got {}", file, ptr, got(r)));
      if (!p.contains("clock_ghz"))
        throw PerfError(fmt::format("{}: {}/clock_ghz: expected the clock (GHz) that rops is multiplied by, got none", file, ptr));
      c.fill_gpix = double(r.get<uint64_t>()) * positive(p, "clock_ghz", file, ptr);
    }
    const ojson& t = member(p, "targets", file, ptr, "an object with resolution");
    std::tie(c.width, c.height) = resolution(t, file, ptr + "/targets");
    if (t.contains("probes_per_frame")) {
      const ojson& v = t["probes_per_frame"];
      if (!v.is_number_unsigned() || v.get<uint64_t>() == 0)
        throw PerfError(fmt::format("{}: {}/targets/probes_per_frame: expected a positive integer, got {}", file, ptr, got(v)));
      c.probes_per_frame = v.get<uint32_t>();
    }
    if (p.contains("resident_threads_per_cu")) {  // resident threads = compute_units x this
      for (const char* key : {"compute_units", "resident_threads_per_cu"}) {
        const ojson& v = member(p, key, file, ptr, "a positive integer (with resident_threads_per_cu)");
        if (!v.is_number_unsigned() || v.get<uint64_t>() == 0)
          throw PerfError(fmt::format("{}: {}/{}: expected a positive integer, got {}", file, ptr, key, got(v)));
      }
      c.resident_threads = p["compute_units"].get<uint64_t>() * p["resident_threads_per_cu"].get<uint64_t>();
    }
    if (t.contains("gi_trace_scale")) c.gi_trace_scale = positive(t, "gi_trace_scale", file, ptr + "/targets");
    if (p.contains("wave_size")) {
      const ojson& w = p["wave_size"];
      if (!w.is_array()) throw PerfError(fmt::format("{}: {}/wave_size: expected an array of integers, got {}", file, ptr, got(w)));
      for (auto& x : w) {
        if (!x.is_number_unsigned())
          throw PerfError(fmt::format("{}: {}/wave_size: expected an array of integers, got {}", file, ptr, got(w)));
        c.wave_size.push_back(x.get<uint32_t>());
      }
    }
    out.push_back(std::move(c));
  }
  return out;
}

std::vector<ConsoleProfile> load_profiles(const std::string& path) { return parse_profiles(read_text(path), path); }

std::vector<ConsoleProfile> select_profiles(const std::vector<ConsoleProfile>& all, const std::string& names) {
  if (names == "all") return all;
  std::vector<ConsoleProfile> out;
  std::stringstream ss(names);
  std::string name;
  while (std::getline(ss, name, ',')) {
    auto it = std::find_if(all.begin(), all.end(), [&](auto& p) { return p.name == name; });
    if (it == all.end()) {
      std::vector<std::string> known;
      for (auto& p : all) known.push_back(p.name);
      throw PerfError(fmt::format("--profile: expected all or one of [{}], got '{}'", fmt::join(known, ", "), name));
    }
    out.push_back(*it);
  }
  if (out.empty()) throw PerfError("--profile: expected all or a profile name, got ''");
  return out;
}

const SeedPlatform* SeedTable::find(const std::string& profile, const std::string& column) const {
  for (auto& p : platforms)
    if (p.profile == profile && p.column == column) return &p;
  return nullptr;
}

namespace {

double milliseconds(const ojson& v, const std::string& file, const std::string& ptr) {
  if (!v.is_number() || v.get<double>() < 0)
    throw PerfError(fmt::format("{}: {}: expected milliseconds (a number >= 0), got {}", file, ptr, got(v)));
  return v.get<double>();
}

// A table's "platforms" object: per platform its rows in milliseconds, at its own "resolution"
// (has_resolution) or at 2560x1440 (per-probe tables); "probes_per_frame" is a budget, not a row.
std::vector<SeedPlatform> read_platforms(const ojson& table, const std::string& file, const std::string& base,
                                         bool has_resolution) {
  const ojson& plats = member(table, "platforms", file, base, "an object of platforms");
  if (!plats.is_object()) throw PerfError(fmt::format("{}: {}/platforms: expected an object, got {}", file, base, got(plats)));
  std::vector<SeedPlatform> out;
  for (auto& [name, p] : plats.items()) {
    std::string ptr = base + "/platforms/" + name;
    SeedPlatform sp;
    sp.profile = name;
    if (has_resolution)
      std::tie(sp.width, sp.height) = resolution(p, file, ptr);
    else
      std::tie(sp.width, sp.height) = std::pair<uint32_t, uint32_t>(2560, 1440);
    for (auto& [k, v] : p.items())
      if (k != "resolution" && k != "probes_per_frame") sp.ms[k] = milliseconds(v, file, ptr + "/" + k);
    out.push_back(std::move(sp));
  }
  return out;
}

// idTech 8's "Hotspot Performance" table: a row set per platform, each at its own resolution.
SeedTable idtech8_table(const ojson& j, const std::string& file) {
  SeedTable t;
  t.name = "idtech8_gi_hotspot";
  t.technique = "radiance-cache";
  // World sampling is the probe ray tracing; the radiance cache row covers update + shading;
  // irradiance volumes their update.
  t.pass_row = {{"probe_trace", "world_sampling"},
                {"radiance_cache_update", "radiance_cache"},
                {"radiance_cache_shade", "radiance_cache"},
                {"irradiance_volume_update", "irradiance_volumes"},
                {"final_gather", "final_gather"},
                {"gi_denoise", "denoise"},
                {"gi_upscale", "upscale"}};
  t.total_row = "total_serial";
  const ojson& table = member(j, t.name, file, "", "the idTech 8 hotspot table");
  const std::string base = "/" + t.name;
  t.source = table.value("source", "");
  t.platforms = read_platforms(table, file, base, true);
  return t;
}

// DOOM: The Dark Ages' "Detailed Performance Results" ("Siege" scene, Xbox Series X, 2560x1440,
// no resolution scaling): a row is milliseconds (the same in both columns) or
// {"no_vrcs": ms, "vrcs": ms}; "overall_no_async" is the sum of its rows.
SeedTable doom_table(const ojson& j, const std::string& file) {
  SeedTable t;
  t.name = "doom_visibility_buffer";
  t.technique = "deferred";
  // The visibility pass (rasterisation) is not in the seed's table; tile classification has no
  // row of its own there either (the seed counts it with the lighting it prepares).
  t.pass_row = {{"material_classify", "pixel_commands_and_dispatch_args"},
                {"attribute_interpolate", "attribute_interpolation"},
                {"vrcs_rate", "vrcs_shading_rate"},
                {"deferred_texturing", "deferred_texturing"},
                {"gbuffer_update", "gbuffer_update"},
                {"tile_classify", "deferred_lighting"},
                {"deferred_lighting", "deferred_lighting"}};
  t.column_option = "vrcs";
  t.column_of_value = {{0.0, "no_vrcs"}, {1.0, "vrcs"}};
  t.total_row = "overall_no_async";
  const ojson& table = member(j, t.name, file, "", "the DOOM visibility buffer table");
  const std::string base = "/" + t.name;
  t.source = table.value("source", "") + ", 'Detailed Performance Results' (Siege scene, Xbox Series X, 2560x1440)";
  const std::string key = "siege_scene_xbox_series_x_1440p_ms";
  const ojson& rows = member(table, key, file, base, "an object of per-pass milliseconds");
  if (!rows.is_object()) throw PerfError(fmt::format("{}: {}/{}: expected an object, got {}", file, base, key, got(rows)));
  for (auto& [value, column] : t.column_of_value) {
    SeedPlatform sp;
    sp.profile = "xbox-series-x";
    sp.column = column;
    sp.width = 2560;
    sp.height = 1440;
    for (auto& [k, v] : rows.items()) {
      const std::string ptr = base + "/" + key + "/" + k;
      // Not rows of ours: the Forward+ pass, and the async total (derived from frame-time
      // differences, not a sum of rows).
      if (k == "forward_plus_opaque" || k == "overall_async") continue;
      // The seed's own total names its columns by path ("deferred", "deferred_vrcs").
      const std::string col = k == "overall_no_async" ? (column == "vrcs" ? "deferred_vrcs" : "deferred") : column;
      if (v.is_object()) {
        if (!v.contains(col)) throw PerfError(fmt::format("{}: {}/{}: expected milliseconds, got nothing (missing)", file, ptr, col));
        sp.ms[k] = milliseconds(v[col], file, ptr + "/" + col);
      } else if (!(k == "vrcs_shading_rate" && column == "no_vrcs")) {  // the rate runs only with VRCS
        sp.ms[k] = milliseconds(v, file, ptr);
      }
    }
    t.platforms.push_back(std::move(sp));
  }
  return t;
}

// AC Shadows' probe update and diffuse GI tables: a row set per platform. The probe update
// has no resolution (it is per probe): its rows are compared at the bench's 2560x1440; its
// "probes_per_frame" is the budget, not a row. Sun shadows have no pass of ours (the shadow rays
// are traced inside probe_gbuffer), so that row is compared through the total only.
SeedTable ac_shadows_table(const ojson& j, const std::string& file, const std::string& name,
                           std::map<std::string, std::string> pass_row, bool has_resolution) {
  SeedTable t;
  t.name = name;
  t.technique = "probe-volume";
  t.pass_row = std::move(pass_row);
  t.total_row = "total";
  const ojson& table = member(j, t.name, file, "", "an AC Shadows timing table");
  const std::string base = "/" + t.name;
  t.source = table.value("source", "");
  t.platforms = read_platforms(table, file, base, has_resolution);
  return t;
}

// God of War Ragnarok's per-pass costs ("Performance numbers given at 4K on PS5"): the shadow
// captions' two views (PCF and contact hardening each; columns shot_1, shot_2) and the
// reflections' profiler capture (column rt_cubemaps). Our reflections_rt_cubemap traces and
// combines in one pass, so it is compared with the sum of the seed's BVH trace and combine;
// ssdo_ssgi (or, with ss_combined 0, ssdo and ssgi) with the seed's combined SSR + SSDO + SSGI
// pass (we have no SSR there: the screen trace is inside reflections_rt_cubemap). Ray binning has no pass of ours; cubemap_capture is
// baked offline in the game (no row).
SeedTable gow_table(const ojson& j, const std::string& file) {
  SeedTable t;
  t.name = "god_of_war_ragnarok";
  t.technique = "gow-ragnarok";
  t.pass_row = {{"shadows_pcf", "pcf"},
                {"shadows_contact_hardening", "contact_hardening"},
                {"reflections_rt_cubemap", "bvh_trace_plus_combine_half_res"},
                {"reflections_resolve", "resolve_full_res"},
                {"ssdo_ssgi", "ssr_ssdo_ssgi"},
                {"ssdo", "ssr_ssdo_ssgi"},
                {"ssgi", "ssr_ssdo_ssgi"}};
  t.own_workload = true;
  const ojson& table = member(j, t.name, file, "", "the God of War Ragnarok timings");
  const std::string base = "/" + t.name;
  t.source = table.value("source", "") + " (PS5 at 4K)";
  const ojson& w = member(table, "workload", file, base, "an object with platform and resolution");
  const ojson& plat = member(w, "platform", file, base + "/workload", "a console profile name");
  if (!plat.is_string())
    throw PerfError(fmt::format("{}: {}/workload/platform: expected a console profile name, got {}", file, base, got(plat)));
  const auto [width, height] = resolution(w, file, base + "/workload");
  auto platform = [&](const std::string& column) {
    SeedPlatform sp;
    sp.profile = plat.get<std::string>();
    sp.column = column;
    sp.width = width;
    sp.height = height;
    return sp;
  };
  const std::string shadows = "shadows_ps5_4k_ms";
  const ojson& sh = member(table, shadows, file, base, "an object of [view 1, view 2] milliseconds");
  SeedPlatform shot[2] = {platform("shot_1"), platform("shot_2")};
  for (const char* row : {"pcf", "contact_hardening"}) {
    const std::string ptr = base + "/" + shadows + "/" + row;
    const ojson& v = member(sh, row, file, base + "/" + shadows, "[view 1, view 2] milliseconds");
    if (!v.is_array() || v.size() != 2)
      throw PerfError(fmt::format("{}: {}: expected [view 1, view 2] milliseconds, got {}", file, ptr, got(v)));
    for (size_t i = 0; i < 2; ++i) shot[i].ms[row] = milliseconds(v[i], file, fmt::format("{}/{}", ptr, i));
  }
  const std::string refl = "raytraced_cubemaps_ps5_4k_ms";
  const ojson& rc = member(table, refl, file, base, "an object of per-pass milliseconds");
  auto ms = [&](const char* key) {
    return milliseconds(member(rc, key, file, base + "/" + refl, "milliseconds"), file, base + "/" + refl + "/" + key);
  };
  SeedPlatform cubemaps = platform("rt_cubemaps");
  cubemaps.ms["bvh_trace_plus_combine_half_res"] = ms("bvh_trace_half_res") + ms("combine_half_res");
  cubemaps.ms["resolve_full_res"] = ms("resolve_full_res");
  cubemaps.ms["ssr_ssdo_ssgi"] = ms("ssr_ssdo_ssgi");
  t.platforms = {shot[0], shot[1], cubemaps};
  return t;
}

}  // namespace

std::vector<SeedTable> parse_seed_tables(const std::string& text, const std::string& file) {
  ojson j = parse_json(text, file);
  return {idtech8_table(j, file), doom_table(j, file),
          ac_shadows_table(j, file, "ac_shadows_probe_update",
                           {{"probe_gbuffer", "gbuffer_update"},
                            {"probe_relight", "lighting_update"},
                            {"probe_convolve", "lighting_convolution"},
                            {"probe_relocate", "probe_relocation"}},
                           false),
          ac_shadows_table(j, file, "ac_shadows_diffuse_gi",
                           {{"screen_trace", "ss_tracing"},
                            {"world_trace", "ws_tracing"},
                            {"hit_lighting", "lighting"},
                            {"pixel_denoise", "denoising"},
                            {"pixel_upscale", "denoising"}},
                           true),
          gow_table(j, file)};
}

std::vector<SeedTable> load_seed_tables(const std::string& path) { return parse_seed_tables(read_text(path), path); }

AlphaCostTable parse_alpha_cost_table(const std::string& text, const std::string& file) {
  ojson j = parse_json(text, file);
  const std::string name = "ac_shadows_alpha_test_cost";
  const ojson& table = member(j, name, file, "", "the AC Shadows alpha-test cost table");
  AlphaCostTable t;
  t.source = table.value("source", "");
  const std::pair<std::pair<uint32_t, uint32_t>, const char*> rows[] = {
      {{0, 2}, "any_hit_limit_2"},
      {{0, 4}, "any_hit_limit_4"},
      {{1, 0}, "dither_average_opacity"},
      {{1, 2}, "dither_plus_any_hit_limit_2"},
      {{2, 0}, "opaque_approximation"}};
  for (auto& [key, row] : rows) {
    const double v = positive(table, row, file, "/" + name);
    t.relative[key] = {row, v};
  }
  return t;
}

AlphaCostTable load_alpha_cost_table(const std::string& path) { return parse_alpha_cost_table(read_text(path), path); }

PassSplit split_pass(double device_ms, double bytes, const DeviceThroughput& dev) {
  PassSplit s;
  s.device_ms = std::max(0.0, device_ms);
  s.bytes = bytes;
  double mem = dev.bandwidth_gbs > 0 ? bytes / (dev.bandwidth_gbs * 1e9) * 1e3 : 0.0;
  // A pass cannot spend longer on memory than it took: when the plan's bytes at the calibrated
  // bandwidth exceed the measured time, caches served part of it; all of it counts as memory.
  s.memory_ms = std::min(mem, s.device_ms);
  s.compute_ms = s.device_ms - s.memory_ms;
  return s;
}

double scale_to_profile(const PassSplit& s, const DeviceThroughput& dev, const ConsoleProfile& p, double occupancy) {
  double mem = p.bandwidth_gbs > 0 ? s.memory_ms * dev.bandwidth_gbs / p.bandwidth_gbs : 0.0;
  double comp = p.fp32_tflops > 0 ? s.compute_ms * dev.fp32_gflops / (p.fp32_tflops * 1e3) * occupancy : 0.0;
  return mem + comp;
}

std::optional<double> scale_raster_to_profile(double device_ms, const DeviceThroughput& dev, const ConsoleProfile& p) {
  if (!(dev.fill_gpix > 0) || !(p.fill_gpix > 0)) return std::nullopt;
  return std::max(0.0, device_ms) * dev.fill_gpix / p.fill_gpix;
}

std::string find_data_dir(const std::string& override_dir) {
  namespace fs = std::filesystem;
  auto ok = [](const fs::path& d) { return fs::exists(d / "console-profiles.json"); };
  if (!override_dir.empty()) {
    if (!ok(override_dir))
      throw PerfError(fmt::format("--data-dir {}: expected a folder with console-profiles.json and seed-timings.json", override_dir));
    return override_dir;
  }
  if (const char* e = std::getenv("GIB_DATA_DIR"); e && *e) {
    if (!ok(e)) throw PerfError(fmt::format("GIB_DATA_DIR={}: expected a folder with console-profiles.json", e));
    return e;
  }
  // The working folder's data/, then the executable's (a pack), then the source tree's.
  const std::vector<fs::path> roots = project_roots();
  std::vector<fs::path> tries{roots.front() / "data"};
  std::error_code ec;
  fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    tries.push_back(exe.parent_path() / "data");
    tries.push_back(exe.parent_path().parent_path() / "data");
  }
  for (size_t i = 1; i < roots.size(); ++i) tries.push_back(roots[i] / "data");
  std::string tried;
  for (const fs::path& d : tries) {
    if (ok(d)) return fs::weakly_canonical(d).string();
    tried += (tried.empty() ? "" : ", ") + d.string();
  }
  throw PerfError(fmt::format(
      "console profiles: expected console-profiles.json in --data-dir, $GIB_DATA_DIR or a data/ folder, found none "
      "(tried {})",
      tried));
}

}  // namespace gib::perf
