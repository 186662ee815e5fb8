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
#define VC_HAS_STATE
#define VC_HAS_VOXELS
#include "renderer/techniques/voxel_clipmap/include/vc_common.glsl"

shared vec4 s_bounce[kVcMaxRays];  // rgb: radiance x weight, a: weight
shared vec4 s_sky[kVcMaxRays];     // rgb: radiance x weight, a: weight of a ray that met voxels (1 - transmittance)
shared vec3 s_result[12];          // per direction (+x, -x, +y, -y, +z, -z): bounce, then direct (sky, emitters)
shared float s_hit[6];             // per direction: the cosine-weighted share of rays that met voxels

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
