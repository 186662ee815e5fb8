#version 460
#extension GL_GOOGLE_include_directive : require
// The same kernel with variable-rate compute shading (vrcs 1).
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_KHR_shader_subgroup_ballot : require
#extension GL_KHR_shader_subgroup_arithmetic : require
// deferred_texturing with the uniform-data / divergent permutations (subgroup vote + ballot).
#define GIB_TEXTURING_SUBGROUPS 1
#define GIB_TEXTURING_VRCS 1
#define GIB_VRCS_SUBGROUP_COUNT 1
#include "renderer/techniques/deferred/deferred_texturing/deferred_texturing.glsl"
