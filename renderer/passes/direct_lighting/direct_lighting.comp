#version 460
#extension GL_GOOGLE_include_directive : require
#include "renderer/passes/direct_lighting/direct_lighting_main.glsl"
