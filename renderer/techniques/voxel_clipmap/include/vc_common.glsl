// Voxel-clipmap geometry and buffer accessors shared by its passes (layout:
// voxel_clipmap_shared.h; design: renderer/techniques/voxel_clipmap/voxel_clipmap.md). CPU
// mirror: renderer/codecs/voxel_clipmap.h (tests/test_voxel_clipmap.cpp checks they agree).
//
// Level l: voxels of size vc_voxel_size(l) = vc.sizes.x * 2^l, N = vc.grid.x per axis; cells of
// twice that size, N / 2 per axis. A level's box starts at its origin (world grid coordinate,
// VcState) and follows the camera; a voxel or cell lives in slot g mod N (toroidal), so the box
// scrolls without copying.
//
// Use: declare the push constants as `VcParams vc` first, then
//   VC_STATE_BUFFER(binding, readonly)   // (voxel_clipmap_shared.h) or with no qualifier to write it
//   VC_VOXEL_BUFFER(binding, readonly)
//   VC_CUBE_BUFFERS(bx, by, bz, bstate, readonly)
//   VC_VIS_BUFFER(binding, readonly)     // with VC_CONVEX_VOXELS: the cells' flood masks
// and include this file after them (the functions below use the names they declare that exist:
// define VC_HAS_VOXELS / VC_HAS_CUBES before including to get the voxel / cube functions).
#ifndef GIB_VC_COMMON_GLSL
#define GIB_VC_COMMON_GLSL
#include "renderer/techniques/voxel_clipmap/include/voxel_clipmap_shared.h"

int vc_n() { return int(vc.grid.x); }
int vc_m() { return int(vc.grid.x) / 2; }
uint vc_levels() { return vc.grid.y; }
uint vc_frame() { return vc.grid.z; }
bool vc_flag(uint f) { return (vc.grid.w & f) != 0u; }
float vc_voxel_size(uint l) { return vc.sizes.x * float(1u << l); }
float vc_cell_size(uint l) { return 2.0 * vc_voxel_size(l); }
uint vc_voxels_per_level() { return vc.grid.x * vc.grid.x * vc.grid.x; }
uint vc_cells_per_level() { uint m = vc.grid.x / 2u; return m * m * m; }

// The level's box origin (in units of its voxels / cells) centred on x: the camera sits in the
// middle of every level, so each finer box lies inside the next coarser one.
ivec3 vc_origin_around(vec3 x, float size, int n) { return ivec3(floor(x / size)) - ivec3(n / 2); }

// Non-negative remainder: the toroidal slot of world grid coordinate g.
ivec3 vc_wrap(ivec3 g, int n) { return ((g % n) + n) % n; }
uint vc_slot_index(ivec3 s, int n) { return uint((s.z * n + s.y) * n + s.x); }
// The world grid coordinate a slot holds for a box starting at origin o.
ivec3 vc_slot_world(ivec3 slot, ivec3 o, int n) { return o + vc_wrap(slot - o, n); }
// The voxel opacity byte: opacity x 255 rounded half up, clamped to [1, 255] (0: no geometry).
uint vc_opacity_byte(float opacity) { return uint(clamp(floor(opacity * 255.0 + 0.5), 1.0, 255.0)); }
// The second triangle (+ 1; 0: none) of a voxel (voxel_clipmap_shared.h: y bits 13-31 hold its
// bits 0-18, w bits 23-26 its bits 19-22), and the voxel with it set. CPU mirror:
// codecs::vc_second_triangle / vc_with_second_triangle.
uint vc_second_triangle(uvec4 v) {
  return (v.y >> kVcSecondLowShift) | (((v.w & kVcSecondHighMask) >> kVcSecondHighShift) << kVcSecondLowBits);
}
uvec4 vc_with_second_triangle(uvec4 v, uint id) {
  uint low = (1u << kVcSecondLowShift) - 1u;
  v.y = (v.y & low) | (id << kVcSecondLowShift);
  v.w = (v.w & ~kVcSecondHighMask) | (((id >> kVcSecondLowBits) << kVcSecondHighShift) & kVcSecondHighMask);
  return v;
}
bool vc_in_box(ivec3 g, ivec3 o, int n) { return all(greaterThanEqual(g, o)) && all(lessThan(g, o + ivec3(n))); }

// One step of the relight's flood (irradiance_cell_vis, voxel_clipmap_shared.h) on one row of
// its window (kVcVisWindow voxels along x, bit x). The flood is monotone: it moves only away
// from the seed box (voxels xlo..xhi along x), so a voxel is reached along a staircase of free
// voxels from the seed, not around a wall's edge and back. The row takes the seeds, its voxels
// reached so far and those of its neighbouring rows on the seed's side (y and z, or-ed into
// `beside`), and spreads them along x through its free voxels outwards from the seed box.
// CPU mirror: codecs::vc_vis_row_step.
uint vc_vis_row_step(uint free_row, uint seed, uint row, uint beside, uint xlo, uint xhi) {
  uint all = (1u << uint(kVcVisWindow)) - 1u;
  uint up = all & ~((2u << xhi) - 1u), down = (1u << xlo) - 1u;  // bits past the seed box
  uint r = seed | (free_row & (row | beside));
  for (int i = 0; i < kVcVisWindow - 1; ++i) r |= free_row & (((r << 1u) & up) | ((r >> 1u) & down));
  return r & all;
}
// The bit of cell k's flood mask that holds voxel g of the cell's level; -1 outside the stored
// middle of its window (voxels 2k - 2 .. 2k + 3). CPU mirror: codecs::vc_vis_bit.
int vc_vis_bit(ivec3 g, ivec3 k) {
  ivec3 c = g - (2 * k - ivec3(2));
  if (any(lessThan(c, ivec3(0))) || any(greaterThanEqual(c, ivec3(kVcVisSpan)))) return -1;
  return (c.z * kVcVisSpan + c.y) * kVcVisSpan + c.x;
}

uint vc_voxel_index(uint l, ivec3 g) { return l * vc_voxels_per_level() + vc_slot_index(vc_wrap(g, vc_n()), vc_n()); }
uint vc_cell_index(uint l, ivec3 k) { return l * vc_cells_per_level() + vc_slot_index(vc_wrap(k, vc_m()), vc_m()); }

#ifdef VC_HAS_STATE
ivec3 vc_voxel_origin(uint l) { return vc_state.voxel_origin[l].xyz; }
ivec3 vc_cell_origin(uint l) { return vc_state.cell_origin[l].xyz; }
// Finest level whose voxel box holds x (levels when none).
uint vc_voxel_level(vec3 x) {
  for (uint l = 0u; l < vc_levels(); ++l)
    if (vc_in_box(ivec3(floor(x / vc_voxel_size(l))), vc_voxel_origin(l), vc_n())) return l;
  return vc_levels();
}
#endif

#ifdef VC_HAS_VOXELS
float vc_opacity(uvec4 v, bool semi) {
  uint a = v.y & kVcOpacityMask;
  return a == 0u ? 0.0 : (semi ? float(a) / 255.0 : 1.0);
}

// Brute-force march through the scene voxels (the seed's "ray casting", no cone tracing): a
// DDA over the finest level holding each point, accumulate-and-extinct through semi-transparent
// voxels (opaque when semi is false). Returns the reflected radiance
// the voxels send back along the ray; `emitted` their emission; `transmittance` what reaches
// past them (the sky's share).
vec3 vc_march(vec3 o, vec3 d, bool semi, out vec3 emitted, out float transmittance) {
  vec3 sum = vec3(0.0);
  emitted = vec3(0.0);
  float T = 1.0;
  float t = 0.0;
  vec3 inv = 1.0 / max(abs(d), vec3(1e-8)) * sign(d + vec3(1e-30));
  for (uint i = 0u; i < vc.rays.y; ++i) {
    vec3 p = o + d * t;
    uint l = vc_voxel_level(p);
    if (l >= vc_levels()) break;
    float s = vc_voxel_size(l);
    ivec3 g = ivec3(floor(p / s));
    uvec4 v = vc_voxels[vc_voxel_index(l, g)];
    float a = vc_opacity(v, semi);
    // A voxel with geometry opacity that neither a pixel nor its triangle has lit yet takes the
    // radiance of a coarser voxel holding the point that was (the coarsest such: the loop goes
    // on; the seed fills finer levels from coarser ones): pixels seen at a grazing angle leave
    // gaps that would read black.
    const uint lit = kVcVoxelFed | kVcVoxelLit;
    for (uint c = l + 1u; a > 0.0 && (v.y & lit) == 0u && c < vc_levels(); ++c) {
      ivec3 gc = ivec3(floor(p / vc_voxel_size(c)));
      if (!vc_in_box(gc, vc_voxel_origin(c), vc_n())) break;
      uvec4 cv = vc_voxels[vc_voxel_index(c, gc)];
      if ((cv.y & lit) != 0u) v = uvec4(cv.x, v.y, cv.z, 0u);
    }
    if (a > 0.0) {
      sum += T * a * gib_unpack_rgb9e5(v.x);
      emitted += T * a * gib_unpack_rgb9e5(v.z);
      T *= 1.0 - a;
      if (T < 1.0 / 64.0) { T = 0.0; break; }
    }
    // Exit of this voxel: the nearest of the three boundary planes ahead.
    vec3 bound = (vec3(g) + step(vec3(0.0), d)) * s;
    vec3 te = (bound - p) * inv;
    float dt = min(te.x, min(te.y, te.z));
    t += max(dt, 0.0) + s * 1e-3;
  }
  transmittance = T;
  return sum;
}
#endif

#ifdef VC_HAS_CUBES
// Ambient cube of cell `cell` towards normal n (the seed's 5.1; Half-Life 2's ambient cube):
// sum over axes of n_a^2 x the value of the direction on n's side. `hit`: the same sum of the
// directions' hit shares (the cosine-weighted share of the cell's rays that met a voxel).
void vc_cube_eval(uint cell, vec3 n, out vec3 bounce, out vec3 sky, out float hit) {
  vec3 w = n * n;
  uint base = cell * kVcCellFloats;
  uint ox = base + (n.x >= 0.0 ? 0u : 3u), oy = base + (n.y >= 0.0 ? 0u : 3u), oz = base + (n.z >= 0.0 ? 0u : 3u);
  bounce = w.x * vec3(vc_cube_x[ox], vc_cube_x[ox + 1u], vc_cube_x[ox + 2u]) +
           w.y * vec3(vc_cube_y[oy], vc_cube_y[oy + 1u], vc_cube_y[oy + 2u]) +
           w.z * vec3(vc_cube_z[oz], vc_cube_z[oz + 1u], vc_cube_z[oz + 2u]);
  sky = w.x * vec3(vc_cube_x[ox + 6u], vc_cube_x[ox + 7u], vc_cube_x[ox + 8u]) +
        w.y * vec3(vc_cube_y[oy + 6u], vc_cube_y[oy + 7u], vc_cube_y[oy + 8u]) +
        w.z * vec3(vc_cube_z[oz + 6u], vc_cube_z[oz + 7u], vc_cube_z[oz + 8u]);
  uint hx = base + (n.x >= 0.0 ? 12u : 13u), hy = base + (n.y >= 0.0 ? 12u : 13u), hz = base + (n.z >= 0.0 ? 12u : 13u);
  hit = w.x * vc_cube_x[hx] + w.y * vc_cube_y[hy] + w.z * vc_cube_z[hz];
}

#ifdef VC_CONVEX_VOXELS
// Whether the segment from a to b crosses the plane of the triangle scene_voxel_fill kept for
// level-l voxel g (through point p0 with unit normal nrm) inside that voxel (grown by a
// hundredth of it). The plane, not the triangle: a crossing just past a triangle's edge, where
// a wall meets a floor, is still the wall.
bool vc_crosses_voxel_plane(vec3 a, vec3 b, vec3 p0, vec3 nrm, ivec3 g, float s) {
  float d0 = dot(a - p0, nrm), d1 = dot(b - p0, nrm);
  if ((d0 > 0.0) == (d1 > 0.0) || d0 == d1) return false;
  vec3 c = mix(a, b, d0 / (d0 - d1));
  vec3 lo = vec3(g) * s - 0.01 * s, hi = vec3(g + 1) * s + 0.01 * s;
  return all(greaterThanEqual(c, lo)) && all(lessThanEqual(c, hi));
}

// Whether the segment from a to b (a just off a surface of normal n) crosses, inside level-l
// voxel g of size s, the plane of triangle `id` + 1 (a triangle scene_voxel_fill kept for that
// voxel). The pixel's own surface is not a wall (the convex test weighs cells behind it): a
// plane within 60 degrees of n that passes within half a voxel of a is taken for it. On a
// curved surface the voxels along the segment keep neighbouring facets tilted from n, whose
// planes a segment leaving the surface crosses outside the object; a wall that blocks a
// segment meets the surface at a corner (near 90 degrees) or lies more than half a voxel away.
bool vc_triangle_plane_blocks(uint id, vec3 a, vec3 b, vec3 n, ivec3 g, float s) {
  GpuTriangle t = gib_triangles[id - 1u];
  vec3 p0 = gib_vertices[t.i0].position;
  vec3 nrm = cross(gib_vertices[t.i1].position - p0, gib_vertices[t.i2].position - p0);
  float len = length(nrm);
  if (!(len > 0.0)) return false;
  nrm /= len;
  bool own = dot(nrm, n) > 0.5 && abs(dot(a - p0, nrm)) < 0.5 * s;
  return !own && vc_crosses_voxel_plane(a, b, p0, nrm, g, s);
}

// Where level-l cell k's rays start: the centre of the voxel of its 2 x 2 x 2 the last relight
// started them in (cell state `state`), or the cell's centre when it was never relit (inherited
// from the coarser level).
vec3 vc_cell_ray_origin(uint l, ivec3 k, uint state) {
  if ((state & (kVcCellRelit | kVcCellOriginCentre)) != kVcCellRelit) return (vec3(k) + 0.5) * vc_cell_size(l);
  uint i = (state & kVcCellOriginMask) >> kVcCellOriginShift;
  return (vec3(2 * k + ivec3(i & 1u, (i >> 1u) & 1u, (i >> 2u) & 1u)) + 0.5) * vc_voxel_size(l);
}

// Whether a wall lies between surface point x (normal n) and point b, where level-l cell k's
// rays start (vc_cell_ray_origin): the
// segment from just off the surface (a twentieth of a voxel along n) to b crosses the
// plane of a triangle kept by a geometry voxel it passes through (a voxel DDA; the fill's flag
// and triangles, which the feed keeps while it writes, so the result does not depend on thread
// timing). A voxel keeps up to three triangles, one per dominant normal axis (two walls and the
// ceiling they meet): with one, a wall's pixel below a ceiling saw its own plane in the voxel
// they share, missed the ceiling, and took the cell above it, whose rays start above the roof.
// A geometry voxel without a triangle (past 2^23 - 2 triangles) counts as a wall. Needs the
// voxel buffers (VC_VOXEL_BUFFER, VC_THIRD_BUFFER) and the scene buffers (GIB_SCENE_BUFFERS).
bool vc_cell_behind_wall(uint l, vec3 x, vec3 n, vec3 b) {
  float s = vc_voxel_size(l);
  vec3 a = x + n * (0.05 * s);
  vec3 d = b - a;
  ivec3 g = ivec3(floor(a / s)), last = ivec3(floor(b / s));
  ivec3 stepv = ivec3(sign(d));
  vec3 inv = 1.0 / max(abs(d), vec3(1e-12));
  // Parameter (0..1 along the segment) of the next voxel boundary on each axis.
  vec3 next = mix((vec3(g) - a / s) * s, (vec3(g + 1) - a / s) * s, greaterThan(d, vec3(0.0))) * sign(d) * inv;
  next = mix(next, vec3(2.0), equal(stepv, ivec3(0)));
  vec3 delta = s * inv;
  for (int i = 0; i < 16; ++i) {
    if (vc_in_box(g, vc_voxel_origin(l), vc_n())) {
      uvec4 v = vc_voxels[vc_voxel_index(l, g)];
      if ((v.y & kVcVoxelGeometry) != 0u) {
        uint tri = v.w & kVcFillTriangleMask, second = vc_second_triangle(v);
        if (tri == 0u || tri > gib_frame.scene_info.x) return true;
        if (vc_triangle_plane_blocks(tri, a, b, n, g, s)) return true;
        if (second != 0u && second <= gib_frame.scene_info.x && vc_triangle_plane_blocks(second, a, b, n, g, s))
          return true;
        uint third = second != 0u ? vc_voxel_third[vc_voxel_index(l, g)] : 0u;
        if (third != 0u && third <= gib_frame.scene_info.x && vc_triangle_plane_blocks(third, a, b, n, g, s))
          return true;
      }
    }
    if (all(equal(g, last))) break;
    // Step across the nearest boundary.
    if (next.x <= next.y && next.x <= next.z) {
      if (next.x > 1.0) break;
      g.x += stepv.x;
      next.x += delta.x;
    } else if (next.y <= next.z) {
      if (next.y > 1.0) break;
      g.y += stepv.y;
      next.y += delta.y;
    } else {
      if (next.z > 1.0) break;
      g.z += stepv.z;
      next.z += delta.z;
    }
  }
  return false;
}

// The voxel of level l that the light of surface point x (normal n) arrives through: the first
// of the points 0.5, 1, 1.5 and 2 voxels off the surface along n whose voxel holds no geometry
// (kVcVoxelGeometry, which the fill sets and the feed and the voxel light keep, so the answer
// does not depend on thread timing) or lies outside the level's box. False when all four hold
// geometry (a point in a crevice, or a floor within a voxel of a wall): the caller walks.
bool vc_air_voxel(uint l, vec3 x, vec3 n, out ivec3 g) {
  float s = vc_voxel_size(l);
  for (int i = 1; i <= 4; ++i) {
    g = ivec3(floor((x + n * (0.5 * float(i) * s)) / s));
    if (!vc_in_box(g, vc_voxel_origin(l), vc_n())) return true;
    if ((vc_voxels[vc_voxel_index(l, g)].y & kVcVoxelGeometry) == 0u) return true;
  }
  return false;
}

// Whether air voxel g (vc_air_voxel) is joined to level-l cell k's ray origin through voxels
// without geometry inside the cell's flood window: one bit of the mask the relight stored
// (irradiance_cell_vis; valid once the cell was relit). Needs VC_VIS_BUFFER.
bool vc_cell_sees(uint cell, ivec3 k, ivec3 g) {
  int bit = vc_vis_bit(g, k);
  if (bit < 0) return false;
  return ((vc_cell_vis[cell * kVcCellVisWords + uint(bit) / 32u] >> (uint(bit) % 32u)) & 1u) != 0u;
}
#endif

// Trilinear ambient cubes of level l at x for normal n; cells never relit get no weight. With
// convex offset filtering the lookup moves half a cell along the normal and corner cells whose
// centres lie behind the surface's plane (more than a quarter cell) get no weight: the filter
// footprint stays on the lit side of a wall; where the includer defines VC_CONVEX_VOXELS and
// geometry_light is on, corner cells behind another wall get none either, so a surface near a
// room's corner does not blend in the cells outside it: wall_test 2 reads one bit of the cell's
// flood mask (vc_cell_sees: is the pixel's air voxel joined to the cell's ray origin through
// voxels without geometry), wall_test 1 (the default) walks the voxels to the cell's ray origin
// through the kept triangles' planes (vc_cell_behind_wall; also the fallback of wall_test 2 for
// a pixel without an air voxel or a cell never relit). Returns the weight found (0: nothing
// usable).
float vc_cubes_trilinear(uint l, vec3 x, vec3 n, bool convex, out vec3 bounce, out vec3 sky, out float hit) {
  float c = vc_cell_size(l);
  vec3 q = convex ? x + n * (0.5 * c) : x;
  vec3 u = q / c - 0.5;
  ivec3 k0 = ivec3(floor(u));
  vec3 f = u - vec3(k0);
  bounce = vec3(0.0);
  sky = vec3(0.0);
  hit = 0.0;
  float wsum = 0.0;
#ifdef VC_CONVEX_VOXELS
  // The wall test (geometry_light): the flood mask's bit for the pixel's air voxel (wall_test 2)
  // where the pixel has one and the cell was relit, else the voxel walk.
  bool wall = convex && vc_flag(kVcFlagGeometryLight) && vc_flag(kVcFlagWallWalk | kVcFlagWallFlood);
  ivec3 air = ivec3(0);
  bool flood = wall && vc_flag(kVcFlagWallFlood) && vc_air_voxel(l, x, n, air);
#endif
  for (int i = 0; i < 8; ++i) {
    ivec3 o = ivec3(i & 1, (i >> 1) & 1, (i >> 2) & 1);
    ivec3 k = k0 + o;
    if (!vc_in_box(k, vc_cell_origin(l), vc_m())) continue;
    uint cell = vc_cell_index(l, k);
    uint state = vc_cell_state[cell];
    if ((state & kVcCellUpdated) == 0u) continue;
    // A solid cell's rays started inside geometry: what they saw is no light at any surface.
    if (convex && (state & kVcCellSolid) != 0u) continue;
    if (convex && dot((vec3(k) + 0.5) * c - x, n) < -0.25 * c) continue;
    vec3 t = mix(1.0 - f, f, vec3(o));
    float w = t.x * t.y * t.z;
    // Before the wall test: a corner of no weight (a point on a cell plane) needs no voxel walk.
    if (w <= 0.0) continue;
#ifdef VC_CONVEX_VOXELS
    if (wall) {
      bool blocked = flood && (state & kVcCellRelit) != 0u ? !vc_cell_sees(cell, k, air)
                                                            : vc_cell_behind_wall(l, x, n, vc_cell_ray_origin(l, k, state));
      if (blocked) continue;
    }
#endif
    vec3 b, s;
    float h;
    vc_cube_eval(cell, n, b, s, h);
    bounce += w * b;
    sky += w * s;
    hit += w * h;
    wsum += w;
  }
  if (wsum > 1e-6) {
    bounce /= wsum;
    sky /= wsum;
    hit /= wsum;
  }
  return wsum;
}

// Irradiance / pi at x for normal n, bounce and direct (sky, emitters) parts (the seed's 5.1),
// and the hit share the bounce was gathered over (vc_cube_eval): the finest level whose cell box
// holds the filter footprint, blended with the next coarser one over the two cells next to its
// border.
void vc_irradiance(vec3 x, vec3 n, bool convex, out vec3 bounce, out vec3 sky, out float hit) {
  bounce = vec3(0.0);
  sky = vec3(0.0);
  hit = 0.0;
  float m = float(vc_m());
  for (uint l = 0u; l < vc_levels(); ++l) {
    vec3 q = x / vc_cell_size(l) - vec3(vc_cell_origin(l));
    float border = min(min(min(q.x, q.y), q.z), min(min(m - q.x, m - q.y), m - q.z)) - 1.0;
    if (border < 0.0) continue;
    vec3 b, s;
    float h;
    if (vc_cubes_trilinear(l, x, n, convex, b, s, h) <= 0.0) continue;
    float w = clamp(border / 2.0, 0.0, 1.0);
    if (w < 1.0) {
      for (uint c = l + 1u; c < vc_levels(); ++c) {
        vec3 cb, cs;
        float ch;
        if (vc_cubes_trilinear(c, x, n, convex, cb, cs, ch) > 0.0) {
          b = mix(cb, b, w);
          s = mix(cs, s, w);
          h = mix(ch, h, w);
          break;
        }
      }
    }
    bounce = b;
    sky = s;
    hit = h;
    return;
  }
}

// The bounce light (irradiance / pi) a surface point takes whose own sky rays (direct_lighting)
// counted the sky and emitters in the directions they escaped or met an emitter: the clipmap's
// bounce is the mean radiance of the voxels its rays met times the share of rays that met one,
// so the point takes that mean times its own share of rays that met a surface (`pixel_hits`,
// direct_light's alpha). Each direction of the point's hemisphere is then counted once: by the
// point's rays where they see the sky, by the clipmap where they meet a surface. (A cell off the
// surface sees the object's own voxels in directions whose sky the point's rays already counted.)
// No hit in the cells: nothing to take the mean radiance from; the bounce is left as it is (0).
vec3 vc_bounce_for_pixel(vec3 bounce, float cube_hits, float pixel_hits) {
  return cube_hits > 1e-4 ? bounce * (pixel_hits / cube_hits) : bounce;
}
#endif

#endif
