// For tests that run the suite on cases they write: approve every golden (the reference and
// each technique's, on this device) of the cases in `cases` into `goldens`, as
// `gibench update-goldens --reference` does, and return the options used.
#pragma once
#include <gtest/gtest.h>

#include <filesystem>

#include "harness/suite.h"

namespace gib::test {

inline UpdateOptions approve_goldens(const std::filesystem::path& cases, const std::filesystem::path& goldens) {
  UpdateOptions o;
  o.suite.cases_dir = cases.string();
  o.suite.goldens_dir = goldens.string();
  o.reference = true;
  o.reason = "test";
  EXPECT_EQ(cmd_update_goldens(o), 0);
  return o;
}

}  // namespace gib::test
