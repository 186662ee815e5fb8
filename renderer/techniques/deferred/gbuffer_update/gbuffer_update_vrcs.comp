#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
// gbuffer_update over the decal tile list with variable-rate compute shading (vrcs 1).
#define GIB_UPDATE_CLASSIFIED 1
#define GIB_UPDATE_VRCS 1
#define GIB_VRCS_SUBGROUP_COUNT 1
#include "renderer/techniques/deferred/gbuffer_update/gbuffer_update.glsl"
