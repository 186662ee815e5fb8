#include "renderer/graph/executor.h"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>

#include "renderer/graph/dispatch_log.h"
#include "renderer/graph/stability_scan_shared.h"
#include "renderer/scene/bvh.h"
#include "renderer/scene/material_eval.h"
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
  b.push_back({glsl::kBindSceneTextures, textures.get(), nullptr});
  return b;
}

std::vector<BindingDecl> scene_bindings() {
  std::vector<BindingDecl> b{{glsl::kBindFrame, DescriptorKind::uniform_buffer}};
  for (uint32_t i = 0; i < glsl::kSceneBufferCount; ++i)
    b.push_back({glsl::kBindSceneFirst + i, DescriptorKind::storage_buffer});
  b.push_back({glsl::kBindSceneTextures, DescriptorKind::storage_buffer});
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
    desc.bindings.push_back({ib.binding, ib.sampled ? DescriptorKind::sampled_image : DescriptorKind::storage_image});
    binds.push_back({ib.binding, nullptr, ib.prev ? &ctx.prev_image(ib.slot) : &ctx.image(ib.slot)});
  }
  for (auto& bb : d.buffers) {
    desc.bindings.push_back({bb.binding, DescriptorKind::storage_buffer});
    binds.push_back({bb.binding, bb.prev ? &ctx.prev_buffer(bb.slot) : &ctx.buffer(bb.slot), nullptr});
  }
  auto pipeline = ctx.gpu.compute_pipeline(desc);
  if (d.label) ctx.cmd.begin_label(d.label);
  ctx.cmd.bind(*pipeline, binds, d.push, d.push_bytes);
  if (d.indirect)
    ctx.cmd.dispatch_indirect(ctx.buffer(d.indirect), d.indirect_offset);
  else
    ctx.cmd.dispatch(d.groups_x, d.groups_y, d.groups_z);
  if (d.label) ctx.cmd.end_label();
  if (d.barrier_after) ctx.cmd.barrier(kStageCompute, kStageCompute);
}

// ---------------------------------------------------------------- Executor
Executor::Executor(Gpu& gpu, const Scene& scene, Settings settings, std::vector<std::unique_ptr<Pass>> passes,
                   std::vector<std::string> outputs)
    : gpu_(gpu),
      scene_(scene),
      settings_(std::move(settings)),
      passes_(std::move(passes)),
      average_opacity_(bake_average_opacity(scene_)) {
  host_timed_passes_ = gpu_.info().is_software();
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
  zero_persistent();
  plan_stability_scan();
}

Executor::~Executor() = default;

// Persistent resources carry values from frame to frame: zero both copies once, so nothing a
// pass reads before it first writes is uninitialised memory (which may hold NaN bit patterns).
// Depth clears to 1 (far), as the Vulkan layer clears a new depth image.
void Executor::zero_persistent() {
  std::unique_ptr<Cmd> cmd;
  for (auto& r : plan_.resources) {
    if (!r.desc.persistent) continue;
    if (!cmd) cmd = gpu_.begin();
    auto& a = allocations_.at(r.name);
    for (int i = 0; i < 2; ++i) {
      if (a.buffer[i]) cmd->fill(*a.buffer[i], 0);
      if (a.image[i]) {
        const float v = a.image[i]->format() == Format::d32_float ? 1.0f : 0.0f;
        const float value[4] = {v, v, v, v};
        cmd->clear(*a.image[i], value);
      }
    }
  }
  if (!cmd) return;
  cmd->barrier(kStageTransfer, kStageCompute | kStageGraphics | kStageTransfer);
  gpu_.submit(std::move(cmd));
}

// ---------------------------------------------------------------- overrides
void Executor::add_override(const ResourceOverride& o) {
  auto running = plan_.running();
  size_t index = running.size();
  for (size_t i = 0; i < running.size(); ++i)
    if (running[i]->name == o.after_pass) index = i;
  if (index == running.size())
    throw GraphError(fmt::format("override of '{}': expected a running pass, got '{}'", o.resource, o.after_pass));
  bool writes = false;
  for (const Slot& s : decls_[running[index]->decl_index].slots)
    writes |= s.name == o.resource && (s.access == Access::write || s.access == Access::read_write);
  if (!writes)
    throw GraphError(fmt::format("override after pass '{}': expected a resource it writes, got '{}'", o.after_pass,
                                 o.resource));
  const ResolvedResource* r = plan_.find(o.resource);
  const bool buffer = r->desc.format == Format::buffer;
  const uint64_t expected =
      buffer ? r->bytes_per_copy : uint64_t(r->width) * r->height * format_bytes_per_texel(r->desc.format);
  if (o.data.size() != expected)
    throw GraphError(fmt::format("override of '{}': expected {} bytes ({}), got {}", o.resource, expected,
                                 buffer ? "the buffer" : fmt::format("{}x{} {}", r->width, r->height,
                                                                     format_name(r->desc.format)),
                                 o.data.size()));
  if (o.first_frame > o.last_frame)
    throw GraphError(fmt::format("override of '{}': expected first_frame <= last_frame, got {} > {}", o.resource,
                                 o.first_frame, o.last_frame));
  Override ov;
  ov.running_index = index;
  ov.first_frame = o.first_frame;
  ov.last_frame = o.last_frame;
  ov.resource = o.resource;
  if (buffer) {
    ov.buffer = gpu_.create_buffer(expected, BufferUsage::storage, o.resource + "_override");
    gpu_.upload(*ov.buffer, o.data.data(), expected);
  } else {
    ov.image = gpu_.create_image(r->desc.format, r->width, r->height, o.resource + "_override");
    gpu_.upload(*ov.image, o.data.data(), expected);
  }
  overrides_.push_back(std::move(ov));
}

void Executor::record_overrides(Cmd& cmd, size_t running_index) {
  bool any = false;
  for (const Override& ov : overrides_) {
    if (ov.running_index != running_index || frame_ < ov.first_frame || frame_ > ov.last_frame) continue;
    if (!any) cmd.barrier(kStageCompute | kStageGraphics | kStageTransfer, kStageTransfer);
    any = true;
    auto& a = allocations_.at(ov.resource);
    const int cur = written_copy(a);
    if (ov.buffer)
      cmd.copy(*ov.buffer, *a.buffer[cur]);
    else
      cmd.copy(*ov.image, *a.image[cur]);
  }
  if (any) cmd.barrier(kStageTransfer, kStageCompute | kStageGraphics | kStageTransfer);
}

// ---------------------------------------------------------------- stability scan
struct Executor::ScanTarget {
  std::string resource;
  bool buffer = false;
  const char* shader = "";
  DescriptorKind source_kind = DescriptorKind::sampled_image;
  glsl::StabilityScanPush push{};
  uint32_t groups_x = 1, groups_y = 1;
  uint32_t width = 0, height = 0;
};

void Executor::plan_stability_scan() {
  auto running = plan_.running();
  scan_of_pass_.assign(running.size(), {});
  for (size_t i = 0; i < running.size(); ++i) {
    const PassDecl& decl = decls_[running[i]->decl_index];
    for (const Slot& s : decl.slots) {
      if (s.access != Access::write && s.access != Access::read_write) continue;
      const ResolvedResource* r = plan_.find(s.name);
      const ValueDomain& declared = r->desc.values;
      if (!declared.scanned()) continue;
      const bool buffer = r->desc.format == Format::buffer;
      const ValueDomain v = effective_domain(r->desc.format, declared);
      ScanTarget t;
      t.resource = s.name;
      t.buffer = buffer;
      uint64_t count = 0;
      if (buffer) {
        if (declared.stride_words == 0) continue;  // no layout: not scanned
        const uint32_t max_words = declared.encoding == Encoding::rgb9e5 ? 10 : 32;
        if (declared.value_words == 0 || declared.value_words > max_words ||
            declared.first_word + declared.value_words > declared.stride_words)
          throw GraphError(fmt::format("pass '{}' slot '{}': buffer value layout words {}+{} of {} is invalid (1..{} "
                                       "value words inside the stride)", decl.name, s.name, declared.first_word,
                                       declared.value_words, declared.stride_words, max_words));
        count = r->bytes_per_copy / 4 / declared.stride_words;
        t.shader = "stability_scan_buffer.comp";
        t.source_kind = DescriptorKind::storage_buffer;
      } else {
        count = uint64_t(r->width) * r->height;
        t.width = r->width;
        t.height = r->height;
        const Format f = r->desc.format;
        if (f == Format::rg32_uint || f == Format::rgba32_uint)
          throw GraphError(fmt::format("pass '{}' slot '{}': a {} image cannot be scanned (only r32_uint among uint "
                                       "formats); declare Domain::none", decl.name, s.name, format_name(f)));
        if (declared.encoding == Encoding::rgb9e5 && f != Format::r32_uint)
          throw GraphError(fmt::format("pass '{}' slot '{}': RGB9E5 encoding needs an r32_uint image, not {}", decl.name,
                                       s.name, format_name(f)));
        if (f == Format::r32_uint) {
          t.shader = "stability_scan_uint.comp";
          t.source_kind = DescriptorKind::storage_image;
        } else {
          t.shader = "stability_scan_image.comp";  // through a sampler: any float format, depth, E5B9G9R9
        }
      }
      if (count == 0 || count > 0xffffffffull) continue;
      t.push.record = uint32_t(scan_targets_.size());
      t.push.count = uint32_t(count);
      t.push.width = t.width;
      t.push.channels = v.channels;
      t.push.signed_channels = v.signed_channels;
      t.push.domain = uint32_t(v.domain);
      t.push.max_value = v.max_value;
      t.push.encoding = v.encoding == Encoding::rgb9e5 ? glsl::kStabilityEncodingRgb9e5 : 0u;
      t.push.stride_words = v.stride_words;
      t.push.first_word = v.first_word;
      t.push.words = v.value_words;
      t.push.height = t.height;
      t.push.format_max = v.format_max;
      t.push.format_max_b = v.format_max_b;
      if (buffer) {
        t.groups_x = uint32_t(std::min<uint64_t>((count + glsl::kStabilityScanGroup - 1) / glsl::kStabilityScanGroup,
                                                 glsl::kStabilityScanMaxGroups));
      } else {  // at most 16 x 16 tiles of 16 x 16: a grid-stride loop covers the rest
        t.groups_x = std::min(div_up(t.width, glsl::kStabilityScanTile), 16u);
        t.groups_y = std::min(div_up(t.height, glsl::kStabilityScanTile), 16u);
      }
      scan_of_pass_[i].push_back(scan_targets_.size());
      scan_targets_.push_back(t);
      StabilityTarget st;
      st.pass = decl.name;
      st.resource = s.name;
      st.values = declared;
      st.buffer = buffer;
      st.elements = count;
      stability_.targets.push_back(st);
    }
  }
  static_assert(kStabilityCategoryCount == glsl::kStabilityCategories &&
                uint32_t(StabilityCategory::saturated) == glsl::kStabilitySaturated &&
                uint32_t(StabilityCategory::above_max) == glsl::kStabilityAboveMax);
  static_assert(uint32_t(Domain::finite) == glsl::kStabilityDomainFinite &&
                uint32_t(Domain::non_negative) == glsl::kStabilityDomainNonNegative &&
                uint32_t(Domain::unit) == glsl::kStabilityDomainUnit);
  stability_.dispatches_per_frame = uint32_t(scan_targets_.size());
}

// Records the scans of running pass `running_index` into cmd; the first of a frame also resets
// the result buffer. Returns the number of dispatches.
uint32_t Executor::record_scans(Cmd& cmd, size_t running_index, bool& reset, uint32_t slot) {
  const auto& targets = scan_of_pass_[running_index];
  if (targets.empty()) return 0;
  if (scan_results_.size() <= slot) scan_results_.resize(slot + 1);
  std::shared_ptr<Buffer>& results = scan_results_[slot];
  if (!results) {
    uint64_t bytes = uint64_t(scan_targets_.size()) * glsl::kStabilityRecordWords * 4;
    results = gpu_.create_buffer(bytes, BufferUsage::storage, "stability_scan_results");
  }
  cmd.begin_label("stability_scan");
  if (!reset) {
    cmd.fill(*results, 0);
    reset = true;
  }
  // The pass's writes (any kind) and the reset before the scan's reads.
  cmd.barrier(kStageCompute | kStageGraphics | kStageTransfer, kStageCompute);
  for (size_t ti : targets) {
    const ScanTarget& t = scan_targets_[ti];
    auto& a = allocations_.at(t.resource);
    const int cur = written_copy(a);
    ComputePipelineDesc desc;
    desc.shader = t.shader;
    desc.bindings = {{glsl::kStabilityScanBindResults, DescriptorKind::storage_buffer},
                     {glsl::kStabilityScanBindSource, t.source_kind}};
    desc.push_constant_bytes = sizeof(t.push);
    auto pipeline = gpu_.compute_pipeline(desc);
    Bind binds[2] = {{glsl::kStabilityScanBindResults, results.get(), nullptr},
                     {glsl::kStabilityScanBindSource, a.buffer[cur].get(), a.image[cur].get()}};
    cmd.bind(*pipeline, binds, &t.push, sizeof(t.push));
    cmd.dispatch(t.groups_x, t.groups_y);
  }
  // Later passes may overwrite what the scan reads.
  cmd.barrier(kStageCompute, kStageCompute | kStageGraphics | kStageTransfer);
  cmd.end_label();
  return uint32_t(targets.size());
}

void Executor::collect_scan_results(uint32_t slot, uint32_t frame) {
  const uint32_t n = uint32_t(scan_targets_.size());
  std::vector<uint32_t> words(size_t(n) * glsl::kStabilityRecordWords);
  gpu_.download(*scan_results_.at(slot), words.data(), words.size() * 4);
  ++stability_.frames;
  // Scan targets are in execution order then slot order, so appending in this order keeps
  // records in order of first offence.
  std::map<std::string, uint32_t> pass_order;
  {
    auto running = plan_.running();
    for (uint32_t i = 0; i < running.size(); ++i) pass_order[running[i]->name] = i;
  }
  for (uint32_t t = 0; t < n; ++t) {
    const uint32_t* rec = &words[size_t(t) * glsl::kStabilityRecordWords];
    StabilityTarget& target = stability_.targets[t];
    const float max_abs = std::bit_cast<float>(rec[glsl::kStabilityRecordMaxAbs]);
    target.max_seen = std::max(target.max_seen, max_abs);
    for (auto& r : stability_.records)
      if (r.pass == target.pass && r.resource == target.resource) r.max_seen = target.max_seen;
    for (uint32_t c = 0; c < kStabilityCategoryCount; ++c) {
      const uint32_t count = rec[c];
      if (!count) continue;
      target.count[c] += count;
      const uint64_t index = ~rec[glsl::kStabilityRecordFirst + c];
      StabilityRecord* r = nullptr;
      for (auto& x : stability_.records)
        if (x.pass == target.pass && x.resource == target.resource && uint32_t(x.category) == c) r = &x;
      if (!r) {
        StabilityRecord nr;
        nr.pass = target.pass;
        nr.resource = target.resource;
        nr.category = StabilityCategory(c);
        nr.first_frame = frame;
        nr.first_count = count;
        nr.first_index = uint32_t(index);
        nr.buffer = target.buffer;
        const uint32_t w = scan_targets_[t].width;
        nr.first_x = target.buffer ? uint32_t(index) : uint32_t(index % w);
        nr.first_y = target.buffer ? 0u : uint32_t(index / w);
        nr.pass_order = pass_order[target.pass];
        nr.max_seen = target.max_seen;
        stability_.records.push_back(nr);
        r = &stability_.records.back();
      }
      r->count += count;
      r->frames_with_issue += 1;
    }
  }
}

void Executor::upload_scene(float time) {
  FlatScene flat = flatten(scene_, time, settings_.world_offset, &average_opacity_);
  if (!settings_.translucency)
    for (GpuMaterial& m : flat.materials) m.translucency = 0.0f;  // option translucency 0 (a control)
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
  if (!scene_gpu_.textures) {  // textures do not change with time: uploaded once
    const uint64_t bytes = flat.textures.size() * sizeof(uint32_t);
    scene_gpu_.textures = gpu_.create_buffer(bytes, BufferUsage::storage, "scene_textures");
    gpu_.upload(*scene_gpu_.textures, flat.textures.data(), bytes);
    texture_bytes_ = bytes;
  }
  scene_gpu_.triangle_count = static_cast<uint32_t>(flat.triangles.size());
  scene_gpu_.instance_count = static_cast<uint32_t>(flat.instances.size());
  scene_gpu_.light_count = static_cast<uint32_t>(flat.lights.size());
  decals_ = std::move(flat.decals);  // carried by the frame constants
  indoor_volumes_ = std::move(flat.indoor_volumes);
}

void Executor::record_frame_constants(Cmd& cmd, float time) {
  Camera cam = scene_.camera_at(time);
  cam.position += settings_.world_offset;  // the camera moves with the scene (upload_scene)
  cam.target += settings_.world_offset;
  float aspect = float(settings_.width) / float(settings_.height);
  float fov = cam.fov_y_deg * 3.14159265f / 180.0f;
  Mat4 view = Mat4::look_at(cam.position, cam.target, cam.up);
  Mat4 proj = Mat4::perspective(fov, aspect, cam.near_plane, cam.far_plane);
  Mat4 vp = proj * view;
  // Camera rays come from the inverse of the view-projection without the camera's translation:
  // NDC to an offset from camera_pos. A world-space inverse, evaluated on the far plane, scales
  // its rounding error (1e-3 of the far point, from the cancelling w) about the world origin,
  // which 10 km away turns into metres sideways: whole pixels.
  Mat4 view_rotation = view;
  view_rotation.m[3][0] = view_rotation.m[3][1] = view_rotation.m[3][2] = 0.0f;
  Mat4 inv_rel = (proj * view_rotation).inverse();
  glsl::GpuFrame f{};
  std::memcpy(f.view_proj.m, vp.m, 64);
  std::memcpy(f.inv_view_proj_rel.m, inv_rel.m, 64);
  std::memcpy(f.prev_view_proj.m, frame_ ? prev_view_proj_ : &vp.m[0][0], 64);
  std::memcpy(prev_view_proj_, vp.m, 64);
  f.camera_pos = {cam.position.x, cam.position.y, cam.position.z, std::tan(fov * 0.5f)};
  const Sun sun = scene_.sun_at(time);
  Vec3 sd = normalize(sun.direction);
  f.sun_dir = {sd.x, sd.y, sd.z, std::cos(sun.angular_radius_deg * 3.14159265f / 180.0f)};
  f.sun_irradiance = {sun.irradiance.x, sun.irradiance.y, sun.irradiance.z, sun.enabled ? 1.0f : 0.0f};
  const Sky& sky = scene_.sky;
  f.sky_zenith = {sky.radiance.x, sky.radiance.y, sky.radiance.z, float(static_cast<uint32_t>(sky.kind))};
  f.sky_horizon = {sky.horizon.x, sky.horizon.y, sky.horizon.z, sky.turbidity};
  f.sky_ground = {sky.ground.x, sky.ground.y, sky.ground.z, 0};
  f.frame_info = {frame_, settings_.width, settings_.height, scene_gpu_.light_count};
  static_assert(sizeof(glsl::GpuDecal) == sizeof(GpuDecal) && glsl::kMaxDecals == kMaxDecals,
                "frame_shared.h GpuDecal mirrors scene.h GpuDecal");
  const uint32_t decal_count = uint32_t(std::min<size_t>(decals_.size(), kMaxDecals));  // the loader refuses more
  std::memcpy(f.decals, decals_.data(), decal_count * sizeof(GpuDecal));
  f.scene_info = {scene_gpu_.triangle_count, scene_gpu_.instance_count, settings_.seed, decal_count};
  f.alpha_info = {static_cast<uint32_t>(settings_.alpha.strategy), settings_.alpha.any_hit_limit, 0, 0};
  static_assert(glsl::kMaxIndoorVolumes == kMaxIndoorVolumes, "frame_shared.h holds scene.h's indoor volumes");
  const uint32_t volumes = uint32_t(std::min<size_t>(indoor_volumes_.size(), kMaxIndoorVolumes));  // the loader refuses more
  f.volume_info = {volumes, 0, 0, 0};
  for (uint32_t i = 0; i < volumes; ++i) {
    const IndoorVolume& v = indoor_volumes_[i];
    f.indoor_min[i] = {v.min.x, v.min.y, v.min.z, 0};
    f.indoor_max[i] = {v.max.x, v.max.y, v.max.z, 0};
  }
  static_assert(sizeof(f) <= 65536 && sizeof(f) % 4 == 0, "frame constants fit Cmd::update");
  if (!scene_gpu_.frame) scene_gpu_.frame = gpu_.create_buffer(sizeof(f), BufferUsage::uniform, "frame_constants");
  cmd.update(*scene_gpu_.frame, &f, sizeof(f));
  cmd.barrier(kStageTransfer, kStageCompute | kStageGraphics);
}

std::map<std::string, ResolvedSlot> Executor::bind_slots(const PassDecl& decl) {
  std::map<std::string, ResolvedSlot> slots;
  for (auto& s : decl.slots) {
    ResolvedSlot rs;
    rs.resource = plan_.find(s.name);
    rs.access = s.access;
    auto& a = allocations_.at(s.name);
    int cur = written_copy(a);
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

namespace {

// Thread counts (an indirect dispatch's groups read back now, after the frame ran) and, where
// a timestamp was written after the dispatch, the time since the previous stamp of the pass.
std::vector<DispatchTiming> resolve_dispatches(Gpu& gpu, const std::vector<LoggedDispatch>& log,
                                               const std::vector<double>& ns, double pass_start_ns) {
  std::vector<DispatchTiming> out;
  double prev = pass_start_ns;
  for (const LoggedDispatch& d : log) {
    DispatchTiming t;
    uint64_t groups = d.groups;
    if (d.args) {
      uint32_t xyz[3] = {0, 0, 0};
      gpu.download(*d.args, xyz, sizeof(xyz), d.args_offset);
      groups = uint64_t(xyz[0]) * xyz[1] * xyz[2];
      t.indirect = true;
    }
    t.threads = groups * d.local_threads;
    t.pipeline = d.pipeline;
    t.ms = std::numeric_limits<double>::quiet_NaN();
    if (d.query >= 0 && size_t(d.query) < ns.size()) {
      t.ms = (ns[size_t(d.query)] - prev) * 1e-6;
      prev = ns[size_t(d.query)];
    }
    out.push_back(t);
  }
  return out;
}

}  // namespace

float Executor::frame_time() const {
  return settings_.scene_time >= 0.0f ? settings_.scene_time : float(frame_) * scene_.frame_time;
}

// Records running pass i (`pp`) between its timestamp pair (queries q, q + 1; q advances past
// them and past any dispatch stamps of the profile), then the overrides after it.
void Executor::record_pass(Cmd& cmd, const PlannedPass& pp, size_t i, uint32_t& q, uint32_t profile_query_limit,
                           std::vector<LoggedDispatch>& logged) {
  const PassDecl& decl = decls_[pp.decl_index];
  if (!pp.barrier_before.resources.empty()) cmd.barrier(pp.barrier_before.src_kinds, pp.barrier_before.dst_kind);
  cmd.begin_label(decl.name);
  cmd.timestamp(q++);
  if (profile_dispatches_) {
    DispatchLogCmd log(cmd, q, profile_query_limit, profile_query_limit > q);
    RecordContext ctx(gpu_, log, scene_, scene_gpu_, settings_, frame_, decl.name, bind_slots(decl));
    passes_[pp.decl_index]->record(ctx);
    logged = log.dispatches();
  } else {
    RecordContext ctx(gpu_, cmd, scene_, scene_gpu_, settings_, frame_, decl.name, bind_slots(decl));
    passes_[pp.decl_index]->record(ctx);
  }
  cmd.timestamp(q++);
  cmd.end_label();
  record_overrides(cmd, i);
}

FrameResult Executor::run_frame() { return run_frames(1).front(); }

std::vector<FrameResult> Executor::run_frames(uint32_t n) {
  std::vector<FrameResult> out;
  out.reserve(n);
  // A moving scene is uploaded before each of its frames, outside any command buffer, so its
  // frames are submitted one at a time.
  const bool moving = scene_.features().has(Feature::motion);
  while (out.size() < n) {
    if (host_timed_passes_) {
      out.push_back(run_frame_host_timed());
      continue;
    }
    const uint32_t batch = moving ? 1u : n - uint32_t(out.size());
    for (FrameResult& fr : run_batch(batch)) out.push_back(std::move(fr));
  }
  return out;
}

// On a CPU device (lavapipe) timestamps inside one submission misattribute work: llvmpipe
// runs dispatches and draws lazily, so a pass's cost shows up in a later pass or between
// passes. There every pass is submitted alone and timed by the host clock around its
// submit-and-wait, which on a CPU device is the time the device spent on it. Stability scans
// run in a submission of their own after the pass's, so pass timings never include them.
FrameResult Executor::run_frame_host_timed() {
  const float time = frame_time();
  if (!scene_uploaded_ || scene_.features().has(Feature::motion)) {
    upload_scene(time);
    scene_uploaded_ = true;
  }
  auto running = plan_.running();
  const bool scan = scan_enabled_ && !scan_targets_.empty();
  bool scan_reset = false;
  FrameResult fr;
  fr.frame = frame_;
  auto t_frame = std::chrono::steady_clock::now();
  for (size_t i = 0; i < running.size(); ++i) {
    auto cmd = gpu_.begin(2);
    if (i == 0) record_frame_constants(*cmd, time);
    uint32_t q = 0;
    std::vector<LoggedDispatch> logged;
    record_pass(*cmd, *running[i], i, q, 0, logged);
    auto t0 = std::chrono::steady_clock::now();
    gpu_.submit(std::move(cmd));
    double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    fr.passes.push_back({running[i]->name, ms, resolve_dispatches(gpu_, logged, {}, 0)});
    if (scan && !scan_of_pass_[i].empty()) {
      auto t1 = std::chrono::steady_clock::now();
      auto scan_cmd = gpu_.begin();
      fr.scan_dispatches += record_scans(*scan_cmd, i, scan_reset, 0);
      gpu_.submit(std::move(scan_cmd));
      fr.scan_ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t1).count();
    }
  }
  fr.total_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t_frame).count() -
                fr.scan_ms;
  if (scan_reset) collect_scan_results(0, frame_);
  ++frame_;
  return fr;
}

// A GPU records `n` frames in one submission, each pass between a timestamp pair, with a full
// barrier between frames (what the next frame reads was written by any pass of the last). The
// commands and their order are those of n single-frame submissions, so the output is the same
// bit for bit; the host pays one submit-and-wait for the n frames. Stability scans are
// recorded after each pass's end timestamp into the frame's own results buffer, and collected
// in frame order after the submission.
std::vector<FrameResult> Executor::run_batch(uint32_t n) {
  if (!scene_uploaded_ || scene_.features().has(Feature::motion)) {
    upload_scene(frame_time());
    scene_uploaded_ = true;
  }
  auto running = plan_.running();
  const size_t passes = running.size();
  const bool scan = scan_enabled_ && !scan_targets_.empty();
  // Dispatch profile: timestamps after each dispatch, up to kProfileQueries a frame.
  constexpr uint32_t kProfileQueries = 2048;
  const uint32_t per_frame = uint32_t(passes * 2 + (scan ? 1 : 0)) + (profile_dispatches_ ? kProfileQueries : 0u);
  struct Recorded {
    FrameResult fr;
    uint32_t first_query = 0;
    std::vector<uint32_t> pass_query, pass_end_query;
    std::vector<std::vector<LoggedDispatch>> logged;
    std::vector<bool> scanned_after;
    bool scan_reset = false;
  };
  std::vector<Recorded> rec(n);
  std::unique_ptr<Cmd> cmd = passes ? gpu_.begin(per_frame * n) : nullptr;
  for (uint32_t k = 0; k < n; ++k) {
    Recorded& r = rec[k];
    r.fr.frame = frame_;
    r.first_query = k * per_frame;
    r.pass_query.resize(passes);
    r.pass_end_query.resize(passes);
    r.logged.resize(passes);
    r.scanned_after.assign(passes, false);
    if (cmd) {
      if (k) cmd->barrier(kStageCompute | kStageGraphics | kStageTransfer, kStageCompute | kStageGraphics | kStageTransfer);
      record_frame_constants(*cmd, frame_time());
    }
    uint32_t q = r.first_query;
    for (size_t i = 0; i < passes; ++i) {
      // The profile's dispatch stamps stop short of the queries this pass's end, every later
      // pass and the closing scan stamp need.
      const uint32_t reserved = 1u + 2u * uint32_t(passes - 1 - i) + (scan ? 1u : 0u);
      const uint32_t limit = profile_dispatches_ ? r.first_query + per_frame - reserved : 0u;
      r.pass_query[i] = q;
      record_pass(*cmd, *running[i], i, q, limit, r.logged[i]);
      r.pass_end_query[i] = q - 1;
      if (scan) {
        const uint32_t d = record_scans(*cmd, i, r.scan_reset, k);
        r.fr.scan_dispatches += d;
        r.scanned_after[i] = d > 0;
      }
    }
    if (cmd && scan) cmd->timestamp(q++);  // closes the last pass's scans
    ++frame_;
  }
  std::vector<double> ns;
  if (cmd) ns = gpu_.submit(std::move(cmd));
  std::vector<FrameResult> out;
  for (uint32_t k = 0; k < n; ++k) {
    Recorded& r = rec[k];
    FrameResult& fr = r.fr;
    for (size_t i = 0; i < passes; ++i) {
      fr.passes.push_back({running[i]->name, (ns[r.pass_end_query[i]] - ns[r.pass_query[i]]) * 1e-6, {}});
      fr.passes.back().dispatches = resolve_dispatches(gpu_, r.logged[i], ns, ns[r.pass_query[i]]);
    }
    if (passes && ns.size() > r.pass_end_query[passes - 1]) {
      // The scans after pass i lie between its end timestamp and the next pass's start; the
      // last pass's, between its end and the closing stamp, outside the frame's span.
      double between = 0;
      for (size_t i = 0; i + 1 < passes; ++i)
        if (r.scanned_after[i]) between += (ns[r.pass_query[i + 1]] - ns[r.pass_end_query[i]]) * 1e-6;
      const size_t last = r.pass_end_query[passes - 1];
      const double last_pass_scan = r.scanned_after[passes - 1] && ns.size() > last + 1 ? (ns[last + 1] - ns[last]) * 1e-6 : 0.0;
      fr.scan_ms += between + last_pass_scan;
      fr.total_ms = (ns[last] - ns[r.first_query]) * 1e-6 - between;
    }
    if (r.scan_reset) collect_scan_results(k, fr.frame);
    out.push_back(std::move(fr));
  }
  return out;
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
  int cur = latest_copy(a);
  const Image& img = *a.image[cur];
  return decode_texels(img.format(), img.width(), img.height(), gpu_.download(img));
}

std::vector<uint8_t> Executor::read_buffer(const std::string& name) {
  auto it = allocations_.find(name);
  if (it == allocations_.end() || !it->second.buffer[0])
    throw GraphError(fmt::format("read_buffer: '{}' is not a buffer resource of the plan", name));
  auto& a = it->second;
  int cur = latest_copy(a);
  const Buffer& buf = *a.buffer[cur];
  std::vector<uint8_t> out(buf.size());
  if (!out.empty()) gpu_.download(buf, out.data(), out.size());
  return out;
}

std::vector<uint8_t> Executor::read_bytes(const std::string& name) {
  auto it = allocations_.find(name);
  if (it == allocations_.end()) throw GraphError(fmt::format("read_bytes: '{}' is not a resource of the plan", name));
  if (it->second.buffer[0]) return read_buffer(name);
  auto& a = it->second;
  return gpu_.download(*a.image[latest_copy(a)]);
}

}  // namespace gib
