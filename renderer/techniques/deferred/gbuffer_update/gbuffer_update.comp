#version 460
#extension GL_GOOGLE_include_directive : require
// gbuffer_update over the decal tile list (tile_classify's kTileListDecals).
#define GIB_UPDATE_CLASSIFIED 1
#include "renderer/techniques/deferred/gbuffer_update/gbuffer_update.glsl"
