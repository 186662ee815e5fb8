#version 460
#extension GL_GOOGLE_include_directive : require
// Cascaded light grid (idTech 8 "Lighting the RT World"): one 4x4x4 group per 4x4x4 block of
// cells. Coarse: the group's 64 threads test every light against the block's union box and set
// bits in a group-shared flat bit array (ordered by light index). Detailed: each thread tests
// its own cell against the lights whose bits are set and writes up to 64 ids, in order.
#include "renderer/techniques/radiance_cache/light_grid/light_grid_shared.h"
#include "frame.glsl"
#include "scene.glsl"
GIB_SCENE_BUFFERS(0, kBindSceneFirst)
layout(push_constant) uniform Push { LightGridPush push; };
#define LG_PARAMS push.lg
#include "renderer/techniques/radiance_cache/include/light_grid.glsl"

layout(local_size_x = kLightGridGroup, local_size_y = kLightGridGroup, local_size_z = kLightGridGroup) in;
layout(std430, set = 0, binding = kLightGridBindGrid) writeonly buffer GridBuffer { uint grid[]; };
layout(std430, set = 0, binding = kLightGridBindStats) buffer StatsBuffer { LightGridStats stats; };

shared uint s_bits[kLightGridBitWords];

// Sphere (centre, radius) overlaps the box: squared distance to the closest point <= r^2.
bool sphere_overlaps_box(vec3 centre, float r, vec3 bmin, vec3 bmax) {
  vec3 d = centre - clamp(centre, bmin, bmax);
  return dot(d, d) <= r * r;
}

// Conservative spot test: false only when the box's bounding sphere lies wholly outside the
// outer cone (or behind the apex). Distance from the sphere centre to the cone's lateral
// surface, cos*h - a*sin (h: distance from the axis, a: along it), never exceeds the distance
// to the solid cone, so rejecting when it exceeds the sphere radius drops no lit point.
bool cone_may_touch_box(GpuLight l, vec3 bmin, vec3 bmax) {
  vec3 c = 0.5 * (bmin + bmax);
  float rb = 0.5 * length(bmax - bmin) * 1.001 + 1e-4;  // margin for rounding
  vec3 v = c - l.position;
  float a = dot(v, l.direction);
  if (a < -rb) return false;
  float h = sqrt(max(dot(v, v) - a * a, 0.0));
  float cos_o = clamp(l.cos_outer, 0.0, 1.0);
  float sin_o = sqrt(max(1.0 - cos_o * cos_o, 0.0));
  return cos_o * h - a * sin_o <= rb;
}

bool light_touches_box(uint i, vec3 bmin, vec3 bmax) {
  GpuLight l = gib_lights[i];
  if (!sphere_overlaps_box(l.position, l.range, bmin, bmax)) return false;
  if ((push.flags & kLightGridFlagConeCull) != 0u && l.kind == GIB_LIGHT_SPOT) return cone_may_touch_box(l, bmin, bmax);
  return true;
}

void main() {
  uint t = gl_LocalInvocationIndex;
  uint cascade = gl_WorkGroupID.z / (kLightGridDim / kLightGridGroup);
  uvec3 local = gl_GlobalInvocationID - uvec3(0u, 0u, cascade * kLightGridDim);
  vec3 camera = gib_frame.camera_pos.xyz;
  uint light_count = min(uint(push.lg.extent.z), kLightGridSceneLights);
  uint words = (light_count + 31u) / 32u;

  for (uint w = t; w < words; w += kLightGridGroup * kLightGridGroup * kLightGridGroup) s_bits[w] = 0u;
  barrier();

  // Coarse: the union box of the group's 64 cells.
  uvec3 block = local - gl_LocalInvocationID;
  vec3 cmin, cmax, unused_min, unused_max;
  lg_cell_bounds(cascade, block, camera, push.lg, cmin, unused_max);
  lg_cell_bounds(cascade, block + uvec3(kLightGridGroup - 1u), camera, push.lg, unused_min, cmax);
  for (uint i = t; i < light_count; i += kLightGridGroup * kLightGridGroup * kLightGridGroup)
    if (light_touches_box(i, cmin, cmax)) atomicOr(s_bits[i >> 5u], 1u << (i & 31u));
  barrier();

  // Detailed: this thread's cell against the survivors, in light order.
  vec3 bmin, bmax;
  lg_cell_bounds(cascade, local, camera, push.lg, bmin, bmax);
  uint base = lg_cell_index(cascade, local) * kLightGridCellWords;
  uint total = 0u;
  for (uint w = 0u; w < words; ++w) {
    uint bits = s_bits[w];
    while (bits != 0u) {
      uint b = uint(findLSB(bits));
      bits &= bits - 1u;
      uint i = w * 32u + b;
      if (!light_touches_box(i, bmin, bmax)) continue;
      if (total < kLightGridMaxLights) grid[base + 1u + total] = i;
      ++total;
    }
  }
  grid[base] = min(total, kLightGridMaxLights);
  if (total > kLightGridMaxLights) atomicAdd(stats.overflowed_cells, 1u);
  if (total > 0u) atomicMax(stats.max_lights_in_a_cell, total);
}
