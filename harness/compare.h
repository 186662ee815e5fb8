// `gibench compare A B`: FLIP, PSNR and relMSE of two images (EXR or PNG), like the reference
// FLIP tool: the mode follows the reference's extension unless --hdr/--ldr is given.
#pragma once
#include <optional>
#include <string>

namespace gib {

struct CompareOptions {
  std::string reference, test;
  std::optional<bool> hdr;  // unset: .exr -> HDR, else LDR
  double ppd = 67.02064514160156;
  std::string tonemapper = "aces";
  std::optional<double> start_exposure, stop_exposure;
  std::optional<int> num_exposures;
  std::string error_map;  // PNG path
  bool json = false;
};

int cmd_compare(const CompareOptions& o);

}  // namespace gib
