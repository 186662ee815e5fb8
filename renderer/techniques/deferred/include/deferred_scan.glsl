// Workgroup-wide exclusive prefix sum over one value per invocation, for kernels whose
// workgroup is GIB_SCAN_SIZE invocations (a power of two). Deterministic: no atomics.
// Usage: #define GIB_SCAN_SIZE 256 before including; call from uniform control flow.
#ifndef GIB_DEFERRED_SCAN_GLSL
#define GIB_DEFERRED_SCAN_GLSL
shared uint gib_scan_buf[GIB_SCAN_SIZE];

// Returns the sum of v over invocations before this one; *total the sum over all.
uint gib_workgroup_exclusive_scan(uint v, out uint total) {
  uint i = gl_LocalInvocationIndex;
  gib_scan_buf[i] = v;
  barrier();
  for (uint off = 1u; off < GIB_SCAN_SIZE; off <<= 1u) {
    uint add = i >= off ? gib_scan_buf[i - off] : 0u;
    barrier();
    gib_scan_buf[i] += add;
    barrier();
  }
  uint inclusive = gib_scan_buf[i];
  total = gib_scan_buf[GIB_SCAN_SIZE - 1u];
  barrier();
  return inclusive - v;
}
#endif
