// Renders, evaluates and judges planned rows on one Gpu: what one process of `gibench run` does
// for each of its rows, whether it runs the suite alone or as a worker of a parallel run.
// Each case's context (goldens, references, noise-floor check) is made at its first row; a
// case that fails there, or whose row throws, is recorded once in SuiteResult::case_errors and
// its later rows are skipped.
#pragma once

#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "harness/evaluate.h"
#include "harness/plan.h"
#include "harness/progress.h"
#include "harness/suite.h"
#include "harness/references.h"
#include "renderer/vk/gpu.h"

namespace gib {

// What every process of a run opens first: the selected cases at the tier, the device and its
// class, the tier and the GPU tier's reference cache.
struct SuiteSetup {
  std::vector<Case> cases;
  std::unique_ptr<Gpu> gpu;
  SuiteResult suite;  // device, device and golden class, tier
  Tier tier = Tier::ci;
  std::string cache_root;
};
SuiteSetup setup_suite(const SuiteOptions& o, const std::string& device);

class RowRunner {
 public:
  // `suite` receives rows, case errors and each case's GPU-tier reference record.
  RowRunner(Gpu& gpu, const SuiteOptions& o, const std::vector<Case>& cases, Tier tier, std::string cache_root,
            SuiteResult& suite);
  // The row, or nothing when its case failed (the error is in suite.case_errors).
  const ResultRow* run(const PlannedRow& p, const RowProgress& progress = {});
  // Writes the report previews of every touched case's references.
  void finish();

 private:
  CaseContext* context(size_t case_index);

  Gpu& gpu_;
  const SuiteOptions& o_;
  const std::vector<Case>& cases_;
  Tier tier_;
  std::string cache_root_;
  SuiteResult& suite_;
  std::map<size_t, std::unique_ptr<CaseContext>> contexts_;
  std::set<size_t> failed_cases_;
};

// The one-line figures a finished row shows (FLIP and PSNR vs the reference, FLIP vs golden, GPU ms).
RowLine row_line(const std::string& key, const ResultRow& row);

}  // namespace gib
