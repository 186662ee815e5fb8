// path_trace: the `reference` technique's progressive, unbiased path tracer. Per sample: a
// jittered camera ray; at each vertex, emission (emissive surfaces are found by BSDF
// sampling only), next-event estimation towards the sun (cone of its angular radius) and every
// local light with a shadow ray, then a cosine-sampled continuation (reflection, or diffuse
// transmission through the back face with probability = translucency). The sky is reached by
// the continuation rays (cosine sampling is its importance sampling for diffuse surfaces), so an
// albedo-1 scene under a uniform sky returns exactly the sky radiance (white furnace). Russian
// roulette from the fourth vertex on, survival = max throughput (albedo-1 paths never die).
// Alpha-tested surfaces are tested for real at every candidate hit (any-hit in traversal).
// Seeded from (seed, sample index, pixel): the same command gives the same image.
// Glossy materials (BrdfKind::glossy, brdf.glsl): NEE evaluates both lobes; the continuation
// picks the GGX lobe (visible-normal sampling) with probability p_spec (the lobes' luminance
// weights at the view angle), else the cosine lobe, and weighs f cos by the mixture's density
// p_spec pdf_ggx + (1 - p_spec) pdf_cos (one-sample MIS, balance heuristic). A direction below
// the shading hemisphere ends the path (masked: single-scattering GGX loses that energy).
// AOVs: radiance; direct = emission seen + light arriving at the first hit straight from
// sun, sky and local lights; indirect_diffuse = the rest (light that bounced at least once),
// reflected at the first hit (albedo included). Sky pixels count as direct. reflection = what
// the first hit's specular lobe reflects along its sampled rays (aov.h): a second throughput
// carries the specular share f_spec cos / pdf of the first hit's continuation.
// Slots: read_write pt_radiance_sum, pt_direct_sum, pt_indirect_sum, pt_reflection_sum
// (persistent, rgba32f).
// Seed: none (the ground truth; docs/architecture.md "Techniques").
// Limits: Lambertian and glossy BRDFs (no transmission through glossy surfaces); no MIS between
// light sampling and BSDF sampling, since no light is sampled by both (the sun and local lights
// by NEE only, the sky and emissive surfaces by the continuation only), so a near-mirror's
// reflection of the small sun is NEE-sampled and noisy. Option glossy_masking 0 (a control)
// drops the specular lobe's Smith masking.
// NaN guard (Settings::nan_guards): a sample with a non-finite contribution is neither added nor
// counted. Debug: inject_nan 3 makes the first sample of pixel (inject_x, inject_y) NaN on frame
// inject_frame.
#pragma once
#include <memory>

#include "renderer/graph/pass.h"

namespace gib {
std::unique_ptr<Pass> make_path_trace_pass();
}
