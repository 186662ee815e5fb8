// Names and sizes of the graph enums and descs, Plan queries, and the two plan dumps: to_text (--plan)
// and to_dot (--dump-graph).
#include <algorithm>
#include <set>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "renderer/graph/graph.h"

namespace gib {

bool same_desc(const ResourceDesc& a, const ResourceDesc& b) {
  if (a.format != b.format || a.size != b.size || a.persistent != b.persistent) return false;
  if (a.size == SizeRule::fixed && (a.width != b.width || a.height != b.height)) return false;
  if (a.size == SizeRule::buffer && a.bytes != b.bytes) return false;
  return true;
}

std::string describe(const ResourceDesc& d) {
  std::string size;
  switch (d.size) {
    case SizeRule::render: size = "render"; break;
    case SizeRule::half: size = "half"; break;
    case SizeRule::quarter: size = "quarter"; break;
    case SizeRule::fixed: size = fmt::format("{}x{}", d.width, d.height); break;
    case SizeRule::buffer: size = fmt::format("{} bytes", d.bytes); break;
  }
  return fmt::format("{} {}{}", format_name(d.format), size, d.persistent ? " persistent" : "");
}

const char* domain_name(Domain d) {
  switch (d) {
    case Domain::none: return "none";
    case Domain::finite: return "finite";
    case Domain::non_negative: return "non_negative";
    case Domain::unit: return "unit";
  }
  return "?";
}

std::string describe(const ValueDomain& v) {
  if (!v.scanned()) return "";
  std::string s = domain_name(v.domain);
  auto mask = [](uint32_t m) {
    static const char* const kNames = "rgba";
    std::string out;
    if (m < 16) {
      for (uint32_t c = 0; c < 4; ++c)
        if (m & (1u << c)) out += kNames[c];
    } else {
      out = fmt::format("{:#x}", m);
    }
    return out;
  };
  if (v.channels != ~0u) s += " " + mask(v.channels);
  if (v.signed_channels) s += " signed " + mask(v.signed_channels);
  if (v.max_value != std::numeric_limits<float>::infinity()) s += fmt::format(" <= {}", v.max_value);
  if (v.encoding == Encoding::rgb9e5) s += " rgb9e5";
  if (v.stride_words) s += fmt::format(" words {}+{} of {}", v.first_word, v.value_words, v.stride_words);
  return s;
}

const char* access_name(Access a) {
  switch (a) {
    case Access::read: return "read";
    case Access::write: return "write";
    case Access::read_write: return "read_write";
    case Access::read_prev: return "read_prev";
  }
  return "?";
}

const char* pass_kind_name(PassKind k) {
  switch (k) {
    case PassKind::compute: return "compute";
    case PassKind::graphics: return "graphics";
    case PassKind::transfer: return "transfer";
  }
  return "?";
}

uint64_t Plan::total_bytes() const {
  uint64_t sum = 0;
  for (const ResolvedResource& r : resources) sum += r.bytes;
  return sum;
}

const ResolvedResource* Plan::find(const std::string& name) const {
  for (const ResolvedResource& r : resources)
    if (r.name == name) return &r;
  return nullptr;
}

std::vector<const PlannedPass*> Plan::running() const {
  std::vector<const PlannedPass*> out;
  for (const PlannedPass& p : passes)
    if (p.runs) out.push_back(&p);
  return out;
}

namespace {

std::string mib(uint64_t bytes) { return fmt::format("{:.2f} MiB", double(bytes) / (1024.0 * 1024.0)); }

std::string kinds_text(uint32_t mask) {
  std::vector<std::string> names;
  for (uint32_t k = 0; k < 3; ++k)
    if (mask & (1u << k)) names.emplace_back(pass_kind_name(PassKind(k)));
  return fmt::format("{}", fmt::join(names, "|"));
}

std::string extent_text(const ResolvedResource& r) {
  if (r.desc.size == SizeRule::buffer) return fmt::format("{} B", r.bytes_per_copy);
  return fmt::format("{}x{}", r.width, r.height);
}

// Graphviz double-quoted string body.
std::string dot_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out;
}

}  // namespace

std::string Plan::to_text() const {
  size_t name_w = 4, res_w = 8;
  for (const PlannedPass& p : passes) name_w = std::max(name_w, p.name.size());
  for (const ResolvedResource& r : resources) res_w = std::max(res_w, r.name.size());
  const size_t n_run = running().size();

  std::string out = fmt::format("passes: {} run, {} culled (render {}x{})\n", n_run,
                                passes.size() - n_run, render_width, render_height);
  for (const PlannedPass& p : passes) {
    out += fmt::format("  {:<6}  {:<{}}  {:<8}  ", p.runs ? "ran" : "culled", p.name, name_w,
                       pass_kind_name(p.kind));
    if (!p.runs) out += "reason: " + p.reason + "; ";
    std::string slots;
    for (const Slot& s : p.slots)
      slots += (slots.empty() ? "" : ", ") + s.name + ":" + access_name(s.access);
    out += "slots: " + (slots.empty() ? std::string("-") : slots);
    if (p.runs && p.bytes_written) out += "; writes " + mib(p.bytes_written);
    if (!p.barrier_before.resources.empty()) {
      std::string rs;
      for (const std::string& r : p.barrier_before.resources) rs += (rs.empty() ? "" : ",") + r;
      out += fmt::format("; barrier {}->{} [{}]", kinds_text(p.barrier_before.src_kinds),
                         kinds_text(p.barrier_before.dst_kind), rs);
    }
    out += '\n';
  }
  out += fmt::format("resources: {} (x2: persistent, read_prev ping-pong, counted twice)\n",
                     resources.size());
  for (const ResolvedResource& r : resources) {
    std::string producer = r.producer >= 0 ? passes[size_t(r.producer)].name : "-";
    out += fmt::format("  {:<{}}  {:<15}  {:<11}  {:>12}  {:<3}  producer {}\n", r.name, res_w,
                       format_name(r.desc.format), extent_text(r), mib(r.bytes),
                       r.copies > 1 ? fmt::format("x{}", r.copies) : "", producer);
  }
  for (const std::string& o : unproduced_outputs)
    out += fmt::format("  output '{}' has no running producer\n", o);
  out += fmt::format("total: {}\n", mib(total_bytes()));
  return out;
}

std::string Plan::to_dot() const {
  std::string out = "digraph render_graph {\n  rankdir=LR;\n  node [fontname=\"Helvetica\"];\n";
  std::set<std::string> res_nodes;
  auto res_node = [&](const std::string& name, bool live) {
    if (!res_nodes.insert(name).second) return;
    std::string label = dot_escape(name);  // escaped piecewise: "\\n" is a dot line break
    if (const ResolvedResource* r = find(name))
      label += fmt::format("\\n{} {}\\n{}", format_name(r->desc.format), extent_text(*r),
                           mib(r->bytes));
    out += fmt::format("  \"res:{}\" [shape=ellipse, label=\"{}\"{}];\n", dot_escape(name), label,
                       live ? "" : ", style=dashed, color=grey, fontcolor=grey");
  };
  // Resource nodes: those of running passes first (solid), then those only culled passes touch.
  for (const PlannedPass& p : passes)
    if (p.runs)
      for (const Slot& s : p.slots) res_node(s.name, true);
  for (const PlannedPass& p : passes)
    for (const Slot& s : p.slots) res_node(s.name, false);

  for (size_t i = 0; i < passes.size(); ++i) {
    const PlannedPass& p = passes[i];
    if (p.runs)
      out += fmt::format("  \"pass:{}\" [shape=box, style=filled, fillcolor=\"#dde8f8\", "
                         "label=\"{}. {}\\n{}\"];\n", dot_escape(p.name), i, dot_escape(p.name),
                         pass_kind_name(p.kind));
    else
      out += fmt::format("  \"pass:{}\" [shape=box, style=dashed, color=grey, fontcolor=grey, "
                         "label=\"{}\\nculled: {}\"];\n", dot_escape(p.name), dot_escape(p.name),
                         dot_escape(p.reason));
  }
  for (const PlannedPass& p : passes) {
    const std::string grey = p.runs ? "" : " [color=grey]";
    for (const Slot& s : p.slots) {
      const std::string pn = dot_escape(p.name), rn = dot_escape(s.name);
      switch (s.access) {
        case Access::write:
          out += fmt::format("  \"pass:{}\" -> \"res:{}\"{};\n", pn, rn, grey);
          break;
        case Access::read:
          out += fmt::format("  \"res:{}\" -> \"pass:{}\"{};\n", rn, pn, grey);
          break;
        case Access::read_write:
          out += fmt::format("  \"res:{}\" -> \"pass:{}\"{};\n", rn, pn, grey);
          out += fmt::format("  \"pass:{}\" -> \"res:{}\"{};\n", pn, rn, grey);
          break;
        case Access::read_prev:
          out += fmt::format("  \"res:{}\" -> \"pass:{}\" [style=dashed, label=\"prev\"{}];\n",
                             rn, pn, p.runs ? "" : ", color=grey");
          break;
      }
    }
  }
  out += "}\n";
  return out;
}

}  // namespace gib
