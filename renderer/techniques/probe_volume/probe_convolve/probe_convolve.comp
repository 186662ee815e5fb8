// probe_convolve: filtered radiance, irradiance and depth moments of each selected probe (see
// probe_convolve.h). One workgroup per probe: the 20x20 texels are box-filtered to 10x10 in
// group-shared memory (the seed's bilinear pre-filter), each thread convolves one output texel,
// then the bordered tiles are written.
//
// Every sum over texels weighs a texel by the solid angle it covers: octahedral texels cover
// equal areas of the octahedron, so a texel towards a face's centre (a diagonal direction)
// subtends 3 sqrt(3) = 5.2 times the solid angle of one on an axis. Counting texels alike
// darkens light arriving from the diagonals and brightens light along the axes (exact only for
// a uniform field).
#version 460
#extension GL_GOOGLE_include_directive : require
#include "renderer/techniques/probe_volume/probe_convolve/probe_convolve_shared.h"
#include "frame.glsl"
#include "scene.glsl"
#include "lights.glsl"
#include "sampling.glsl"
layout(constant_id = kPvConvolveSpecSky) const bool kHasSky = true;
layout(push_constant) uniform Push { PvParams pv; };
#include "renderer/techniques/probe_volume/include/pv_common.glsl"
PV_STATE_BUFFER(kPvConvolveBindState, )
layout(std430, set = 0, binding = kPvConvolveBindSelection) readonly buffer SelectionBuffer {
  PvSelection sel;
  uint pv_entries[];
};
layout(std430, set = 0, binding = kPvConvolveBindMaterial) readonly buffer MaterialBuffer { uvec2 gb_material[]; };
PV_GBUFFER_DEPTH(kPvConvolveBindDepth, readonly)
layout(std430, set = 0, binding = kPvConvolveBindRadianceIn) readonly buffer RadianceIn { vec4 texel_radiance[]; };
layout(std430, set = 0, binding = kPvConvolveBindLocal) readonly buffer LocalIn { float texel_local[]; };
layout(std430, set = 0, binding = kPvConvolveBindIrradiance) buffer IrradianceOut { uvec2 out_irradiance[]; };
layout(std430, set = 0, binding = kPvConvolveBindRadiance) buffer RadianceOut { uvec2 out_radiance[]; };
layout(std430, set = 0, binding = kPvConvolveBindVisibility) buffer VisibilityOut { uint out_visibility[]; };
layout(local_size_x = kPvConvolveGroup) in;

const uint kBlocks = kPvRadianceInterior * kPvRadianceInterior;  // 10x10 blocks of 2x2 texels
const uint kIrr = kPvIrradianceInterior * kPvIrradianceInterior;
shared vec3 s_dir[kBlocks];
shared float s_solid[kBlocks];   // the block's solid angle, up to a constant factor
shared vec3 s_total[kBlocks];     // everything arriving: reflected + emission + sky x visibility
shared vec4 s_reflected[kBlocks]; // rgb reflected, a sky visibility
shared vec2 s_moments[kBlocks];
shared float s_local[kBlocks];
shared vec4 s_out_radiance[kBlocks];
shared vec2 s_out_moments[kBlocks];
shared vec3 s_out_irradiance[kIrr];
shared vec3 s_out_vertex[4];  // the middle border texels of the irradiance tile (pv_irradiance_vertex_texel)
shared float s_scale;

// Irradiance / pi for normal n: the cosine-weighted mean of everything arriving.
vec3 irradiance_for(vec3 n) {
  vec3 sum = vec3(0.0);
  float weight = 0.0;
  for (uint b = 0u; b < kBlocks; ++b) {
    float w = max(dot(n, s_dir[b]), 0.0) * s_solid[b];
    sum += w * s_total[b];
    weight += w;
  }
  return sum / weight;
}

void main() {
  uint e = gl_WorkGroupID.x;
  uint probe = pv_entries[e];
  uint tid = gl_LocalInvocationIndex;
  PvProbe p = pv_probes[probe];
  bool quarter = (uint(p.coord.w) & kPvProbeQuarter) != 0u;
  float unit = pv_spacing(pv_cascade_of(probe)) * kPvSqrt3;

  if (tid < kBlocks) {
    uint bx = tid % kPvRadianceInterior, by = tid / kPvRadianceInterior;
    vec3 d = gib_oct_decode((vec2(bx, by) + 0.5) / float(kPvRadianceInterior));
    vec3 sky = kHasSky ? gib_sky_radiance(d) : vec3(0.0);
    vec3 total = vec3(0.0);
    vec4 reflected = vec4(0.0);
    vec2 moments = vec2(0.0);
    float local = 0.0, solid = 0.0;
    for (uint k = 0u; k < 4u; ++k) {
      uint t = (by * 2u + (k >> 1u)) * kPvGbufferSide + bx * 2u + (k & 1u);
      uint src = quarter ? (by * 2u) * kPvGbufferSide + bx * 2u : t;  // a quarter probe lit one texel per block
      float w = pv_texel_solid_angle(pv_gbuffer_direction(t, false));
      vec4 r = texel_radiance[e * kPvGbufferTexels + src];
      float depth = pv_texel_depth(probe, t, 3.4e38);
      vec3 emission = depth < 3.4e38 ? gib_unpack_rgb9e5(gb_material[pv_gbuffer_index(probe, t)].y) : vec3(0.0);
      total += w * (r.rgb + emission + r.a * sky);
      reflected += w * r;
      // Rescaled and clamped before averaging (the seed: fewer leaks in interior corners).
      float z = min(depth / unit, 1.0);
      moments += w * vec2(z, z * z);
      local += w * texel_local[e * kPvGbufferTexels + src];
      solid += w;
    }
    s_dir[tid] = d;
    s_solid[tid] = solid;
    s_total[tid] = total / solid;
    s_reflected[tid] = reflected / solid;
    s_moments[tid] = moments / solid;
    s_local[tid] = local / solid;
  }
  barrier();
  if (tid == 0u) {
    float sky = 0.0, lum = 0.0, local = 0.0, solid = 0.0;
    for (uint b = 0u; b < kBlocks; ++b) {
      float w = s_solid[b];
      sky += w * s_reflected[b].a;
      lum += w * gib_luminance(s_total[b]);
      local += w * s_local[b];
      solid += w;
    }
    sky /= solid;
    lum /= solid;
    local /= solid;
    // Each probe stores its lighting times 1 / its mean luminance (the seed's lighting scale:
    // precision from dark caves to noon).
    float scale = lum > 1e-6 ? 1.0 / lum : 1.0;
    s_scale = scale;
    pv_probes[probe].offset.w = scale;
    pv_probes[probe].meta = vec4(sky, pv_sun_sky_estimate(sky), local, lum);
    pv_probes[probe].coord.w = p.coord.w | int(kPvProbeValid);
  }
  if (tid < kBlocks) {
    // Filtered radiance and depth moments: the seed's small lobe pow(saturate((cos - 0.75) / 0.25), 4).
    vec3 d = s_dir[tid];
    vec4 sum = vec4(0.0);
    vec2 moments = vec2(0.0);
    float weight = 0.0;
    for (uint b = 0u; b < kBlocks; ++b) {
      float w = clamp((dot(d, s_dir[b]) - 0.75) * 4.0, 0.0, 1.0);
      w = (w * w) * (w * w) * s_solid[b];
      sum += w * s_reflected[b];
      moments += w * s_moments[b];
      weight += w;
    }
    s_out_radiance[tid] = sum / weight;
    s_out_moments[tid] = moments / weight;
    if (tid < 4u) s_out_vertex[tid] = irradiance_for(pv_irradiance_vertex_direction(tid));
  } else if (tid < kBlocks + kIrr) {
    uint i = tid - kBlocks;
    s_out_irradiance[i] = irradiance_for(gib_oct_decode((vec2(i % kPvIrradianceInterior, i / kPvIrradianceInterior) + 0.5) / float(kPvIrradianceInterior)));
  }
  barrier();
  float scale = s_scale;
  for (uint t = tid; t < kPvRadianceTexels; t += kPvConvolveGroup) {
    ivec2 at = ivec2(t % kPvRadianceSide, t / kPvRadianceSide);
    ivec2 src = gib_oct_border_source(at, int(kPvRadianceInterior)) - 1;
    vec4 r = s_out_radiance[uint(src.y) * kPvRadianceInterior + uint(src.x)];
    out_radiance[pv_radiance_index(probe, at)] = uvec2(gib_pack_half2x16(r.rg * scale), gib_pack_half2x16(vec2(r.b * scale, r.a)));
  }
  for (uint pair = tid; pair < kPvRadianceTexels / 2u; pair += kPvConvolveGroup) {
    uint word = 0u;
    for (uint k = 0u; k < 2u; ++k) {
      uint t = pair * 2u + k;
      ivec2 src = gib_oct_border_source(ivec2(t % kPvRadianceSide, t / kPvRadianceSide), int(kPvRadianceInterior)) - 1;
      uvec2 m = uvec2(clamp(s_out_moments[uint(src.y) * kPvRadianceInterior + uint(src.x)], 0.0, 1.0) * 255.0 + 0.5);
      word |= (m.x | (m.y << 8u)) << (16u * k);
    }
    out_visibility[probe * (kPvRadianceTexels / 2u) + pair] = word;
  }
  for (uint t = tid; t < kPvIrradianceTexels; t += kPvConvolveGroup) {
    ivec2 at = ivec2(t % kPvIrradianceSide, t / kPvIrradianceSide);
    ivec2 src = gib_oct_border_source(at, int(kPvIrradianceInterior)) - 1;
    uint vertex = pv_irradiance_vertex_of(at);
    vec3 r = (vertex < 4u ? s_out_vertex[vertex] : s_out_irradiance[uint(src.y) * kPvIrradianceInterior + uint(src.x)]) * scale;
    out_irradiance[pv_irradiance_index(probe, at)] = uvec2(gib_pack_half2x16(r.rg), gib_pack_half2x16(vec2(r.b, 0.0)));
  }
}
