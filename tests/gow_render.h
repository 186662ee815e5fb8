// The gow-ragnarok tests' one-frame render: runs the technique's passes once with settings `s`
// and reads back `resources` (test_gow_shadows.cpp, test_gow_ssdo.cpp).
#pragma once
#include <map>
#include <string>
#include <vector>

#include "renderer/graph/executor.h"
#include "renderer/techniques/technique.h"

namespace gib::test {

inline std::map<std::string, FloatImage> render_gow(Gpu& gpu, const Scene& scene, const Settings& s,
                                                    const std::vector<std::string>& resources) {
  Executor ex(gpu, scene, s, make_passes(find_technique("gow-ragnarok")), resources);
  ex.run_frame();
  std::map<std::string, FloatImage> out;
  for (auto& r : resources) out[r] = ex.read(r);
  return out;
}

}  // namespace gib::test
