#include "harness/case.h"
#include "renderer/scene/json_messages.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <iterator>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>
#include <utility>

#include "renderer/scene/scene_loader.h"
#include "renderer/techniques/technique.h"

namespace gib {

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
using json_messages::ascii_line;
using json_messages::describe;
using json_messages::dump_safe;
using json_messages::pointer_token;

// ---------------------------------------------------------------- message helpers




std::string json_quoted(std::string_view s) { return dump_safe(json(std::string(s))); }


std::string join(const std::vector<std::string>& names, std::string_view sep = ", ") {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : std::string(sep)) + n;
  return out;
}

std::string number_text(double d) { return fmt::format("{}", d); }

// A value in the case document with its JSON pointer; every check reports through fail().
struct Node {
  const json* v = nullptr;  // nullptr: the key is missing
  std::string path;         // "" is the document root
  const std::string* file = nullptr;

  bool present() const { return v != nullptr; }
  std::string pointer() const { return path.empty() ? "/" : path; }

  [[noreturn]] void fail(std::string_view expected, std::string_view got) const {
    throw CaseError(ascii_line(fmt::format("{}: {}: expected {}, got {}", *file, pointer(), expected, got)));
  }
  [[noreturn]] void fail(std::string_view expected) const { fail(expected, present() ? describe(*v) : "missing key"); }

  Node operator[](const std::string& key) const {
    auto it = v->find(key);
    return {it == v->end() ? nullptr : &*it, path + "/" + pointer_token(key), file};
  }
  Node operator[](size_t i) const { return {&(*v)[i], path + "/" + std::to_string(i), file}; }
};

void require_object(const Node& n, const std::vector<std::string>& allowed) {
  if (!n.present() || !n.v->is_object()) n.fail("object");
  for (auto it = n.v->begin(); it != n.v->end(); ++it)
    if (std::find(allowed.begin(), allowed.end(), it.key()) == allowed.end())
      n[it.key()].fail("one of the keys " + join(allowed), "unknown key " + json_quoted(it.key()));
}

void require_array(const Node& n, bool non_empty) {
  if (!n.present() || !n.v->is_array()) n.fail(non_empty ? "non-empty array" : "array");
  if (non_empty && n.v->empty()) n.fail("non-empty array");
}

std::string read_string(const Node& n, std::string_view what = "string") {
  if (!n.present() || !n.v->is_string()) n.fail(what);
  return n.v->get<std::string>();
}

std::string read_nonempty_string(const Node& n) {
  std::string s = read_string(n, "non-empty string");
  if (s.empty()) n.fail("non-empty string");
  return s;
}

// `choices` are printed as given; the value must equal one of them.
std::string read_choice(const Node& n, const std::vector<std::string>& choices, std::string_view what = "one of") {
  std::string expected = fmt::format("{} {}", what, join(choices));
  std::string s = read_string(n, expected);
  if (std::find(choices.begin(), choices.end(), s) == choices.end()) n.fail(expected);
  return s;
}

double read_number(const Node& n, std::string_view what, double lo, double hi, bool lo_open = false) {
  if (!n.present() || !n.v->is_number()) n.fail(what);
  double d = n.v->get<double>();
  if (!std::isfinite(d) || (lo_open ? !(d > lo) : !(d >= lo)) || !(d <= hi)) n.fail(what);
  return d;
}

double read_finite(const Node& n) { return read_number(n, "finite number", -std::numeric_limits<double>::max(), std::numeric_limits<double>::max()); }

uint32_t read_uint(const Node& n, double lo, double hi) {
  std::string what = fmt::format("integer in [{}, {}]", number_text(lo), number_text(hi));
  double d = read_number(n, what, lo, hi);
  if (d != std::floor(d)) n.fail(what);
  return static_cast<uint32_t>(d);
}

bool is_name(const std::string& s, bool underscore) {
  if (s.empty()) return false;
  for (char c : s)
    if (!((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-' || (underscore && c == '_'))) return false;
  return true;
}

std::string read_name(const Node& n) {
  static constexpr std::string_view what = "name of a-z, 0-9, '_' and '-'";
  std::string s = read_string(n, what);
  if (!is_name(s, true)) n.fail(what);
  return s;
}

// ---------------------------------------------------------------- reading the file

// Parses JSON, rejecting duplicate keys (nlohmann would keep the last one silently, so a
// pasted-twice "max" would quietly change a threshold).
json parse_json(const std::string& text, const std::string& file) {
  struct Frame {
    bool object = false;
    std::set<std::string> keys;
    std::string key;   // object: the key of the member being parsed
    size_t index = 0;  // array: index of the element being parsed
  };
  std::vector<Frame> stack;
  auto element_done = [&] {
    if (!stack.empty() && !stack.back().object) ++stack.back().index;
  };
  auto cb = [&](int, json::parse_event_t event, json& parsed) -> bool {
    switch (event) {
      case json::parse_event_t::object_start: stack.push_back({true}); break;
      case json::parse_event_t::array_start: stack.push_back({false}); break;
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end:
        stack.pop_back();
        element_done();
        break;
      case json::parse_event_t::key: {
        Frame& top = stack.back();
        top.key = parsed.get<std::string>();
        if (!top.keys.insert(top.key).second) {
          std::string ptr;
          for (const Frame& f : stack) {
            ptr += '/';
            ptr += f.object ? pointer_token(f.key) : std::to_string(f.index);
          }
          throw CaseError(ascii_line(fmt::format("{}: {}: expected each key once per object, got {} again", file, ptr,
                                                 json_quoted(top.key))));
        }
        break;
      }
      case json::parse_event_t::value: element_done(); break;
    }
    return true;
  };
  try {
    return json::parse(text, cb);
  } catch (const json::parse_error& e) {
    size_t end = std::min<size_t>(e.byte > 0 ? e.byte - 1 : 0, text.size());
    size_t line = 1, column = 1;
    for (size_t i = 0; i < end; ++i) {
      if (text[i] == '\n') {
        ++line;
        column = 1;
      } else {
        ++column;
      }
    }
    std::string why = e.what();
    if (auto colon = why.find(": "); colon != std::string::npos) why = why.substr(colon + 2);
    throw CaseError(ascii_line(fmt::format("{}: line {}, column {}: expected valid JSON, got {}", file, line, column, why)));
  } catch (const json::exception& e) {
    // e.g. a number literal that overflows a double ("1e999"): the parser gives no position.
    std::string why = e.what();
    if (auto bracket = why.find("] "); bracket != std::string::npos) why = why.substr(bracket + 2);
    throw CaseError(ascii_line(fmt::format("{}: expected valid JSON, got {}", file, why)));
  }
}

// ---------------------------------------------------------------- case parts

// known_failure / not_caught_on: a string (every device class and tier: key "*") or an object
// whose keys are a device class, or CLASS@TIER / *@TIER for what shows at one tier only
// (harness/tier.h: a few pixels of the CI tier's 128x72 decide an ROI that 640x360 does not).
std::map<std::string, std::string> read_device_keyed(const Node& kf) {
  std::map<std::string, std::string> out;
  if (kf.v->is_object()) {
    std::vector<std::string> classes = {"lavapipe", "nvidia", "amd", "intel", "other"};
    for (const std::string cls : {"lavapipe", "nvidia", "amd", "intel", "other", "*"})
      for (const char* tier : {"ci", "gpu"}) classes.push_back(cls + "@" + tier);
    require_object(kf, classes);
    if (kf.v->empty()) kf.fail("a string, or an object of device class -> string with at least one key");
    for (auto it = kf.v->begin(); it != kf.v->end(); ++it) out[it.key()] = read_nonempty_string(kf[it.key()]);
  } else {
    out["*"] = read_string(kf, "a non-empty string, or an object of device class -> string");
    if (out["*"].empty()) kf.fail("a non-empty string, or an object of device class -> string");
  }
  return out;
}

// Inline scenes are parsed with the case file as their source, so the scene loader's message
// is "<file>: <pointer inside the scene>: ..."; re-root the pointer under /scene.
[[noreturn]] void rethrow_inline_scene_error(const SceneError& e, const std::string& file) {
  std::string msg = e.what();
  std::string prefix = file + ": ";
  std::string rest = msg.rfind(prefix, 0) == 0 ? msg.substr(prefix.size()) : msg;
  if (rest.rfind("/: ", 0) == 0) rest = "/scene: " + rest.substr(3);
  else if (!rest.empty() && rest[0] == '/') rest = "/scene" + rest;
  else rest = "/scene: " + rest;
  throw CaseError(ascii_line(file + ": " + rest));
}

void read_scene(const Node& n, Case& c) {
  static constexpr std::string_view what = "a scene object or the path of a scene file relative to the case file";
  if (!n.present() || !(n.v->is_object() || n.v->is_string())) n.fail(what);
  if (n.v->is_object()) {
    try {
      c.scene = parse_scene(*n.v, c.file);
    } catch (const SceneError& e) {
      rethrow_inline_scene_error(e, c.file);
    }
    c.scene_text = n.v->dump();
    return;
  }
  std::string rel = n.v->get<std::string>();
  if (rel.empty()) n.fail(what);
  fs::path p = fs::path(rel);
  if (p.is_relative()) p = fs::path(c.file).parent_path() / p;
  std::string resolved = p.lexically_normal().string();
  std::error_code ec;
  if (!fs::is_regular_file(resolved, ec))
    n.fail("the path of a scene file relative to the case file",
           fmt::format("{} ({} is not a file)", json_quoted(rel), resolved));
  try {
    c.scene = load_scene(resolved);
  } catch (const SceneError& e) {
    n.fail("a valid scene file", e.what());
  }
  c.scene_file = resolved;
  std::ifstream in(resolved, std::ios::binary);
  c.scene_text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::vector<Roi> read_rois(const Node& n) {
  std::vector<Roi> rois;
  if (!n.present()) return rois;
  require_array(n, false);
  for (size_t i = 0; i < n.v->size(); ++i) {
    Node r = n[i];
    require_object(r, {"name", "box"});
    Roi roi;
    Node name = r["name"];
    roi.name = read_name(name);
    for (const Roi& other : rois)
      if (other.name == roi.name) name.fail("a ROI name not used before", json_quoted(roi.name) + " again");
    Node box = r["box"];
    static constexpr std::string_view box_what = "[x0, y0, x1, y1] in [0, 1] with x0 < x1 and y0 < y1";
    if (!box.present() || !box.v->is_array() || box.v->size() != 4) box.fail(box_what);
    float v[4];
    for (size_t k = 0; k < 4; ++k) v[k] = static_cast<float>(read_number(box[k], "number in [0, 1]", 0.0, 1.0));
    if (!(v[0] < v[2]) || !(v[1] < v[3]))
      box.fail(box_what, fmt::format("[{}, {}, {}, {}]", v[0], v[1], v[2], v[3]));
    roi.x0 = v[0];
    roi.y0 = v[1];
    roi.x1 = v[2];
    roi.y1 = v[3];
    rois.push_back(roi);
  }
  return rois;
}

// The contract AOVs (renderer/techniques/aov.h), all of which the reference produces.
std::vector<std::string> reference_outputs() { return contract_aov_names(find_technique("reference")); }

std::string roi_name_what(const Case& c) {
  std::vector<std::string> names;
  for (const Roi& r : c.rois) names.push_back(r.name);
  return names.empty() ? std::string("the name of a ROI in /rois (none defined)")
                       : fmt::format("the name of a ROI in /rois ({})", join(names));
}

std::string read_roi_name(const Node& n, const Case& c) {
  std::string what = roi_name_what(c);
  std::string name = read_string(n, what);
  if (std::none_of(c.rois.begin(), c.rois.end(), [&](const Roi& r) { return r.name == name; })) n.fail(what);
  return name;
}

Threshold read_threshold(const Node& n, const Case& c, const TechniqueRun& run) {
  require_object(n, {"metric", "against", "roi", "max", "min", "frame"});
  Threshold t;
  Node metric = n["metric"];
  // stat_<name>: a counter the run's technique declares (Technique::stats).
  if (metric.present() && metric.v->is_string() && metric.v->get<std::string>().rfind("stat_", 0) == 0) {
    std::vector<std::string> stats;  // read_run has checked the technique's name
    for (const TechniqueStat& st : find_technique(run.technique).stats) stats.push_back("stat_" + st.name);
    t.metric = read_choice(metric, stats.empty() ? std::vector<std::string>{"a technique with stats"} : stats);
  } else {
    t.metric = read_choice(metric, case_metrics());
  }
  if (t.metric == "flicker" && c.flicker_frames < 2)
    metric.fail("a metric other than flicker, or a top-level \"flicker_frames\" >= 2", json_quoted(t.metric));
  if (t.metric.rfind("nan_", 0) == 0 && t.metric != "nan_count" && !c.track_nan)
    metric.fail(fmt::format("a top-level \"track_nan\": true for metric {}", t.metric), json_quoted(t.metric));
  if (t.metric.rfind("conv_", 0) == 0 && !c.convergence)
    metric.fail(fmt::format("a top-level \"convergence\" object for metric {}", t.metric), json_quoted(t.metric));
  Node against = n["against"];
  if (!metric_uses_against(t.metric)) {
    if (against.present())
      against.fail(fmt::format("no \"against\" for metric {} (it measures the output alone)", t.metric));
    t.against = "";
  } else if (against.present()) {
    std::vector<std::string> choices = {"reference", "golden", "analytic"};
    for (auto& [name, opts] : run.variants) choices.push_back("variant:" + name);
    t.against = read_choice(against, choices);
    if (t.against == "analytic" && !c.analytic_value)
      against.fail("\"analytic\" only in a case with a top-level analytic_value", json_quoted(t.against));
  }
  if (metric_uses_against(t.metric) && t.against == "reference" && c.reference_spp == 0)
    (against.present() ? against : metric)
        .fail("a comparison other than \"reference\" (reference_spp is 0: the case has no reference)",
              json_quoted(t.against));
  if (Node f = n["frame"]; f.present()) {
    std::vector<std::string> frames;
    for (uint32_t e : c.eval_frames) frames.push_back(std::to_string(e));
    std::string what = frames.empty() ? std::string("no \"frame\" (the case has no eval_frames)")
                                      : fmt::format("one of the eval_frames ({})", join(frames));
    t.frame = read_uint(f, 1, c.frames);
    if (std::find(c.eval_frames.begin(), c.eval_frames.end(), t.frame) == c.eval_frames.end())
      f.fail(what, number_text(t.frame));
  }
  if (Node roi = n["roi"]; roi.present()) t.roi = read_roi_name(roi, c);
  if (Node mx = n["max"]; mx.present()) t.max = read_finite(mx);
  if (Node mn = n["min"]; mn.present()) t.min = read_finite(mn);
  if (!t.max && !t.min) n.fail("\"max\" or \"min\" (or both)", "neither");
  if (t.max && t.min && *t.min > *t.max) n["min"].fail(fmt::format("number <= max ({})", number_text(*t.max)));
  return t;
}

// Fields shared by technique entries and negative controls.
const std::vector<std::string> kRunKeys = {"technique",  "label",    "presets",       "options", "compare_aov",
                                           "thresholds", "variants", "known_failure", "spp",
                                           "frames",     "attribute"};

// An object of option name -> number, validated against the technique's options.
std::map<std::string, double> read_options(const Node& options, const Technique& tech) {
  if (!options.v->is_object()) options.fail("object of option name -> number");
  std::map<std::string, double> out;
  const auto& known = technique_options(tech);
  for (auto it = options.v->begin(); it != options.v->end(); ++it) {
    Node o = options[it.key()];
    auto k = std::find_if(known.begin(), known.end(), [&](const TechniqueOption& t) { return t.name == it.key(); });
    std::string err;
    if (k == known.end()) {
      err = check_option(tech, it.key(), 0);
    } else if (!it.value().is_number()) {
      err = fmt::format("expected an integer in [{}, {}], got {}", number_text(k->min), number_text(k->max),
                        describe(it.value()));
    } else {
      err = check_option(tech, it.key(), it.value().get<double>());
    }
    if (!err.empty()) throw CaseError(ascii_line(fmt::format("{}: {}: {}", *options.file, o.pointer(), err)));
    out[it.key()] = it.value().get<double>();
  }
  return out;
}

TechniqueRun read_run(const Node& n, const Case& c, bool negative) {
  TechniqueRun run;
  std::vector<std::string> names;
  for (const Technique& t : techniques()) names.push_back(t.name);
  run.technique = read_choice(n["technique"], names, "one of the techniques");
  const Technique& tech = find_technique(run.technique);
  if (Node label = n["label"]; label.present()) {
    if (negative) label.fail("no label in a negative control (its name tells it apart)");
    if (!label.v->is_string()) label.fail("a string of a-z, 0-9, '_' and '-'");
    run.label = label.v->get<std::string>();
    const bool ok = !run.label.empty() && run.label.size() <= 32 &&
                    std::all_of(run.label.begin(), run.label.end(), [](char ch) {
                      return (ch >= 'a' && ch <= 'z') || (ch >= '0' && ch <= '9') || ch == '_' || ch == '-';
                    });
    if (!ok) label.fail("a string of 1 to 32 characters a-z, 0-9, '_' and '-'");
  }

  if (Node presets = n["presets"]; presets.present()) {
    require_array(presets, true);
    if (negative && presets.v->size() != 1) presets.fail("an array of exactly one preset");
    run.presets.clear();
    for (size_t i = 0; i < presets.v->size(); ++i) {
      Node p = presets[i];
      std::string name = read_choice(p, tech.presets, fmt::format("one of the presets of {}", tech.name));
      if (std::find(run.presets.begin(), run.presets.end(), name) != run.presets.end())
        p.fail("each preset once", json_quoted(name) + " again");
      run.presets.push_back(name);
    }
  } else {
    run.presets = {"medium"};
  }

  if (Node options = n["options"]; options.present()) run.options = read_options(options, tech);
  if (Node variants = n["variants"]; variants.present()) {
    if (!variants.v->is_object() || variants.v->empty()) variants.fail("non-empty object of variant name -> options");
    for (auto it = variants.v->begin(); it != variants.v->end(); ++it) {
      Node v = variants[it.key()];
      if (!is_name(it.key(), true)) v.fail("a variant name of a-z, 0-9, '_' and '-'", json_quoted(it.key()));
      run.variants[it.key()] = read_options(v, tech);
    }
  }

  if (Node spp = n["spp"]; spp.present()) {
    if (tech.name != "reference") spp.fail("no \"spp\" outside a reference (path tracer) run");
    run.spp = read_uint(spp, 1, 1048576);
  }
  if (Node f = n["frames"]; f.present()) {
    if (tech.name == "reference") f.fail("no \"frames\" in a reference (path tracer) run (it has \"spp\")");
    if (!c.eval_frames.empty() || c.convergence || c.flicker_frames)
      f.fail("no \"frames\" in a case evaluated per frame (eval_frames, convergence or flicker_frames)");
    run.frames = read_uint(f, 1, 100000);
  }
  if (Node kf = n["known_failure"]; kf.present()) {
    if (negative) kf.fail("no \"known_failure\" in a negative control (it must fail anyway)");
    run.known_failure = read_device_keyed(kf);
  }
  if (Node a = n["attribute"]; a.present()) {
    if (negative) a.fail("no \"attribute\" in a negative control");
    if (!a.v->is_boolean()) a.fail("true or false");
    const bool oracles = std::any_of(tech.stages.begin(), tech.stages.end(), [](const TechniqueStage& s) { return bool(s.make); });
    if (a.v->get<bool>() && !oracles) a.fail(fmt::format("a technique with stage oracles ({} declares none)", tech.name), "true");
    run.attribute = a.v->get<bool>();
  }
  if (Node aov = n["compare_aov"]; aov.present())
    run.compare_aov = read_choice(aov, reference_outputs(), "one of the reference outputs");
  // The AOV contract (renderer/techniques/aov.h): a run compares an AOV only if its technique
  // produces that very light path set.
  std::string compared = run.compare_aov.empty() ? c.output : run.compare_aov;
  if (contract_resource(tech, compared).empty()) {
    Node where = n["compare_aov"].present() ? n["compare_aov"] : n["technique"];
    where.fail(fmt::format("a technique that produces the compared AOV \"{}\" ({} declares: {})", compared, tech.name,
                           fmt::join(contract_aov_names(tech), ", ")),
               json_quoted(where.present() ? where.v->get<std::string>() : tech.name));
  }

  Node thresholds = n["thresholds"];
  if (negative || thresholds.present()) {
    require_array(thresholds, negative);
    for (size_t i = 0; i < thresholds.v->size(); ++i) run.thresholds.push_back(read_threshold(thresholds[i], c, run));
  }
  return run;
}

const std::vector<std::string> kTopKeys = {
    "$schema",         "description",  "scene",          "width", "height",          "frames",
    "output",          "reference_spp", "reference_seed", "analytic_value", "flip_mode", "ppd",
    "golden_flip_max", "rois",          "techniques",     "negative_controls", "eval_frames", "convergence",
    "flicker_frames", "track_nan", "timing_frames", "gpu_width", "gpu_height"};

Case parse_case(const json& doc, const std::string& file) {
  Case c;
  c.file = file;
  c.name = fs::path(file).stem().string();
  if (!is_name(c.name, false))
    throw CaseError(ascii_line(fmt::format("{}: expected a file name (the case name) of a-z, 0-9 and '-', got {}", file,
                                           json_quoted(c.name))));

  Node root{&doc, "", &file};
  require_object(root, kTopKeys);
  if (Node s = root["$schema"]; s.present()) read_string(s);
  c.description = read_nonempty_string(root["description"]);
  read_scene(root["scene"], c);
  if (Node n = root["width"]; n.present()) c.width = read_uint(n, 1, 8192);
  if (Node n = root["height"]; n.present()) c.height = read_uint(n, 1, 8192);
  if (Node n = root["gpu_width"]; n.present()) c.gpu_width = read_uint(n, 1, 8192);
  if (Node n = root["gpu_height"]; n.present()) c.gpu_height = read_uint(n, 1, 8192);
  if (Node n = root["frames"]; n.present()) c.frames = read_uint(n, 1, 100000);
  if (Node n = root["output"]; n.present()) c.output = read_choice(n, reference_outputs(), "one of the reference outputs");
  if (Node n = root["reference_spp"]; n.present()) c.reference_spp = read_uint(n, 0, 1048576);
  if (Node n = root["reference_seed"]; n.present()) c.reference_seed = read_uint(n, 0, 4294967295.0);
  if (Node n = root["analytic_value"]; n.present()) c.analytic_value = read_finite(n);
  if (Node n = root["flip_mode"]; n.present()) c.flip_mode = read_choice(n, {"hdr", "ldr"});
  if (Node n = root["ppd"]; n.present())
    c.ppd = read_number(n, "number > 0", 0.0, std::numeric_limits<double>::max(), true);
  if (Node n = root["golden_flip_max"]; n.present()) c.golden_flip_max = read_number(n, "number in [0, 1]", 0.0, 1.0);
  c.rois = read_rois(root["rois"]);
  if (Node n = root["eval_frames"]; n.present()) {
    require_array(n, true);
    for (size_t i = 0; i < n.v->size(); ++i) {
      uint32_t f = read_uint(n[i], 1, c.frames);
      if (!c.eval_frames.empty() && f <= c.eval_frames.back())
        n[i].fail(fmt::format("a frame after {} (increasing)", c.eval_frames.back()), number_text(f));
      c.eval_frames.push_back(f);
    }
  }
  if (Node n = root["convergence"]; n.present()) {
    require_object(n, {"roi", "target", "settle_frame"});
    Convergence conv;
    if (Node r = n["roi"]; r.present()) conv.roi = read_roi_name(r, c);
    if (Node t = n["target"]; t.present())
      conv.target = read_number(t, "number > 0", 0.0, std::numeric_limits<double>::max(), true);
    else if (c.analytic_value && *c.analytic_value > 0)
      conv.target = *c.analytic_value;
    else
      n.fail("\"target\" (or a positive top-level analytic_value)", "neither");
    if (Node f = n["settle_frame"]; f.present()) conv.settle_frame = read_uint(f, 1, c.frames);
    c.convergence = conv;
  }
  if (Node n = root["flicker_frames"]; n.present()) c.flicker_frames = read_uint(n, 2, c.frames);
  if (Node n = root["timing_frames"]; n.present()) c.timing_frames = read_uint(n, 0, 1000);
  if (Node n = root["track_nan"]; n.present()) {
    if (!n.v->is_boolean()) n.fail("true or false");
    c.track_nan = n.v->get<bool>();
  }

  Node techs = root["techniques"];
  require_array(techs, true);
  for (size_t i = 0; i < techs.v->size(); ++i) {
    Node t = techs[i];
    require_object(t, kRunKeys);
    TechniqueRun run = read_run(t, c, false);
    // One result row (and one golden file) per technique and preset.
    for (size_t j = 0; j < run.presets.size(); ++j)
      for (size_t k = 0; k < c.techniques.size(); ++k) {
        const TechniqueRun& o = c.techniques[k];
        if (o.name() == run.name() &&
            std::find(o.presets.begin(), o.presets.end(), run.presets[j]) != o.presets.end()) {
          Node where = t["presets"].present() ? t["presets"][j] : t;
          where.fail(fmt::format("a technique (and label) and preset not listed before (/techniques/{} has {} {})", k,
                                 run.name(), run.presets[j]),
                     json_quoted(run.presets[j]) + " again");
        }
      }
    c.techniques.push_back(std::move(run));
  }

  if (Node ncs = root["negative_controls"]; ncs.present()) {
    require_array(ncs, false);
    std::vector<std::string> keys = {"name", "why", "not_caught_on"};
    keys.insert(keys.end(), kRunKeys.begin(), kRunKeys.end());
    for (size_t i = 0; i < ncs.v->size(); ++i) {
      Node n = ncs[i];
      require_object(n, keys);
      NegativeControl nc;
      Node name = n["name"];
      nc.name = read_name(name);
      for (const NegativeControl& o : c.negative_controls)
        if (o.name == nc.name) name.fail("a negative control name not used before", json_quoted(nc.name) + " again");
      nc.why = read_nonempty_string(n["why"]);
      if (Node m = n["not_caught_on"]; m.present()) nc.not_caught_on = read_device_keyed(m);
      nc.run = read_run(n, c, true);
      c.negative_controls.push_back(std::move(nc));
    }
  }
  return c;
}

}  // namespace

std::vector<std::string> compared_aovs(const Case& c) {
  std::vector<std::string> aovs{c.output};
  auto add = [&](const TechniqueRun& r) {
    std::string aov = r.compare_aov.empty() ? c.output : r.compare_aov;
    if (std::find(aovs.begin(), aovs.end(), aov) == aovs.end()) aovs.push_back(aov);
  };
  for (auto& r : c.techniques) add(r);
  for (auto& nc : c.negative_controls) add(nc.run);
  return aovs;
}

const std::vector<std::string>& case_metrics() {
  static const std::vector<std::string> m = {
      "flip",      "psnr",    "relmse",         "roi_mean",         "roi_ratio",      "max_abs_error",
      "nan_count", "inf_count", "uv_shift_max", "banding",          "banding_excess", "flicker",
      "conv_error_final", "conv_error_max", "conv_drift", "conv_oscillation",
      "scan_nan", "scan_inf", "scan_negative", "scan_above_max", "scan_saturated", "nan_frames",
      "nan_last_frame", "nan_max_pixels", "penumbra_width_error"};
  return m;
}

bool metric_uses_against(const std::string& metric) {
  if (metric.rfind("stat_", 0) == 0) return false;
  static const std::set<std::string> alone = {"roi_mean", "nan_count", "inf_count", "banding", "flicker",
                                              "conv_error_final", "conv_error_max", "conv_drift",
                                              "conv_oscillation", "scan_nan", "scan_inf", "scan_negative",
                                              "scan_above_max", "scan_saturated", "nan_frames", "nan_last_frame",
                                              "nan_max_pixels"};
  return alone.count(metric) == 0;
}

Case load_case(const std::string& path) {
  try {
    std::error_code ec;
    if (fs::is_directory(path, ec)) throw CaseError(fmt::format("{}: expected a case file, got a directory", path));
    std::ifstream in(path, std::ios::binary);
    if (!in) throw CaseError(fmt::format("{}: expected a readable file, got {}", path, std::strerror(errno)));
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) throw CaseError(fmt::format("{}: expected a readable file, got a read error", path));
    return parse_case(parse_json(text, path), path);
  } catch (const CaseError&) {
    throw;
  } catch (const std::exception& e) {
    // Every access is checked first; this only keeps a missed check from escaping as a
    // library exception without the file name.
    throw CaseError(ascii_line(fmt::format("{}: expected a valid case, got {}", path, e.what())));
  }
}

std::vector<Case> load_cases(const std::string& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw CaseError(fmt::format("{}: expected a directory of case files, got {}", dir,
                                                              fs::exists(dir, ec) ? "a file" : "nothing there"));
  std::vector<std::string> names;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    std::string name = it->path().filename().string();
    bool json_file = name.size() > 5 && name.ends_with(".json") && !name.ends_with(".schema.json");
    if (json_file && it->is_regular_file(ec)) names.push_back(name);
  }
  if (ec) throw CaseError(fmt::format("{}: expected a readable directory, got {}", dir, ec.message()));
  if (names.empty()) throw CaseError(fmt::format("{}: expected at least one *.json case file, got none", dir));
  std::sort(names.begin(), names.end());
  std::vector<Case> cases;
  for (const auto& n : names) cases.push_back(load_case((fs::path(dir) / n).string()));
  return cases;
}

}  // namespace gib
