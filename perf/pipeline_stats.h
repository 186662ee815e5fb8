// What the driver says of the pipelines a pass ran (VK_KHR_pipeline_executable_properties,
// Pipeline::statistics): register count, shared memory, code size, as each driver names them.
// bench prints them under each pass and records them in its JSON, so a pass's cost can be read
// beside what limits how many of its threads fit an SM (registers, shared memory).
#pragma once
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "renderer/vk/gpu.h"

namespace gib::perf {

// Adds each pipeline not yet in `pipelines` (first-use order); null entries are skipped.
void add_pipelines(std::vector<const Pipeline*>& pipelines, const std::vector<const Pipeline*>& ran);

// "name: Stat value, Stat value; name2: ..." for the pipelines that carry statistics ("" if none
// does). A statistic of the pipeline's only executable is printed without the executable's name;
// integers print as integers (in hex from 2^32), other values with 4 significant digits.
std::string pipeline_statistics_line(const std::vector<const Pipeline*>& pipelines);

// [{"name", "statistics": [{"executable", "name", "value"}]}] for every pipeline.
nlohmann::json pipeline_statistics_json(const std::vector<const Pipeline*>& pipelines);

}  // namespace gib::perf
