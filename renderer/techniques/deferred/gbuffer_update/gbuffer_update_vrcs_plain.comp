#version 460
#extension GL_GOOGLE_include_directive : require
// gbuffer_update_vrcs for devices without subgroup arithmetic (statistics: one atomic per
// invocation).
#define GIB_UPDATE_CLASSIFIED 1
#define GIB_UPDATE_VRCS 1
#include "renderer/techniques/deferred/gbuffer_update/gbuffer_update.glsl"
