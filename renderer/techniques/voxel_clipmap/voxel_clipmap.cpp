// `voxel-clipmap`: Enlisted's scalable real-time GI (GDC 2019, "Scalable Real-Time Global
// Illumination for Large Scenes"): a toroidal clipmap of lit scene voxels fed stochastically
// from the G-buffer, an irradiance clipmap of ambient cubes relit from age-weighted queues by
// brute-force voxel ray marching, convex offset filtering against leaks, semi-transparent
// voxels for foliage. Design notes: voxel_clipmap.md beside this file.
#include "renderer/techniques/voxel_clipmap/voxel_clipmap.h"

#include "renderer/passes/composite/composite.h"
#include "renderer/passes/gbuffer/gbuffer.h"
#include "renderer/passes/visibility/visibility.h"
#include "renderer/techniques/direct_light_modes.h"
#include "renderer/techniques/technique.h"
#include "renderer/techniques/voxel_clipmap/voxel_clipmap_stages.h"
#include "renderer/techniques/voxel_clipmap/irradiance_clipmap/irradiance_clipmap.h"
#include "renderer/techniques/voxel_clipmap/irradiance_relight/irradiance_relight.h"
#include "renderer/techniques/voxel_clipmap/irradiance_select/irradiance_select.h"
#include "renderer/techniques/voxel_clipmap/irradiance_shade/irradiance_shade.h"
#include "renderer/techniques/voxel_clipmap/scene_voxel_feed/scene_voxel_feed.h"
#include "renderer/techniques/voxel_clipmap/scene_voxel_fill/scene_voxel_fill.h"
#include "renderer/techniques/voxel_clipmap/scene_voxel_invalidate/scene_voxel_invalidate.h"
#include "renderer/techniques/voxel_clipmap/scene_voxel_light/scene_voxel_light.h"
#include "renderer/techniques/voxel_clipmap/scene_voxels/scene_voxels.h"

namespace gib {
namespace {
// The seed's ranges: up to 32768 feed pixels per frame ("we have chosen this number to be
// 32768 or smaller"; ultra takes 65536, still below its "hundred thousand pixels" timing),
// queue A 512-1024 and queue B 64-128 cells; A' is an eighth of A. Levels and grid set the
// memory (voxels 16 bytes, cells 172 bytes); rays per cell are one workgroup; direct_lighting's
// sky rays follow the ladder of the other techniques.
struct Preset {
  const char* name;
  uint32_t levels, grid, feed_pixels, queue_a, queue_a_new, queue_b, rays_per_cell, sky_rays;
};
// scene_voxel_light visits one level's voxels a frame (grid^3), so each voxel every `levels`
// frames (the seed refreshes one clipmap level a frame).
constexpr Preset kPresets[] = {{"low", 3, 32, 8192, 512, 64, 64, 32, 1},
                               {"medium", 4, 32, 32768, 1024, 128, 128, 64, 4},
                               {"high", 4, 64, 32768, 1024, 128, 128, 128, 16},
                               {"ultra", 5, 64, 65536, 1024, 128, 128, 256, 64}};
void apply_preset_row(VoxelClipmapSettings& s, const Preset& p) {
  s.levels = p.levels;
  s.grid = p.grid;
  s.feed_pixels = p.feed_pixels;
  s.queue_a = p.queue_a;
  s.queue_a_new = p.queue_a_new;
  s.queue_b = p.queue_b;
  s.rays_per_cell = p.rays_per_cell;
  s.sky_rays = p.sky_rays;
  s.lit_voxels = p.grid * p.grid * p.grid;
}

using S = VoxelClipmapSettings;
std::vector<TechniqueOption> own_options() {
  return {
      option("sky_rays",
             "direct_lighting's cosine rays per pixel for sky and emissive light (0: sky and emitters come from the "
             "irradiance clipmap, the seed's; `direct` is then the voxel approximation, not exact)",
             0, 4096, &DirectLightingParams::sky_rays),
      option("levels", "nested clipmap levels (voxel size doubles per level)", 1, 8, &S::levels),
      option("grid", "voxels per axis per level (a multiple of 4; irradiance cells: grid / 2)", 8, 128, &S::grid),
      option("voxel_size", "level-0 voxel edge in metres (irradiance cells are twice that)", 0.005, 100, &S::voxel_size),
      option("feed_pixels", "G-buffer pixels fed into the voxels per frame (K)", 0, 1048576, &S::feed_pixels),
      option("feed_weight", "exponential-average weight of a new feed sample", 0.001, 1, &S::feed_weight),
      option("geometry_fill", "voxels entering the clipmap take opacity from the scene's triangles (0: empty, the control)",
             0, 1, &S::geometry_fill),
      option("invalidate", "voxels in the box of moved geometry are cleared and refilled (0/1)", 0, 1, &S::invalidate),
      option("semi_transparent",
             "alpha-tested surfaces give voxels their mean opacity and rays accumulate-and-extinct (0: opaque voxels)", 0,
             1, &S::semi_transparent),
      option("multi_bounce",
             "fed pixels add albedo x the irradiance clipmap's bounce light (0: voxels hold direct light only, one "
             "bounce: the control)",
             0, 1, &S::multi_bounce),
      option("geometry_light",
             "voxels no pixel has fed are lit at their triangle (direct light, emission, albedo x the irradiance "
             "clipmap), cells with geometry out of view take queue A's spare capacity, cube lookups skip cells behind "
             "another wall (0: unfed voxels keep a coarser voxel's radiance or stay black, and a closed room no pixel "
             "sees all of goes dark)",
             0, 1, &S::geometry_light),
      option("lit_voxels", "voxels scene_voxel_light visits per frame (a window moving over the clipmap atlas)", 1,
             16777216, &S::lit_voxels),
      option("queue_a", "irradiance cells with geometry relit per frame at most (queue A, A' included)", 0, 65536,
             &S::queue_a),
      option("queue_a_new", "cells with geometry never relit, relit first (queue A')", 0, 65536, &S::queue_a_new),
      option("queue_b", "empty irradiance cells relit per frame at most (queue B)", 0, 65536, &S::queue_b),
      option("rays_per_cell", "rays per relit cell, one thread each (32, 64, 128 or 256)", 32, 256, &S::rays_per_cell),
      option("march_steps", "voxels a ray visits at most", 1, 4096, &S::march_steps),
      option("select_per_queue",
             "irradiance_select adapts one threshold P for cells with geometry (towards queue A's capacity) and one for "
             "empty cells (towards queue B's), instead of one P for both (0/1)",
             0, 1, &S::select_per_queue),
      option("history_frames", "relight temporal weight min(1, age / history_frames)", 1, 1024, &S::history_frames),
      option("convex_offset",
             "leak mitigation: lookup moved along the normal, cells behind the surface's plane dropped (0/1)", 0, 1,
             &S::convex_offset),
      option("wall_test",
             "with geometry_light, cube lookups skip corner cells behind another wall: 0 none, 1 a voxel walk per "
             "pixel and cell through the kept triangles' planes, 2 one bit of the cell's flood mask (voxels without "
             "geometry joined to its ray origin, flooded at relight; the walk where it has no answer)",
             0, 2, &S::wall_test),
  };
}

}  // namespace

Technique voxel_clipmap_technique() {
  Technique t;
  t.name = "voxel-clipmap";
  t.description =
      "Enlisted GI: toroidal clipmap of lit scene voxels fed from K random G-buffer pixels, irradiance clipmap of "
      "ambient cubes relit from age-weighted queues by brute-force voxel ray marching, convex offset filtering, "
      "semi-transparent voxels (renderer/techniques/voxel_clipmap/voxel_clipmap.md)";
  t.passes = {{"visibility", make_visibility_pass},
              {"gbuffer", make_gbuffer_pass},
              {"direct_lighting", make_direct_lighting_pass},
              {"scene_voxels", make_scene_voxels_pass},
              {"scene_voxel_invalidate", make_scene_voxel_invalidate_pass},
              {"scene_voxel_fill", make_scene_voxel_fill_pass},
              {"irradiance_clipmap", make_irradiance_clipmap_pass},
              {"irradiance_select", make_irradiance_select_pass},
              {"irradiance_relight", make_irradiance_relight_pass},
              {"scene_voxel_feed", make_scene_voxel_feed_pass},
              {"scene_voxel_light", make_scene_voxel_light_pass},
              {"irradiance_shade", make_irradiance_shade_pass},
              {"composite", make_composite_pass}};
  t.output = "final_color";
  t.contract_aovs = {{"direct", "direct_radiance"}, {"indirect_diffuse", "indirect_diffuse"}};
  t.aovs = {"indirect_diffuse", "direct_radiance", "gi_irradiance",  "gi_direct_irradiance",
            "direct_light",     "gbuffer_albedo",  "gbuffer_normal", "gbuffer_position"};
  t.stages = voxel_clipmap_stages();
  // VcState: 4 x 8 ivec4 origins (128 words), select (4), stats (4); VcQueue: args (4), counts (4).
  t.stats = {
      {"voxels_entered", "voxels that entered the clipmap or were invalidated this frame", "voxel_clip_state", 132},
      {"voxels_fed", "voxel writes from G-buffer pixels this frame", "voxel_clip_state", 133},
      {"voxels_geometry", "entered voxels given opacity by voxelising triangles this frame", "voxel_clip_state", 134},
      {"cells_entered", "irradiance cells that entered the clipmap this frame", "voxel_clip_state", 135},
      {"cells_new", "cells relit from queue A' (geometry, never relit) this frame", "irradiance_queue", 4},
      {"cells_a", "cells relit from queue A (geometry) this frame", "irradiance_queue", 5},
      {"cells_b", "cells relit from queue B (empty) this frame", "irradiance_queue", 6},
      {"cells_passed", "visible cells that passed age x random > P this frame", "irradiance_queue", 7},
  };
  define_settings<VoxelClipmapSettings>(t, kPresets, apply_preset_row);
  t.options = with_common_options(own_options(), {0, 1});
  add_direct_light_modes(t);  // option direct_light: traced or shadow_mapped
  return t;
}

}  // namespace gib
