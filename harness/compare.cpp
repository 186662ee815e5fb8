#include "harness/compare.h"

#include <fmt/format.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "harness/image_io.h"
#include "metrics/flip.h"
#include "metrics/image_metrics.h"
#include "harness/report.h"

namespace gib {
namespace {

bool is_exr(const std::string& path) {
  auto dot = path.rfind('.');
  if (dot == std::string::npos) return false;
  std::string ext = path.substr(dot + 1);
  for (auto& c : ext) c = char(std::tolower(c));
  return ext == "exr";
}

// LDR inputs follow the reference tool: 8-bit sRGB decoded to linear and clamped.
FloatImage load_for_flip(const std::string& path, bool hdr) {
  if (hdr) return read_image(path);
  const Rgb8Image in = read_rgb8(path);
  return srgb8_to_linear(in.rgb, in.width, in.height);
}

}  // namespace

int cmd_compare(const CompareOptions& o) {
  bool hdr = o.hdr.value_or(is_exr(o.reference));
  FloatImage ref = load_for_flip(o.reference, hdr), test = load_for_flip(o.test, hdr);
  if (ref.width != test.width || ref.height != test.height)
    throw std::invalid_argument(fmt::format("{}: expected {}x{} like {}, got {}x{}", o.test, ref.width, ref.height,
                                            o.reference, test.width, test.height));
  FlipOptions fo;
  fo.ppd = o.ppd;
  fo.mode = hdr ? FlipOptions::Mode::hdr : FlipOptions::Mode::ldr;
  fo.tonemapper = o.tonemapper;
  fo.start_exposure = o.start_exposure;
  fo.stop_exposure = o.stop_exposure;
  fo.num_exposures = o.num_exposures;
  FlipResult f = flip(ref, test, fo);
  double psnr = metrics::psnr(ref, test), relmse = metrics::relmse(ref, test);
  if (!o.error_map.empty()) write_png_preview(o.error_map, magma_error_map(f.error_map, true));
  if (o.json) {
    nlohmann::json j{{"reference", o.reference}, {"test", o.test}, {"mode", hdr ? "hdr" : "ldr"},
                     {"flip_mean", f.mean}, {"flip_weighted_median", f.weighted_median},
                     {"flip_weighted_q1", f.weighted_q1}, {"flip_weighted_q3", f.weighted_q3},
                     {"flip_min", f.min}, {"flip_max", f.max}, {"psnr", std::isfinite(psnr) ? nlohmann::json(psnr) : nlohmann::json("inf")},
                     {"psnr_definition", metrics::psnr_description()}, {"relmse", relmse}, {"ppd", f.ppd}};
    if (hdr)
      j.update({{"tonemapper", o.tonemapper}, {"start_exposure", f.start_exposure}, {"stop_exposure", f.stop_exposure},
                {"num_exposures", f.num_exposures}});
    fmt::print("{}\n", j.dump(1));
    return 0;
  }
  fmt::print("mode: {}  ppd: {:.4f}\n", hdr ? "HDR-FLIP" : "LDR-FLIP", f.ppd);
  if (hdr)
    fmt::print("tone mapper: {}  exposures: {:.4f} .. {:.4f} ({})\n", o.tonemapper, f.start_exposure, f.stop_exposure,
               f.num_exposures);
  fmt::print("FLIP mean: {:.6f}\nFLIP weighted median: {:.6f}  (q1 {:.6f}, q3 {:.6f})\nFLIP min/max: {:.6f} / {:.6f}\n",
             f.mean, f.weighted_median, f.weighted_q1, f.weighted_q3, f.min, f.max);
  fmt::print("PSNR: {} dB ({})\nrelMSE: {:.6g}\n", std::isfinite(psnr) ? fmt::format("{:.3f}", psnr) : "inf",
             metrics::psnr_description(), relmse);
  if (!o.error_map.empty()) fmt::print("wrote {}\n", o.error_map);
  return 0;
}

}  // namespace gib
