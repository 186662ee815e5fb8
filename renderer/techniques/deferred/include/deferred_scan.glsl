// Workgroup-wide exclusive prefix sums in gl_LocalInvocationIndex order, over one value or three
// per invocation, for kernels whose workgroup is GIB_SCAN_SIZE invocations (a multiple of
// kGibScanChunk). Deterministic: integer sums, no atomics, no subgroup operations (Vulkan does
// not tie subgroups to gl_LocalInvocationIndex).
// Two levels, three barriers: every value goes to shared memory; one invocation per chunk of
// kGibScanChunk sums its chunk; each invocation then adds the chunks before its own and the
// values before it in its chunk. A log-step scan over 256 values takes 17 barriers.
// Usage: #define GIB_SCAN_SIZE 256 (and GIB_SCAN_UVEC2 / GIB_SCAN_UVEC3 for the two- and
// three-value scans) before including; call from uniform control flow.
#ifndef GIB_DEFERRED_SCAN_GLSL
#define GIB_DEFERRED_SCAN_GLSL
const uint kGibScanChunk = 16u;
const uint kGibScanChunks = GIB_SCAN_SIZE / kGibScanChunk;

// Defines `T NAME(T v, out T total)` over shared arrays of T: the sum of v over invocations
// before this one, and in *total the sum over all.
#define GIB_DEFINE_WORKGROUP_SCAN(T, NAME)                                        \
  shared T NAME##_values[GIB_SCAN_SIZE];                                          \
  shared T NAME##_chunks[kGibScanChunks];                                         \
  T NAME(T v, out T total) {                                                      \
    uint i = gl_LocalInvocationIndex;                                             \
    NAME##_values[i] = v;                                                         \
    barrier();                                                                    \
    if (i < kGibScanChunks) {                                                     \
      T s = T(0u);                                                                \
      for (uint k = 0u; k < kGibScanChunk; ++k) s += NAME##_values[i * kGibScanChunk + k]; \
      NAME##_chunks[i] = s;                                                       \
    }                                                                             \
    barrier();                                                                    \
    uint c = i / kGibScanChunk;                                                   \
    T before = T(0u), sum = T(0u);                                                \
    for (uint k = 0u; k < kGibScanChunks; ++k) {                                  \
      T s = NAME##_chunks[k];                                                     \
      sum += s;                                                                   \
      if (k < c) before += s;                                                     \
    }                                                                             \
    for (uint k = c * kGibScanChunk; k < i; ++k) before += NAME##_values[k];      \
    total = sum;                                                                  \
    barrier(); /* the next call overwrites the arrays */                          \
    return before;                                                                \
  }

GIB_DEFINE_WORKGROUP_SCAN(uint, gib_workgroup_exclusive_scan)
#ifdef GIB_SCAN_UVEC2
GIB_DEFINE_WORKGROUP_SCAN(uvec2, gib_workgroup_exclusive_scan2)
#endif
#ifdef GIB_SCAN_UVEC3
GIB_DEFINE_WORKGROUP_SCAN(uvec3, gib_workgroup_exclusive_scan3)
#endif
#endif
