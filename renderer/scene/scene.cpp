#include "renderer/scene/scene.h"

#include "renderer/scene/material_eval.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace gib {

namespace {

bool any_positive(Vec3 v) { return v.x > 0 || v.y > 0 || v.z > 0; }

Vec3 lerp(Vec3 a, Vec3 b, float t) { return a + (b - a) * t; }

// Keys are sorted by time (the loader enforces strictly increasing times). Returns the pair
// of keys around `time` and the blend weight, clamped at both ends.
template <typename Key>
void bracket(const std::vector<Key>& keys, float time, size_t& i0, size_t& i1, float& w) {
  // Written as !(time > front) so a NaN time resolves to the first key instead of indexing past the end.
  if (!(time > keys.front().time) || keys.size() == 1) { i0 = i1 = 0; w = 0; return; }
  if (time >= keys.back().time) { i0 = i1 = keys.size() - 1; w = 0; return; }
  auto it = std::upper_bound(keys.begin(), keys.end(), time,
                             [](float t, const Key& k) { return t < k.time; });
  i1 = static_cast<size_t>(it - keys.begin());
  i0 = i1 - 1;
  float span = keys[i1].time - keys[i0].time;
  w = span > 0 ? (time - keys[i0].time) / span : 0.0f;
}

// The keys around `time` and the weight of the second: false for an empty animation.
template <class Key>
bool keys_at(const std::vector<Key>& keys, float time, const Key*& a, const Key*& b, float& w) {
  if (keys.empty()) return false;
  size_t i0, i1;
  bracket(keys, time, i0, i1, w);
  a = &keys[i0];
  b = &keys[i1];
  return true;
}

// Upper-left 3x3 cofactor matrix times sign(det) == det-scaled inverse-transpose with the
// right orientation. Unlike inverse().transpose() it stays finite for zero scale, so a
// collapsed instance gets (renormalised or zero) normals instead of NaN.
struct NormalMatrix {
  Vec3 c0, c1, c2;  // columns
  bool mirrored = false;  // negative determinant: the transform flips winding
  explicit NormalMatrix(const Mat4& m) {
    Vec3 a{m.m[0][0], m.m[0][1], m.m[0][2]};
    Vec3 b{m.m[1][0], m.m[1][1], m.m[1][2]};
    Vec3 c{m.m[2][0], m.m[2][1], m.m[2][2]};
    float det = dot(a, cross(b, c));
    mirrored = det < 0;
    float sign = mirrored ? -1.0f : 1.0f;
    c0 = cross(b, c) * sign;
    c1 = cross(c, a) * sign;
    c2 = cross(a, b) * sign;
  }
  Vec3 apply(Vec3 n) const { return normalize(c0 * n.x + c1 * n.y + c2 * n.z); }
};

GpuDecal to_gpu(const Decal& d, Vec3 world_offset) {
  const Mat4 r = Mat4::trs({0, 0, 0}, d.rotation_deg, {1, 1, 1});
  GpuDecal g{};
  const Vec3 c = d.position + world_offset;
  g.centre[0] = c.x; g.centre[1] = c.y; g.centre[2] = c.z;
  g.centre[3] = float(static_cast<uint32_t>(d.shape));
  float* axes[3] = {g.axis_x, g.axis_y, g.axis_z};
  const Vec3 local[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (int i = 0; i < 3; ++i) {
    const Vec3 a = normalize(r.transform_point(local[i]));  // r has no translation
    axes[i][0] = a.x; axes[i][1] = a.y; axes[i][2] = a.z;
    axes[i][3] = 1.0f / d.size[i];
  }
  g.albedo[0] = d.albedo.x; g.albedo[1] = d.albedo.y; g.albedo[2] = d.albedo.z;
  g.albedo[3] = d.opacity;
  return g;
}

GpuLight to_gpu(const LocalLight& l) {
  constexpr float kDegToRad = std::numbers::pi_v<float> / 180.0f;
  GpuLight g{};
  g.position[0] = l.position.x; g.position[1] = l.position.y; g.position[2] = l.position.z;
  g.kind = static_cast<uint32_t>(l.kind);
  Vec3 d = normalize(l.direction);
  g.direction[0] = d.x; g.direction[1] = d.y; g.direction[2] = d.z;
  g.range = l.range;
  g.intensity[0] = l.intensity.x; g.intensity[1] = l.intensity.y; g.intensity[2] = l.intensity.z;
  // Cone angles are half angles from the axis; shaders compare cos(angle to axis) directly.
  g.cos_inner = std::cos(l.inner_cone_deg * kDegToRad);
  g.cos_outer = std::cos(l.outer_cone_deg * kDegToRad);
  return g;
}

}  // namespace

GpuMaterial material_to_gpu(const Material& m) {
  GpuMaterial g{};
  g.albedo[0] = m.albedo.x; g.albedo[1] = m.albedo.y; g.albedo[2] = m.albedo.z;
  g.roughness = m.roughness;
  g.emissive[0] = m.emissive.x; g.emissive[1] = m.emissive.y; g.emissive[2] = m.emissive.z;
  g.metalness = m.metalness;
  g.albedo2[0] = m.albedo2.x; g.albedo2[1] = m.albedo2.y; g.albedo2[2] = m.albedo2.z;
  g.translucency = m.translucency;
  g.texture = static_cast<uint32_t>(m.texture);
  g.alpha = static_cast<uint32_t>(m.alpha);
  g.alpha_cutoff = m.alpha_cutoff;
  g.texture_scale = m.texture_scale;
  g.opacity = m.opacity;
  g.sheen = m.brdf == BrdfKind::cloth ? m.sheen : 0.0f;
  g.avg_opacity = 1.0f;
  auto index = [](int32_t t) { return t < 0 ? kTextureNone : uint32_t(t); };
  g.base_color_texture = index(m.base_color_texture);
  g.emissive_texture = index(m.emissive_texture);
  g.metallic_roughness_texture = index(m.metallic_roughness_texture);
  g.normal_texture = index(m.normal_texture);
  g.normal_scale = m.normal_scale;
  g.brdf = m.brdf == BrdfKind::glossy ? uint32_t(BrdfKind::glossy) : 0u;
  return g;
}

SceneFeatures Scene::features() const {
  SceneFeatures f;
  const bool sun_keys_lit = std::any_of(sun.animation.begin(), sun.animation.end(),
                                        [](const SunKey& k) { return any_positive(k.irradiance); });
  if (sun.enabled && (any_positive(sun.irradiance) || sun_keys_lit)) f |= Feature::sun;
  bool sky_lit = sky.kind == SkyKind::constant
                     ? any_positive(sky.radiance)
                     : any_positive(sky.radiance) || any_positive(sky.horizon) || any_positive(sky.ground);
  if (sky.kind != SkyKind::none && sky_lit) f |= Feature::sky;
  if (!lights.empty()) f |= Feature::local_lights;

  // Only materials some instance uses count: an unused emissive material in the library
  // must not keep the emissive passes alive.
  std::vector<bool> used(materials.size(), false);
  for (const Instance& inst : instances)
    if (inst.material < used.size()) used[inst.material] = true;
  for (size_t i = 0; i < materials.size(); ++i) {
    if (!used[i]) continue;
    const Material& m = materials[i];
    if (any_positive(m.emissive)) f |= Feature::emissive;
    if (m.alpha != AlphaKind::none) f |= Feature::alpha_tested;
    if (m.translucency > 0) f |= Feature::translucent;
    if (m.texture != TextureKind::none || m.base_color_texture >= 0 || m.emissive_texture >= 0 ||
        m.metallic_roughness_texture >= 0 || m.normal_texture >= 0)
      f |= Feature::textured;
    if (m.brdf == BrdfKind::cloth && m.sheen > 0) f |= Feature::cloth;
    if (m.brdf == BrdfKind::glossy) f |= Feature::glossy;
  }
  if (std::any_of(decals.begin(), decals.end(), [](const Decal& d) { return d.opacity > 0; })) f |= Feature::decals;
  if (!indoor_volumes.empty()) f |= Feature::indoor_volumes;

  bool camera_moves = false;
  for (size_t i = 1; i < camera.animation.size() && !camera_moves; ++i) {
    const CameraKey& a = camera.animation[0];
    const CameraKey& b = camera.animation[i];
    camera_moves = !(a.position == b.position) || !(a.target == b.target) || a.fov_y_deg != b.fov_y_deg;
  }
  bool object_moves = std::any_of(instances.begin(), instances.end(),
                                  [](const Instance& inst) { return inst.changes(); });
  if (camera_moves || object_moves) f |= Feature::motion;
  return f;
}

namespace {
// The keyframed (or static) transform of one instance, removal aside.
Mat4 keyed_transform(const Instance& inst, float time) {
  if (inst.animation.empty()) return inst.transform;
  size_t i0, i1;
  float w;
  bracket(inst.animation, time, i0, i1, w);
  const Keyframe& a = inst.animation[i0];
  const Keyframe& b = inst.animation[i1];
  // Euler angles are interpolated per component: keys are authored close enough together
  // that this matches what the scene author means, and it allows spins past 180 degrees.
  return Mat4::trs(lerp(a.translation, b.translation, w), lerp(a.rotation_deg, b.rotation_deg, w),
                   lerp(a.scale, b.scale, w));
}
}  // namespace

Mat4 Scene::instance_transform(uint32_t instance, float time) const {
  if (instance >= instances.size())
    throw std::out_of_range("instance_transform: instance " + std::to_string(instance) + " of " +
                            std::to_string(instances.size()));
  const Instance& inst = instances[instance];
  // Removed (`removed_at`): the transform at the removal time squeezed to the instance's origin,
  // finite, every triangle of zero area.
  if (time >= inst.removed_at) return keyed_transform(inst, inst.removed_at) * Mat4::scaling({0, 0, 0});
  return keyed_transform(inst, time);
}

Camera Scene::camera_at(float time) const {
  Camera c = camera;
  c.animation.clear();
  const CameraKey *a, *b;
  float w;
  if (!keys_at(camera.animation, time, a, b, w)) return c;
  c.position = lerp(a->position, b->position, w);
  c.target = lerp(a->target, b->target, w);
  c.fov_y_deg = a->fov_y_deg + (b->fov_y_deg - a->fov_y_deg) * w;
  return c;
}

Sun Scene::sun_at(float time) const {
  Sun s = sun;
  s.animation.clear();
  const SunKey *k0, *k1;
  float w;
  if (!keys_at(sun.animation, time, k0, k1, w)) return s;
  const SunKey& a = *k0;
  const SunKey& b = *k1;
  // Directions turn at a constant rate between keys (slerp); nearly equal ones lerp, and keys
  // pointing opposite ways (no defined arc) are refused by the loader.
  const float c = std::clamp(dot(a.direction, b.direction), -1.0f, 1.0f);
  const float angle = std::acos(c);
  if (angle < 1e-4f) {
    s.direction = normalize(lerp(a.direction, b.direction, w));
  } else {
    const float sa = std::sin(angle);
    s.direction = normalize(a.direction * (std::sin((1.0f - w) * angle) / sa) + b.direction * (std::sin(w * angle) / sa));
  }
  s.irradiance = lerp(a.irradiance, b.irradiance, w);
  return s;
}

bool Scene::lighting_changes() const {
  for (size_t i = 1; i < sun.animation.size(); ++i)
    if (!(sun.animation[i].direction == sun.animation[0].direction) ||
        !(sun.animation[i].irradiance == sun.animation[0].irradiance))
      return sun.enabled;
  return false;
}

FlatScene flatten(const Scene& scene, float time, Vec3 world_offset, const std::vector<float>* average_opacity) {
  FlatScene out;
  size_t vertex_total = 0, triangle_total = 0;
  for (const Instance& inst : scene.instances) {
    if (inst.mesh >= scene.meshes.size())
      throw std::out_of_range("flatten: instance '" + inst.name + "' uses mesh " + std::to_string(inst.mesh) +
                              " of " + std::to_string(scene.meshes.size()));
    if (inst.material >= scene.materials.size())
      throw std::out_of_range("flatten: instance '" + inst.name + "' uses material " +
                              std::to_string(inst.material) + " of " + std::to_string(scene.materials.size()));
    vertex_total += scene.meshes[inst.mesh].positions.size();
    triangle_total += scene.meshes[inst.mesh].indices.size() / 3;
  }
  out.vertices.reserve(vertex_total);
  out.triangles.reserve(triangle_total);
  out.instances.reserve(scene.instances.size());

  for (uint32_t i = 0; i < scene.instances.size(); ++i) {
    const Instance& inst = scene.instances[i];
    const Mesh& mesh = scene.meshes[inst.mesh];
    Mat4 m = scene.instance_transform(i, time);
    NormalMatrix nm(m);
    uint32_t base = static_cast<uint32_t>(out.vertices.size());
    for (size_t v = 0; v < mesh.positions.size(); ++v) {
      Vec3 p = m.transform_point(mesh.positions[v]) + world_offset;
      Vec3 n = v < mesh.normals.size() ? mesh.normals[v] : Vec3{};
      // A non-finite input normal stays NaN (normalize() would turn it into a zero normal and
      // hide it from the GPU guard the degenerate-geometry case tests).
      const bool finite_n = std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z);
      constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
      n = finite_n ? nm.apply(n) : Vec3{kNaN, kNaN, kNaN};
      Vec2 uv = v < mesh.uvs.size() ? mesh.uvs[v] : Vec2{};
      out.vertices.push_back({p.x, p.y, p.z, uv.x, n.x, n.y, n.z, uv.y});
    }
    GpuInstance gi{};
    gi.material = inst.material;
    gi.first_triangle = static_cast<uint32_t>(out.triangles.size());
    size_t tri_count = mesh.indices.size() / 3;
    for (size_t t = 0; t < tri_count; ++t) {
      uint32_t a = mesh.indices[3 * t], b = mesh.indices[3 * t + 1], c = mesh.indices[3 * t + 2];
      if (a >= mesh.positions.size() || b >= mesh.positions.size() || c >= mesh.positions.size())
        throw std::out_of_range("flatten: mesh '" + mesh.name + "' triangle " + std::to_string(t) +
                                " indexes past its " + std::to_string(mesh.positions.size()) + " vertices");
      // Degenerate triangles are kept on purpose: stress cases feed them to the BVH.
      out.triangles.push_back({base + a, base + b, base + c, i});
    }
    gi.triangle_count = static_cast<uint32_t>(tri_count);
    if (inst.solid) gi.flags = kInstanceSolid | (nm.mirrored ? kInstanceMirrored : 0u);
    out.instances.push_back(gi);
  }

  out.materials.reserve(scene.materials.size());
  for (const Material& m : scene.materials) out.materials.push_back(material_to_gpu(m));
  for (GpuInstance& gi : out.instances)
    if (gi.material < out.materials.size() && out.materials[gi.material].normal_texture != kTextureNone)
      gi.flags |= kInstanceNormalMapped;
  const std::vector<float> opacity = average_opacity ? *average_opacity : bake_average_opacity(scene);
  for (size_t i = 0; i < out.materials.size() && i < opacity.size(); ++i) out.materials[i].avg_opacity = opacity[i];
  out.lights.reserve(scene.lights.size());
  for (const LocalLight& l : scene.lights) {
    GpuLight g = to_gpu(l);
    for (int k = 0; k < 3; ++k) g.position[k] += world_offset[k];
    out.lights.push_back(g);
  }
  for (const Decal& d : scene.decals) out.decals.push_back(to_gpu(d, world_offset));
  out.textures = pack_textures(scene.textures);
  for (IndoorVolume v : scene.indoor_volumes) {
    v.min = v.min + world_offset;
    v.max = v.max + world_offset;
    out.indoor_volumes.push_back(v);
  }
  return out;
}

}  // namespace gib
