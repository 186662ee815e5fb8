#version 460
#extension GL_GOOGLE_include_directive : require
// deferred_lighting's uber kernel (tile_classification 0): every pixel, every feature.
// The shadow_mapped mode in a scene with a sun: the sun's visibility read from a slot.
#define GIB_LIGHTING_SUN_VISIBILITY 1
#include "renderer/techniques/deferred/deferred_lighting/deferred_lighting.glsl"
