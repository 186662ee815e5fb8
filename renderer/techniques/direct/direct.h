// The `direct` technique's settings (definition: direct.cpp).
#pragma once
#include "renderer/graph/settings.h"
#include "renderer/passes/direct_lighting/direct_lighting.h"

namespace gib {

struct DirectSettings : TechniqueSettingsOf<DirectSettings>, DirectLightingParams {};

}  // namespace gib
