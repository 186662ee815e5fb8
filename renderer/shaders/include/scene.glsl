// Scene buffers shared by every pass that reads geometry, materials or the BVH: std430 mirrors
// of GpuVertex / GpuTriangle / GpuInstance / GpuMaterial / GpuLight (renderer/scene/scene.h)
// and GpuBvhNode (renderer/scene/bvh.h).
//
// GIB_SCENE_BUFFERS(set, b) declares, in this binding order (the C++ side binds exactly so):
//   b + 0  gib_vertices       GpuVertex[]     world-space positions, normals, uvs
//   b + 1  gib_triangles      GpuTriangle[]   vertex indices + instance, original order
//   b + 2  gib_instances      GpuInstance[]
//   b + 3  gib_materials      GpuMaterial[]
//   b + 4  gib_bvh_nodes      GpuBvhNode[]    root at 0
//   b + 5  gib_bvh_tri_index  uint[]          leaf slot -> original triangle id
//   b + 6  gib_lights         GpuLight[]
//   b + 30 gib_textures       uint[]          packed image textures (renderer/scene/texture.h)
// All are readonly storage buffers. A pass declares them once, before including bvh.glsl or
// material.glsl's gib_alpha_accept_default.
#ifndef GIB_SCENE_GLSL
#define GIB_SCENE_GLSL

#define GIB_SCENE_BINDING_VERTICES 0
#define GIB_SCENE_BINDING_TRIANGLES 1
#define GIB_SCENE_BINDING_INSTANCES 2
#define GIB_SCENE_BINDING_MATERIALS 3
#define GIB_SCENE_BINDING_BVH_NODES 4
#define GIB_SCENE_BINDING_BVH_TRI_INDEX 5
#define GIB_SCENE_BINDING_LIGHTS 6
#define GIB_SCENE_BINDING_COUNT 7
// The packed image textures (renderer/scene/texture.h), far above the pass bindings that start
// right after the other scene buffers (frame_shared.h kBindSceneTextures = kBindSceneFirst + 30).
#define GIB_SCENE_BINDING_TEXTURES 30

// TextureKind / AlphaKind / LightKind values.
#define GIB_TEXTURE_NONE 0u
#define GIB_TEXTURE_CHECKER 1u
#define GIB_TEXTURE_VALUE_NOISE 2u
#define GIB_TEXTURE_IMAGE 3u
#define GIB_ALPHA_NONE 0u
#define GIB_ALPHA_LEAF_MASK 1u
#define GIB_ALPHA_CHECKER_MASK 2u
#define GIB_ALPHA_OPACITY 3u
#define GIB_ALPHA_TEXTURE_MASK 4u
#define GIB_ALPHA_TEXTURE_OPACITY 5u
#define GIB_LIGHT_POINT 0u
#define GIB_LIGHT_SPOT 1u

struct GpuVertex {  // 32 bytes
  vec3 position;
  float u;
  vec3 normal;
  float v;
};

struct GpuTriangle {  // 16 bytes
  uint i0;
  uint i1;
  uint i2;
  uint instance;
};

struct GpuInstance {  // 16 bytes
  uint material;
  uint first_triangle;
  uint triangle_count;
  uint flags;  // kGibInstanceSolid | kGibInstanceMirrored | kGibInstanceNormalMapped (scene.h kInstance*)
};
const uint kGibInstanceSolid = 1u;
const uint kGibInstanceMirrored = 2u;
const uint kGibInstanceNormalMapped = 4u;

struct GpuMaterial {  // 112 bytes
  vec3 albedo;
  float roughness;
  vec3 emissive;
  float metalness;
  vec3 albedo2;
  float translucency;
  uint texture;  // TextureKind
  uint alpha;    // AlphaKind
  float alpha_cutoff;
  float texture_scale;
  float opacity;
  float sheen;  // cloth: sheen lobe strength; 0: the standard BRDF (brdf.glsl)
  float avg_opacity;  // baked mean alpha coverage (1 without alpha): alpha_strategy.glsl
  float normal_scale;       // glTF normalTexture.scale (normal_map.glsl)
  uint base_color_texture;  // image textures: indices into gib_textures' table, or
  uint emissive_texture;    // GIB_TEXTURE_NO_INDEX (textures.glsl)
  uint metallic_roughness_texture;
  uint normal_texture;      // tangent-space normal map (linear), sampled by gib_surface
  uint brdf;                // GIB_BRDF_GLOSSY: the glossy class (brdf.glsl); else 0
  uint brdf_pad0, brdf_pad1, brdf_pad2;
};

struct GpuLight {  // 64 bytes
  vec3 position;
  uint kind;
  vec3 direction;
  float range;
  vec3 intensity;
  float cos_inner;
  float cos_outer;
  float pad0;
  float pad1;
  float pad2;
};

// count > 0: leaf, triangles gib_bvh_tri_index[left_or_first .. +count).
// count == 0: interior, children left_or_first and left_or_first + 1;
// count == 0 && left_or_first == 0: empty BVH (root only).
struct GpuBvhNode {  // 32 bytes
  vec3 bmin;
  uint left_or_first;
  vec3 bmax;
  uint count;
};

#define GIB_SCENE_BUFFERS(SET, B)                                                              \
  layout(std430, set = SET, binding = (B) + GIB_SCENE_BINDING_VERTICES)                        \
  readonly buffer GibVertexBuffer { GpuVertex gib_vertices[]; };                               \
  layout(std430, set = SET, binding = (B) + GIB_SCENE_BINDING_TRIANGLES)                       \
  readonly buffer GibTriangleBuffer { GpuTriangle gib_triangles[]; };                          \
  layout(std430, set = SET, binding = (B) + GIB_SCENE_BINDING_INSTANCES)                       \
  readonly buffer GibInstanceBuffer { GpuInstance gib_instances[]; };                          \
  layout(std430, set = SET, binding = (B) + GIB_SCENE_BINDING_MATERIALS)                       \
  readonly buffer GibMaterialBuffer { GpuMaterial gib_materials[]; };                          \
  layout(std430, set = SET, binding = (B) + GIB_SCENE_BINDING_BVH_NODES)                       \
  readonly buffer GibBvhNodeBuffer { GpuBvhNode gib_bvh_nodes[]; };                            \
  layout(std430, set = SET, binding = (B) + GIB_SCENE_BINDING_BVH_TRI_INDEX)                   \
  readonly buffer GibBvhTriIndexBuffer { uint gib_bvh_tri_index[]; };                          \
  layout(std430, set = SET, binding = (B) + GIB_SCENE_BINDING_LIGHTS)                          \
  readonly buffer GibLightBuffer { GpuLight gib_lights[]; };                                   \
  layout(std430, set = SET, binding = (B) + GIB_SCENE_BINDING_TEXTURES)                        \
  readonly buffer GibTextureBuffer { uint gib_textures[]; };

#endif  // GIB_SCENE_GLSL
