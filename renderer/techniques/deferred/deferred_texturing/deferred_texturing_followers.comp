#version 460
#extension GL_GOOGLE_include_directive : require
// deferred_texturing's VRCS follower kernel (vrcs 1): the pixels a coarse cell's anchor covers
// write their own G-buffer texels with the anchor's albedo.
#define GIB_TEXTURING_FOLLOWERS 1
#include "renderer/techniques/deferred/deferred_texturing/deferred_texturing.glsl"
