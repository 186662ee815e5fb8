#version 460
#extension GL_GOOGLE_include_directive : require
// gbuffer_update's uber kernel (tile_classification 0): every pixel.
#include "renderer/techniques/deferred/gbuffer_update/gbuffer_update.glsl"
