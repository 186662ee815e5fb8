// Sharding the suite across GPUs and machines with the tools CI systems already have: `gibench
// run --shard K/N` (or GTEST_SHARD_INDEX / GTEST_TOTAL_SHARDS) runs a deterministic 1/N of the
// rows, `gibench merge` joins the shards' outputs into one results.json, junit.xml and report.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "harness/case.h"
#include "harness/plan.h"

namespace gib {

struct Shard {
  uint32_t index = 0, count = 1;  // 0-based, as GTEST_SHARD_INDEX
  bool active() const { return count > 1; }
};

// "K/N" with 0 <= K < N; throws std::invalid_argument naming the flag and the expected form.
Shard parse_shard(const std::string& text);
// --shard when given, else GTEST_SHARD_INDEX / GTEST_TOTAL_SHARDS when both are set (and then
// touches GTEST_SHARD_STATUS_FILE, as a sharding-aware test runner does), else 0/1.
Shard shard_from(const std::string& flag);

// Row i of the plan (plan.h plan_rows) belongs to shard i % N: round robin keeps the expensive rows
// of one case on different shards.

struct MergeOptions {
  std::string out = "out";
  std::vector<std::string> shard_dirs;
};
// Reads each shard folder's results.json, checks the shards are one plan's 0..N-1, each once,
// with every planned row present once (a case whose error is recorded may miss its rows) and one
// device class, then writes the merged results.json, results.js, junit.xml, report and img/.
// Throws on a merge error (one line naming the folder and what was expected); returns 1 when a
// merged row failed, 0 otherwise.
int cmd_merge(const MergeOptions& o);

}  // namespace gib
