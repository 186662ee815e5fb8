#version 460
#extension GL_GOOGLE_include_directive : require
// deferred_texturing's sky kernel (classify_materials 1): zero G-buffer texels where the
// vbuffer shows no geometry (those pixels are in no material list).
#define GIB_TEXTURING_SKY 1
#include "renderer/techniques/deferred/deferred_texturing/deferred_texturing.glsl"
