// probe_classify: indoor / outdoor class of each selected probe (see probe_classify.h).
#version 460
#extension GL_GOOGLE_include_directive : require
#include "renderer/techniques/probe_volume/probe_classify/probe_classify_shared.h"
#include "frame.glsl"
layout(push_constant) uniform Push { PvParams pv; };
#include "renderer/techniques/probe_volume/include/pv_common.glsl"
PV_STATE_BUFFER(kPvClassifyBindState, )
layout(std430, set = 0, binding = kPvClassifyBindSelection) readonly buffer SelectionBuffer {
  PvSelection sel;
  uint pv_entries[];
};
layout(local_size_x = kPvClassifyGroup) in;

void main() {
  uint e = gl_GlobalInvocationID.x;
  if (e >= sel.all_args.x) return;
  uint probe = pv_entries[e];
  PvProbe p = pv_probes[probe];
  uint f = uint(p.coord.w);
  // Where it will be traced and lit from: a pending relocation applies at this frame's trace.
  vec3 offset = (f & kPvProbeRetrace) != 0u ? p.pending.xyz : p.offset.xyz;
  vec3 x = pv_cell_position(pv_cascade_of(probe), p.coord.xyz) + offset;
  f = pv_point_indoor(x, vec3(0.0)) ? (f | kPvProbeIndoor) : (f & ~kPvProbeIndoor);
  pv_probes[probe].coord.w = int(f);
}
