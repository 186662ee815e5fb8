#version 460
#extension GL_GOOGLE_include_directive : require
// deferred_lighting_vrcs for devices without subgroup arithmetic (statistics: one atomic per
// invocation).
#define GIB_LIGHTING_CLASSIFIED 1
#define GIB_LIGHTING_VRCS 1
// The shadow_mapped mode in a scene with a sun: the sun's visibility read from a slot.
#define GIB_LIGHTING_SUN_VISIBILITY 1
#include "renderer/techniques/deferred/deferred_lighting/deferred_lighting.glsl"
