#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
// deferred_lighting over one workload's tile list with variable-rate compute shading (vrcs 1).
#define GIB_LIGHTING_CLASSIFIED 1
#define GIB_LIGHTING_VRCS 1
#define GIB_VRCS_SUBGROUP_COUNT 1
// The shadow_mapped mode in a scene with a sun: the sun's visibility read from a slot.
#define GIB_LIGHTING_SUN_VISIBILITY 1
#include "renderer/techniques/deferred/deferred_lighting/deferred_lighting.glsl"
