#version 460
#extension GL_GOOGLE_include_directive : require
#include "tests/rc_world_test_shared.h"
#include "frame.glsl"
#include "scene.glsl"
GIB_SCENE_BUFFERS(0, kBindSceneFirst)
layout(constant_id = kRcTestSpecMode) const uint kMode = 0u;
layout(local_size_x = kRcTestGroup) in;
layout(std430, set = 0, binding = kRcTestBindHits) readonly buffer HitBuffer { ProbeHit probe_hits[]; };
layout(std430, set = 0, binding = kRcTestBindKeys) writeonly buffer KeyBuffer { RcTestKey keys[]; };
layout(set = 0, binding = kRcTestBindIrradiance, r32ui) uniform readonly uimage2D atlas_irradiance;
layout(set = 0, binding = kRcTestBindVisibility, rg16f) uniform readonly image2D atlas_visibility;
layout(set = 0, binding = kRcTestBindDecoded, rgba32f) uniform writeonly image2D decoded;
layout(push_constant) uniform Push { RcParams rc; };
#include "renderer/techniques/radiance_cache/include/probe_volume.glsl"
#include "renderer/techniques/radiance_cache/include/radiance_cache.glsl"

void main() {
  uint id = gl_GlobalInvocationID.x;
  if (kMode == 0u) {
    uint rays = rc_rays_per_probe();
    if (id >= kProbeGridDim * kProbeGridDim * kProbeGridDim * rays) return;
    ProbeHit h = probe_hits[id];
    RcTestKey k;
    k.position = vec4(0.0);
    k.key = uvec4(0u, 0u, 0u, h.key);  // w: the key probe_trace stored
    uint probe = id / rays, ray = id - probe * rays;
    uint c = rc_updated_cascade();
    vec3 d = rc_ray_direction(ray, rays, rc_frame_rotation(rc.misc.x));
    if (h.triangle_plus1 != 0u && !rc_probe_ray_inside(h, d, c)) {
      vec3 p = rc_hit_position(rc_probe_position(c, rc_probe_coord(probe)), d, h.distance);
      vec3 n = rc_facing_normal(h.triangle_plus1 - 1u, d);
      float lod;
      uint key = rc_cell_key(p, n, lod);
      k.position = vec4(p, lod);
      k.key = uvec4(key, rc_cell_first_slot(key), rc_side(n), h.key);
    }
    keys[id] = k;
  } else {
    ivec2 size = imageSize(decoded);
    ivec2 t = ivec2(int(id) % size.x, int(id) / size.x);
    if (t.y >= size.y) return;
    vec2 m = imageLoad(atlas_visibility, t).xy;
    imageStore(decoded, t, vec4(gib_unpack_rgb9e5(imageLoad(atlas_irradiance, t).x), m.x));
  }
}
