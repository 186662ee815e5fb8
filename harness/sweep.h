// `gibench sweep --case NAME`: every technique x preset of a case, error (FLIP vs the
// reference golden) against GPU time per frame; writes sweep.csv, sweep.json and sweep.svg
// (one series per technique, the Pareto front marked) under --out.
#pragma once
#include <string>
#include <vector>

#include "harness/goldens.h"
#include "harness/suite.h"

namespace gib {

struct SweepPoint {
  std::string technique, preset;  // technique: the case row's name, TECHNIQUE or TECHNIQUE+LABEL
  double gpu_ms = 0, flip = 0;
  // The case's ROIs: mean luminance of the row's image / the reference's (1: no leak, no lost light).
  std::vector<std::pair<std::string, double>> roi_ratios;
  bool pareto = false;
  uint32_t timed_frames = 0;  // frames gpu_ms comes from (CaseRender::timing; a reference: its sum)
  bool scan_free = false;
};

// Marks points not dominated by any other (lower or equal time and error, one strictly lower).
void mark_pareto(std::vector<SweepPoint>& points);
std::string sweep_svg(const std::string& case_name, const std::vector<SweepPoint>& points);
// One case (already at its tier): every row of the selected techniques (all when empty) x every
// preset of its technique, FLIP and ROI ratios against the case's reference golden in `store`;
// each point printed as it is measured when `print`.
std::vector<SweepPoint> sweep_case(Gpu& gpu, const Case& c, const GoldenStore& store,
                                   const std::vector<std::string>& techniques, bool print = true);
int cmd_sweep(const SuiteOptions& o);

}  // namespace gib
