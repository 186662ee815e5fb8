#version 460
#extension GL_GOOGLE_include_directive : require
// material_classify's count kernel, one atomic per pixel (devices without subgroup ballot).
#include "renderer/techniques/deferred/material_classify/material_classify_count.glsl"
