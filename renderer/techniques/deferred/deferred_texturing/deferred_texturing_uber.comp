#version 460
#extension GL_GOOGLE_include_directive : require
// deferred_texturing's uber kernel (classify_materials 0): every pixel, the material's shader
// chosen per pixel.
#define GIB_TEXTURING_UBER 1
#include "renderer/techniques/deferred/deferred_texturing/deferred_texturing.glsl"
