#version 460
#extension GL_GOOGLE_include_directive : require
// deferred_texturing over the pixel lists without subgroup operations, for
// devices without subgroup vote and ballot (one permutation).
#include "renderer/techniques/deferred/deferred_texturing/deferred_texturing.glsl"
