// Colour maps for error visualisation. Magma: black -> purple -> red-orange -> light yellow,
// perceptually ordered, as used by FLIP's error maps.
#pragma once
#include <array>

#include "renderer/image/float_image.h"

namespace gib {

// Magma at t in [0, 1] (clamped; NaN counts as 0), as display (sRGB-encoded) RGB in [0, 1].
std::array<float, 3> magma(float t);

// Colours a 1-channel error image (values in [0, 1], clamped) with magma; returns 3-channel
// RGB. By default the values are display-referred sRGB-encoded, ready to be quantised to
// 8 bits as they are. Pass linear_output = true to get linear RGB instead (sRGB EOTF
// applied), e.g. for a writer that sRGB-encodes itself such as write_png_preview or EXR.
FloatImage magma_error_map(const FloatImage& error, bool linear_output = false);

}  // namespace gib
