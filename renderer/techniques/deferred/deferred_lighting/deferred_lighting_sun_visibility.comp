#version 460
#extension GL_GOOGLE_include_directive : require
// deferred_lighting over one workload's tile list (spec constant kLightSpecWorkload).
#define GIB_LIGHTING_CLASSIFIED 1
// The shadow_mapped mode in a scene with a sun: the sun's visibility read from a slot.
#define GIB_LIGHTING_SUN_VISIBILITY 1
#include "renderer/techniques/deferred/deferred_lighting/deferred_lighting.glsl"
