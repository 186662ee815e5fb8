#version 460
#extension GL_GOOGLE_include_directive : require
// The same kernel with variable-rate compute shading (vrcs 1).
// deferred_texturing over the pixel lists without subgroup operations, for
// devices without subgroup vote and ballot (one permutation).
#define GIB_TEXTURING_VRCS 1
#include "renderer/techniques/deferred/deferred_texturing/deferred_texturing.glsl"
