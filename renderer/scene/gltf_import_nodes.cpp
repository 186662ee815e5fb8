// The node tree of a glTF scene: transforms, instances, lights and the camera (Importer,
// gltf_importer.h).
#include <fmt/format.h>

#include <cmath>
#include <string>
#include <vector>

#include "renderer/scene/gltf_importer.h"

namespace gib::gltf {

namespace {

bool is_identity(const Mat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (m.m[c][r] != (c == r ? 1.0f : 0.0f)) return false;
  return true;
}
// parent * local, skipping identities so an untransformed file keeps its matrices bit for bit.
Mat4 compose(const Mat4& parent, const Mat4& local) {
  if (is_identity(parent)) return local;
  if (is_identity(local)) return parent;
  return parent * local;
}

}  // namespace

Mat4 Importer::trs_matrix(Vec3 t, const double q[4], Vec3 s) {
  const double x = q[0], y = q[1], z = q[2], w = q[3];
  const double r[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y + z * w), 2 * (x * z - y * w)},
                          {2 * (x * y - z * w), 1 - 2 * (x * x + z * z), 2 * (y * z + x * w)},
                          {2 * (x * z + y * w), 2 * (y * z - x * w), 1 - 2 * (x * x + y * y)}};  // columns
  Mat4 m = Mat4::translation(t);
  for (int c = 0; c < 3; ++c)
    for (int row = 0; row < 3; ++row) m.m[c][row] = static_cast<float>(r[c][row]) * s[c];
  return m;
}

Mat4 Importer::local_matrix(const tg::Node& n, const std::string& np) {
  auto check = [&](const std::vector<double>& v, size_t len, const char* key) {
    if (!v.empty() && v.size() != len) w_.fail(np + "/" + key, fmt::format("array of {} numbers", len), fmt::format("array of {} numbers", v.size()));
  };
  check(n.matrix, 16, "matrix");
  check(n.translation, 3, "translation");
  check(n.rotation, 4, "rotation");
  check(n.scale, 3, "scale");
  auto num = [&](const char* key, const std::vector<double>& v, size_t i) {
    return w_.number(fmt::format("{}/{}/{}", np, key, i), v[i], -kInf, kInf);
  };
  if (!n.matrix.empty()) {
    if (!n.translation.empty() || !n.rotation.empty() || !n.scale.empty())
      w_.fail(np, "either \"matrix\" or \"translation\"/\"rotation\"/\"scale\"", "both");
    Mat4 r;
    for (size_t i = 0; i < 16; ++i) r.m[i / 4][i % 4] = num("matrix", n.matrix, i);
    if (r.m[0][3] != 0 || r.m[1][3] != 0 || r.m[2][3] != 0 || r.m[3][3] != 1)
      w_.fail(np + "/matrix", "an affine matrix (last row 0, 0, 0, 1)",
              fmt::format("last row {}, {}, {}, {}", r.m[0][3], r.m[1][3], r.m[2][3], r.m[3][3]));
    return r;
  }
  Vec3 t{0, 0, 0}, s{1, 1, 1};
  double q[4] = {0, 0, 0, 1};
  for (int i = 0; i < 3 && !n.translation.empty(); ++i) t[i] = num("translation", n.translation, i);
  for (int i = 0; i < 3 && !n.scale.empty(); ++i) s[i] = num("scale", n.scale, i);
  if (!n.rotation.empty()) {
    double len = 0;
    for (int i = 0; i < 4; ++i) {
      q[i] = num("rotation", n.rotation, static_cast<size_t>(i));
      len += q[i] * q[i];
    }
    len = std::sqrt(len);
    if (!(len > 0)) w_.fail(np + "/rotation", "a unit quaternion", "[0, 0, 0, 0]");
    for (double& c : q) c /= len;
  }
  return trs_matrix(t, q, s);
}

// Depth first, children in order: instances come out in the file's node order.
void Importer::visit_scene(const Mat4& transform) {
  size_t si = 0;
  if (m_.defaultScene != -1) si = w_.index("/scene", m_.defaultScene, m_.scenes.size(), "scene");
  else if (m_.scenes.empty()) w_.fail("/scenes", "a scene to import (\"scene\" or \"scenes\")", "none");
  struct Item { int node; std::string ref; Mat4 parent; };
  std::vector<Item> stack;
  const std::vector<int>& roots = m_.scenes[si].nodes;
  for (size_t k = roots.size(); k-- > 0;) stack.push_back({roots[k], fmt::format("/scenes/{}/nodes/{}", si, k), transform});
  std::vector<char> visited(m_.nodes.size(), 0);
  while (!stack.empty()) {
    Item item = std::move(stack.back());
    stack.pop_back();
    const size_t ni = w_.index(item.ref, item.node, m_.nodes.size(), "node");
    if (visited[ni]) w_.fail(item.ref, "a node not yet in the scene's hierarchy (glTF nodes form trees)", fmt::format("node {} again", ni));
    visited[ni] = 1;
    const tg::Node& n = m_.nodes[ni];
    const std::string np = "/nodes/" + std::to_string(ni);
    const Mat4 world = compose(item.parent, local_matrix(n, np));
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r)
        if (!std::isfinite(world.m[c][r])) w_.fail(np, "a transform that stays finite with its parents'", "an overflowing product");
    if (n.mesh != -1) add_instances(ni, np, world);
    if (n.camera != -1) add_camera(n, np, world);
    if (auto it = n.extensions.find("KHR_lights_punctual"); it != n.extensions.end()) add_light(it->second, np, world);
    for (size_t k = n.children.size(); k-- > 0;) stack.push_back({n.children[k], fmt::format("{}/children/{}", np, k), world});
  }
}

void Importer::add_instances(size_t ni, const std::string& np, const Mat4& world) {
  const tg::Node& n = m_.nodes[ni];
  const size_t mi = w_.index(np + "/mesh", n.mesh, m_.meshes.size(), "mesh");
  const auto& prims = m_.meshes[mi].primitives;
  // extras.gibench_solid (bool): the file vouches that the node's mesh is closed and wound
  // counter-clockwise seen from outside, and nothing is seen from inside it (Instance::solid).
  bool solid = false;
  if (n.extras.IsObject() && n.extras.Has("gibench_solid")) {
    const tg::Value& v = n.extras.Get("gibench_solid");
    if (!v.IsBool()) w_.fail(np + "/extras/gibench_solid", "a boolean", "another type");
    solid = v.Get<bool>();
  }
  for (size_t pj = 0; pj < prims.size(); ++pj) {
    if (prims[pj].mode < TINYGLTF_MODE_TRIANGLES) {  // POINTS, LINES, LINE_LOOP, LINE_STRIP
      skipped_.insert({mi, pj});
      continue;
    }
    Instance inst;
    inst.mesh = mesh_for(mi, pj);
    inst.material = material_for(prims[pj].material, fmt::format("/meshes/{}/primitives/{}/material", mi, pj));
    const Mesh& mesh = scene_.meshes[inst.mesh];
    report_.triangles += mesh.indices.size() / 3;
    report_.vertices += mesh.positions.size();
    if (report_.triangles > kGltfMaxTriangles || report_.vertices > kGltfMaxVertices)
      w_.fail(np + "/mesh", fmt::format("at most {} triangles and {} vertices in all instances", kGltfMaxTriangles, kGltfMaxVertices),
              fmt::format("{} triangles and {} vertices with node {}", report_.triangles, report_.vertices, ni));
    inst.name = opt_.instance_prefix + (n.name.empty() ? "node" + std::to_string(ni) : n.name) +
                (prims.size() > 1 ? "/" + std::to_string(pj) : "");
    inst.transform = world;
    inst.solid = solid;
    scene_.instances.push_back(std::move(inst));
    ++report_.instance_count;
  }
}

Vec3 Importer::axis(const Mat4& world, Vec3 local, const std::string& np, const char* what) {
  const Vec3 a = normalize(world.transform_vector(local));
  if (!finite(a) || !(length(a) > 0)) w_.fail(np, fmt::format("a {} node whose transform keeps its axes", what), "a degenerate transform");
  return a;
}

Vec3 Importer::origin(const Mat4& world, const std::string& np, const char* what) {
  const Vec3 p = world.transform_point({0, 0, 0});
  if (!finite(p)) w_.fail(np, fmt::format("a {} node at a finite position", what), "an overflowing transform");
  return p;
}

void Importer::add_camera(const tg::Node& n, const std::string& np, const Mat4& world) {
  const size_t ci = w_.index(np + "/camera", n.camera, m_.cameras.size(), "camera");
  if (!opt_.take_camera || report_.camera) return;
  const tg::Camera& c = m_.cameras[ci];
  const std::string cp = fmt::format("/cameras/{}/perspective", ci);
  if (c.type != "perspective") {
    report_.notes.push_back(fmt::format("camera {} ({}) ignored: only perspective cameras are imported", ci, c.type));
    return;
  }
  Camera cam;
  const double yfov = c.perspective.yfov;
  if (!(yfov > 0 && yfov < kPi)) w_.fail(cp + "/yfov", "number in (0, pi) radians", fmt::format("{}", yfov));
  cam.fov_y_deg = static_cast<float>(yfov * 180.0 / kPi);
  if (!(cam.fov_y_deg < 180.0f)) w_.fail(cp + "/yfov", "number in (0, pi) radians", fmt::format("{}", yfov));
  if (!(c.perspective.znear > 0)) w_.fail(cp + "/znear", "number > 0", fmt::format("{}", c.perspective.znear));
  cam.near_plane = w_.number(cp + "/znear", c.perspective.znear, 0, kInf);
  if (c.perspective.zfar != 0) {  // tinygltf's 0: absent, an infinite projection; the default far stands
    if (!(c.perspective.zfar > c.perspective.znear))
      w_.fail(cp + "/zfar", fmt::format("number > znear ({})", c.perspective.znear), fmt::format("{}", c.perspective.zfar));
    cam.far_plane = w_.number(cp + "/zfar", c.perspective.zfar, 0, kInf);
  } else if (cam.far_plane <= cam.near_plane) {
    cam.far_plane = cam.near_plane * 1000.0f;
  }
  if (!(cam.far_plane > cam.near_plane) || !std::isfinite(cam.far_plane))  // after rounding to float
    w_.fail(cp + "/zfar", fmt::format("number well above znear ({})", cam.near_plane), fmt::format("{}", cam.far_plane));
  cam.position = origin(world, np, "camera");
  const Vec3 forward = axis(world, {0, 0, -1}, np, "camera");
  cam.target = cam.position + forward * std::fmax(1.0f, length(cam.position));
  const Vec3 up = normalize(world.transform_vector({0, 1, 0}));
  if (finite(up) && length(up) > 0) cam.up = up;
  scene_.camera = cam;
  report_.camera = true;
}

void Importer::add_light(const tg::Value& ext, const std::string& np, const Mat4& world) {
  const std::string ep = np + "/extensions/KHR_lights_punctual";
  if (!ext.IsObject() || !ext.Has("light") || !ext.Get("light").IsInt()) w_.fail(ep + "/light", "a light index", "none");
  const size_t li = w_.index(ep + "/light", ext.Get("light").GetNumberAsInt(), m_.lights.size(), "light");
  const tg::Light& l = m_.lights[li];
  const std::string lp = fmt::format("/extensions/KHR_lights_punctual/lights/{}", li);
  const Vec3 color = l.color.empty() ? Vec3{1, 1, 1} : factors3(l.color, lp + "/color", kInf);
  w_.number(lp + "/intensity", l.intensity, 0, kInf);
  Vec3 value;
  for (int k = 0; k < 3; ++k) value[k] = w_.number(lp + "/intensity", double(color[k]) * l.intensity, 0, kInf);
  if (l.type == "directional") {
    if (!opt_.take_sun) { ++ignored_suns_; return; }
    if (scene_.sun.enabled)
      w_.fail(ep, "at most one directional light in the scene (it has one sun; a \"sun\" in the scene file replaces them)",
              fmt::format("another one (light {})", li));
    scene_.sun = Sun{};
    scene_.sun.enabled = true;
    scene_.sun.direction = axis(world, {0, 0, 1}, np, "light");  // towards the sun: glTF lights shine along -Z
    scene_.sun.irradiance = value;
    report_.sun = true;
    return;
  }
  LocalLight out;
  if (l.type == "spot") out.kind = LightKind::spot;
  else if (l.type != "point") w_.fail(lp + "/type", "one of \"point\", \"spot\", \"directional\"", quoted(l.type));
  out.position = origin(world, np, "light");
  out.intensity = value;
  if (l.range != 0) {  // tinygltf's 0: absent (infinite); LocalLight's default range stands
    if (!(l.range > 0)) w_.fail(lp + "/range", "number > 0", fmt::format("{}", l.range));
    out.range = w_.number(lp + "/range", l.range, 0, kInf);
  }
  if (out.kind == LightKind::spot) {
    const double outer = l.spot.outerConeAngle, inner = l.spot.innerConeAngle;
    if (!(outer > 0 && outer <= kPi / 2)) w_.fail(lp + "/spot/outerConeAngle", "number in (0, pi/2] radians", fmt::format("{}", outer));
    if (!(inner >= 0 && inner <= outer)) w_.fail(lp + "/spot/innerConeAngle", "number in [0, outerConeAngle] radians", fmt::format("{}", inner));
    out.outer_cone_deg = static_cast<float>(outer * 180.0 / kPi);
    out.inner_cone_deg = std::fmin(static_cast<float>(inner * 180.0 / kPi), out.outer_cone_deg);
    out.direction = axis(world, {0, 0, -1}, np, "light");
  }
  scene_.lights.push_back(out);
  ++report_.lights;
}

}  // namespace gib::gltf
