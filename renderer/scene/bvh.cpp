// The triangle test must round exactly like the GLSL one (which marks its arithmetic precise).
#include "renderer/scene/fp_contract_off.h"

#include "renderer/scene/bvh.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace gib {
namespace {

constexpr int kBins = 16;
constexpr uint32_t kSahLeafSize = 4;     // always a leaf at or below this
constexpr uint32_t kSahMaxLeafSize = 8;  // SAH may stop at up to this many
constexpr uint32_t kSahMaxDepth = 32;    // below this, object-median splits (depth bound)
// Slack on the far end of the box interval: covers the rounding of the slab test and of the
// triangle's t, so a box is never culled when a triangle inside it would be accepted.
// Same constant in bvh.glsl (GIB_BVH_BOX_SLACK).
constexpr float kBoxSlack = 1.0f + 0x1p-20f;
// Zero direction components become +-kTinyDir for the slab test (no 0 * inf NaNs).
constexpr float kTinyDir = 1e-30f;
constexpr float kBoxPad = 1e-20f;

struct Aabb {
  Vec3 lo{std::numeric_limits<float>::infinity(), std::numeric_limits<float>::infinity(),
          std::numeric_limits<float>::infinity()};
  Vec3 hi{-std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(),
          -std::numeric_limits<float>::infinity()};
  // Plain comparisons (inputs are finite): std::fmin is a library call without -ffast-math.
  static Vec3 lo3(Vec3 a, Vec3 b) { return {a.x < b.x ? a.x : b.x, a.y < b.y ? a.y : b.y, a.z < b.z ? a.z : b.z}; }
  static Vec3 hi3(Vec3 a, Vec3 b) { return {a.x > b.x ? a.x : b.x, a.y > b.y ? a.y : b.y, a.z > b.z ? a.z : b.z}; }
  void grow(Vec3 p) { lo = lo3(lo, p); hi = hi3(hi, p); }
  void grow(const Aabb& b) { lo = lo3(lo, b.lo); hi = hi3(hi, b.hi); }
  bool empty() const { return lo.x > hi.x; }
  // Half the surface area; the SAH only uses ratios.
  double half_area() const {
    if (empty()) return 0.0;
    double dx = double(hi.x) - lo.x, dy = double(hi.y) - lo.y, dz = double(hi.z) - lo.z;
    return dx * dy + dy * dz + dz * dx;
  }
};

Vec3 vertex_pos(const FlatScene& s, uint32_t i) {
  const GpuVertex& v = s.vertices[i];
  return {v.px, v.py, v.pz};
}

bool finite3(Vec3 p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

bool degenerate_positions(Vec3 p0, Vec3 p1, Vec3 p2) {
  if (!finite3(p0) || !finite3(p1) || !finite3(p2)) return true;
  double e1[3] = {double(p1.x) - p0.x, double(p1.y) - p0.y, double(p1.z) - p0.z};
  double e2[3] = {double(p2.x) - p0.x, double(p2.y) - p0.y, double(p2.z) - p0.z};
  double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                 e1[0] * e2[1] - e1[1] * e2[0]};
  double nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
  double l1 = e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2];
  double l2 = e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2];
  // |n| <= 1e-14 |e1||e2|: sine of the angle at p0 below 1e-14. Collinear float vertices give
  // about 1e-16 here (double rounding); any triangle a float test can resolve is far above.
  return !(nn > 1e-28 * l1 * l2);
}

// Per-ray constants of the watertight test (same names as in bvh.glsl).
struct RayPre {
  float o[3];
  float inv[3];  // 1/dir with zero components replaced by +-kTinyDir: no 0*inf NaNs
  int kx, ky, kz;
  float sx, sy, sz;
  bool valid;
};

RayPre prepare_ray(const Ray& ray) {
  RayPre r{};
  const float d[3] = {ray.dir.x, ray.dir.y, ray.dir.z};
  r.o[0] = ray.origin.x; r.o[1] = ray.origin.y; r.o[2] = ray.origin.z;
  const float ad[3] = {std::fabs(d[0]), std::fabs(d[1]), std::fabs(d[2])};
  r.kz = ad[0] > ad[1] ? (ad[0] > ad[2] ? 0 : 2) : (ad[1] > ad[2] ? 1 : 2);
  r.kx = r.kz == 2 ? 0 : r.kz + 1;
  r.ky = r.kx == 2 ? 0 : r.kx + 1;
  if (d[r.kz] < 0.0f) std::swap(r.kx, r.ky);  // keep the winding
  r.valid = ad[r.kz] > 0.0f && std::isfinite(ad[0] + ad[1] + ad[2]) &&
            std::isfinite(r.o[0] + r.o[1] + r.o[2]);
  r.sx = d[r.kx] / d[r.kz];
  r.sy = d[r.ky] / d[r.kz];
  r.sz = 1.0f / d[r.kz];
  for (int i = 0; i < 3; ++i) {
    float di = ad[i] < kTinyDir ? (std::signbit(d[i]) ? -kTinyDir : kTinyDir) : d[i];
    r.inv[i] = 1.0f / di;
  }
  return r;
}

// Watertight ray/triangle test without a t interval. Returns false on a miss, a parallel ray
// or a zero projected area. t, u (weight of p1), v (weight of p2) on a hit.
inline bool triangle_test(const RayPre& r, const float* p0, const float* p1, const float* p2,
                          float& t, float& u, float& v) {
  const int kx = r.kx, ky = r.ky, kz = r.kz;
  const float a_z = p0[kz] - r.o[kz], b_z = p1[kz] - r.o[kz], c_z = p2[kz] - r.o[kz];
  const float ax = (p0[kx] - r.o[kx]) - r.sx * a_z;
  const float ay = (p0[ky] - r.o[ky]) - r.sy * a_z;
  const float bx = (p1[kx] - r.o[kx]) - r.sx * b_z;
  const float by = (p1[ky] - r.o[ky]) - r.sy * b_z;
  const float cx = (p2[kx] - r.o[kx]) - r.sx * c_z;
  const float cy = (p2[ky] - r.o[ky]) - r.sy * c_z;
  float e0 = cx * by - cy * bx;  // weight of p0
  float e1 = ax * cy - ay * cx;  // weight of p1
  float e2 = bx * ay - by * ax;  // weight of p2
  // A float edge function never has the wrong sign (rounding is monotonic), but it can round
  // to 0; recompute those exactly (the products of two floats are exact in double) so both
  // triangles sharing the edge agree on which side the ray passes.
  if (e0 == 0.0f) e0 = float(double(cx) * double(by) - double(cy) * double(bx));
  if (e1 == 0.0f) e1 = float(double(ax) * double(cy) - double(ay) * double(cx));
  if (e2 == 0.0f) e2 = float(double(bx) * double(ay) - double(by) * double(ax));
  if ((e0 < 0.0f || e1 < 0.0f || e2 < 0.0f) && (e0 > 0.0f || e1 > 0.0f || e2 > 0.0f)) return false;
  const float det = (e0 + e1) + e2;
  if (!(det != 0.0f)) return false;
  const float tt = (e0 * (r.sz * a_z) + e1 * (r.sz * b_z)) + e2 * (r.sz * c_z);
  const float rcp = 1.0f / det;
  t = tt * rcp;
  u = e1 * rcp;
  v = e2 * rcp;
  return true;
}

// Closest-hit acceptance: inside [tmin, best_t], ties to the lower original id.
inline bool improves(float t, uint32_t id, float tmin, float best_t, uint32_t best_id) {
  return t >= tmin && (t < best_t || (t == best_t && id < best_id));
}

inline bool box_visit(const RayPre& r, const GpuBvhNode& n, float tmin, float tmax, float& tnear) {
  float tn = tmin, tf = tmax;
  for (int i = 0; i < 3; ++i) {
    const float t0 = (n.bmin[i] - r.o[i]) * r.inv[i];
    const float t1 = (n.bmax[i] - r.o[i]) * r.inv[i];
    tn = std::max(tn, std::min(t0, t1));
    tf = std::min(tf, std::max(t0, t1));
  }
  tnear = tn;
  return tn <= tf * kBoxSlack;
}

struct BuildItem {
  uint32_t node, begin, end, depth;
};

}  // namespace

bool triangle_is_degenerate(const FlatScene& scene, uint32_t triangle) {
  const GpuTriangle& tr = scene.triangles[triangle];
  const uint32_t nv = uint32_t(scene.vertices.size());
  if (tr.i0 >= nv || tr.i1 >= nv || tr.i2 >= nv) return true;
  return degenerate_positions(vertex_pos(scene, tr.i0), vertex_pos(scene, tr.i1),
                              vertex_pos(scene, tr.i2));
}

Bvh build_bvh(const FlatScene& scene) {
  const auto start = std::chrono::steady_clock::now();
  Bvh bvh;
  const uint32_t tri_count = uint32_t(scene.triangles.size());

  std::vector<uint32_t> prims;
  std::vector<Aabb> boxes(tri_count);
  std::vector<Vec3> centroids(tri_count);
  prims.reserve(tri_count);
  for (uint32_t i = 0; i < tri_count; ++i) {
    if (triangle_is_degenerate(scene, i)) continue;
    const GpuTriangle& tr = scene.triangles[i];
    Aabb b;
    b.grow(vertex_pos(scene, tr.i0));
    b.grow(vertex_pos(scene, tr.i1));
    b.grow(vertex_pos(scene, tr.i2));
    boxes[i] = b;
    // Midpoint of the box rather than the vertex mean: exact enough and never overflows.
    centroids[i] = b.lo * 0.5f + b.hi * 0.5f;
    prims.push_back(i);
  }
  bvh.stats.triangles = uint32_t(prims.size());
  bvh.stats.skipped_triangles = tri_count - bvh.stats.triangles;

  // Outward by one ulp and at least kBoxPad: flat boxes get volume, and a ray with a zero
  // direction component whose origin lies on the geometry's bound stays >= kBoxPad inside the
  // slab, so its slab distance times 1/kTinyDir is >= 1e10 (effectively unbounded).
  auto write_box = [](GpuBvhNode& n, const Aabb& b) {
    constexpr float inf = std::numeric_limits<float>::infinity();
    for (int k = 0; k < 3; ++k) {
      n.bmin[k] = std::min(std::nextafter(b.lo[k], -inf), b.lo[k] - kBoxPad);
      n.bmax[k] = std::max(std::nextafter(b.hi[k], inf), b.hi[k] + kBoxPad);
    }
  };

  bvh.nodes.push_back(GpuBvhNode{});
  if (prims.empty()) {  // empty leaf root
    bvh.stats.nodes = 1;
    bvh.stats.leaves = 1;
    bvh.stats.build_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return bvh;
  }
  bvh.nodes.reserve(2 * prims.size() / kSahLeafSize + 8);

  double root_area = 0;
  double sah = 0;
  std::vector<BuildItem> stack;
  stack.push_back({0, 0, uint32_t(prims.size()), 0});
  while (!stack.empty()) {
    const BuildItem item = stack.back();
    stack.pop_back();
    const uint32_t n = item.end - item.begin;
    Aabb bounds, cbounds;
    for (uint32_t i = item.begin; i < item.end; ++i) {
      bounds.grow(boxes[prims[i]]);
      cbounds.grow(centroids[prims[i]]);
    }
    write_box(bvh.nodes[item.node], bounds);
    const double area = bounds.half_area();
    if (item.node == 0) root_area = area > 0 ? area : 1.0;
    bvh.stats.max_depth = std::max(bvh.stats.max_depth, item.depth);

    auto make_leaf = [&] {
      GpuBvhNode& node = bvh.nodes[item.node];
      node.left_or_first = item.begin;
      node.count = n;
      bvh.stats.leaves++;
      sah += area / root_area * double(n);
    };
    if (n <= kSahLeafSize) {
      make_leaf();
      continue;
    }

    // Binned SAH over the centroid bounds of every axis that has extent.
    int best_axis = -1, best_bin = -1;
    double best_cost = std::numeric_limits<double>::infinity();
    float best_scale = 0;
    if (item.depth < kSahMaxDepth) {
      for (int axis = 0; axis < 3; ++axis) {
        const float extent = cbounds.hi[axis] - cbounds.lo[axis];
        if (!(extent > 0.0f)) continue;
        const float scale = float(kBins) / extent;
        if (!std::isfinite(scale)) continue;
        std::array<Aabb, kBins> bin_box{};
        std::array<uint32_t, kBins> bin_count{};
        for (uint32_t i = item.begin; i < item.end; ++i) {
          const uint32_t p = prims[i];
          int b = int((centroids[p][axis] - cbounds.lo[axis]) * scale);
          b = std::clamp(b, 0, kBins - 1);
          bin_count[b]++;
          bin_box[b].grow(boxes[p]);
        }
        // Sweep: right-side areas from the back, then left side forward.
        std::array<double, kBins> right_area{};
        std::array<uint32_t, kBins> right_count{};
        Aabb acc;
        uint32_t cnt = 0;
        for (int b = kBins - 1; b > 0; --b) {
          acc.grow(bin_box[b]);
          cnt += bin_count[b];
          right_area[b] = acc.half_area();
          right_count[b] = cnt;
        }
        acc = Aabb{};
        cnt = 0;
        for (int b = 0; b < kBins - 1; ++b) {  // split between bin b and b+1
          acc.grow(bin_box[b]);
          cnt += bin_count[b];
          const uint32_t rc = right_count[b + 1];
          if (cnt == 0 || rc == 0) continue;
          const double cost = acc.half_area() * cnt + right_area[b + 1] * rc;
          if (cost < best_cost) {
            best_cost = cost;
            best_axis = axis;
            best_bin = b;
            best_scale = scale;
          }
        }
      }
    }

    uint32_t mid;
    if (best_axis >= 0) {
      // Traversal cost 1, triangle cost 1, in units of the node's area.
      const double split_cost = area + best_cost;
      const double leaf_cost = area * double(n);
      if (split_cost >= leaf_cost && n <= kSahMaxLeafSize) {
        make_leaf();
        continue;
      }
      const int axis = best_axis;
      const float lo = cbounds.lo[axis];
      auto it = std::partition(prims.begin() + item.begin, prims.begin() + item.end,
                               [&](uint32_t p) {
                                 int b = int((centroids[p][axis] - lo) * best_scale);
                                 return std::clamp(b, 0, kBins - 1) <= best_bin;
                               });
      mid = uint32_t(it - prims.begin());
    } else {
      // No usable split (all centroids equal, or too deep for SAH): object median along the
      // widest centroid axis. Halving bounds the depth and always terminates.
      int axis = 0;
      Vec3 ext = cbounds.hi - cbounds.lo;
      if (ext.y > ext[axis]) axis = 1;
      if (ext.z > ext[axis]) axis = 2;
      mid = item.begin + n / 2;
      std::nth_element(prims.begin() + item.begin, prims.begin() + mid, prims.begin() + item.end,
                       [&](uint32_t a, uint32_t b) {
                         const float ca = centroids[a][axis], cb = centroids[b][axis];
                         return ca < cb || (ca == cb && a < b);
                       });
    }
    if (mid == item.begin || mid == item.end) mid = item.begin + n / 2;  // cannot happen; be safe

    const uint32_t left = uint32_t(bvh.nodes.size());
    bvh.nodes.push_back(GpuBvhNode{});
    bvh.nodes.push_back(GpuBvhNode{});
    bvh.nodes[item.node].left_or_first = left;
    bvh.nodes[item.node].count = 0;
    sah += area / root_area;
    stack.push_back({left + 1, mid, item.end, item.depth + 1});
    stack.push_back({left, item.begin, mid, item.depth + 1});
  }
  if (bvh.stats.max_depth >= kBvhMaxDepth) {
    throw std::runtime_error("build_bvh: depth " + std::to_string(bvh.stats.max_depth) +
                             " exceeds the traversal stack (" + std::to_string(kBvhMaxDepth) + ")");
  }

  bvh.tri_index = std::move(prims);
  bvh.slot_positions.resize(bvh.tri_index.size() * 9);
  for (size_t s = 0; s < bvh.tri_index.size(); ++s) {
    const GpuTriangle& tr = scene.triangles[bvh.tri_index[s]];
    const uint32_t idx[3] = {tr.i0, tr.i1, tr.i2};
    for (int k = 0; k < 3; ++k) {
      const GpuVertex& v = scene.vertices[idx[k]];
      bvh.slot_positions[s * 9 + k * 3 + 0] = v.px;
      bvh.slot_positions[s * 9 + k * 3 + 1] = v.py;
      bvh.slot_positions[s * 9 + k * 3 + 2] = v.pz;
    }
  }
  bvh.stats.nodes = uint32_t(bvh.nodes.size());
  bvh.stats.sah_cost = float(sah);
  bvh.stats.build_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return bvh;
}

Hit intersect_triangle(const FlatScene& scene, uint32_t triangle, Ray ray) {
  Hit h;
  const RayPre r = prepare_ray(ray);
  if (!r.valid || triangle_is_degenerate(scene, triangle)) return h;
  const GpuTriangle& tr = scene.triangles[triangle];
  const GpuVertex& a = scene.vertices[tr.i0];
  const GpuVertex& b = scene.vertices[tr.i1];
  const GpuVertex& c = scene.vertices[tr.i2];
  const float p0[3] = {a.px, a.py, a.pz}, p1[3] = {b.px, b.py, b.pz}, p2[3] = {c.px, c.py, c.pz};
  float t, u, v;
  if (triangle_test(r, p0, p1, p2, t, u, v)) {
    h = Hit{t, triangle, u, v, true};
  }
  return h;
}

Hit intersect_brute_force(const FlatScene& scene, Ray ray, float tmin, float tmax,
                          AlphaTest alpha) {
  Hit best;
  const RayPre r = prepare_ray(ray);
  if (!r.valid) return best;
  float best_t = tmax;
  uint32_t best_id = UINT32_MAX;
  for (uint32_t i = 0; i < uint32_t(scene.triangles.size()); ++i) {
    if (triangle_is_degenerate(scene, i)) continue;
    const GpuTriangle& tr = scene.triangles[i];
    const GpuVertex& a = scene.vertices[tr.i0];
    const GpuVertex& b = scene.vertices[tr.i1];
    const GpuVertex& c = scene.vertices[tr.i2];
    const float p0[3] = {a.px, a.py, a.pz}, p1[3] = {b.px, b.py, b.pz}, p2[3] = {c.px, c.py, c.pz};
    float t, u, v;
    if (!triangle_test(r, p0, p1, p2, t, u, v)) continue;
    if (!improves(t, i, tmin, best_t, best_id)) continue;
    if (alpha.accept && !alpha.accept(alpha.user, i, u, v)) continue;
    best_t = t;
    best_id = i;
    best = Hit{t, i, u, v, true};
  }
  return best;
}

namespace {

template <bool kAnyHit>
Hit traverse(const Bvh& bvh, const RayPre& r, float tmin, float tmax, AlphaTest alpha) {
  Hit best;
  if (!r.valid || bvh.nodes.empty()) return best;
  const GpuBvhNode* nodes = bvh.nodes.data();
  const float* pos = bvh.slot_positions.data();
  const uint32_t* ids = bvh.tri_index.data();
  float best_t = tmax;
  uint32_t best_id = UINT32_MAX;

  struct Entry { uint32_t node; float tnear; };
  Entry stack[kBvhMaxDepth];
  int sp = 0;
  float tnear;
  if (nodes[0].count == 0 && nodes[0].left_or_first == 0) return best;
  if (!box_visit(r, nodes[0], tmin, best_t, tnear)) return best;
  uint32_t node = 0;
  for (;;) {
    const GpuBvhNode& n = nodes[node];
    if (n.count > 0) {
      for (uint32_t s = n.left_or_first, e = n.left_or_first + n.count; s < e; ++s) {
        float t, u, v;
        const float* p = pos + size_t(s) * 9;
        if (!triangle_test(r, p, p + 3, p + 6, t, u, v)) continue;
        const uint32_t id = ids[s];
        if (!improves(t, id, tmin, best_t, best_id)) continue;
        if (alpha.accept && !alpha.accept(alpha.user, id, u, v)) continue;
        best_t = t;
        best_id = id;
        best = Hit{t, id, u, v, true};
        if constexpr (kAnyHit) return best;
      }
    } else {
      const uint32_t l = n.left_or_first;
      float tl, tr;
      const bool hl = box_visit(r, nodes[l], tmin, best_t, tl);
      const bool hr = box_visit(r, nodes[l + 1], tmin, best_t, tr);
      if (hl && hr) {
        const bool left_first = tl <= tr;
        stack[sp++] = left_first ? Entry{l + 1, tr} : Entry{l, tl};
        node = left_first ? l : l + 1;
        continue;
      }
      if (hl) { node = l; continue; }
      if (hr) { node = l + 1; continue; }
    }
    // Pop, skipping entries that the best hit found since the push makes unreachable.
    for (;;) {
      if (sp == 0) return best;
      const Entry e = stack[--sp];
      if (e.tnear <= best_t * kBoxSlack) { node = e.node; break; }
    }
  }
}

}  // namespace

Hit intersect_bvh(const Bvh& bvh, const FlatScene&, Ray ray, float tmin, float tmax,
                  AlphaTest alpha) {
  return traverse<false>(bvh, prepare_ray(ray), tmin, tmax, alpha);
}

bool occluded_bvh(const Bvh& bvh, const FlatScene&, Ray ray, float tmin, float tmax,
                  AlphaTest alpha) {
  return traverse<true>(bvh, prepare_ray(ray), tmin, tmax, alpha).hit;
}

}  // namespace gib
