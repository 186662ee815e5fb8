// `deferred`: DOOM: The Dark Ages' deferred path on the visibility buffer (deferred.md): material
// classification, deferred attribute interpolation, deferred texturing per material shader, tile
// classification and tiled deferred lighting. Every step is switchable against its uber form.
#include "renderer/techniques/deferred/deferred.h"

#include <fmt/format.h>

#include "renderer/passes/visibility/visibility.h"
#include "renderer/techniques/deferred/attribute_interpolate/attribute_interpolate.h"
#include "renderer/techniques/deferred/deferred_lighting/deferred_lighting.h"
#include "renderer/techniques/deferred/deferred_texturing/deferred_texturing.h"
#include "renderer/techniques/deferred/gbuffer_update/gbuffer_update.h"
#include "renderer/techniques/deferred/include/deferred_shared.h"
#include "renderer/techniques/deferred/material_classify/material_classify.h"
#include "renderer/techniques/deferred/tile_classify/tile_classify.h"
#include "renderer/techniques/deferred/vrcs_rate/vrcs_rate.h"
#include "renderer/techniques/direct_light_modes.h"
#include "renderer/techniques/technique.h"

namespace gib {
namespace {

// The seed's tile-classification debug view: each 32x32 tile in its lighting workload's colour
// (sky blue, opaque green, cloth purple, translucent orange), tile edges darker; tiles
// gbuffer_update runs over (decals) have a white diagonal.
FloatImage draw_tile_classes(const std::vector<uint8_t>& bytes, uint32_t width, uint32_t height) {
  using namespace glsl;
  static constexpr float kColour[kWorkloadCount][3] = {
      {0.1f, 0.2f, 0.6f}, {0.1f, 0.65f, 0.15f}, {0.6f, 0.2f, 0.75f}, {0.95f, 0.55f, 0.1f}};
  const uint32_t tiles = deferred_tiles(width, height), tiles_x = div_up(width, kDeferredTile);
  std::vector<int> workload(tiles, -1);
  for (uint32_t w = 0; w < kWorkloadCount; ++w)
    for (uint32_t i = 0, n = buffer_word(bytes, 4 * w + 3); i < n && i < tiles; ++i) {
      const uint32_t t = buffer_word(bytes, kTileHeader + uint64_t(w) * tiles + i);
      if (t < tiles) workload[t] = int(w);
    }
  std::vector<bool> decals(tiles, false);
  for (uint32_t i = 0, n = buffer_word(bytes, 4 * kTileListDecals + 3); i < n && i < tiles; ++i) {
    const uint32_t t = buffer_word(bytes, kTileHeader + uint64_t(kTileListDecals) * tiles + i);
    if (t < tiles) decals[t] = true;
  }
  FloatImage img(width, height, 3);
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      const uint32_t tile = (y / kDeferredTile) * tiles_x + x / kDeferredTile;
      const int w = workload[tile];
      const float edge = (x % kDeferredTile == 0 || y % kDeferredTile == 0) ? 0.5f : 1.0f;
      const bool diagonal = decals[tile] && x % kDeferredTile == y % kDeferredTile;
      for (uint32_t c = 0; c < 3; ++c)
        img.at(x, y, c) = w < 0 || diagonal ? 1.0f : kColour[w][c] * edge;  // white: no workload
    }
  return img;
}

// The shading-rate view: each 8x8 tile by its VRCS rate (1x1 grey, 2x1 red, 1x2 green, 2x2 yellow).
FloatImage draw_vrcs_rates(const std::vector<uint8_t>& bytes, uint32_t width, uint32_t height) {
  using namespace glsl;
  static constexpr float kColour[4][3] = {{0.2f, 0.2f, 0.2f}, {0.85f, 0.15f, 0.1f}, {0.1f, 0.7f, 0.15f}, {0.95f, 0.85f, 0.1f}};
  const uint32_t tiles_x = div_up(width, kVrcsTile);
  FloatImage img(width, height, 3);
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      const uint32_t rate = buffer_word(bytes, kVrcsHeader + (y / kVrcsTile) * tiles_x + x / kVrcsTile) & 3u;
      for (uint32_t c = 0; c < 3; ++c) img.at(x, y, c) = kColour[rate][c];
    }
  return img;
}

// The seed's tile-classification statistics (its shader-printf lines): per dispatch, the
// full-screen thread groups it would take, those dispatched through the indirect arguments,
// those discarded, and each workload's share; then how many tiles carry each feature bit. A
// full-screen dispatch here counts 16 groups of 8x8 per 32x32 tile, as the tiled dispatches do.
std::string print_tile_stats(const std::vector<uint8_t>& bytes, uint32_t width, uint32_t height) {
  using namespace glsl;
  const uint32_t tiles = deferred_tiles(width, height);
  const double full = double(tiles) * kLightingGroupsPerTile;
  auto pct = [&](double n) { return full > 0 ? 100.0 * n / full : 0.0; };
  auto groups = [&](uint32_t list) { return double(buffer_word(bytes, 4 * list + 0)); };
  std::string out;
  auto summary = [&](const char* what, double dispatched) {
    out += fmt::format("{} group stats ({} tiles of 32x32, {}x{})\n", what, tiles, width, height);
    out += fmt::format("  1a. theoretical fullscreen threadgroups: {} (100%)\n", full);
    out += fmt::format("  1b. actual dispatched threadgroups: {} ({:.0f}%)\n", dispatched, pct(dispatched));
    out += fmt::format("  1c. discarded threadgroups (not dispatched): {} ({:.0f}%)\n", full - dispatched,
                       pct(full - dispatched));
  };
  static constexpr const char* kWorkload[kWorkloadCount] = {"SKY", "OPAQUE", "OPAQUE_CLOTH", "TRANSLUCENT"};
  double lit = 0;
  for (uint32_t w = 0; w < kWorkloadCount; ++w) lit += groups(w);
  summary("1. deferred lighting", lit);
  for (uint32_t w = 0; w < kWorkloadCount; ++w)
    out += fmt::format("  indirect dispatch DEFERRED_LIGHTING_{}: {} threadgroups ({:.1f}%)\n", kWorkload[w],
                       groups(w), pct(groups(w)));
  summary("2. deferred gbuffer update", groups(kTileListDecals));
  out += fmt::format("  indirect dispatch DEFERRED_GBUFFERUPDATE_DECALS: {} threadgroups ({:.1f}%)\n",
                     groups(kTileListDecals), pct(groups(kTileListDecals)));
  static constexpr std::pair<uint32_t, const char*> kFeature[] = {
      {kTileFeatureSky, "SKY"},         {kTileFeatureOpaque, "OPAQUE_DEFERRED"}, {kTileFeatureTranslucent, "TRANSLUCENT"},
      {kTileFeatureEmissive, "EMISSIVE"}, {kTileFeatureCloth, "BRDF_CLOTH"},     {kTileFeatureDecals, "DECALS"}};
  out += "3. feature bits\n";
  for (auto [bit, name] : kFeature) {
    uint32_t n = 0;
    for (uint32_t t = 0; t < tiles; ++t) n += (buffer_word(bytes, kTileHeader + uint64_t(kTileListCount) * tiles + t) & bit) ? 1 : 0;
    out += fmt::format("  {} / {} tiles have {} ({:.0f} percent)\n", n, tiles, name, tiles ? 100.0 * n / tiles : 0.0);
  }
  return out;
}

}  // namespace
Technique deferred_technique() {
  Technique t;
  t.name = "deferred";
  t.description =
      "visibility buffer, material classification, attribute interpolation, deferred texturing per material "
      "shader, tile classification, G-buffer update (decals), tiled direct lighting (DOOM: The Dark Ages)";
  t.passes = {{"visibility", make_visibility_pass},
              {"material_classify", make_material_classify_pass},
              {"attribute_interpolate", make_attribute_interpolate_pass},
              {"vrcs_rate", make_vrcs_rate_pass},
              {"deferred_texturing", make_deferred_texturing_pass},
              {"tile_classify", make_tile_classify_pass},
              {"gbuffer_update", make_gbuffer_update_pass},
              {"deferred_lighting", make_deferred_lighting_pass}};
  t.output = "direct_light";
  // Only direct light, as `direct`: its output is the contract's `direct` exactly.
  t.contract_aovs = {{"direct", "direct_light"}};
  t.aovs = {"vbuffer",          "depth",           "gbuffer_albedo", "gbuffer_normal",    "gbuffer_position",
            "gbuffer_emissive", "vis_bary",        "vis_bary_deriv", "vis_tangent_frame", "material_segments",
            "pixel_commands",   "tile_workloads", "vrcs_rates"};
  using namespace glsl;
  t.stats = {
      {"padding_per_wave", "empty entries per 64-entry wave of the padded pixel lists", "material_segments",
       kSegStats + kStatPaddingSlots, kSegStats + kStatWaves},
      {"waves", "64-entry waves of the texturing pixel lists", "material_segments", kSegStats + kStatWaves},
      {"uniform_subgroups", "texturing subgroups that took the uniform-data permutation", "material_segments",
       kSegStats + kStatSubgroupsUniform},
      {"divergent_subgroups", "texturing subgroups that took the divergent permutation", "material_segments",
       kSegStats + kStatSubgroupsDivergent},
      // The seed's tile-classification debug print: tiles (of all) per lighting workload.
      {"tiles_sky", "share of 32x32 tiles lit by the sky-only workload", "tile_workloads", 4 * kWorkloadSky + 3,
       kTileStats + kTileStatTiles},
      {"tiles_opaque", "share of tiles lit by the opaque workload", "tile_workloads", 4 * kWorkloadOpaque + 3,
       kTileStats + kTileStatTiles},
      {"tiles_cloth", "share of tiles lit by the cloth workload (standard + sheen lobe)", "tile_workloads",
       4 * kWorkloadCloth + 3, kTileStats + kTileStatTiles},
      {"tiles_translucent", "share of tiles lit by the translucent workload", "tile_workloads",
       4 * kWorkloadTranslucent + 3, kTileStats + kTileStatTiles},
      // The seed's G-buffer update statistics: dispatched tiles of all (Siege: 68 %).
      {"tiles_decals", "share of tiles gbuffer_update ran over (some decal covers a pixel)", "tile_workloads",
       4 * kTileListDecals + 3, kTileStats + kTileStatTiles},
      {"vrcs_textured", "VRCS: share of geometry pixels whose material the texturing evaluated", "vrcs_rates",
       kVrcsStats + kVrcsStatTextured, kVrcsStats + kVrcsStatTexturedOf},
      {"vrcs_lit", "VRCS: share of geometry pixels the lighting shaded itself", "vrcs_rates", kVrcsStats + kVrcsStatLit,
       kVrcsStats + kVrcsStatLitOf},
      {"vrcs_decaled", "VRCS: share of geometry pixels of decal tiles whose decals gbuffer_update evaluated",
       "vrcs_rates", kVrcsStats + kVrcsStatDecaled, kVrcsStats + kVrcsStatDecaledOf},
  };
  t.views = {
      {"tile_classes",
       "lighting workload per 32x32 tile: sky blue, opaque green, cloth purple, translucent orange; white diagonal: "
       "decal tiles (gbuffer_update)",
       "tile_workloads", draw_tile_classes},
      {"vrcs_rates", "VRCS rate per 8x8 tile: 1x1 grey, 2x1 red, 1x2 green, 2x2 yellow", "vrcs_rates", draw_vrcs_rates},
  };
  t.printouts = {{"tile_classification",
                  "the seed's group stats: full-screen vs dispatched thread groups per dispatch, share per workload, "
                  "tiles per feature bit",
                  "tile_workloads", print_tile_stats}};
  // The lighting ladder of `direct` (same rays, same result): the deferred path changes how the
  // work is dispatched, not what it computes.
  define_settings<DeferredSettings>(t, kSkyRaysPresets, apply_sky_rays_preset<DeferredSettings>);
  t.options = with_common_options(
      {
          option("sky_rays", "sky visibility rays per pixel (0: no sky light)", 0, 4294967295.0,
                 &DirectLightingParams::sky_rays),
          option("classify_materials", "texture over per-shader pixel lists (0: one uber kernel over every pixel)", 0, 1,
                 &DeferredSettings::classify_materials),
          option("uniform_permutation",
                 "dispatch the uniform-data texturing permutation beside the divergent one (needs subgroup vote and ballot)",
                 0, 1, &DeferredSettings::uniform_permutation),
          option("tile_classification", "light per tile workload (0: one uber kernel over every pixel)", 0, 1,
                 &DeferredSettings::tile_classification),
          option("gbuffer_update", "blend the scene's decals into the G-buffer (0: decals missing, a negative control)", 0,
                 1, &DeferredSettings::gbuffer_update),
          option("sheen_lobe", "light the cloth BRDF's sheen lobe (0: cloth lit as the standard BRDF, a negative control)",
                 0, 1, &DeferredSettings::sheen_lobe),
          option("vrcs", "variable-rate compute shading in the classified texturing, the G-buffer update and the tiled lighting", 0, 1,
                 &DeferredSettings::vrcs),
          option("vrcs_threshold", "largest tone-mapped luminance step, l = L / (1 + L), a coarse pixel pair may hide", 0,
                 1, &DeferredSettings::vrcs_threshold),
          option("vrcs_edges", "keep full rate across instance changes and normal creases", 0, 1,
                 &DeferredSettings::vrcs_edges),
          option("vrcs_force", "0: rate chosen per tile; 1 2x1, 2 1x2, 3 2x2 everywhere (negative controls)", 0, 3,
                 &DeferredSettings::vrcs_force),
      },
      {0, 1});
  add_direct_light_modes(t);  // option direct_light: traced or shadow_mapped
  return t;
}

}  // namespace gib
