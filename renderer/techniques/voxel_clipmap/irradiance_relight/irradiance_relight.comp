// irradiance_relight: one workgroup per queued cell, one thread per ray (see
// irradiance_relight.h). The six directions are reduced in shared memory in a fixed order, so
// the result does not depend on thread timing.
#version 460
#extension GL_GOOGLE_include_directive : require
#include "renderer/techniques/voxel_clipmap/irradiance_relight/irradiance_relight_shared.h"
#include "frame.glsl"
#include "scene.glsl"
#include "hash.glsl"
#include "packing.glsl"
#include "finite.glsl"
#include "lights.glsl"
layout(local_size_x_id = kIrrRelightSpecRays) in;
layout(push_constant) uniform Push { VcParams vc; };
VC_STATE_BUFFER(kIrrRelightBindState, readonly)
VC_VOXEL_BUFFER(kIrrRelightBindVoxels, readonly)
layout(std430, set = 0, binding = kIrrRelightBindQueue) readonly buffer QueueBuffer {
  VcQueue queue;
  uint entries[];
};
VC_CUBE_BUFFERS(kIrrRelightBindX, kIrrRelightBindY, kIrrRelightBindZ, kIrrRelightBindCells, )
VC_VIS_BUFFER(kIrrRelightBindVis, writeonly)
#define VC_HAS_STATE
#define VC_HAS_VOXELS
#include "renderer/techniques/voxel_clipmap/include/vc_common.glsl"

shared vec4 s_bounce[kVcMaxRays];  // rgb: radiance x weight, a: weight
shared vec4 s_sky[kVcMaxRays];     // rgb: radiance x weight, a: weight of a ray that met voxels (1 - transmittance)
shared vec3 s_result[12];          // per direction (+x, -x, +y, -y, +z, -z): bounce, then direct (sky, emitters)
shared float s_hit[6];             // per direction: the cosine-weighted share of rays that met voxels
const uint kVisRows = uint(kVcVisWindow * kVcVisWindow);
shared uint s_free[kVisRows];       // flood window rows (y, z): bit x set where the voxel holds no geometry
shared uint s_seed[kVisRows];       // bit x set where the flood starts (the rays' origin voxel)
shared uint s_reach[2][kVisRows];   // voxels reached, double-buffered so the steps do not race

// The cell's flood mask (irradiance_cell_vis, voxel_clipmap_shared.h): the voxels without
// geometry joined to the voxel its rays start in (`origin`, as the cell state records it; the
// seed box is every voxel of the 2 x 2 x 2 for a cell whose rays start at its centre, none for
// a solid one) by a staircase of free voxels moving away from it on every axis (monotone: a
// path over a roof's edge and back under it is not line of sight), within the window of world
// voxels 2k - 3 .. 2k + 4; kVcVisSteps steps, each spreading along x through a row and one
// voxel across rows. A voxel outside the level's box counts as free. The cube lookups then test a pixel's air voxel against one bit instead of
// walking the voxels between them (wall_test 2). Called by every thread (it has barriers).
void flood_cell_vis(uint l, ivec3 k, uint origin, uint cell) {
  uint tid = gl_LocalInvocationIndex, threads = gl_WorkGroupSize.x;
  const int w = kVcVisWindow;
  ivec3 base = 2 * k - ivec3(3);
  uint seed_at = (origin & kVcCellOriginMask) >> kVcCellOriginShift;
  // The seed box in window coordinates (the cell's voxels are 3 and 4 on each axis).
  ivec3 lo = ivec3(3), hi = ivec3(4);
  if (origin != kVcCellOriginCentre) lo = hi = ivec3(3) + ivec3(seed_at & 1u, (seed_at >> 1u) & 1u, (seed_at >> 2u) & 1u);
  for (uint r = tid; r < kVisRows; r += threads) {
    uint free_row = 0u, seed = 0u;
    for (int x = 0; x < w; ++x) {
      ivec3 g = base + ivec3(x, int(r) % w, int(r) / w);
      bool geometry = vc_in_box(g, vc_voxel_origin(l), vc_n()) && (vc_voxels[vc_voxel_index(l, g)].y & kVcVoxelGeometry) != 0u;
      ivec3 c = g - 2 * k;
      bool in_cell = all(greaterThanEqual(c, ivec3(0))) && all(lessThan(c, ivec3(2)));
      uint i = uint(c.x + 2 * c.y + 4 * c.z);
      bool starts = in_cell && origin != kVcCellSolid && (origin == kVcCellOriginCentre || i == seed_at);
      free_row |= geometry ? 0u : 1u << uint(x);
      seed |= starts ? 1u << uint(x) : 0u;
    }
    s_free[r] = free_row;
    s_seed[r] = seed;
    s_reach[0][r] = seed;
  }
  barrier();
  for (uint it = 0u; it < kVcVisSteps; ++it) {
    uint src = it & 1u, dst = src ^ 1u;
    for (uint r = tid; r < kVisRows; r += threads) {
      int y = int(r) % w, z = int(r) / w;
      // The neighbouring rows on the seed box's side (none along an axis inside the box).
      uint beside = (y > hi.y ? s_reach[src][r - 1u] : 0u) | (y < lo.y ? s_reach[src][r + 1u] : 0u) |
                    (z > hi.z ? s_reach[src][r - uint(w)] : 0u) | (z < lo.z ? s_reach[src][r + uint(w)] : 0u);
      s_reach[dst][r] = vc_vis_row_step(s_free[r], s_seed[r], s_reach[src][r], beside, uint(lo.x), uint(hi.x));
    }
    barrier();
  }
  uint last = kVcVisSteps & 1u;
  if (tid < kVcCellVisWords) {
    const int span = kVcVisSpan;
    uint word = 0u;
    for (uint b = 0u; b < 32u; ++b) {
      int bit = int(tid * 32u + b);
      if (bit >= span * span * span) break;
      ivec3 c = ivec3(bit % span, (bit / span) % span, bit / (span * span)) + ivec3(1);
      word |= ((s_reach[last][uint(c.z * w + c.y)] >> uint(c.x)) & 1u) << b;
    }
    vc_cell_vis[cell * kVcCellVisWords + tid] = word;
  }
}

void main() {
  uint cell = entries[gl_WorkGroupID.x];
  uint tid = gl_LocalInvocationIndex, rays = gl_WorkGroupSize.x;
  uint l = cell / vc_cells_per_level(), slot = cell % vc_cells_per_level();
  int m = vc_m();
  ivec3 s = ivec3(int(slot) % m, (int(slot) / m) % m, int(slot) / (m * m));
  ivec3 k = vc_slot_world(s, vc_cell_origin(l), m);
  // Rays start in the cell's first empty voxel (of its 2x2x2, nearest the origin corner first),
  // not at its centre: a centre on a wall would see the wall's inside or back from within it.
  // A cell whose voxels are all opaque is marked solid (kVcCellSolid): the lookups give it no
  // weight. One of semi-transparent voxels (foliage) with none empty starts at its centre.
  vec3 centre = (vec3(k) + 0.5) * vc_cell_size(l);
  float vs = vc_voxel_size(l);
  uint origin = kVcCellSolid;
  bool opaque = true;
  for (int i = 0; i < 8; ++i) {
    ivec3 g = 2 * k + ivec3(i & 1, (i >> 1) & 1, (i >> 2) & 1);
    bool inside = vc_in_box(g, vc_voxel_origin(l), vc_n());
    uint op8 = inside ? vc_voxels[vc_voxel_index(l, g)].y & kVcOpacityMask : 0u;
    if (inside && op8 == 0u) {
      centre = (vec3(g) + 0.5) * vs;
      origin = uint(i) << kVcCellOriginShift;
      break;
    }
    opaque = opaque && inside && vc_opacity(uvec4(0u, op8, 0u, 0u), vc_flag(kVcFlagSemiTransparent)) >= 1.0;
  }
  if (origin == kVcCellSolid && !opaque) origin = kVcCellOriginCentre;
  if (vc_flag(kVcFlagWallFlood) && vc_flag(kVcFlagGeometryLight)) flood_cell_vis(l, k, origin, cell);

  GibRng rng = gib_rng(vc.rays.z, vc_frame(), uvec2(cell, tid), 13u);
  float z = 1.0 - (2.0 * float(tid) + gib_next(rng)) / float(rays);
  float phi = 6.2831853 * fract(float(tid) * 0.61803399 + gib_next(rng));
  float r = sqrt(max(1.0 - z * z, 0.0));
  vec3 d = vec3(r * cos(phi), r * sin(phi), z);
  float T;
  vec3 emitted;
  vec3 hit = vc_march(centre, d, vc_flag(kVcFlagSemiTransparent), emitted, T);
  vec3 sky = emitted + T * gib_sky_radiance(d);
  if (vc_flag(kVcFlagNanGuards) && !(gib_finite(hit) && gib_finite(sky))) {
    hit = vec3(0.0);
    sky = vec3(0.0);
  }
  float met = 1.0 - T;

  for (uint dir = 0u; dir < 6u; ++dir) {
    float w = max((dir & 1u) == 0u ? d[dir >> 1u] : -d[dir >> 1u], 0.0);
    s_bounce[tid] = vec4(hit * w, w);
    s_sky[tid] = vec4(sky * w, met * w);
    barrier();
    for (uint stride = rays / 2u; stride > 0u; stride /= 2u) {
      if (tid < stride) {
        s_bounce[tid] += s_bounce[tid + stride];
        s_sky[tid] += s_sky[tid + stride];
      }
      barrier();
    }
    if (tid == 0u) {
      float wsum = max(s_bounce[0].a, 1e-6);
      s_result[dir] = s_bounce[0].rgb / wsum;
      s_result[6u + dir] = s_sky[0].rgb / wsum;
      s_hit[dir] = s_sky[0].a / wsum;
    }
    barrier();
  }

  // 3 x kVcCellFloats floats to write: (axis, float f of the axis buffer's 14).
  uint state = vc_cell_state[cell];
  bool relit = (state & kVcCellRelit) != 0u;
  float w = relit ? clamp(float(state & kVcAgeMask) / vc.sizes.z, 1.0 / vc.sizes.z, 1.0) : 1.0;
  for (uint t = tid; t < 3u * kVcCellFloats; t += rays) {
    uint axis = t / kVcCellFloats, f = t % kVcCellFloats;
    // f: 0-2 bounce +axis, 3-5 bounce -axis, 6-8 direct +axis, 9-11 direct -axis, 12-13 hit +/-axis.
    float value;
    if (f < 12u) {
      uint dir = 2u * axis + ((f / 3u) & 1u);
      vec3 v = f < 6u ? s_result[dir] : s_result[6u + dir];
      value = v[f % 3u];
    } else {
      value = s_hit[2u * axis + (f - 12u)];
    }
    uint at = cell * kVcCellFloats + f;
    if (axis == 0u) vc_cube_x[at] = mix(vc_cube_x[at], value, w);
    else if (axis == 1u) vc_cube_y[at] = mix(vc_cube_y[at], value, w);
    else vc_cube_z[at] = mix(vc_cube_z[at], value, w);
  }
  barrier();  // every thread has read the old state before it changes
  if (tid == 0u)
    vc_cell_state[cell] = (state & ~(kVcAgeMask | kVcCellSolid | kVcCellOriginMask | kVcCellOriginCentre)) | kVcCellUpdated | kVcCellRelit | origin;
}
