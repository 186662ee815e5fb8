// Body of the deferred_texturing kernels: deferred_texturing.comp (pixel lists, subgroup
// permutations), deferred_texturing_plain.comp (pixel lists, no subgroup operations) and
// deferred_texturing_uber.comp (GIB_TEXTURING_UBER: every pixel, no lists bound);
// deferred_texturing_sky.comp (GIB_TEXTURING_SKY) writes the sky pixels the lists leave out. One invocation
// per list entry or per pixel; all call load_texel(), material_albedo() and store_texel(), so
// they agree bit for bit. GIB_TEXTURING_VRCS (the *_vrcs kernels): variable-rate shading over the lists.
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
#if !defined(GIB_TEXTURING_UBER) && !defined(GIB_TEXTURING_SKY)
layout(std430, set = 0, binding = kTexBindSegments) buffer Segments { uint seg[]; };
layout(std430, set = 0, binding = kTexBindCommands) readonly buffer Commands { uint commands[]; };
#endif
#ifdef GIB_TEXTURING_VRCS
layout(std430, set = 0, binding = kTexBindRates) buffer Rates { uint vrcs_rate_words[]; };
#include "renderer/techniques/deferred/include/vrcs.glsl"
#endif
layout(push_constant) uniform Push { TexPush push; };

// What texturing reads of one geometry pixel, loaded once: its triangle's vertices and the
// interpolated attributes attribute_interpolate stored.
struct Texel {
  GpuVertex va, vb, vc;
  vec2 bc;     // barycentrics
  uvec4 dv;    // packed derivatives and flags
  vec4 frame;  // tangent frame
};

Texel load_texel(ivec2 p, uint tri) {
  GpuTriangle t = gib_triangles[tri];
  Texel x;
  x.va = gib_vertices[t.i0];
  x.vb = gib_vertices[t.i1];
  x.vc = gib_vertices[t.i2];
  x.bc = imageLoad(in_bary, p).xy;
  x.dv = imageLoad(in_deriv, p);
  x.frame = imageLoad(in_frame, p);
  return x;
}

// The material's albedo at a pixel, filtered over its footprint. `shader`: the texture kind
// this pipeline evaluates (the uber kernel passes the material's own).
// The pixel's uv and its footprint (uv derivatives from the barycentric differentials).
void texel_uv(Texel x, out vec2 uv, out vec2 duv_dx, out vec2 duv_dy) {
  float w = 1.0 - x.bc.x - x.bc.y;
  vec2 uva = vec2(x.va.u, x.va.v), uvb = vec2(x.vb.u, x.vb.v), uvc = vec2(x.vc.u, x.vc.v);
  uv = uva * w + uvb * x.bc.x + uvc * x.bc.y;
  vec2 bcx = vec2(gib_unpack_bary_deriv(x.dv.x), gib_unpack_bary_deriv(x.dv.y));
  vec2 bcy = vec2(gib_unpack_bary_deriv(x.dv.z), gib_unpack_bary_deriv(x.dv.w));
  duv_dx = (uvb - uva) * bcx.x + (uvc - uva) * bcx.y;
  duv_dy = (uvb - uva) * bcy.x + (uvc - uva) * bcy.y;
}

vec3 material_albedo(Texel x, GpuMaterial m, uint shader) {
  vec2 uv, duv_dx, duv_dy;
  texel_uv(x, uv, duv_dx, duv_dy);
  m.texture = shader;  // a classified pipeline's constant: the texture switch folds away
  return gib_material_albedo_filtered(m, uv, duv_dx, duv_dy);
}

// Its emitted radiance (an emissive texture filtered like the albedo).
vec3 material_emissive(Texel x, GpuMaterial m) {
  if (m.emissive_texture == GIB_TEXTURE_NO_INDEX) return m.emissive;
  vec2 uv, duv_dx, duv_dy;
  texel_uv(x, uv, duv_dx, duv_dy);
  return gib_material_emissive_filtered(m, uv, duv_dx, duv_dy);
}

// Writes the G-buffer texel of geometry pixel p (its own position and normal, from x) with
// material m and the given albedo (its own, or its VRCS anchor's).
void store_texel(ivec2 p, Texel x, GpuMaterial m, vec3 albedo) {
  vec3 a = x.va.position, b = x.vb.position, c = x.vc.position;
  vec3 n = vec3(x.frame.xy, gib_unit_z_from_xy(x.frame.x, x.frame.y, gib_bary_deriv_flag(x.dv.y)));
  if (push.inject_nan != 0u && all(equal(uvec2(p), uvec2(push.inject_x, push.inject_y)))) n = vec3(gib_nan());
  vec3 o, d;
  gib_camera_ray(vec2(p) + 0.5, o, d);
  // Position: the camera ray meets the triangle's plane (as an engine rebuilds it from depth).
  // The half-float barycentrics would place it up to ~5e-4 of an edge length off: 1 cm on a
  // 20 m floor, a 0.2 % bias in a point light's irradiance (tests/test_aov_contract.cpp).
  vec3 g = cross(b - a, c - a);
  float denom = dot(d, g);
  float w = 1.0 - x.bc.x - x.bc.y;
  vec3 position = abs(denom) > 0.0 ? o + d * (dot(a - o, g) / denom) : a * w + b * x.bc.x + c * x.bc.y;
  imageStore(out_albedo, p, vec4(albedo, m.sheen));  // decals: gbuffer_update
  imageStore(out_normal, p, vec4(n, m.roughness));
  imageStore(out_position, p, vec4(position, distance(position, o)));
  imageStore(out_emissive, p, vec4(material_emissive(x, m), m.translucency));
}

#if defined(GIB_TEXTURING_SKY)
// The classified kernels' companion: sky pixels are in no pixel list, so their G-buffer texels
// are written here, zero, as the uber kernel writes them. A dispatch over the vbuffer, not a
// clear of the four images: vkCmdClearColorImage on these storage images cost 2.8 ms at
// 2560x1440 on an H200, this kernel a few microseconds.
void main() {
  ivec2 p = ivec2(gl_WorkGroupID.xy) * 8 + ivec2(gl_LocalInvocationIndex % 8u, gl_LocalInvocationIndex / 8u);
  if (any(greaterThanEqual(p, imageSize(vbuffer)))) return;
  if (imageLoad(vbuffer, p).x != kVisibilityNone) return;
  imageStore(out_albedo, p, vec4(0.0));
  imageStore(out_normal, p, vec4(0.0));
  imageStore(out_position, p, vec4(0.0));
  imageStore(out_emissive, p, vec4(0.0));
}

#elif defined(GIB_TEXTURING_UBER)
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
  Texel x = load_texel(p, ids.x - 1u);
  store_texel(p, x, m, material_albedo(x, m, min(m.texture, kDeferredShaderCount - 1u)));
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
  Texel x = load_texel(p, ids.x - 1u);
  vec3 albedo = material_albedo(x, m, kShader);
  store_texel(p, x, m, albedo);
#ifdef GIB_TEXTURING_VRCS
  uint covered = 0u;
  if (p == anchor)
    for (int y = 0; y < cell.y; ++y)
      for (int x = 0; x < cell.x; ++x) {
        ivec2 q = anchor + ivec2(x, y);
        if (!gib_vrcs_follows(q, anchor, imageSize(vbuffer))) continue;
        store_texel(q, load_texel(q, imageLoad(vbuffer, q).x - 1u), m, albedo);
        ++covered;
      }
  gib_vrcs_count(kVrcsStats + kVrcsStatTextured, 1u, 1u + covered);  // kVrcsStatTexturedOf follows
#endif
}
#endif
