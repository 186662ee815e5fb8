// probe_trace: traces the rays of every probe of one irradiance-volume cascade (seed
// the idTech 8 "Global Illumination" talk, "Sampling the World": interleaved updates,
// one cascade per frame, each probe traces N visibility rays from its cell centre, a 128-bit
// hit record per ray). Cascade frame % cascades; its 16^3 probes (geometry in
// renderer/techniques/radiance_cache/include/probe_volume.glsl) each trace rays_per_probe rays in spherical
// Fibonacci directions rotated by a random rotation hashed from the frame (rc_ray_direction, the
// same for every probe), closest hit with alpha testing, up to kProbeMissDistance (10 km).
// Each hit then triggers its cache update, as the seed's trace does: insertion round 0, the
// find (include/rc_insert.glsl, radiance_cache_update.h): the hit's key is searched in the world
// radiance cache; a key found is placed and its cell queued for shading (rc_active, the shade's
// indirect args), a new key bids for its first slot and joins round 1's pending list, a key whose
// slots are all taken is dropped. rc_counters has two copies (ping-pong): a frame counts into
// one while its first workgroup zeroes the other for the next frame (no fill, no barrier).
// Option insertion_find 1 moves the find to a dispatch of radiance_cache_update over every hit
// record (the former layout): the same table and counters.
// Slots: reads the scene and BVH; writes `probe_hits` (buffer, 16^3 x rays_per_probe ProbeHit,
// probe-major: record probe * rays + ray; radiance_cache_shared.h), and creates the insertion's
// buffers: rc_cells (persistent, read_write, 2^cache_log2_cells x 16 bytes), rc_active (16^3 x
// max(64, rays_per_probe) uint), rc_counters (persistent ping-pong, 32 bytes + 16 per round),
// rc_pending (two lists of 16^3 x rays_per_probe (hit id, key)).
// Needs compute subgroup ballot and arithmetic operations (a clear error without them).
// Limits: no probe relocation (DDGI's); a probe inside geometry is found by its rays
// (rc_probe_ray_inside) and left unused (irradiance_volume_update). rays_per_probe must be
// 1..256 (declare() throws otherwise). The hit record holds triangle + 1, the hit's cache-cell
// key (0 on a miss or a ray inside geometry), unorm16 barycentrics and distance (the seed packs
// an SBT index; we have one material model): the key is made here, where the hit is found, so
// the insertion and irradiance_volume_update read it instead of fetching the triangle again.
#pragma once
#include <memory>

#include "renderer/graph/pass.h"

namespace gib {
std::unique_ptr<Pass> make_probe_trace_pass();
}
