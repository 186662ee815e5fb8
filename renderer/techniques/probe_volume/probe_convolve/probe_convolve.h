// probe_convolve: the probes' cached lighting (AC Shadows RTGI, "Convolution"). For each
// selected probe the 20x20 lit texels are box-filtered to 10x10 in group-shared memory (the
// seed's 4x bilinear pre-filter), then: filtered radiance 10x10 with the lobe
// pow(saturate((cos - 0.75) / 0.25), 4) (reflected radiance and sky visibility: what a
// per-pixel ray that ends in the volume would have found beyond, sky excluded); depth moments
// 10x10 with the same lobe, depth rescaled by spacing * sqrt(3) and clamped to [0, 1] before
// averaging, unorm8; irradiance / pi 5x5, the cosine-weighted mean of everything arriving
// (reflected + emission + sky x visibility). Per probe: sky visibility, mean luminance,
// local-light luminance and the sun/sky estimate; lighting scale = 1 / mean luminance, by
// which radiance and irradiance are stored (half floats). Tiles are written with a 1-texel
// border (renderer/codecs/octahedral.h, oct_border_source) for seamless bilinear filtering.
// Marks the probe valid.
// Slots: read probe_selection, probe_gb_material, probe_gb_depth, probe_texel_radiance,
// probe_texel_local; read_write probe_state, probe_irradiance, probe_radiance,
// probe_visibility (persistent, probe-major; zeroed on the first frame).
// Limits: texels are weighted equally (not by solid angle), as the seed's pre-filter.
#pragma once
#include <memory>

#include "renderer/graph/pass.h"

namespace gib {
std::unique_ptr<Pass> make_probe_convolve_pass();
}
