#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_ballot : require
// material_classify's count kernel, one atomic per (tile, material) and subgroup.
#define GIB_COUNT_SUBGROUPS 1
#include "renderer/techniques/deferred/material_classify/material_classify_count.glsl"
