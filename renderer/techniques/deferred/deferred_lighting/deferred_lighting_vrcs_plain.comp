#version 460
#extension GL_GOOGLE_include_directive : require
// deferred_lighting_vrcs for devices without subgroup arithmetic (statistics: one atomic per
// invocation).
#define GIB_LIGHTING_CLASSIFIED 1
#define GIB_LIGHTING_VRCS 1
#include "renderer/techniques/deferred/deferred_lighting/deferred_lighting.glsl"
