#version 460
#extension GL_GOOGLE_include_directive : require
#include "renderer/techniques/deferred/tile_classify/tile_classify_mask.glsl"
