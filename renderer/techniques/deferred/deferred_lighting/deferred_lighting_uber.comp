#version 460
#extension GL_GOOGLE_include_directive : require
// deferred_lighting's uber kernel (tile_classification 0): every pixel, every feature.
#include "renderer/techniques/deferred/deferred_lighting/deferred_lighting.glsl"
