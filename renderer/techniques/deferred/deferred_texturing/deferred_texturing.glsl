// Body of the deferred_texturing kernels: deferred_texturing.comp (pixel lists, subgroup
// permutations), deferred_texturing_plain.comp (pixel lists, no subgroup operations) and
// deferred_texturing_uber.comp (GIB_TEXTURING_UBER: every pixel, no lists bound). One invocation
// per list entry or per pixel; all call material_albedo() and store_texel(), so they agree bit
// for bit. GIB_TEXTURING_VRCS (the *_vrcs kernels): variable-rate shading over the lists.
#include "renderer/techniques/deferred/deferred_texturing/deferred_texturing_shared.h"
#include "frame.glsl"
#include "scene.glsl"
GIB_SCENE_BUFFERS(0, kBindSceneFirst)
#include "hash.glsl"
#include "material.glsl"
#include "surface.glsl"
#include "finite.glsl"
#include "renderer/techniques/deferred/include/deferred_attributes.glsl"

layout(constant_id = kTexSpecShader) const uint kShader = 0u;
layout(constant_id = kTexSpecPermutation) const uint kPermutation = kTexPermPlain;
layout(constant_id = kTexSpecHasUniform) const bool kHasUniform = false;

layout(local_size_x = kDeferredWave) in;
layout(set = 0, binding = kTexBindVbuffer, rg32ui) uniform readonly uimage2D vbuffer;
layout(set = 0, binding = kTexBindBary, rg16f) uniform readonly image2D in_bary;
layout(set = 0, binding = kTexBindBaryDeriv, rgba16ui) uniform readonly uimage2D in_deriv;
layout(set = 0, binding = kTexBindTangentFrame, rgba16f) uniform readonly image2D in_frame;
layout(set = 0, binding = kTexBindAlbedo, rgba16f) uniform writeonly image2D out_albedo;
layout(set = 0, binding = kTexBindNormal, rgba16f) uniform writeonly image2D out_normal;
layout(set = 0, binding = kTexBindPosition, rgba32f) uniform writeonly image2D out_position;
layout(set = 0, binding = kTexBindEmissive, rgba16f) uniform writeonly image2D out_emissive;
#ifndef GIB_TEXTURING_UBER
layout(std430, set = 0, binding = kTexBindSegments) buffer Segments { uint seg[]; };
layout(std430, set = 0, binding = kTexBindCommands) readonly buffer Commands { uint commands[]; };
#endif
#ifdef GIB_TEXTURING_VRCS
layout(std430, set = 0, binding = kTexBindRates) buffer Rates { uint vrcs_rate_words[]; };
#include "renderer/techniques/deferred/include/vrcs.glsl"
#endif
layout(push_constant) uniform Push { TexPush push; };

// The material's albedo at geometry pixel p (triangle tri), filtered over the pixel footprint.
// `shader`: the texture kind this pipeline evaluates (the uber kernel passes the material's own).
vec3 material_albedo(ivec2 p, uint tri, GpuMaterial m, uint shader) {
  vec2 bc = imageLoad(in_bary, p).xy;
  uvec4 dv = imageLoad(in_deriv, p);
  GpuTriangle t = gib_triangles[tri];
  GpuVertex va = gib_vertices[t.i0], vb = gib_vertices[t.i1], vc = gib_vertices[t.i2];
  float w = 1.0 - bc.x - bc.y;
  vec2 uva = vec2(va.u, va.v), uvb = vec2(vb.u, vb.v), uvc = vec2(vc.u, vc.v);
  vec2 uv = uva * w + uvb * bc.x + uvc * bc.y;
  vec2 bcx = vec2(gib_unpack_bary_deriv(dv.x), gib_unpack_bary_deriv(dv.y));
  vec2 bcy = vec2(gib_unpack_bary_deriv(dv.z), gib_unpack_bary_deriv(dv.w));
  vec2 duv_dx = (uvb - uva) * bcx.x + (uvc - uva) * bcx.y;
  vec2 duv_dy = (uvb - uva) * bcy.x + (uvc - uva) * bcy.y;
  m.texture = shader;  // a classified pipeline's constant: the texture switch folds away
  return gib_material_albedo_filtered(m, uv, duv_dx, duv_dy);
}

// Writes the G-buffer texel of geometry pixel p (its own position and normal) with material m
// and the given albedo (its own, or its VRCS anchor's).
void store_texel(ivec2 p, GpuMaterial m, vec3 albedo) {
  uint tri = imageLoad(vbuffer, p).x - 1u;
  vec2 bc = imageLoad(in_bary, p).xy;
  uvec4 dv = imageLoad(in_deriv, p);
  vec4 frame = imageLoad(in_frame, p);
  GpuTriangle t = gib_triangles[tri];
  vec3 a = gib_vertices[t.i0].position, b = gib_vertices[t.i1].position, c = gib_vertices[t.i2].position;
  vec3 n = vec3(frame.xy, gib_unit_z_from_xy(frame.x, frame.y, gib_bary_deriv_flag(dv.y)));
  if (push.inject_nan != 0u && all(equal(uvec2(p), uvec2(push.inject_x, push.inject_y)))) n = vec3(gib_nan());
  vec3 o, d;
  gib_camera_ray(vec2(p) + 0.5, o, d);
  // Position: the camera ray meets the triangle's plane (as an engine rebuilds it from depth).
  // The half-float barycentrics would place it up to ~5e-4 of an edge length off: 1 cm on a
  // 20 m floor, a 0.2 % bias in a point light's irradiance (tests/test_aov_contract.cpp).
  vec3 g = cross(b - a, c - a);
  float denom = dot(d, g);
  float w = 1.0 - bc.x - bc.y;
  vec3 position = abs(denom) > 0.0 ? o + d * (dot(a - o, g) / denom) : a * w + b * bc.x + c * bc.y;
  imageStore(out_albedo, p, vec4(albedo, m.metalness));
  imageStore(out_normal, p, vec4(n, m.roughness));
  imageStore(out_position, p, vec4(position, distance(position, o)));
  imageStore(out_emissive, p, vec4(m.emissive, m.translucency));
}

#ifdef GIB_TEXTURING_UBER
void main() {
  // 8x8 pixels per workgroup.
  ivec2 p = ivec2(gl_WorkGroupID.xy) * 8 + ivec2(gl_LocalInvocationIndex % 8u, gl_LocalInvocationIndex / 8u);
  if (any(greaterThanEqual(p, imageSize(vbuffer)))) return;
  uvec2 ids = imageLoad(vbuffer, p).xy;
  if (ids.x == kVisibilityNone) {
    imageStore(out_albedo, p, vec4(0.0));
    imageStore(out_normal, p, vec4(0.0));
    imageStore(out_position, p, vec4(0.0));
    imageStore(out_emissive, p, vec4(0.0));
    return;
  }
  GpuMaterial m = gib_materials[gib_instances[ids.y].material];
  store_texel(p, m, material_albedo(p, ids.x - 1u, m, min(m.texture, kDeferredShaderCount - 1u)));
}

#else
void main() {
  uint wave = seg[4u * kShader + 3u] + gl_WorkGroupID.x;
  uint command = commands[wave * kDeferredWave + gl_LocalInvocationIndex];
  if (command == kDeferredPixelPad) return;  // padding: inactive from here on
  uint tile = command >> 10u;
  ivec2 p = ivec2(tile % push.tiles_x, tile / push.tiles_x) * int(kDeferredTile) +
            ivec2(command & 31u, (command >> 5u) & 31u);
  uvec2 ids = imageLoad(vbuffer, p).xy;
  uint instance = ids.y;
#ifdef GIB_TEXTURING_VRCS
  // A pixel its coarse cell's anchor covers retires: the anchor writes its texel below.
  ivec2 cell;
  ivec2 anchor = gib_vrcs_anchor(p, gib_vrcs_rate(p, push.rate_tiles_x), cell);
  if (gib_vrcs_follows(p, anchor, imageSize(vbuffer))) return;
#endif
#ifdef GIB_TEXTURING_SUBGROUPS
  // The seed's uniform-data trick: the material is uniform per wave by construction; the
  // instance usually is. The uniform permutation takes subgroups whose active invocations share
  // it (and tells the compiler so by broadcasting); the divergent one the rest.
  bool uniform_data = subgroupAllEqual(instance);
  if (kPermutation == kTexPermUniform) {
    if (!uniform_data) return;
    instance = subgroupBroadcastFirst(instance);
  } else if (kPermutation == kTexPermDivergent && kHasUniform && uniform_data) {
    return;
  }
  if (subgroupElect())
    atomicAdd(seg[kSegStats + (kPermutation == kTexPermUniform ? kStatSubgroupsUniform : kStatSubgroupsDivergent)], 1u);
#endif
  GpuMaterial m = gib_materials[gib_instances[instance].material];
  vec3 albedo = material_albedo(p, ids.x - 1u, m, kShader);
  store_texel(p, m, albedo);
#ifdef GIB_TEXTURING_VRCS
  uint covered = 0u;
  if (p == anchor)
    for (int y = 0; y < cell.y; ++y)
      for (int x = 0; x < cell.x; ++x) {
        ivec2 q = anchor + ivec2(x, y);
        if (!gib_vrcs_follows(q, anchor, imageSize(vbuffer))) continue;
        store_texel(q, m, albedo);
        ++covered;
      }
  gib_vrcs_count(kVrcsStats + kVrcsStatTextured, 1u, 1u + covered);  // kVrcsStatTexturedOf follows
#endif
}
#endif
