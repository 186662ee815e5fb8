// LDR-/HDR-FLIP. Pipeline and constants: data/flip-vectors/NOTES.md (sections in
// brackets below). float32 throughout (as the reference tool), double for the mean.
// All filters are separable, with clamp-to-edge borders and folded symmetric taps. Rows are
// split into one band per usable CPU; each band streams, for every exposure:
//   A: per row, input -> YCxCz -> horizontal CSF passes (Y', Cx, Cz twice) and horizontal
//      feature passes (G, D1, D2 of the normalised luminance), into a ring of the last
//      2 * pad + 1 rows per plane (7 planes per image);
//   B: per row, vertical passes, back to RGB, clamp, CIELAB + Hunt, HyAB, colour-error
//      remap, feature difference, combination (and max over exposures for HDR).
// Bands recompute `pad` rows of support at their edges; nothing image-sized is allocated
// besides the error map and the sort buffers for the weighted percentiles.
#include "metrics/flip.h"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <exception>
#include <numbers>
#include <stdexcept>
#include <thread>

#if defined(__linux__)
#include <sched.h>
#endif

namespace gib {
namespace {

constexpr double kPi = std::numbers::pi;

// [1] linear sRGB -> XYZ (exact rationals), XYZ -> linear sRGB (tool's 9-decimal inverse).
constexpr float kRgbToXyz[3][3] = {
    {float(10135552.0 / 24577794.0), float(8788810.0 / 24577794.0), float(4435075.0 / 24577794.0)},
    {float(2613072.0 / 12288897.0), float(8788810.0 / 12288897.0), float(887015.0 / 12288897.0)},
    {float(1425312.0 / 73733382.0), float(8788810.0 / 73733382.0), float(70074185.0 / 73733382.0)},
};
constexpr float kXyzToRgb[3][3] = {
    {3.241003275f, -1.537398934f, -0.498615861f},
    {-0.969224334f, 1.875930071f, 0.041554224f},
    {0.055639423f, -0.204011202f, 1.057148933f},
};
constexpr float kWhite[3] = {0.950428545f, 1.0f, 1.088900371f};
constexpr float kInvWhite[3] = {1.052156925f, 1.0f, 0.918357670f};

// [7] colour-error compression; [8] feature constants.
constexpr double kQc = 0.7, kPc = 0.4, kPt = 0.95;
constexpr double kFeatureWidth = 0.082;  // degrees

// ---------------------------------------------------------------- threading

// CPUs this process may run on (cpuset/taskset aware on Linux).
int usable_cpus() {
#if defined(__linux__)
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof(set), &set) == 0 && CPU_COUNT(&set) > 0) return CPU_COUNT(&set);
#endif
  return int(std::max(1u, std::thread::hardware_concurrency()));
}

// Runs fn(begin, end) over contiguous bands of [0, rows). Each band recomputes `overlap`
// rows of filter support on either side, so bands are kept at least 4x that tall.
template <class F>
void parallel_rows(int rows, int overlap, F&& fn) {
  int threads = std::min(usable_cpus(), 64);
  threads = std::max(1, std::min(threads, rows / std::max(16, 4 * overlap)));
  if (threads <= 1) {
    fn(0, rows);
    return;
  }
  auto range = [&](int t) { return std::pair{int(int64_t(rows) * t / threads), int(int64_t(rows) * (t + 1) / threads)}; };
  std::vector<std::exception_ptr> errors(static_cast<size_t>(threads));
  auto run = [&](int t) {
    try {
      auto [b, e] = range(t);
      fn(b, e);
    } catch (...) {
      errors[size_t(t)] = std::current_exception();
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(size_t(threads - 1));
  for (int t = 1; t < threads; ++t) pool.emplace_back(run, t);
  run(0);
  for (auto& th : pool) th.join();
  for (auto& e : errors)
    if (e) std::rethrow_exception(e);
}

// ---------------------------------------------------------------- kernels

struct Kernel {
  int r = 0;
  std::vector<float> w;  // 2r+1 taps, index i <-> offset i - r
};

Kernel from_double(int r, const std::vector<double>& w) {
  Kernel k;
  k.r = r;
  k.w.assign(w.begin(), w.end());
  return k;
}

struct Kernels {
  Kernel y, cx, cz1, cz2;  // [3] CSF, 1D
  Kernel g, d1, d2;        // [8] features, 1D
  int pad = 0;             // largest radius
};

Kernels make_kernels(double ppd) {
  Kernels k;
  // [3] CSF radius from the widest Gaussian (b = 0.04).
  const int rc = int(std::ceil(3.0 * std::sqrt(0.04 / (2.0 * kPi * kPi)) * ppd));
  auto gauss = [&](double b, double amp) {
    std::vector<double> w(size_t(2 * rc + 1));
    for (int i = -rc; i <= rc; ++i) {
      double t = double(i) / ppd;
      w[size_t(i + rc)] = amp * std::exp(-kPi * kPi * t * t / b);
    }
    return w;
  };
  auto sum = [](const std::vector<double>& w) {
    double s = 0;
    for (double v : w) s += v;
    return s;
  };
  auto normalised = [&](std::vector<double> w) {
    double s = sum(w);
    for (double& v : w) v /= s;
    return w;
  };
  k.y = from_double(rc, normalised(gauss(0.0047, 1.0)));
  k.cx = from_double(rc, normalised(gauss(0.0053, 1.0)));
  // Cz: two Gaussians, each separable with amplitude sqrt(a * sqrt(pi / b)) per pass (the
  // exponent is not halved); both scaled so the summed 2D kernel has unit weight.
  std::vector<double> c1 = gauss(0.04, std::sqrt(34.1 * std::sqrt(kPi / 0.04)));
  std::vector<double> c2 = gauss(0.025, std::sqrt(13.5 * std::sqrt(kPi / 0.025)));
  double s1 = sum(c1), s2 = sum(c2), norm = 1.0 / std::sqrt(s1 * s1 + s2 * s2);
  for (double& v : c1) v *= norm;
  for (double& v : c2) v *= norm;
  k.cz1 = from_double(rc, c1);
  k.cz2 = from_double(rc, c2);

  // [8] feature filters.
  const double sigma = 0.5 * kFeatureWidth * ppd;
  const int rf = int(std::ceil(3.0 * sigma));
  std::vector<double> g(size_t(2 * rf + 1)), d1(g.size()), d2(g.size());
  for (int i = -rf; i <= rf; ++i) {
    double t = double(i), gv = std::exp(-t * t / (2.0 * sigma * sigma));
    g[size_t(i + rf)] = gv;
    d1[size_t(i + rf)] = -t * gv;
    d2[size_t(i + rf)] = (t * t / (sigma * sigma) - 1.0) * gv;
  }
  auto pos_neg_normalised = [](std::vector<double> w) {
    double p = 0, n = 0;
    for (double v : w) (v > 0 ? p : n) += v;
    for (double& v : w) {
      if (v > 0) v /= p;
      else if (v < 0) v /= -n;
    }
    return w;
  };
  k.g = from_double(rf, normalised(g));
  k.d1 = from_double(rf, pos_neg_normalised(d1));
  k.d2 = from_double(rf, pos_neg_normalised(d2));
  k.pad = std::max(rc, rf);
  return k;
}

// The convolution loops are compiled for AVX2+FMA as well, picked at run time (ifunc).
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && defined(__linux__)
#define GIB_FLIP_SIMD __attribute__((target_clones("arch=x86-64-v3", "default")))
#else
#define GIB_FLIP_SIMD
#endif

// The kernels are symmetric (sym = +1) or antisymmetric (D1, sym = -1) about their centre,
// so each tap pair is folded: w[r] c + sum_{j>0} w[r + j] (in[+j] + sym in[-j]).
float kernel_symmetry(const Kernel& k) { return k.w.front() * k.w.back() < 0 ? -1.0f : 1.0f; }

// out[x] = sum_j w[j] * in[x + j - r]; `in` points at x = 0 of a row padded by >= r.
GIB_FLIP_SIMD void hconv(const float* in, int width, const Kernel& k, float* out) {
  const float wc = k.w[size_t(k.r)];
  for (int x = 0; x < width; ++x) out[x] = wc * in[x];
  if (kernel_symmetry(k) > 0) {
    for (int j = 1; j <= k.r; ++j) {
      const float wj = k.w[size_t(k.r + j)];
      const float* a = in + j;
      const float* b = in - j;
      for (int x = 0; x < width; ++x) out[x] += wj * (a[x] + b[x]);
    }
  } else {
    for (int j = 1; j <= k.r; ++j) {
      const float wj = k.w[size_t(k.r + j)];
      const float* a = in + j;
      const float* b = in - j;
      for (int x = 0; x < width; ++x) out[x] += wj * (a[x] - b[x]);
    }
  }
}

// out[x] = sum_j w[j] * rows[j][x]: rows holds the 2r+1 (clamped) input rows, top to bottom.
GIB_FLIP_SIMD void vconv(const float* const* rows, int width, const Kernel& k, float* out) {
  const float* c = rows[k.r];
  const float wc = k.w[size_t(k.r)];
  for (int x = 0; x < width; ++x) out[x] = wc * c[x];
  const bool sym = kernel_symmetry(k) > 0;
  for (int j = 1; j <= k.r; ++j) {
    const float wj = k.w[size_t(k.r + j)];
    const float* a = rows[k.r + j];
    const float* b = rows[k.r - j];
    if (sym) {
      for (int x = 0; x < width; ++x) out[x] += wj * (a[x] + b[x]);
    } else {
      for (int x = 0; x < width; ++x) out[x] += wj * (a[x] - b[x]);
    }
  }
}

// ---------------------------------------------------------------- tone mapping [12]

struct ToneMapper {
  enum class Kind { aces, hable, reinhard } kind = Kind::aces;
  double c[6] = {};
};

ToneMapper make_tonemapper(const std::string& name) {
  ToneMapper t;
  if (name == "aces") {
    t.kind = ToneMapper::Kind::aces;
    const double k[6] = {0.6 * 0.6 * 2.51, 0.6 * 0.03, 0.0, 0.6 * 0.6 * 2.43, 0.6 * 0.59, 0.14};
    std::copy(k, k + 6, t.c);
  } else if (name == "hable") {
    t.kind = ToneMapper::Kind::hable;
    const double k[6] = {0.231683, 0.013791, 0.0, 0.18, 0.3, 0.018};
    std::copy(k, k + 6, t.c);
  } else if (name == "reinhard") {
    t.kind = ToneMapper::Kind::reinhard;
    const double k[6] = {0.0, 1.0, 0.0, 0.0, 1.0, 1.0};
    std::copy(k, k + 6, t.c);
  } else {
    throw std::invalid_argument(fmt::format("flip: unknown tone mapper '{}' (aces, reinhard, hable)", name));
  }
  return t;
}

// Larger root of T(x) = 0.85.
double tonemapper_x_max(const ToneMapper& t) {
  const double a = t.c[0] - 0.85 * t.c[3], b = t.c[1] - 0.85 * t.c[4], c = t.c[2] - 0.85 * t.c[5];
  if (a == 0.0) return -c / b;
  const double d = std::sqrt(std::max(0.0, b * b - 4.0 * a * c));
  return std::max((-b + d) / (2.0 * a), (-b - d) / (2.0 * a));
}

float luminance(float r, float g, float b) { return 0.2126f * r + 0.7152f * g + 0.0722f * b; }

// ---------------------------------------------------------------- the LDR-FLIP core

// Source of clamped linear RGB for one row: LDR (clamp) or HDR (exposure, tone map, clamp).
struct RowSource {
  const FloatImage* img = nullptr;
  bool hdr = false;
  ToneMapper tm;
  float c[6] = {};

  void row(int y, float exposure_scale, float* r, float* g, float* b) const {
    const uint32_t ch = img->channels;
    const float* p = img->pixels.data() + size_t(y) * img->width * ch;
    const int w = int(img->width);
    for (int x = 0; x < w; ++x, p += ch) {
      float v[3];
      if (ch >= 3) v[0] = p[0], v[1] = p[1], v[2] = p[2];
      else v[0] = v[1] = v[2] = p[0];
      if (hdr) {
        for (float& s : v) s *= exposure_scale;
        if (tm.kind == ToneMapper::Kind::reinhard) {
          const float inv = 1.0f / (1.0f + luminance(v[0], v[1], v[2]));
          for (float& s : v) s *= inv;
        } else {
          for (float& s : v) s = (c[0] * s * s + c[1] * s + c[2]) / (c[3] * s * s + c[4] * s + c[5]);
        }
      }
      r[x] = std::clamp(v[0], 0.0f, 1.0f);
      g[x] = std::clamp(v[1], 0.0f, 1.0f);
      b[x] = std::clamp(v[2], 0.0f, 1.0f);
    }
  }
};

enum Plane { kY = 0, kCx, kCz1, kCz2, kG, kD1, kD2, kPlanes };

// Stage-A output rows of one image, for the 2 * pad + 1 most recent rows (all a vertical
// pass needs): a ring per plane, so a band streams through a few MiB instead of full planes.
class RowRing {
 public:
  RowRing(int width, int pad)
      : width_(width), size_(2 * pad + 1), data_(size_t(kPlanes) * size_t(size_) * size_t(width)) {}
  float* row(int plane, int y) { return data_.data() + (size_t(plane) * size_t(size_) + size_t(y % size_)) * size_t(width_); }
  const float* row(int plane, int y) const {
    return data_.data() + (size_t(plane) * size_t(size_) + size_t(y % size_)) * size_t(width_);
  }

 private:
  int width_, size_;
  std::vector<float> data_;
};

struct StageAScratch {
  std::vector<float> r, g, b, padY, padCx, padCz, padL;
  StageAScratch(int width, int pad)
      : r(size_t(width)), g(r.size()), b(r.size()), padY(size_t(width + 2 * pad)), padCx(padY.size()),
        padCz(padY.size()), padL(padY.size()) {}
};

// Stage A for row y of one image: input -> YCxCz -> horizontal passes into the ring.
void stage_a_row(const RowSource& src, float exposure_scale, const Kernels& k, int width, int y, StageAScratch& s,
                 RowRing& ring) {
  const int pad = k.pad;
  src.row(y, exposure_scale, s.r.data(), s.g.data(), s.b.data());
  for (int x = 0; x < width; ++x) {
    const float R = s.r[size_t(x)], G = s.g[size_t(x)], B = s.b[size_t(x)];
    const float X = kRgbToXyz[0][0] * R + kRgbToXyz[0][1] * G + kRgbToXyz[0][2] * B;
    const float Y = kRgbToXyz[1][0] * R + kRgbToXyz[1][1] * G + kRgbToXyz[1][2] * B;
    const float Z = kRgbToXyz[2][0] * R + kRgbToXyz[2][1] * G + kRgbToXyz[2][2] * B;
    const float xn = X * kInvWhite[0], yn = Y * kInvWhite[1], zn = Z * kInvWhite[2];
    const float Yp = 116.0f * yn - 16.0f;
    const size_t i = size_t(pad + x);
    s.padY[i] = Yp;
    s.padCx[i] = 500.0f * (xn - yn);
    s.padCz[i] = 200.0f * (yn - zn);
    s.padL[i] = (Yp + 16.0f) / 116.0f;  // [8] normalised luminance
  }
  for (std::vector<float>* v : {&s.padY, &s.padCx, &s.padCz, &s.padL}) {  // clamp-to-edge
    std::fill(v->begin(), v->begin() + pad, (*v)[size_t(pad)]);
    std::fill(v->begin() + pad + width, v->end(), (*v)[size_t(pad + width - 1)]);
  }
  hconv(s.padY.data() + pad, width, k.y, ring.row(kY, y));
  hconv(s.padCx.data() + pad, width, k.cx, ring.row(kCx, y));
  hconv(s.padCz.data() + pad, width, k.cz1, ring.row(kCz1, y));
  hconv(s.padCz.data() + pad, width, k.cz2, ring.row(kCz2, y));
  hconv(s.padL.data() + pad, width, k.g, ring.row(kG, y));
  hconv(s.padL.data() + pad, width, k.d1, ring.row(kD1, y));
  hconv(s.padL.data() + pad, width, k.d2, ring.row(kD2, y));
}

// Cube root for t > (6/29)^3 (always positive here): bit-level first guess, then two
// Halley steps in double; exact to float rounding, and much cheaper than cbrtf.
inline float cbrt_positive(float t) {
  const uint32_t bits = std::bit_cast<uint32_t>(t) / 3u + 709921077u;
  double y = std::bit_cast<float>(bits);
  const double td = t;
  for (int i = 0; i < 2; ++i) {
    const double y3 = y * y * y;
    y = y * (y3 + 2.0 * td) / (2.0 * y3 + td);
  }
  return float(y);
}

// Per-pixel selects below use integer compares on the float bits and bit masks: GCC will
// not if-convert float compares or a division under the default trapping-math rules, and
// the row loops would not vectorise. Results are bit-identical to the plain expressions.

// Clamp to [0, 1]: negative values (sign bit set) -> 0, above 1 (incl. +inf) -> 1.
inline float clamp01(float v) {
  int32_t b = std::bit_cast<int32_t>(v);
  b = b < 0 ? 0 : b;
  b = b > 0x3f800000 ? 0x3f800000 : b;
  return std::bit_cast<float>(b);
}

// CIELAB f(t) for t >= 0.
inline float lab_f(float t) {
  constexpr float kD3 = float((6.0 / 29.0) * (6.0 / 29.0) * (6.0 / 29.0));
  constexpr float kSlope = float(1.0 / (3.0 * (6.0 / 29.0) * (6.0 / 29.0)));
  const int32_t tb = std::bit_cast<int32_t>(t), db = std::bit_cast<int32_t>(kD3);
  const bool cube = tb > db;  // t > (6/29)^3 for non-negative t
  const float c = cbrt_positive(std::bit_cast<float>(cube ? tb : db));
  const float lin = t * kSlope + float(4.0 / 29.0);
  const uint32_t mask = 0u - uint32_t(cube);
  return std::bit_cast<float>((std::bit_cast<uint32_t>(c) & mask) | (std::bit_cast<uint32_t>(lin) & ~mask));
}

// Hunt-adjusted CIELAB of clamped linear RGB [4][5].
inline void rgb_to_lab_hunt(float R, float G, float B, float& L, float& a, float& b) {
  const float X = kRgbToXyz[0][0] * R + kRgbToXyz[0][1] * G + kRgbToXyz[0][2] * B;
  const float Y = kRgbToXyz[1][0] * R + kRgbToXyz[1][1] * G + kRgbToXyz[1][2] * B;
  const float Z = kRgbToXyz[2][0] * R + kRgbToXyz[2][1] * G + kRgbToXyz[2][2] * B;
  const float fx = lab_f(X * kInvWhite[0]), fy = lab_f(Y * kInvWhite[1]), fz = lab_f(Z * kInvWhite[2]);
  L = 116.0f * fy - 16.0f;
  a = 0.01f * L * (500.0f * (fx - fy));
  b = 0.01f * L * (200.0f * (fy - fz));
}

double cmax_value() {
  float L1, a1, b1, L2, a2, b2;
  rgb_to_lab_hunt(0, 1, 0, L1, a1, b1);
  rgb_to_lab_hunt(0, 0, 1, L2, a2, b2);
  double d = std::fabs(double(L1) - L2) + std::hypot(double(a1) - a2, double(b1) - b2);
  return std::pow(d, kQc);
}

// Filtered YCxCz (Cz as its two separable parts) -> XYZ -> linear RGB, clamp, Hunt Lab [4].
GIB_FLIP_SIMD void filtered_to_lab_hunt(const float* __restrict yf, const float* __restrict cxf,
                                        const float* __restrict cz1, const float* __restrict cz2, int width,
                                        float* __restrict L, float* __restrict A, float* __restrict B) {
  for (int x = 0; x < width; ++x) {
    const float yy = (yf[x] + 16.0f) / 116.0f;
    const float xx = yy + cxf[x] / 500.0f;
    const float zz = yy - (cz1[x] + cz2[x]) / 200.0f;
    const float X = xx * kWhite[0], Y = yy * kWhite[1], Z = zz * kWhite[2];
    const float R = clamp01(kXyzToRgb[0][0] * X + kXyzToRgb[0][1] * Y + kXyzToRgb[0][2] * Z);
    const float G = clamp01(kXyzToRgb[1][0] * X + kXyzToRgb[1][1] * Y + kXyzToRgb[1][2] * Z);
    const float Bl = clamp01(kXyzToRgb[2][0] * X + kXyzToRgb[2][1] * Y + kXyzToRgb[2][2] * Z);
    rgb_to_lab_hunt(R, G, Bl, L[x], A[x], B[x]);
  }
}

struct RowScratch {
  std::vector<float> yf, cxf, czf, tmp, L, A, B, E, P;
  std::vector<const float*> rows;  // kPlanes x (2 pad + 1) row pointers
  RowScratch(int w, int pad)
      : yf(size_t(w)), cxf(yf.size()), czf(yf.size()), tmp(yf.size()), L(yf.size()), A(yf.size()), B(yf.size()),
        E(yf.size()), P(yf.size()), rows(size_t(kPlanes) * size_t(2 * pad + 1)) {}
};

// Stage B, one image, one row: Hunt-adjusted Lab of the filtered image and feature magnitudes.
void stage_b_image(const RowRing& ring, const Kernels& k, int width, int height, int y, RowScratch& s) {
  // Row pointers per plane for offsets -pad..pad; a kernel of radius r uses the middle 2r+1.
  const int pad = k.pad;
  const size_t n = size_t(2 * pad + 1);
  for (int p = 0; p < kPlanes; ++p)
    for (int dy = -pad; dy <= pad; ++dy) s.rows[size_t(p) * n + size_t(dy + pad)] = ring.row(p, std::clamp(y + dy, 0, height - 1));
  auto at = [&](int plane, const Kernel& kk) { return &s.rows[size_t(plane) * n + size_t(pad - kk.r)]; };
  vconv(at(kY, k.y), width, k.y, s.yf.data());
  vconv(at(kCx, k.cx), width, k.cx, s.cxf.data());
  vconv(at(kCz1, k.cz1), width, k.cz1, s.czf.data());
  vconv(at(kCz2, k.cz2), width, k.cz2, s.tmp.data());
  filtered_to_lab_hunt(s.yf.data(), s.cxf.data(), s.czf.data(), s.tmp.data(), width, s.L.data(), s.A.data(),
                       s.B.data());
  // Features: edge_x = D1(x) G(y), edge_y = G(x) D1(y), point likewise with D2.
  float* ex = s.yf.data();
  float* ey = s.cxf.data();
  float* px = s.czf.data();
  float* py = s.tmp.data();
  vconv(at(kD1, k.g), width, k.g, ex);
  vconv(at(kG, k.d1), width, k.d1, ey);
  vconv(at(kD2, k.g), width, k.g, px);
  vconv(at(kG, k.d2), width, k.d2, py);
  for (int x = 0; x < width; ++x) {
    const size_t i = size_t(x);
    s.E[i] = std::sqrt(ex[i] * ex[i] + ey[i] * ey[i]);
    s.P[i] = std::sqrt(px[i] * px[i] + py[i] * py[i]);
  }
}

// Per-thread state for a band of rows.
struct BandState {
  RowRing ring_ref, ring_test;
  StageAScratch a;
  RowScratch b_ref, b_test;
  BandState(int width, int pad) : ring_ref(width, pad), ring_test(width, pad), a(width, pad), b_ref(width, pad), b_test(width, pad) {}
};

// One LDR-FLIP evaluation of rows [y0, y1): writes, or max-combines into, `map`.
void flip_band(const RowSource& ref, const RowSource& test, float exposure_scale, const Kernels& k, float cmax,
               int y0, int y1, bool combine_max, BandState& st, float* map) {
  const int w = int(ref.img->width), h = int(ref.img->height);
  const float pccmax = float(kPc) * cmax;
  const float qf_scale = float(1.0 / std::numbers::sqrt2);
  int next = std::max(0, y0 - k.pad);  // next stage-A row to compute
  for (int y = y0; y < y1; ++y) {
    for (const int last = std::min(h - 1, y + k.pad); next <= last; ++next) {
      stage_a_row(ref, exposure_scale, k, w, next, st.a, st.ring_ref);
      stage_a_row(test, exposure_scale, k, w, next, st.a, st.ring_test);
    }
    RowScratch& sr = st.b_ref;
    RowScratch& tt = st.b_test;
    stage_b_image(st.ring_ref, k, w, h, y, sr);
    stage_b_image(st.ring_test, k, w, h, y, tt);
    float* out = map + size_t(y) * size_t(w);
    for (int x = 0; x < w; ++x) {
      const size_t i = size_t(x);
      // [6] HyAB, [7] compression.
      const float da = sr.A[i] - tt.A[i], db = sr.B[i] - tt.B[i];
      const float hyab = std::fabs(sr.L[i] - tt.L[i]) + std::sqrt(da * da + db * db);
      const float d = std::pow(hyab, float(kQc));
      const float ec =
          d < pccmax ? d * float(kPt) / pccmax : float(kPt) + (d - pccmax) / (cmax - pccmax) * float(1.0 - kPt);
      // [8] feature difference, [9] combination.
      const float fd = std::max(std::fabs(sr.E[i] - tt.E[i]), std::fabs(sr.P[i] - tt.P[i]));
      const float ef = std::sqrt(fd * qf_scale);
      const float e = std::pow(ec, 1.0f - ef);
      if (combine_max) out[x] = std::max(out[x], e);
      else out[x] = e;
    }
  }
}

// Ascending sort of non-negative floats: LSD radix sort on the bit patterns (which order
// like the values for non-negative floats), 3 passes of 11 bits; std::sort otherwise.
std::vector<float> sorted_copy(const std::vector<float>& v) {
  std::vector<float> out = v;
  const bool non_negative = std::all_of(v.begin(), v.end(), [](float e) { return e >= 0.0f && !std::signbit(e); });
  if (!non_negative || v.size() < 4096) {
    // NaN (from non-finite HDR input) sorts last.
    std::sort(out.begin(), out.end(), [](float x, float y) { return x < y || (!std::isnan(x) && std::isnan(y)); });
    return out;
  }
  const size_t n = v.size();
  std::vector<uint32_t> a(n), b(n);
  std::memcpy(a.data(), v.data(), n * 4);
  for (int pass = 0; pass < 3; ++pass) {
    const int shift = pass * 11;
    std::vector<size_t> count(2049, 0);
    for (uint32_t k : a) ++count[((k >> shift) & 2047u) + 1];
    for (size_t i = 1; i < count.size(); ++i) count[i] += count[i - 1];
    for (uint32_t k : a) b[count[(k >> shift) & 2047u]++] = k;
    a.swap(b);
  }
  std::memcpy(out.data(), a.data(), n * 4);
  return out;
}

void pool_stats(FlipResult& r) {
  const std::vector<float>& v = r.error_map.pixels;
  if (v.empty()) return;
  double sum = 0;
  float fsum = 0, mn = v[0], mx = v[0];
  for (float e : v) {
    sum += e;
    fsum += e;
    mn = std::min(mn, e);
    mx = std::max(mx, e);
  }
  r.mean = sum / double(v.size());
  r.min = mn;
  r.max = mx;
  const std::vector<float> sorted = sorted_copy(v);
  auto percentile = [&](float p) -> double {
    if (fsum == 0.0f) return 0.0;
    const float target = p * fsum;
    float run = 0;
    for (float e : sorted) {
      run += e;
      if (run > target) return e;
    }
    return sorted.back();
  };
  r.weighted_q1 = percentile(0.25f);
  r.weighted_median = percentile(0.5f);
  r.weighted_q3 = percentile(0.75f);
}

}  // namespace

double flip_ppd(double distance_m, double monitor_width_m, double monitor_width_px) {
  return distance_m * (monitor_width_px / monitor_width_m) * kPi / 180.0;
}

FloatImage srgb8_to_linear(const std::vector<uint8_t>& rgb, uint32_t width, uint32_t height) {
  if (rgb.size() < size_t(width) * height * 3) throw std::invalid_argument("srgb8_to_linear: buffer too small");
  float lut[256];
  for (int i = 0; i < 256; ++i) {
    const float c = float(i) / 255.0f;
    const float l = c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
    lut[i] = std::clamp(l, 0.0f, 1.0f);
  }
  FloatImage img(width, height, 3);
  for (size_t i = 0; i < img.pixels.size(); ++i) img.pixels[i] = lut[rgb[i]];
  return img;
}

FlipResult flip(const FloatImage& reference, const FloatImage& test, const FlipOptions& opt) {
  if (reference.width != test.width || reference.height != test.height)
    throw std::invalid_argument(fmt::format("flip: size mismatch: reference {}x{}, test {}x{}", reference.width,
                                            reference.height, test.width, test.height));
  if (reference.width == 0 || reference.height == 0) throw std::invalid_argument("flip: empty image");
  for (const FloatImage* im : {&reference, &test})
    if (im->channels < 1 || im->channels > 4 || im->pixels.size() != im->pixel_count() * im->channels)
      throw std::invalid_argument("flip: image must have 1-4 channels and matching pixel storage");
  if (!(opt.ppd > 0.0) || !std::isfinite(opt.ppd)) throw std::invalid_argument("flip: ppd must be positive");

  const Kernels k = make_kernels(opt.ppd);
  const float cmax = float(cmax_value());
  FlipResult res;
  res.ppd = opt.ppd;
  res.error_map = FloatImage(reference.width, reference.height, 1, 0.0f);
  RowSource sref, stest;
  sref.img = &reference;
  stest.img = &test;

  const int w = int(reference.width), h = int(reference.height);
  std::vector<float> exposure_scales;  // empty: LDR
  if (opt.mode == FlipOptions::Mode::hdr) {
    const ToneMapper tm = make_tonemapper(opt.tonemapper);
    double start = 0, stop = 0;
    if (!opt.start_exposure || !opt.stop_exposure) {
      // [12] automatic range from the reference's luminance.
      const size_t n = reference.pixel_count();
      std::vector<float> lum(n);
      const uint32_t ch = reference.channels;
      for (size_t i = 0; i < n; ++i) {
        const float* p = reference.pixels.data() + i * ch;
        lum[i] = ch >= 3 ? luminance(p[0], p[1], p[2]) : luminance(p[0], p[0], p[0]);
      }
      const float lmax = *std::max_element(lum.begin(), lum.end());
      std::nth_element(lum.begin(), lum.begin() + std::ptrdiff_t(n / 2), lum.end());
      float lmed = lum[n / 2];
      if (!(lmed > 0.0f)) {
        // More than half the reference is black (a noisy low-spp render, a night scene): the
        // paper's median is 0 and the stop exposure infinite. Use the median of the lit pixels,
        // the exposure at which the image's typical lit pixel maps to mid-grey.
        std::vector<float> lit;
        for (float v : lum)
          if (v > 0.0f) lit.push_back(v);
        if (!lit.empty()) {
          std::nth_element(lit.begin(), lit.begin() + std::ptrdiff_t(lit.size() / 2), lit.end());
          lmed = lit[lit.size() / 2];
        }
      }
      const double xmax = tonemapper_x_max(tm);
      start = std::log2(xmax / double(lmax));
      stop = std::log2(xmax / double(lmed));
    }
    if (opt.start_exposure) start = *opt.start_exposure;
    if (opt.stop_exposure) stop = *opt.stop_exposure;
    if (!std::isfinite(start) || !std::isfinite(stop))
      throw std::invalid_argument(fmt::format("flip: exposure range is not finite (start {}, stop {}): the reference "
                                              "has no positive luminance; set start/stop exposures",
                                              start, stop));
    if (start > stop)
      throw std::invalid_argument(fmt::format("flip: start exposure {} is larger than stop exposure {}", start, stop));
    const int count = opt.num_exposures ? *opt.num_exposures : std::max(2, int(std::ceil(stop - start)));
    if (count < 1) throw std::invalid_argument("flip: num_exposures must be at least 1");
    res.start_exposure = start;
    res.stop_exposure = stop;
    res.num_exposures = count;

    for (RowSource* s : {&sref, &stest}) {
      s->hdr = true;
      s->tm = tm;
      for (int i = 0; i < 6; ++i) s->c[i] = float(tm.c[i]);
    }
    const double step = count > 1 ? (stop - start) / double(count - 1) : 0.0;
    for (int i = 0; i < count; ++i) exposure_scales.push_back(float(std::exp2(start + double(i) * step)));
  }

  // Rows are split into bands, one per thread; every band runs all exposures.
  float* map = res.error_map.pixels.data();
  parallel_rows(h, k.pad, [&](int y0, int y1) {
    BandState st(w, k.pad);
    if (exposure_scales.empty()) {
      flip_band(sref, stest, 1.0f, k, cmax, y0, y1, false, st, map);
    } else {
      for (float scale : exposure_scales) flip_band(sref, stest, scale, k, cmax, y0, y1, true, st, map);
    }
  });
  pool_stats(res);
  return res;
}

}  // namespace gib
