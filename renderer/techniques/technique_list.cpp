// The registry of techniques, in the order `gibench` lists them. Adding a technique: its folder
// renderer/techniques/<name>/ with <name>.cpp defining `Technique <name>_technique()`, and one
// line here.
#include "renderer/techniques/technique.h"

#define GIB_TECHNIQUE_LIST(X) \
  X(direct)                   \
  X(reference)                \
  X(radiance_cache)           \
  X(deferred)                 \
  X(probe_volume)             \
  X(gow_ragnarok)             \
  X(voxel_clipmap)

namespace gib {

#define GIB_DECLARE_TECHNIQUE(name) Technique name##_technique();
GIB_TECHNIQUE_LIST(GIB_DECLARE_TECHNIQUE)
#undef GIB_DECLARE_TECHNIQUE

const std::vector<Technique>& techniques() {
#define GIB_TECHNIQUE_ENTRY(name) name##_technique(),
  static const std::vector<Technique> t = {GIB_TECHNIQUE_LIST(GIB_TECHNIQUE_ENTRY)};
#undef GIB_TECHNIQUE_ENTRY
  return t;
}

}  // namespace gib
