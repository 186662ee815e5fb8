// compile(): validation, feature culling, cascade culling, reachability from the requested
// outputs, stable topological order, resource resolution and barrier placement.
#include <algorithm>
#include <functional>
#include <queue>
#include <unordered_map>

#include <fmt/format.h>

#include "renderer/graph/graph.h"

namespace gib {
namespace {

bool reads(Access a) { return a == Access::read || a == Access::read_write; }
bool writes(Access a) { return a == Access::write || a == Access::read_write; }

// Everything compile() knows about one resource name, gathered from all declared passes.
struct Resource {
  std::string name;
  int writer = -1;               // decl index of the pass with a `write` slot
  std::vector<int> modifiers;    // read_write, declaration order
  std::vector<int> readers;      // read
  std::vector<int> prev_readers; // read_prev
  ResourceDesc desc;             // canonical desc (writer's, else first specified modifier's)
  int desc_owner = -1;           // decl index that defined desc
  bool has_producer() const { return writer >= 0 || !modifiers.empty(); }
};

class Compiler {
 public:
  Compiler(const std::vector<PassDecl>& decls, const CompileOptions& options)
      : decls_(decls), options_(options), culled_(decls.size()), reason_(decls.size()) {}

  Plan run() {
    gather();
    validate();
    cull_by_declaration();
    cull_cascade();
    cull_unreachable();
    std::vector<int> order = topo_order(alive_mask());
    return build_plan(order);
  }

 private:
  const std::vector<PassDecl>& decls_;
  const CompileOptions& options_;
  std::vector<Resource> resources_;  // first-declared first
  std::unordered_map<std::string, size_t> by_name_;
  std::vector<bool> culled_;
  std::vector<std::string> reason_;

  const std::string& pname(int p) const { return decls_[p].name; }
  [[noreturn]] static void fail(const std::string& msg) { throw GraphError(msg); }

  Resource& res(const std::string& name) {
    auto [it, inserted] = by_name_.try_emplace(name, resources_.size());
    if (inserted) {
      resources_.emplace_back();
      resources_.back().name = name;
    }
    return resources_[it->second];
  }
  const Resource* find(const std::string& name) const {
    auto it = by_name_.find(name);
    return it == by_name_.end() ? nullptr : &resources_[it->second];
  }

  void gather() {
    std::unordered_map<std::string, int> names;
    for (int p = 0; p < int(decls_.size()); ++p) {
      const PassDecl& d = decls_[p];
      if (d.name.empty()) fail(fmt::format("pass #{} has no name", p));
      if (auto [it, ok] = names.try_emplace(d.name, p); !ok)
        fail(fmt::format("two passes are named '{}' (#{} and #{})", d.name, it->second, p));
      for (size_t s = 0; s < d.slots.size(); ++s) {
        const Slot& slot = d.slots[s];
        if (slot.name.empty()) fail(fmt::format("pass '{}' slot #{} has no name", d.name, s));
        // One access per name, except read_prev next to this frame's access (history).
        for (size_t t = 0; t < s; ++t)
          if (d.slots[t].name == slot.name &&
              (d.slots[t].access == Access::read_prev) == (slot.access == Access::read_prev))
            fail(fmt::format("pass '{}' declares slot '{}' twice (use read_write)", d.name,
                             slot.name));
        Resource& r = res(slot.name);
        switch (slot.access) {
          case Access::write:
            if (r.writer >= 0)
              fail(fmt::format("pass '{}' writes '{}' but pass '{}' already writes it", d.name,
                               slot.name, pname(r.writer)));
            r.writer = p;
            break;
          case Access::read_write: r.modifiers.push_back(p); break;
          case Access::read: r.readers.push_back(p); break;
          case Access::read_prev: r.prev_readers.push_back(p); break;
        }
      }
    }
  }

  const Slot& slot_of(int p, const std::string& name) const {
    for (const Slot& s : decls_[p].slots)
      if (s.name == name && s.access != Access::read_prev) return s;
    fail("internal: slot lookup failed");  // unreachable: only called for gathered slots
  }

  void resolve_desc(Resource& r) {
    const ResourceDesc unspecified{};
    if (r.writer >= 0) {
      r.desc = slot_of(r.writer, r.name).desc;
      r.desc_owner = r.writer;
    }
    for (int m : r.modifiers) {
      const ResourceDesc& d = slot_of(m, r.name).desc;
      if (r.desc_owner < 0) {
        if (same_desc(d, unspecified) && m != r.modifiers.back()) continue;
        r.desc = d;
        r.desc_owner = m;
      } else if (!same_desc(d, unspecified) && !same_desc(d, r.desc)) {
        fail(fmt::format("pass '{}' declares '{}' as {} but pass '{}' declares it as {}", pname(m),
                         r.name, describe(d), pname(r.desc_owner), describe(r.desc)));
      }
    }
    if (r.desc_owner < 0) return;
    resolve_values(r);
    if ((r.desc.format == Format::buffer) != (r.desc.size == SizeRule::buffer))
      fail(fmt::format("pass '{}' slot '{}': format buffer and SizeRule::buffer go together",
                       pname(r.desc_owner), r.name));
  }

  // The value domain is metadata: any slot producing the resource may declare it (a
  // read_write slot with an otherwise unspecified desc too); declarations must agree.
  void resolve_values(Resource& r) {
    int owner = -1;
    ValueDomain values;
    auto take = [&](int p) {
      const ValueDomain& v = slot_of(p, r.name).desc.values;
      if (!v.scanned()) return;
      if (owner >= 0 && !(v == values))
        fail(fmt::format("pass '{}' declares the values of '{}' as '{}' but pass '{}' declares '{}'", pname(p),
                         r.name, describe(v), pname(owner), describe(values)));
      if (owner < 0) {
        owner = p;
        values = v;
      }
    };
    if (r.writer >= 0) take(r.writer);
    for (int m : r.modifiers) take(m);
    r.desc.values = values;
  }

  void validate() {
    for (Resource& r : resources_) resolve_desc(r);
    for (const Resource& r : resources_) {
      for (int p : r.modifiers)
        if (r.writer < 0 && !r.desc.persistent)
          fail(fmt::format("pass '{}' modifies '{}' (read_write) but no pass writes it and it is "
                           "not persistent", pname(p), r.name));
      for (int p : r.readers)
        if (r.writer < 0 && !(r.desc.persistent && !r.modifiers.empty()))
          fail(fmt::format("pass '{}' reads '{}' but no pass writes it", pname(p), r.name));
      for (int p : r.prev_readers) {
        if (!r.has_producer())
          fail(fmt::format("pass '{}' reads previous '{}' but no pass writes it", pname(p), r.name));
        if (!r.desc.persistent)
          fail(fmt::format("pass '{}' reads previous '{}' but '{}' is not persistent (set "
                           "ResourceDesc::persistent on its producer)", pname(p), r.name, r.name));
      }
    }
    for (const std::string& out : options_.outputs) {
      const Resource* r = find(out);
      if (!r || !r->has_producer())
        fail(fmt::format("requested output '{}' is not written by any pass", out));
    }
    check_cycles();
  }

  // Dependency edges between the passes in `mask`: for each resource, writer -> modifiers (in
  // declaration order, chained) -> readers. read_prev adds none.
  std::vector<std::vector<int>> edges(const std::vector<bool>& mask) const {
    std::vector<std::vector<int>> out(decls_.size());
    auto add = [&](int a, int b) {
      if (std::find(out[a].begin(), out[a].end(), b) == out[a].end()) out[a].push_back(b);
    };
    for (const Resource& r : resources_) {
      int last = (r.writer >= 0 && mask[r.writer]) ? r.writer : -1;
      for (int m : r.modifiers) {
        if (!mask[m]) continue;
        if (last >= 0) add(last, m);
        last = m;
      }
      if (last < 0) continue;
      for (int rd : r.readers)
        if (mask[rd]) add(last, rd);
    }
    return out;
  }

  void check_cycles() const {
    auto adj = edges(std::vector<bool>(decls_.size(), true));
    std::vector<int> state(decls_.size(), 0);  // 0 new, 1 on stack, 2 done
    std::vector<int> stack;
    std::vector<int> cycle;
    auto dfs = [&](auto& self, int u) -> bool {
      state[u] = 1;
      stack.push_back(u);
      for (int v : adj[u]) {
        if (state[v] == 1) {
          cycle.assign(std::find(stack.begin(), stack.end(), v), stack.end());
          cycle.push_back(v);
          return true;
        }
        if (state[v] == 0 && self(self, v)) return true;
      }
      stack.pop_back();
      state[u] = 2;
      return false;
    };
    for (int p = 0; p < int(decls_.size()); ++p) {
      if (state[p] != 0 || !dfs(dfs, p)) continue;
      std::string path;
      for (int c : cycle) path += (path.empty() ? "'" : " -> '") + pname(c) + "'";
      fail("dependency cycle between passes: " + path);
    }
  }

  void cull(int p, std::string reason) {
    culled_[p] = true;
    reason_[p] = std::move(reason);
  }

  // Passes the settings switch off, and passes needing a scene feature the scene lacks.
  void cull_by_declaration() {
    for (int p = 0; p < int(decls_.size()); ++p) {
      SceneFeatures missing = decls_[p].needs.missing_from(options_.features);
      if (!decls_[p].switched_off.empty())
        cull(p, "switched off: " + decls_[p].switched_off);
      else if (!missing.empty())
        cull(p, "scene lacks " + to_string(missing));
    }
  }

  // Producers of r that pass p depends on for a read of the current frame's copy.
  std::vector<int> producers_for(const Resource& r, int p, Access a) const {
    std::vector<int> out;
    if (a == Access::read_write && !r.desc.persistent) {
      if (r.writer >= 0) out.push_back(r.writer);
      return out;
    }
    if (r.writer >= 0 && (r.writer != p || a == Access::read_prev)) out.push_back(r.writer);
    for (int m : r.modifiers)
      if (m != p || a == Access::read_prev) out.push_back(m);
    return out;
  }

  void cull_cascade() {
    for (bool changed = true; changed;) {
      changed = false;
      for (int p = 0; p < int(decls_.size()); ++p) {
        if (culled_[p]) continue;
        for (const Slot& s : decls_[p].slots) {
          if (s.access == Access::write) continue;
          const Resource& r = *find(s.name);
          if (s.access == Access::read_write && r.desc.persistent) continue;  // starts zeroed
          std::vector<int> prod = producers_for(r, p, s.access);
          if (prod.empty() || std::any_of(prod.begin(), prod.end(),
                                          [&](int q) { return !culled_[q]; }))
            continue;
          std::string names;
          for (int q : prod) names += (names.empty() ? "" : ", ") + pname(q);
          cull(p, fmt::format("input '{}' has no producer ({} culled)", s.name, names));
          changed = true;
          break;
        }
      }
    }
  }

  void cull_unreachable() {
    std::vector<bool> kept(decls_.size(), false), needed(resources_.size(), false);
    std::vector<size_t> work;
    auto need = [&](const std::string& name) {
      size_t i = by_name_.at(name);
      if (!needed[i]) { needed[i] = true; work.push_back(i); }
    };
    auto keep = [&](int p) {
      if (kept[p] || culled_[p]) return;
      kept[p] = true;
      for (const Slot& s : decls_[p].slots)
        if (s.access != Access::write) need(s.name);
    };
    for (const std::string& out : options_.outputs) need(out);
    for (int p = 0; p < int(decls_.size()); ++p)
      if (decls_[p].side_effect) keep(p);
    while (!work.empty()) {
      const Resource& r = resources_[work.back()];
      work.pop_back();
      if (r.writer >= 0) keep(r.writer);
      for (int m : r.modifiers) keep(m);
    }
    for (int p = 0; p < int(decls_.size()); ++p)
      if (!culled_[p] && !kept[p]) cull(p, "outputs unused");
  }

  std::vector<bool> alive_mask() const {
    std::vector<bool> m(decls_.size());
    for (size_t p = 0; p < m.size(); ++p) m[p] = !culled_[p];
    return m;
  }

  // Kahn's algorithm, always taking the ready pass declared first (stable).
  std::vector<int> topo_order(const std::vector<bool>& mask) const {
    auto adj = edges(mask);
    std::vector<int> indeg(decls_.size(), 0);
    for (const auto& out : adj)
      for (int v : out) ++indeg[v];
    std::priority_queue<int, std::vector<int>, std::greater<int>> ready;
    int total = 0;
    for (int p = 0; p < int(decls_.size()); ++p)
      if (mask[p]) { ++total; if (indeg[p] == 0) ready.push(p); }
    std::vector<int> order;
    while (!ready.empty()) {
      int u = ready.top();
      ready.pop();
      order.push_back(u);
      for (int v : adj[u])
        if (--indeg[v] == 0) ready.push(v);
    }
    if (int(order.size()) != total) fail("dependency cycle between running passes");
    return order;
  }

  ResolvedResource resolve(const Resource& r, bool ping_pong) const {
    ResolvedResource rr;
    rr.name = r.name;
    rr.desc = r.desc;
    const uint32_t w = options_.render_width, h = options_.render_height;
    switch (r.desc.size) {
      case SizeRule::render: rr.width = w; rr.height = h; break;
      case SizeRule::half: rr.width = (w + 1) / 2; rr.height = (h + 1) / 2; break;
      case SizeRule::quarter: rr.width = (w + 3) / 4; rr.height = (h + 3) / 4; break;
      case SizeRule::fixed: rr.width = r.desc.width; rr.height = r.desc.height; break;
      case SizeRule::buffer: break;
    }
    rr.bytes_per_copy = r.desc.size == SizeRule::buffer
                            ? r.desc.bytes
                            : uint64_t(rr.width) * rr.height * format_bytes_per_texel(r.desc.format);
    rr.copies = ping_pong ? 2 : 1;
    rr.bytes = rr.bytes_per_copy * rr.copies;
    return rr;
  }

  Plan build_plan(const std::vector<int>& order) {
    Plan plan;
    plan.render_width = options_.render_width;
    plan.render_height = options_.render_height;
    auto make = [&](int p, bool runs) {
      PlannedPass pp;
      pp.decl_index = uint32_t(p);
      pp.name = pname(p);
      pp.runs = runs;
      pp.reason = runs ? "" : reason_[p];
      pp.kind = decls_[p].kind;
      pp.traces_rays = decls_[p].traces_rays;
      pp.slots = decls_[p].slots;
      pp.work = decls_[p].work;
      pp.measured = decls_[p].measured;
      return pp;
    };
    for (int p : order) plan.passes.push_back(make(p, true));
    for (int p = 0; p < int(decls_.size()); ++p)
      if (culled_[p]) plan.passes.push_back(make(p, false));

    // Resources in order of first use by a running pass.
    std::unordered_map<std::string, size_t> slot_of_res;
    for (size_t i = 0; i < order.size(); ++i) {
      for (const Slot& s : decls_[order[i]].slots) {
        const Resource& r = *find(s.name);
        auto [it, inserted] = slot_of_res.try_emplace(s.name, plan.resources.size());
        if (inserted) {
          bool ping_pong = r.desc.persistent && std::any_of(
              r.prev_readers.begin(), r.prev_readers.end(), [&](int q) { return !culled_[q]; });
          plan.resources.push_back(resolve(r, ping_pong));
        }
        ResolvedResource& rr = plan.resources[it->second];
        if (writes(s.access)) {
          if (rr.producer < 0) rr.producer = int(i);
          plan.passes[i].bytes_written += rr.bytes_per_copy;
        }
      }
    }
    for (const std::string& out : options_.outputs)
      if (!slot_of_res.count(out)) plan.unproduced_outputs.push_back(out);
    place_barriers(plan);
    return plan;
  }

  // Per resource: the kind of the last write, whether some kind has synchronised with it yet,
  // which kinds already see it, and which kinds read it since (for write-after-read).
  struct Track {
    bool written = false, pending = false;
    uint32_t writer_kind = 0, visible = 0, readers = 0;
  };

  static void place_barriers(Plan& plan) {
    std::unordered_map<std::string, Track> track;
    for (PlannedPass& pp : plan.passes) {
      if (!pp.runs) break;
      const uint32_t bit = 1u << uint32_t(pp.kind);
      Barrier& b = pp.barrier_before;
      for (const Slot& s : pp.slots) {
        if (s.access == Access::read_prev) continue;  // last frame's copy: no hazard this frame
        Track& t = track[s.name];
        uint32_t src = 0;
        if (reads(s.access) && t.written && !(t.visible & bit)) src |= t.writer_kind;  // RAW
        if (writes(s.access)) {
          if (t.pending) src |= t.writer_kind;  // WAW
          src |= t.readers;                     // WAR
        }
        if (src) {
          b.resources.push_back(s.name);
          b.src_kinds |= src;
          t.pending = false;
        }
        if (writes(s.access)) {
          t = Track{.written = true, .pending = true, .writer_kind = bit, .visible = 0,
                    .readers = 0};
        } else {
          t.visible |= bit;
          t.readers |= bit;
        }
      }
      if (!b.resources.empty()) b.dst_kind = bit;
    }
  }
};

}  // namespace

Plan compile(const std::vector<PassDecl>& decls, const CompileOptions& options) {
  return Compiler(decls, options).run();
}

}  // namespace gib
