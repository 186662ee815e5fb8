#include "renderer/graph/executor.h"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <cstring>

#include "renderer/scene/bvh.h"
#include "renderer/shaders/include/frame_shared.h"

namespace gib {

// ---------------------------------------------------------------- RecordContext
const ResolvedSlot& RecordContext::slot(const std::string& name) const {
  auto it = slots_.find(name);
  if (it == slots_.end())
    throw GraphError(fmt::format("pass '{}' touched resource '{}' it did not declare", pass_, name));
  return it->second;
}
const Image& RecordContext::image(const std::string& name) const {
  auto& s = slot(name);
  if (!s.image) throw GraphError(fmt::format("pass '{}': resource '{}' is not an image", pass_, name));
  return *s.image;
}
const Image& RecordContext::prev_image(const std::string& name) const {
  auto& s = slot(name);
  if (!s.prev_image) throw GraphError(fmt::format("pass '{}': resource '{}' has no last-frame image", pass_, name));
  return *s.prev_image;
}
const Buffer& RecordContext::buffer(const std::string& name) const {
  auto& s = slot(name);
  if (!s.buffer) throw GraphError(fmt::format("pass '{}': resource '{}' is not a buffer", pass_, name));
  return *s.buffer;
}
const Buffer& RecordContext::prev_buffer(const std::string& name) const {
  auto& s = slot(name);
  if (!s.prev_buffer) throw GraphError(fmt::format("pass '{}': resource '{}' has no last-frame buffer", pass_, name));
  return *s.prev_buffer;
}

std::vector<Bind> SceneGpu::binds() const {
  std::vector<Bind> b;
  b.push_back({glsl::kBindFrame, frame.get(), nullptr});
  for (uint32_t i = 0; i < buffers.size(); ++i) b.push_back({glsl::kBindSceneFirst + i, buffers[i].get(), nullptr});
  return b;
}

std::vector<BindingDecl> scene_bindings() {
  std::vector<BindingDecl> b{{glsl::kBindFrame, DescriptorKind::uniform_buffer}};
  for (uint32_t i = 0; i < glsl::kSceneBufferCount; ++i)
    b.push_back({glsl::kBindSceneFirst + i, DescriptorKind::storage_buffer});
  return b;
}

void record_compute(RecordContext& ctx, const ComputeDispatch& d) {
  ComputePipelineDesc desc;
  desc.shader = d.shader;
  if (d.scene) desc.bindings = scene_bindings();
  desc.push_constant_bytes = d.push_bytes;
  desc.spec_constants = d.spec_constants;
  std::vector<Bind> binds;
  if (d.scene) binds = ctx.scene_gpu.binds();
  for (auto& ib : d.images) {
    desc.bindings.push_back({ib.binding, DescriptorKind::storage_image});
    binds.push_back({ib.binding, nullptr, ib.prev ? &ctx.prev_image(ib.slot) : &ctx.image(ib.slot)});
  }
  for (auto& bb : d.buffers) {
    desc.bindings.push_back({bb.binding, DescriptorKind::storage_buffer});
    binds.push_back({bb.binding, bb.prev ? &ctx.prev_buffer(bb.slot) : &ctx.buffer(bb.slot), nullptr});
  }
  auto pipeline = ctx.gpu.compute_pipeline(desc);
  ctx.cmd.bind(*pipeline, binds, d.push, d.push_bytes);
  if (d.indirect)
    ctx.cmd.dispatch_indirect(ctx.buffer(d.indirect), d.indirect_offset);
  else
    ctx.cmd.dispatch(d.groups_x, d.groups_y, d.groups_z);
}

// ---------------------------------------------------------------- Executor
Executor::Executor(Gpu& gpu, const Scene& scene, Settings settings, std::vector<std::unique_ptr<Pass>> passes,
                   std::vector<std::string> outputs)
    : gpu_(gpu), scene_(scene), settings_(std::move(settings)), passes_(std::move(passes)) {
  for (auto& p : passes_) decls_.push_back(p->declare(scene_, settings_));
  CompileOptions opts;
  opts.features = scene_.features();
  opts.outputs = std::move(outputs);
  opts.render_width = settings_.width;
  opts.render_height = settings_.height;
  plan_ = compile(decls_, opts);

  std::map<std::string, bool> read_prev;
  for (auto* pp : plan_.running())
    for (auto& s : decls_[pp->decl_index].slots)
      if (s.access == Access::read_prev) read_prev[s.name] = true;
  for (auto& r : plan_.resources) {
    Allocation a;
    a.ping_pong = read_prev.count(r.name) > 0;
    for (int i = 0; i < (a.ping_pong ? 2 : 1); ++i) {
      std::string dbg = i ? r.name + "_prev" : r.name;
      if (r.desc.format == Format::buffer)
        a.buffer[i] = gpu_.create_buffer(r.bytes / (a.ping_pong ? 2 : 1), BufferUsage::storage, dbg);
      else
        a.image[i] = gpu_.create_image(r.desc.format, r.width, r.height, dbg);
    }
    allocations_[r.name] = std::move(a);
  }
}

Executor::~Executor() = default;

void Executor::upload_scene(float time) {
  FlatScene flat = flatten(scene_, time);
  Bvh bvh = build_bvh(flat);
  auto put = [&](uint32_t i, const void* data, uint64_t bytes, const char* name) {
    uint64_t alloc = std::max<uint64_t>(bytes, 16);
    if (!scene_gpu_.buffers[i] || scene_gpu_.buffers[i]->size() < alloc)
      scene_gpu_.buffers[i] = gpu_.create_buffer(alloc, BufferUsage::storage, name);
    if (bytes) gpu_.upload(*scene_gpu_.buffers[i], data, bytes);
  };
  put(0, flat.vertices.data(), flat.vertices.size() * sizeof(GpuVertex), "scene_vertices");
  put(1, flat.triangles.data(), flat.triangles.size() * sizeof(GpuTriangle), "scene_triangles");
  put(2, flat.instances.data(), flat.instances.size() * sizeof(GpuInstance), "scene_instances");
  put(3, flat.materials.data(), flat.materials.size() * sizeof(GpuMaterial), "scene_materials");
  put(4, bvh.nodes.data(), bvh.nodes.size() * sizeof(bvh.nodes[0]), "scene_bvh_nodes");
  put(5, bvh.tri_index.data(), bvh.tri_index.size() * sizeof(uint32_t), "scene_bvh_tri_index");
  put(6, flat.lights.data(), flat.lights.size() * sizeof(GpuLight), "scene_lights");
  scene_gpu_.triangle_count = static_cast<uint32_t>(flat.triangles.size());
  scene_gpu_.instance_count = static_cast<uint32_t>(flat.instances.size());
  scene_gpu_.light_count = static_cast<uint32_t>(flat.lights.size());
}

void Executor::upload_frame_constants(float time) {
  Camera cam = scene_.camera_at(time);
  float aspect = float(settings_.width) / float(settings_.height);
  float fov = cam.fov_y_deg * 3.14159265f / 180.0f;
  Mat4 view = Mat4::look_at(cam.position, cam.target, cam.up);
  Mat4 proj = Mat4::perspective(fov, aspect, cam.near_plane, cam.far_plane);
  Mat4 vp = proj * view;
  Mat4 inv = vp.inverse();
  glsl::GpuFrame f{};
  std::memcpy(f.view_proj.m, vp.m, 64);
  std::memcpy(f.inv_view_proj.m, inv.m, 64);
  std::memcpy(f.prev_view_proj.m, frame_ ? prev_view_proj_ : &vp.m[0][0], 64);
  std::memcpy(prev_view_proj_, vp.m, 64);
  f.camera_pos = {cam.position.x, cam.position.y, cam.position.z, std::tan(fov * 0.5f)};
  const Sun& sun = scene_.sun;
  Vec3 sd = normalize(sun.direction);
  f.sun_dir = {sd.x, sd.y, sd.z, std::cos(sun.angular_radius_deg * 3.14159265f / 180.0f)};
  f.sun_irradiance = {sun.irradiance.x, sun.irradiance.y, sun.irradiance.z, sun.enabled ? 1.0f : 0.0f};
  const Sky& sky = scene_.sky;
  f.sky_zenith = {sky.radiance.x, sky.radiance.y, sky.radiance.z, float(static_cast<uint32_t>(sky.kind))};
  f.sky_horizon = {sky.horizon.x, sky.horizon.y, sky.horizon.z, sky.turbidity};
  f.sky_ground = {sky.ground.x, sky.ground.y, sky.ground.z, 0};
  f.frame_info = {frame_, settings_.width, settings_.height, scene_gpu_.light_count};
  f.scene_info = {scene_gpu_.triangle_count, scene_gpu_.instance_count, settings_.seed,
                  frame_ * settings_.spp_per_frame};
  if (!scene_gpu_.frame) scene_gpu_.frame = gpu_.create_buffer(sizeof(f), BufferUsage::uniform, "frame_constants");
  gpu_.upload(*scene_gpu_.frame, &f, sizeof(f));
}

std::map<std::string, ResolvedSlot> Executor::bind_slots(const PassDecl& decl) {
  std::map<std::string, ResolvedSlot> slots;
  for (auto& s : decl.slots) {
    ResolvedSlot rs;
    rs.resource = plan_.find(s.name);
    rs.access = s.access;
    auto& a = allocations_.at(s.name);
    int cur = a.ping_pong ? int(frame_ & 1) : 0;
    rs.image = a.image[cur];
    rs.buffer = a.buffer[cur];
    if (a.ping_pong) {
      rs.prev_image = a.image[cur ^ 1];
      rs.prev_buffer = a.buffer[cur ^ 1];
    }
    if (s.access == Access::read_prev) {
      auto it = slots.find(s.name);
      if (it != slots.end()) {  // also accessed this frame: add last frame's copy to that slot
        it->second.prev_image = rs.prev_image;
        it->second.prev_buffer = rs.prev_buffer;
        continue;
      }
      // Only last frame's copy is read: it is what the plain name refers to.
      rs.image = rs.prev_image;
      rs.buffer = rs.prev_buffer;
    }
    slots[s.name] = rs;
  }
  return slots;
}

FrameResult Executor::run_frame() {
  float time = float(frame_) * scene_.frame_time;
  if (!scene_uploaded_ || scene_.features().has(Feature::motion)) {
    upload_scene(time);
    scene_uploaded_ = true;
  }
  upload_frame_constants(time);
  auto running = plan_.running();
  // On a CPU device (lavapipe) timestamps inside one submission misattribute work: llvmpipe
  // runs dispatches and draws lazily, so a pass's cost shows up in a later pass or between
  // passes. There every pass is submitted alone and timed by the host clock around its
  // submit-and-wait, which on a CPU device is the time the device spent on it. A GPU records
  // the whole frame in one submission with a timestamp pair around every pass.
  const bool per_pass_submit = gpu_.info().is_software();
  FrameResult fr;
  fr.frame = frame_;
  std::unique_ptr<Cmd> cmd;
  uint32_t q = 0;
  std::vector<double> ns;
  auto t_frame = std::chrono::steady_clock::now();
  for (auto* pp : running) {
    if (!cmd) cmd = gpu_.begin(per_pass_submit ? 2u : static_cast<uint32_t>(running.size() * 2));
    const PassDecl& decl = decls_[pp->decl_index];
    if (!pp->barrier_before.resources.empty())
      cmd->barrier(pp->barrier_before.src_kinds, pp->barrier_before.dst_kind);
    cmd->begin_label(decl.name);
    cmd->timestamp(q++);
    RecordContext ctx(gpu_, *cmd, scene_, scene_gpu_, settings_, frame_, decl.name, bind_slots(decl));
    passes_[pp->decl_index]->record(ctx);
    cmd->timestamp(q++);
    cmd->end_label();
    if (per_pass_submit) {
      auto t0 = std::chrono::steady_clock::now();
      gpu_.submit(std::move(cmd));
      double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      fr.passes.push_back({decl.name, ms});
      q = 0;
    }
  }
  if (per_pass_submit) {
    fr.total_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t_frame).count();
  } else if (cmd) {
    ns = gpu_.submit(std::move(cmd));
    for (size_t i = 0; i < running.size(); ++i)
      fr.passes.push_back({running[i]->name, (ns[2 * i + 1] - ns[2 * i]) * 1e-6});
    if (!ns.empty()) fr.total_ms = (ns.back() - ns.front()) * 1e-6;
  }
  ++frame_;
  return fr;
}

std::vector<std::string> Executor::image_names() const {
  std::vector<std::string> out;
  for (auto& r : plan_.resources)
    if (r.desc.format != Format::buffer) out.push_back(r.name);
  return out;
}

FloatImage Executor::read(const std::string& name) {
  auto it = allocations_.find(name);
  if (it == allocations_.end()) {
    std::string names;
    for (auto& n : image_names()) names += (names.empty() ? "" : ", ") + n;
    throw GraphError(fmt::format("--dump: expected one of the plan's images [{}], got '{}'", names, name));
  }
  auto& a = it->second;
  if (!a.image[0]) throw GraphError(fmt::format("--dump '{}': a buffer, not an image", name));
  // The copy written most recently: frame_ was already advanced by run_frame.
  int cur = a.ping_pong ? int((frame_ + 1) & 1) : 0;
  const Image& img = *a.image[cur];
  return decode_texels(img.format(), img.width(), img.height(), gpu_.download(img));
}

std::vector<uint8_t> Executor::read_buffer(const std::string& name) {
  auto it = allocations_.find(name);
  if (it == allocations_.end() || !it->second.buffer[0])
    throw GraphError(fmt::format("read_buffer: '{}' is not a buffer resource of the plan", name));
  auto& a = it->second;
  int cur = a.ping_pong ? int((frame_ + 1) & 1) : 0;
  const Buffer& buf = *a.buffer[cur];
  std::vector<uint8_t> out(buf.size());
  if (!out.empty()) gpu_.download(buf, out.data(), out.size());
  return out;
}

}  // namespace gib
