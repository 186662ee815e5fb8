// World radiance cache: an open-addressing hash table of RcCell (radiance_cache_shared.h) keyed
// by quantised world position and a camera-distance LOD (spatial hashing after Gautron 2020, as
// in the seed's "Sampling the World"). Owner: the world-sampling passes; design:
// renderer/techniques/radiance_cache/radiance_cache.md.
//
//   LOD  = 2^floor(log2(1 + |p - camera| / cache.y))       (1, 2, 4, ...)
//   cell = floor(p / (cache.x * LOD))                      (ivec3)
//   h    = pcg(LOD + pcg(cell.z + pcg(cell.y + pcg(cell.x))))   (gib_pcg, hash.glsl; uint wrap)
//   key  = (h & ~3) | 1 (0 marks an empty cell; low bits 2 and 3 mark a pending insertion bid),
//          first slot (key >> 2) & (2^cache.z - 1), then linear probing over at most cache.w
//          slots. Cells are never removed, so an empty slot ends a search.
//
// Insertion (radiance_cache_update.comp) is deterministic: in round r every key not yet in the
// table bids for the r-th slot of its probe sequence with (h & ~3) | (2 + r % 2) if that slot is
// empty or holds only this round's bids; atomicMax picks the largest, the winner commits it
// (low bits -> 1) in round r + 1, losers move on. Which key ends in which slot, and which keys
// are dropped when the sequence is full, depend only on the frame's set of keys and the table.
// The C++ mirror in tests/test_radiance_cache_world.cpp repeats these operations.
//
// Use (push constants named `rc` and frame.glsl first):
//   #include "frame.glsl"
//   layout(push_constant) uniform Push { RcParams rc; ... };
//   #include "renderer/techniques/radiance_cache/include/radiance_cache.glsl"
//   RC_CELL_BUFFER(binding, readonly)    // or coherent (writers), or nothing; declares
//                                        // RcCell rc_cells[] and the accessors used here
//   vec3 radiance;
//   if (rc_lookup(p, n, radiance)) ...  // n: geometric normal facing the ray (rc_facing_normal)       // outgoing diffuse radiance of a shaded cell
#ifndef GIB_RADIANCE_CACHE_GLSL
#define GIB_RADIANCE_CACHE_GLSL
#include "renderer/techniques/radiance_cache/include/radiance_cache_shared.h"
#include "hash.glsl"
#include "packing.glsl"

// Declares the cell buffer and the accessors the lookups below use (prototyped here, so the
// macro may come after this include).
#define RC_CELL_BUFFER(B, QUALIFIER)                                                       \
  layout(std430, set = 0, binding = (B)) QUALIFIER buffer RcCellBuffer { RcCell rc_cells[]; }; \
  uint rc_cell_key_at(uint i) { return rc_cells[i].key; }                                  \
  uint rc_cell_radiance_at(uint i) { return rc_cells[i].radiance; }                        \
  uint rc_cell_shaded_frame_at(uint i) { return rc_cells[i].shaded_frame; }

uint rc_cell_key_at(uint i);
uint rc_cell_radiance_at(uint i);
uint rc_cell_shaded_frame_at(uint i);

uint rc_cell_mask() { return (1u << uint(rc.cache.z)) - 1u; }
uint rc_max_probe() { return uint(rc.cache.w); }

// Which side of a surface a point was seen from: the dominant axis and sign of the unit
// geometric normal facing the viewer/ray (0..5). Part of the key, so the two faces of a wall
// thinner than a cell get separate cells: without it the sunlit outside of a thin wall lights
// its inside (the cache's own thin-wall leak).
uint rc_side(vec3 n) {
  vec3 a = abs(n);
  uint axis = a.x >= a.y && a.x >= a.z ? 0u : (a.y >= a.z ? 1u : 2u);
  return axis * 2u + (n[axis] < 0.0 ? 1u : 0u);
}

// cross(b - a, c - a) of a triangle's world-space vertices (its winding's face normal, unscaled).
vec3 rc_face_cross(uint triangle) {
  GpuTriangle t = gib_triangles[triangle];
  vec3 a = gib_vertices[t.i0].position, b = gib_vertices[t.i1].position, c = gib_vertices[t.i2].position;
  return cross(b - a, c - a);
}

// Unit geometric normal of a triangle, turned to face against `dir` (the ray that hit it).
vec3 rc_facing_normal(uint triangle, vec3 dir) {
  vec3 g = rc_face_cross(triangle);
  float len = length(g);
  g = len > 0.0 ? g / len : vec3(0.0, 1.0, 0.0);
  return dot(g, dir) > 0.0 ? -g : g;
}

// Did a ray travelling along `dir` hit `triangle` from inside a closed mesh (the back of a
// solid's face)? Such a ray started inside the solid (a probe inside a wall) or slipped through
// an edge; what it reaches is not lit and is no surface anyone sees. Open meshes (quads, leaf
// cards) have no inside: false.
bool rc_inside_solid(uint triangle, vec3 dir) {
  uint flags = gib_instances[gib_triangles[triangle].instance].flags;
  if ((flags & kGibInstanceSolid) == 0u) return false;
  float side = dot(rc_face_cross(triangle), dir);
  return (flags & kGibInstanceMirrored) != 0u ? side < 0.0 : side > 0.0;
}

#ifdef GIB_PROBE_VOLUME_GLSL
// A probe ray of cascade c that hit h from inside geometry: the back of a solid's face, or any
// face closer than kRcOnSurface spacings (the probe sits on a surface: a cascade whose lattice
// falls on a wall plane). It inserts no cache cell (a cell shaded from a point on an edge or
// inside a wall sees through it) and carries no light into the probe; a probe with more than
// kRcInsideFraction of its rays inside is inside geometry and is not sampled (DDGI's probe
// classification: backface fraction 0.25, Majercik et al. 2021). Constants: probe_volume.glsl.
bool rc_probe_ray_inside(ProbeHit h, vec3 d, uint c) {
  if (h.triangle_plus1 == 0u || (rc.flags.x & kRcFlagInsideTest) == 0u) return false;
  return h.distance < kRcOnSurface * rc_spacing(c) || rc_inside_solid(h.triangle_plus1 - 1u, d);
}
#endif

// Hash of position, side and LOD; lod receives the LOD factor (1, 2, 4, ...).
uint rc_cell_hash(vec3 p, vec3 n, out float lod) {
  precise vec3 dp = p - gib_frame.camera_pos.xyz;
  precise float dist = sqrt(dot(dp, dp));
  lod = exp2(floor(log2(1.0 + dist / rc.cache.y)));
  precise float size = rc.cache.x * lod;
  precise vec3 q = floor(p / size);
  ivec3 cell = ivec3(clamp(q, vec3(-2e9), vec3(2e9)));
  uint h = gib_pcg(uint(cell.x));
  h = gib_pcg(uint(cell.y) + h);
  h = gib_pcg(uint(cell.z) + h);
  if ((rc.flags.x & kRcFlagSideKey) != 0u) h = gib_pcg(rc_side(n) + h);
  return gib_pcg(uint(lod) + h);
}

uint rc_cell_key(vec3 p, vec3 n, out float lod) { return (rc_cell_hash(p, n, lod) & ~3u) | 1u; }

// First slot of a key's probe sequence (bits 0-1 are the insertion tag, so skip them).
uint rc_cell_first_slot(uint key) { return (key >> 2u) & rc_cell_mask(); }

// Index of the cell holding key, or 0xffffffff when the probe sequence holds none.
uint rc_find_cell(uint key) {
  uint mask = rc_cell_mask();
  uint n = rc_max_probe();
  for (uint s = 0u; s < n; ++s) {
    uint i = (rc_cell_first_slot(key) + s) & mask;
    uint k = rc_cell_key_at(i);
    if (k == key) return i;
    if (k == 0u) break;
  }
  return 0xffffffffu;
}

// Outgoing diffuse radiance stored for the cell of `key`, when it exists and was ever shaded.
bool rc_lookup_key(uint key, out vec3 radiance) {
  radiance = vec3(0.0);
  uint i = rc_find_cell(key);
  if (i == 0xffffffffu || rc_cell_shaded_frame_at(i) == 0u) return false;
  radiance = gib_unpack_rgb9e5(rc_cell_radiance_at(i));
  return true;
}

// The same for p's cell (n: the geometric normal facing the ray, rc_facing_normal).
bool rc_lookup(vec3 p, vec3 n, out vec3 radiance) {
  float lod;
  return rc_lookup_key(rc_cell_key(p, n, lod), radiance);
}
#endif  // GIB_RADIANCE_CACHE_GLSL
