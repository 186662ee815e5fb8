// Scene model: what a JSON scene file describes, after procedural primitives are expanded
// into triangles. The loader (scene_loader.cpp) fills it; flatten() produces the world-space
// triangle soup every GPU pass and the BVH consume.
#pragma once
#include <array>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "renderer/scene/features.h"
#include "renderer/scene/math.h"
#include "renderer/scene/texture.h"

namespace gib {

// image: the base colour is albedo times the base_color_texture (an image, Scene::textures).
enum class TextureKind : uint32_t { none = 0, checker = 1, value_noise = 2, image = 3 };
// texture_mask: glTF MASK, coverage = opacity (the base colour factor's alpha) times the base
// colour texture's alpha, against alpha_cutoff; texture_opacity: glTF BLEND with a texture, the
// same product as stochastic coverage.
enum class AlphaKind : uint32_t { none = 0, leaf_mask = 1, checker_mask = 2, opacity = 3, texture_mask = 4, texture_opacity = 5 };
// BRDF classes: standard (Lambertian, with thin translucency), cloth (Lambertian plus a
// Charlie sheen lobe) and glossy (a GGX specular layer over a Lambertian base, metalness and
// roughness read); renderer/shaders/include/brdf.glsl, CPU mirror material_eval.h.
enum class BrdfKind : uint32_t { standard = 0, cloth = 1, glossy = 2 };

struct Material {
  std::string name;
  Vec3 albedo{0.8f, 0.8f, 0.8f};
  float roughness = 1.0f;
  float metalness = 0.0f;
  Vec3 emissive{0, 0, 0};        // radiance emitted (linear, W/(sr m^2) in scene units)
  float translucency = 0.0f;     // fraction of diffuse scattering transmitted to the back face
  AlphaKind alpha = AlphaKind::none;
  float alpha_cutoff = 0.5f;     // for masks: texel alpha < cutoff is a miss
  float opacity = 1.0f;          // for AlphaKind::opacity: stochastic coverage
  TextureKind texture = TextureKind::none;
  Vec3 albedo2{0.2f, 0.2f, 0.2f};  // second colour of checker / noise
  float texture_scale = 1.0f;      // pattern repeats per UV unit
  BrdfKind brdf = BrdfKind::standard;
  float sheen = 0.0f;  // cloth: sheen lobe strength (grey), > 0; its roughness is `roughness`
  // Image textures (indices into Scene::textures, -1: none): base colour (sRGB, TextureKind::image
  // and the texture alphas read it), emissive (sRGB, multiplies `emissive`), metallic-roughness
  // (linear; recorded: only the glossy class reads metalness and roughness, the texture is not read),
  // normal (linear, tangent space, glTF's convention: every pass's shading normal, normal_map.h;
  // normal_scale scales its x and y).
  int32_t base_color_texture = -1;
  int32_t emissive_texture = -1;
  int32_t metallic_roughness_texture = -1;
  int32_t normal_texture = -1;
  float normal_scale = 1.0f;
};

// A box-projected decal (the seed's projected decals, blended into the G-buffer albedo): a box
// of `size` centred at `position`, rotated by `rotation_deg` (the objects' Euler convention);
// it projects along its local -z onto surfaces facing its local +z, fading out between 60 and
// 75.5 degrees from that axis. The scene key and its errors: cases/scenes/README.md.
enum class DecalShape : uint32_t { rect = 0, disc = 1 };
struct Decal {
  std::string name;
  Vec3 position{0, 0, 0};
  Vec3 size{1, 1, 1};
  Vec3 rotation_deg{0, 0, 0};
  Vec3 albedo{0.1f, 0.1f, 0.1f};
  float opacity = 1.0f;
  DecalShape shape = DecalShape::disc;
};
inline constexpr uint32_t kMaxDecals = 16;  // glsl::kMaxDecals: the frame constants hold them

// An indoor volume (AC Shadows' "Indoor volumes": interiors the GI keeps apart from the outside):
// an axis-aligned box. probe-volume classifies its probes and the points it lights as indoor
// (inside any volume) or outdoor and blends only probes of the point's class. The scene key and
// its errors: cases/scenes/README.md. No other technique reads it.
struct IndoorVolume {
  std::string name;
  Vec3 min{0, 0, 0}, max{0, 0, 0};
};
inline constexpr uint32_t kMaxIndoorVolumes = 8;  // glsl::kMaxIndoorVolumes: the frame constants hold them

struct Keyframe {
  float time = 0;  // seconds
  Vec3 translation{0, 0, 0};
  Vec3 rotation_deg{0, 0, 0};  // XYZ Euler, applied Z then Y then X (R = Rx*Ry*Rz)
  Vec3 scale{1, 1, 1};
};

struct Mesh {
  std::string name;
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;
  std::vector<Vec2> uvs;
  std::vector<uint32_t> indices;  // 3 per triangle
  // A closed surface wound counter-clockwise seen from outside (cross(b - a, c - a) points out):
  // the primitives box, thin_slab, sphere and the capped cylinder. Open meshes (quads, leaf
  // cards, glTF meshes) are two-sided surfaces with no inside.
  bool closed = false;
};

struct Instance {
  std::string name;
  uint32_t mesh = 0;
  uint32_t material = 0;
  Mat4 transform = Mat4::identity();  // static transform (or base when animated)
  std::vector<Keyframe> animation;    // empty: static; else overrides transform
  // Scene key "solid" (default: true for thin_slab, else false; closed primitives only; glTF:
  // node extras.gibench_solid, the file vouching for a closed mesh wound outwards): nothing is
  // ever seen from inside it, so a ray that meets the back of one of its faces started inside
  // or slipped through an edge (GpuInstance::flags, kInstanceSolid). A box used as a room seen
  // from inside is not solid.
  bool solid = false;
  // Scene key `removed_at` (seconds): from this time on the instance is collapsed to its origin
  // (scale 0: no area, so no raster, no BVH triangle), a step, not a fade. Infinity: never.
  float removed_at = std::numeric_limits<float>::infinity();
  bool removable() const { return removed_at < std::numeric_limits<float>::infinity(); }
  // Its transform can differ between two times (keyframed motion or a removal).
  bool changes() const { return animation.size() > 1 || removable(); }
};

enum class LightKind : uint32_t { point = 0, spot = 1 };
struct LocalLight {
  LightKind kind = LightKind::point;
  Vec3 position{0, 0, 0};
  Vec3 direction{0, -1, 0};  // spot axis (normalised by the loader)
  Vec3 intensity{1, 1, 1};   // W/sr (radiant intensity), falls off with 1/d^2
  float range = 100.0f;      // bound for culling; contribution beyond it is zero
  float inner_cone_deg = 20.0f;
  float outer_cone_deg = 30.0f;
};

// A sun keyframe: a time-of-day change (direction slerped, irradiance linear between keys).
struct SunKey {
  float time = 0;
  Vec3 direction{0, 1, 0};
  Vec3 irradiance{0, 0, 0};
};

struct Sun {
  bool enabled = false;
  Vec3 direction{0, 1, 0};   // towards the sun, normalised
  Vec3 irradiance{0, 0, 0};  // W/m^2 on a surface facing the sun
  float angular_radius_deg = 0.27f;
  std::vector<SunKey> animation;  // empty: static
};

enum class SkyKind : uint32_t { none = 0, constant = 1, gradient = 2, analytic = 3 };
struct Sky {
  SkyKind kind = SkyKind::none;
  Vec3 radiance{0, 0, 0};  // constant; gradient: zenith
  Vec3 horizon{0, 0, 0};   // gradient: horizon; analytic: horizon tint
  Vec3 ground{0, 0, 0};    // radiance below the horizon (gradient/analytic)
  float turbidity = 3.0f;  // analytic only
};

struct CameraKey {
  float time = 0;
  Vec3 position{0, 1, 5};
  Vec3 target{0, 1, 0};
  float fov_y_deg = 60.0f;
};

struct Camera {
  Vec3 position{0, 1, 5};
  Vec3 target{0, 1, 0};
  Vec3 up{0, 1, 0};
  float fov_y_deg = 60.0f;
  float near_plane = 0.05f;
  float far_plane = 1000.0f;
  std::vector<CameraKey> animation;  // empty: static
};

// What one glTF object read from its file and what of the file it ignored, so a user can tell
// why an image differs from their glTF viewer's (`gibench render` prints it with the scene load).
struct SceneImport {
  std::string file;
  std::string read;                  // one line: meshes, instances, triangles, materials, ...
  std::vector<std::string> ignored;  // one line each: content present in the file but not imported
};

struct Scene {
  std::string source;  // file it came from (for messages)
  std::vector<SceneImport> imports;  // the glTF objects' imports, in object order
  std::vector<Material> materials;
  std::vector<Texture> textures;  // image textures (glTF imports), with their mips
  std::vector<Mesh> meshes;
  std::vector<Instance> instances;
  std::vector<LocalLight> lights;
  std::vector<Decal> decals;  // static, world space, applied in order
  std::vector<IndoorVolume> indoor_volumes;  // static, world space
  Sun sun;
  Sky sky;
  Camera camera;
  float frame_time = 1.0f / 60.0f;  // seconds per frame for animation

  SceneFeatures features() const;  // derived, never typed by hand
  Mat4 instance_transform(uint32_t instance, float time) const;
  Camera camera_at(float time) const;  // animation resolved
  Sun sun_at(float time) const;        // animation resolved
  // Anything changes with time: motion (camera, objects) or lighting (sun keys that differ).
  // Cases evaluated at several frames of such a scene get a reference per frame.
  bool lighting_changes() const;
  bool time_varying() const { return features().has(Feature::motion) || lighting_changes(); }
};

// ---- GPU layout (std430), mirrored in renderer/shaders/include/scene.glsl ----
struct GpuVertex {  // 32 bytes
  float px, py, pz, u;
  float nx, ny, nz, v;
};
struct GpuTriangle {  // 16 bytes
  uint32_t i0, i1, i2;
  uint32_t instance;  // index into GpuInstance
};
struct GpuInstance {  // 16 bytes
  uint32_t material;
  uint32_t first_triangle;
  uint32_t triangle_count;
  uint32_t flags;  // kInstanceSolid | kInstanceMirrored | kInstanceNormalMapped
};
// GpuInstance::flags. Solid: Instance::solid (a closed mesh nothing is seen from inside of), so
// the back of one of its triangles is only ever met from inside the solid. Mirrored: its transform has a negative
// determinant, so in world space the winding (and the face normal cross(b - a, c - a)) points
// inwards. NormalMapped: its material has a normal texture, so a surface lookup reads the material
// only for these instances (one dependent load fewer for every other hit).
constexpr uint32_t kInstanceSolid = 1u, kInstanceMirrored = 2u, kInstanceNormalMapped = 4u;
struct GpuMaterial {  // 112 bytes
  float albedo[3];
  float roughness;
  float emissive[3];
  float metalness;
  float albedo2[3];
  float translucency;
  uint32_t texture;  // TextureKind
  uint32_t alpha;    // AlphaKind
  float alpha_cutoff;
  float texture_scale;
  float opacity;
  float sheen;  // cloth's sheen strength; 0: the standard BRDF
  // Baked mean coverage of its alpha mask over the triangles that use it (1 without alpha):
  // the dither and opaque-approximation alpha strategies (alpha_strategy.glsl).
  float avg_opacity;
  float normal_scale;  // glTF normalTexture.scale
  // Image textures (indices into the packed texture buffer, kTextureNone: none).
  uint32_t base_color_texture;
  uint32_t emissive_texture;
  uint32_t metallic_roughness_texture;
  uint32_t normal_texture;  // tangent-space normal map (linear; normal_map.h)
  uint32_t brdf;            // BrdfKind (standard and cloth read as 0: cloth is sheen > 0)
  uint32_t pad[3];
};
struct GpuLight {  // 64 bytes
  float position[3];
  uint32_t kind;
  float direction[3];
  float range;
  float intensity[3];
  float cos_inner;
  float cos_outer;
  float pad[3];
};

// A decal as the frame constants carry it (glsl::GpuDecal in frame_shared.h, 80 bytes): a point
// x is at box coordinates l_i = dot(axis_i.xyz, x - centre.xyz) * axis_i.w in [-0.5, 0.5].
struct GpuDecal {
  float centre[4];  // xyz, w: DecalShape
  float axis_x[4];  // unit local axes in world space, w: 1 / size along it
  float axis_y[4];
  float axis_z[4];  // the surfaces it colours face +axis_z
  float albedo[4];  // rgb, a: opacity
};

// World-space triangle soup at a given time: what the BVH and the passes consume.
// Normals are unit, zero (a zero input normal, a mesh without normals, or a collapsed instance:
// shading uses the face normal) or NaN (a non-finite input normal, passed on unrepaired: the
// GPU's guard, Settings::nan_guards, is what repairs it, and what the degenerate-geometry case
// tests).
struct FlatScene {
  std::vector<GpuVertex> vertices;
  std::vector<GpuTriangle> triangles;
  std::vector<GpuInstance> instances;
  std::vector<GpuMaterial> materials;
  std::vector<GpuLight> lights;
  std::vector<GpuDecal> decals;
  std::vector<IndoorVolume> indoor_volumes;  // world_offset applied
  std::vector<uint32_t> textures;  // pack_textures(scene.textures): the tables and every texel
};
// world_offset translates every position (vertices and lights) after the instance transform:
// the far-from-origin stress cases move the whole scene (Settings::world_offset), the camera
// with it (Executor), so the image is unchanged in exact arithmetic. average_opacity: the
// materials' bake_average_opacity(scene) (material_eval.h), which depends on no time, for a
// caller that flattens every frame (an animated scene) and keeps it; null: baked here.
FlatScene flatten(const Scene& scene, float time, Vec3 world_offset = {},
                  const std::vector<float>* average_opacity = nullptr);
// A material as the GPU reads it (avg_opacity left at 1: flatten bakes it, material_eval.h).
GpuMaterial material_to_gpu(const Material& m);

}  // namespace gib
