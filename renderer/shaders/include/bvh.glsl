// BVH traversal (closest hit and any hit) over the scene buffers, mirroring the CPU reference
// in renderer/scene/bvh.cpp (intersect_bvh / occluded_bvh): the same watertight ray/triangle
// test (Woop, Benthin, Wald 2013) with the same operation order, marked precise so that no
// multiply-add is fused and results round like the CPU's; the same tie rule (equal t: lower
// original triangle id wins); the same conservative box slack.
//
// Use:
//   #include "scene.glsl"
//   GIB_SCENE_BUFFERS(0, 0)
//   #define GIB_ALPHA_TEST            // optional: then define, anywhere in the shader, bool
//   #include "bvh.glsl"               //   gib_alpha_accept(uint triangle, float u, float v,
//                                     //                    inout uint calls, uint ray_key)
//
// trace_closest / trace_any accept hits with tmin <= t <= tmax. d need not be normalised (t is
// in units of d); a zero or non-finite d, or a non-finite o, misses. u, v are the barycentrics
// of the triangle's second and third vertex; triangle is the original GpuTriangle index.
// With GIB_ALPHA_TEST, a candidate hit is kept only if gib_alpha_accept returns true (shadow
// rays included); `calls` starts at 0 for each ray and is the accept function's to count with
// (any-hit limits), `ray_key` is gib_alpha_ray_key(o, d) (alpha_strategy.glsl). The GPU result can differ from the CPU's by float ulps where the driver's
// division is not correctly rounded (Vulkan allows 2.5 ulp) or flushes denormals.
#ifndef GIB_BVH_GLSL
#define GIB_BVH_GLSL

#include "scene.glsl"
#ifdef GIB_ALPHA_TEST
#include "material.glsl"
#include "alpha_strategy.glsl"
#endif

#define GIB_BVH_STACK_SIZE 64            // == kBvhMaxDepth (bvh.h); the build guarantees depth
#define GIB_BVH_BOX_SLACK (1.0 + 1.0 / 1048576.0)  // 1 + 2^-20, == kBoxSlack (bvh.cpp)
#define GIB_BVH_TINY_DIR 1e-30
#define GIB_BVH_NO_TRIANGLE 0xffffffffu

struct GibHit {
  float t;
  uint triangle;  // original triangle id
  float u;        // barycentric of vertex 1
  float v;        // barycentric of vertex 2
};

#ifdef GIB_ALPHA_TEST
bool gib_alpha_accept(uint triangle, float u, float v, inout uint calls, uint ray_key);
#endif

struct GibRayPre {
  vec3 o;
  vec3 inv;  // 1/d, zero components replaced by +-GIB_BVH_TINY_DIR
  int kx;
  int ky;
  int kz;
  float sx;
  float sy;
  float sz;
  bool valid;
};

GibRayPre gib_prepare_ray(vec3 o, vec3 d) {
  GibRayPre r;
  r.o = o;
  vec3 ad = abs(d);
  r.kz = ad.x > ad.y ? (ad.x > ad.z ? 0 : 2) : (ad.y > ad.z ? 1 : 2);
  r.kx = r.kz == 2 ? 0 : r.kz + 1;
  r.ky = r.kx == 2 ? 0 : r.kx + 1;
  if (d[r.kz] < 0.0) {
    int tmp = r.kx;
    r.kx = r.ky;
    r.ky = tmp;
  }
  float sum = ad.x + ad.y + ad.z + abs(o.x + o.y + o.z);
  r.valid = ad[r.kz] > 0.0 && !isinf(sum) && !isnan(sum);
  r.sx = d[r.kx] / d[r.kz];
  r.sy = d[r.ky] / d[r.kz];
  r.sz = 1.0 / d[r.kz];
  // Sign bit, like std::signbit on the CPU: -0 counts as negative.
  bvec3 neg = notEqual(floatBitsToUint(d) & uvec3(0x80000000u), uvec3(0u));
  vec3 tiny = mix(vec3(GIB_BVH_TINY_DIR), vec3(-GIB_BVH_TINY_DIR), neg);
  vec3 safe_d = mix(d, tiny, lessThan(ad, vec3(GIB_BVH_TINY_DIR)));
  r.inv = 1.0 / safe_d;
  return r;
}

// Rounding error of p = a * b (a * b == p + err exactly), by Dekker's product: only
// correctly rounded multiplies and adds (Vulkan requires them to be), so it does not depend on
// fma being fused, which Vulkan does not require.
float gib_bvh_product_error(float a, float b, float p) {
  precise float ca = 4097.0 * a;
  precise float ah = ca - (ca - a);
  precise float al = a - ah;
  precise float cb = 4097.0 * b;
  precise float bh = cb - (cb - b);
  precise float bl = b - bh;
  precise float err = ((ah * bh - p) + ah * bl + al * bh) + al * bl;
  return err;
}

// a*b - c*d for an edge function that rounded to 0: then a*b and c*d round to the same float
// and the exact difference is that of the rounding errors, rounded once, as the CPU's double.
float gib_bvh_exact_edge(float a, float b, float c, float d) {
  precise float p = a * b;
  precise float q = c * d;
  precise float r = (p - q) + (gib_bvh_product_error(a, b, p) - gib_bvh_product_error(c, d, q));
  return r;
}

// Watertight ray/triangle test, no t interval; false on a miss, a parallel ray or zero
// projected area.
bool gib_triangle_test(GibRayPre r, vec3 p0, vec3 p1, vec3 p2, out float t, out float u,
                       out float v) {
  t = 0.0;
  u = 0.0;
  v = 0.0;
  precise float a_z = p0[r.kz] - r.o[r.kz];
  precise float b_z = p1[r.kz] - r.o[r.kz];
  precise float c_z = p2[r.kz] - r.o[r.kz];
  precise float ax = (p0[r.kx] - r.o[r.kx]) - r.sx * a_z;
  precise float ay = (p0[r.ky] - r.o[r.ky]) - r.sy * a_z;
  precise float bx = (p1[r.kx] - r.o[r.kx]) - r.sx * b_z;
  precise float by = (p1[r.ky] - r.o[r.ky]) - r.sy * b_z;
  precise float cx = (p2[r.kx] - r.o[r.kx]) - r.sx * c_z;
  precise float cy = (p2[r.ky] - r.o[r.ky]) - r.sy * c_z;
  precise float e0 = cx * by - cy * bx;
  precise float e1 = ax * cy - ay * cx;
  precise float e2 = bx * ay - by * ax;
  if (e0 == 0.0) e0 = gib_bvh_exact_edge(cx, by, cy, bx);
  if (e1 == 0.0) e1 = gib_bvh_exact_edge(ax, cy, ay, cx);
  if (e2 == 0.0) e2 = gib_bvh_exact_edge(bx, ay, by, ax);
  if ((e0 < 0.0 || e1 < 0.0 || e2 < 0.0) && (e0 > 0.0 || e1 > 0.0 || e2 > 0.0)) return false;
  precise float det = (e0 + e1) + e2;
  if (!(det != 0.0)) return false;
  precise float tt = (e0 * (r.sz * a_z) + e1 * (r.sz * b_z)) + e2 * (r.sz * c_z);
  precise float rcp = 1.0 / det;
  precise float tr = tt * rcp;
  precise float ur = e1 * rcp;
  precise float vr = e2 * rcp;
  t = tr;
  u = ur;
  v = vr;
  return true;
}

bool gib_box_visit(GibRayPre r, GpuBvhNode n, float tmin, float tmax, out float tnear) {
  vec3 t0 = (n.bmin - r.o) * r.inv;
  vec3 t1 = (n.bmax - r.o) * r.inv;
  vec3 lo = min(t0, t1);
  vec3 hi = max(t0, t1);
  float tn = max(max(tmin, lo.x), max(lo.y, lo.z));
  float tf = min(min(tmax, hi.x), min(hi.y, hi.z));
  tnear = tn;
  return tn <= tf * GIB_BVH_BOX_SLACK;
}

// One traversal for both queries; any_hit is a constant at every call site, so the compiler
// specialises it.
bool gib_bvh_traverse(vec3 o, vec3 d, float tmin, float tmax, const bool any_hit,
                      inout GibHit hit) {
  hit = GibHit(tmax, GIB_BVH_NO_TRIANGLE, 0.0, 0.0);
  GibRayPre r = gib_prepare_ray(o, d);
  if (!r.valid) return false;
  GpuBvhNode node = gib_bvh_nodes[0];
  if (node.count == 0u && node.left_or_first == 0u) return false;
  float tnear;
  if (!gib_box_visit(r, node, tmin, tmax, tnear)) return false;

  uint stack[GIB_BVH_STACK_SIZE];
  int sp = 0;
  bool found = false;
#ifdef GIB_ALPHA_TEST
  uint alpha_calls = 0u;
  uint ray_key = gib_alpha_ray_key(o, d);
#endif
  for (;;) {
    bool descend = false;
    if (node.count > 0u) {
      uint end = node.left_or_first + node.count;
      for (uint s = node.left_or_first; s < end; ++s) {
        uint id = gib_bvh_tri_index[s];
        GpuTriangle tri = gib_triangles[id];
        float t, u, v;
        if (!gib_triangle_test(r, gib_vertices[tri.i0].position, gib_vertices[tri.i1].position,
                               gib_vertices[tri.i2].position, t, u, v)) {
          continue;
        }
        if (!(t >= tmin && (t < hit.t || (t == hit.t && id < hit.triangle)))) continue;
#ifdef GIB_ALPHA_TEST
        if (!gib_alpha_accept(id, u, v, alpha_calls, ray_key)) continue;
#endif
        hit = GibHit(t, id, u, v);
        found = true;
        if (any_hit) return true;
      }
    } else {
      uint l = node.left_or_first;
      GpuBvhNode nl = gib_bvh_nodes[l];
      GpuBvhNode nr = gib_bvh_nodes[l + 1u];
      float tl, tr;
      bool hl = gib_box_visit(r, nl, tmin, hit.t, tl);
      bool hr = gib_box_visit(r, nr, tmin, hit.t, tr);
      if (hl && hr) {
        bool left_first = tl <= tr;
        stack[sp++] = left_first ? l + 1u : l;
        node = left_first ? nl : nr;
        descend = true;
      } else if (hl) {
        node = nl;
        descend = true;
      } else if (hr) {
        node = nr;
        descend = true;
      }
    }
    if (descend) continue;
    // Pop; a node pushed before the best hit shrank is tested again and skipped if now beyond.
    bool popped = false;
    while (sp > 0) {
      node = gib_bvh_nodes[stack[--sp]];
      if (gib_box_visit(r, node, tmin, hit.t, tnear)) {
        popped = true;
        break;
      }
    }
    if (!popped) break;
  }
  return found;
}

bool trace_closest(vec3 o, vec3 d, float tmin, float tmax, out GibHit hit) {
  GibHit h;
  bool found = gib_bvh_traverse(o, d, tmin, tmax, false, h);
  hit = h;
  return found;
}

bool trace_any(vec3 o, vec3 d, float tmin, float tmax) {
  GibHit h;
  return gib_bvh_traverse(o, d, tmin, tmax, true, h);
}

#endif  // GIB_BVH_GLSL
