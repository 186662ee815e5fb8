// Render graph compilation on synthetic graphs: no GPU.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "renderer/graph/graph.h"

namespace gib {
namespace {

ResourceDesc image(Format f, SizeRule s = SizeRule::render) {
  ResourceDesc d;
  d.format = f;
  d.size = s;
  return d;
}
ResourceDesc persistent(Format f, SizeRule s = SizeRule::render) {
  ResourceDesc d = image(f, s);
  d.persistent = true;
  return d;
}
ResourceDesc buffer(uint64_t bytes) {
  ResourceDesc d;
  d.format = Format::buffer;
  d.size = SizeRule::buffer;
  d.bytes = bytes;
  return d;
}

Slot W(const std::string& n, ResourceDesc d = image(Format::rgba16_float)) {
  return Slot{n, Access::write, d};
}
Slot R(const std::string& n) { return Slot{n, Access::read, {}}; }
Slot RW(const std::string& n, ResourceDesc d = {}) { return Slot{n, Access::read_write, d}; }
Slot RP(const std::string& n) { return Slot{n, Access::read_prev, {}}; }

PassDecl pass(const std::string& name, std::vector<Slot> slots, SceneFeatures needs = {},
              PassKind kind = PassKind::compute) {
  PassDecl d;
  d.name = name;
  d.kind = kind;
  d.needs = needs;
  d.slots = std::move(slots);
  return d;
}

CompileOptions opts(std::vector<std::string> outputs, SceneFeatures f = {}) {
  CompileOptions o;
  o.features = f;
  o.outputs = std::move(outputs);
  return o;
}

std::vector<std::string> ran(const Plan& p) {
  std::vector<std::string> out;
  for (const PlannedPass* pp : p.running()) out.push_back(pp->name);
  return out;
}

const PlannedPass& get(const Plan& p, const std::string& name) {
  for (const PlannedPass& pp : p.passes)
    if (pp.name == name) return pp;
  throw std::runtime_error("no pass " + name);
}

std::string error_of(const std::vector<PassDecl>& decls, const CompileOptions& o) {
  try {
    compile(decls, o);
  } catch (const GraphError& e) {
    return e.what();
  }
  return "";
}

using Names = std::vector<std::string>;

TEST(GraphFormats, BytesPerTexelAndNames) {
  EXPECT_EQ(format_bytes_per_texel(Format::r32_uint), 4u);
  EXPECT_EQ(format_bytes_per_texel(Format::rg32_uint), 8u);
  EXPECT_EQ(format_bytes_per_texel(Format::rgba32_uint), 16u);
  EXPECT_EQ(format_bytes_per_texel(Format::r32_float), 4u);
  EXPECT_EQ(format_bytes_per_texel(Format::rg32_float), 8u);
  EXPECT_EQ(format_bytes_per_texel(Format::rgba32_float), 16u);
  EXPECT_EQ(format_bytes_per_texel(Format::rg16_float), 4u);
  EXPECT_EQ(format_bytes_per_texel(Format::rgba16_float), 8u);
  EXPECT_EQ(format_bytes_per_texel(Format::rgba8_unorm), 4u);
  EXPECT_EQ(format_bytes_per_texel(Format::b10g11r11_float), 4u);
  EXPECT_EQ(format_bytes_per_texel(Format::e5b9g9r9_float), 4u);
  EXPECT_EQ(format_bytes_per_texel(Format::d32_float), 4u);
  EXPECT_EQ(format_bytes_per_texel(Format::buffer), 0u);
  EXPECT_STREQ(format_name(Format::e5b9g9r9_float), "e5b9g9r9_float");
  EXPECT_STREQ(access_name(Access::read_prev), "read_prev");
  EXPECT_STREQ(pass_kind_name(PassKind::graphics), "graphics");
  EXPECT_EQ(describe(persistent(Format::r32_float, SizeRule::half)), "r32_float half persistent");
  EXPECT_EQ(describe(buffer(64)), "buffer 64 bytes");
  EXPECT_TRUE(same_desc(image(Format::r32_uint), image(Format::r32_uint)));
  EXPECT_FALSE(same_desc(image(Format::r32_uint), persistent(Format::r32_uint)));
  EXPECT_FALSE(same_desc(buffer(64), buffer(65)));
}

TEST(GraphOrder, ReverseDeclarationIsSortedByDependency) {
  std::vector<PassDecl> g = {
      pass("tonemap", {R("lit"), W("final_color", image(Format::rgba8_unorm))}),
      pass("shade", {R("gbuffer"), W("lit")}),
      pass("gbuffer", {R("vbuffer"), W("gbuffer")}),
      pass("visibility", {W("vbuffer", image(Format::rg32_uint))}, {}, PassKind::graphics),
  };
  Plan p = compile(g, opts({"final_color"}));
  EXPECT_EQ(ran(p), (Names{"visibility", "gbuffer", "shade", "tonemap"}));
  EXPECT_EQ(p.passes[0].decl_index, 3u);
  EXPECT_EQ(p.find("vbuffer")->producer, 0);
  EXPECT_EQ(p.find("final_color")->producer, 3);
}

TEST(GraphOrder, ReadWriteModifiersGoBetweenProducerAndReaders) {
  std::vector<PassDecl> g = {
      pass("present", {R("color"), W("final_color")}),
      pass("add_b", {RW("color")}),
      pass("add_a", {RW("color")}),
      pass("clear", {W("color")}),
  };
  Plan p = compile(g, opts({"final_color"}));
  // Modifiers keep their declaration order among themselves.
  EXPECT_EQ(ran(p), (Names{"clear", "add_b", "add_a", "present"}));
  EXPECT_EQ(p.find("color")->producer, 0);
  EXPECT_EQ(get(p, "add_a").bytes_written, uint64_t(256) * 144 * 8);
}

TEST(GraphOrder, IndependentPassesKeepDeclarationOrder) {
  std::vector<PassDecl> g = {
      pass("c", {W("z")}), pass("a", {W("x")}), pass("b", {W("y")}),
      pass("join", {R("y"), R("x"), R("z"), W("out")}),
  };
  Plan p = compile(g, opts({"out"}));
  EXPECT_EQ(ran(p), (Names{"c", "a", "b", "join"}));
}

TEST(GraphCull, ByFeatureWithReason) {
  std::vector<PassDecl> g = {
      pass("base", {W("color")}),
      pass("lights", {RW("color")}, SceneFeatures(Feature::local_lights) | Feature::sun),
      pass("out", {R("color"), W("final_color")}),
  };
  Plan p = compile(g, opts({"final_color"}, Feature::sun));
  EXPECT_EQ(ran(p), (Names{"base", "out"}));
  const PlannedPass& c = get(p, "lights");
  EXPECT_FALSE(c.runs);
  EXPECT_EQ(c.reason, "scene lacks " + to_string(SceneFeatures(Feature::local_lights)));
  // Culled passes come after the running ones.
  EXPECT_EQ(p.passes.back().name, "lights");
}

// A pass the settings switch off is culled with the pass's own words, whatever the scene has,
// even when it modifies a resource others read (the resource keeps its other writers).
TEST(GraphCull, SwitchedOffWithReason) {
  std::vector<PassDecl> g = {
      pass("base", {W("color")}),
      pass("extra", {RW("color")}),
      pass("out", {R("color"), W("final_color")}),
  };
  g[1].switched_off = "extra_light is 0";
  Plan p = compile(g, opts({"final_color"}, Feature::sun));
  EXPECT_EQ(ran(p), (Names{"base", "out"}));
  const PlannedPass& c = get(p, "extra");
  EXPECT_FALSE(c.runs);
  EXPECT_EQ(c.reason, "switched off: extra_light is 0");
  // Its only-readers cascade as after a missing feature.
  std::vector<PassDecl> h = {pass("make", {W("x")}), pass("use", {R("x"), W("out")})};
  h[0].switched_off = "make is 0";
  Plan q = compile(h, opts({"out"}));
  EXPECT_TRUE(q.running().empty());
  EXPECT_EQ(get(q, "use").reason, "input 'x' has no producer (make culled)");
}

TEST(GraphCull, CascadesThroughMissingInputs) {
  std::vector<PassDecl> g = {
      pass("light_grid", {W("light_grid", buffer(1024))}, Feature::local_lights),
      pass("cull_lights", {R("light_grid"), W("light_lists", buffer(4096))}),
      pass("shade_local", {R("light_lists"), W("local")}),
      pass("base", {W("color")}),
      pass("side", {R("local")}),  // a side effect still loses its input
  };
  g[4].side_effect = true;
  Plan p = compile(g, opts({"color"}));
  EXPECT_EQ(ran(p), (Names{"base"}));
  EXPECT_EQ(get(p, "cull_lights").reason, "input 'light_grid' has no producer (light_grid culled)");
  EXPECT_EQ(get(p, "shade_local").reason,
            "input 'light_lists' has no producer (cull_lights culled)");
  EXPECT_EQ(get(p, "side").reason, "input 'local' has no producer (shade_local culled)");
  // Culled ones in declaration order.
  std::vector<std::string> culled;
  for (const PlannedPass& pp : p.passes)
    if (!pp.runs) culled.push_back(pp.name);
  EXPECT_EQ(culled, (Names{"light_grid", "cull_lights", "shade_local", "side"}));
}

TEST(GraphCull, ReadWriteOfCulledWriterCascades) {
  std::vector<PassDecl> g = {
      pass("w", {W("x")}, Feature::motion),
      pass("m", {RW("x")}),
      pass("r", {R("x"), W("out")}),
  };
  Plan p = compile(g, opts({}));
  EXPECT_TRUE(p.running().empty());
  EXPECT_EQ(get(p, "m").reason, "input 'x' has no producer (w culled)");
  EXPECT_EQ(get(p, "r").reason, "input 'x' has no producer (w, m culled)");
}

TEST(GraphCull, ReadPrevOfCulledProducerCascades) {
  std::vector<PassDecl> g = {
      pass("accumulate", {RW("history", persistent(Format::rgba32_float))}, Feature::motion),
      pass("use", {RP("history"), W("out")}),
  };
  Plan p = compile(g, opts({"out"}));
  EXPECT_TRUE(p.running().empty());
  EXPECT_EQ(get(p, "use").reason, "input 'history' has no producer (accumulate culled)");
  ASSERT_EQ(p.unproduced_outputs.size(), 1u);
  EXPECT_EQ(p.unproduced_outputs[0], "out");
}

TEST(GraphCull, UnusedOutputsAndSideEffects) {
  std::vector<PassDecl> g = {
      pass("main", {W("color")}),
      pass("debug_view", {R("color"), W("debug")}),
      pass("stats", {R("color")}, {}, PassKind::transfer),
      pass("orphan", {W("nobody_reads")}),
      pass("final", {R("color"), W("final_color")}),
  };
  g[2].side_effect = true;
  Plan p = compile(g, opts({"final_color"}));
  EXPECT_EQ(ran(p), (Names{"main", "stats", "final"}));
  EXPECT_EQ(get(p, "debug_view").reason, "outputs unused");
  EXPECT_EQ(get(p, "orphan").reason, "outputs unused");
  EXPECT_EQ(p.find("debug"), nullptr);
  EXPECT_EQ(p.find("nobody_reads"), nullptr);

  // Asking for the debug output keeps its pass.
  Plan q = compile(g, opts({"debug"}));
  EXPECT_EQ(ran(q), (Names{"main", "debug_view", "stats"}));
  EXPECT_EQ(get(q, "final").reason, "outputs unused");
}

TEST(GraphCull, ReadPrevKeepsLastFramesProducer) {
  std::vector<PassDecl> g = {
      pass("trace", {RP("radiance_cache"), W("gather")}),
      pass("update_cache", {R("gather"), RW("radiance_cache", persistent(Format::rgba16_float))}),
      pass("resolve", {R("gather"), W("final_color")}),
  };
  Plan p = compile(g, opts({"final_color"}));
  // update_cache only matters through read_prev: still kept, and no ordering edge from it.
  EXPECT_EQ(ran(p), (Names{"trace", "update_cache", "resolve"}));
}

TEST(GraphError, CycleNamesPasses) {
  std::vector<PassDecl> g = {
      pass("start", {W("seed")}),
      pass("a", {R("seed"), R("y"), W("x")}),
      pass("b", {R("x"), W("y")}),
  };
  std::string e = error_of(g, opts({"x"}));
  EXPECT_NE(e.find("cycle"), std::string::npos) << e;
  EXPECT_NE(e.find("'a'"), std::string::npos) << e;
  EXPECT_NE(e.find("'b'"), std::string::npos) << e;
  EXPECT_EQ(e.find("'start'"), std::string::npos) << e;
}

TEST(GraphError, ReadWithoutWriter) {
  std::vector<PassDecl> g = {pass("shade", {R("gbuffer"), W("lit")})};
  EXPECT_EQ(error_of(g, opts({"lit"})), "pass 'shade' reads 'gbuffer' but no pass writes it");
  EXPECT_THROW(compile(g, opts({"lit"})), GraphError);
}

TEST(GraphError, ReadWriteOfTransientWithoutWriter) {
  std::vector<PassDecl> g = {pass("acc", {RW("sum")}), pass("out", {R("sum"), W("o")})};
  std::string e = error_of(g, opts({"o"}));
  EXPECT_NE(e.find("pass 'acc'"), std::string::npos) << e;
  EXPECT_NE(e.find("'sum'"), std::string::npos) << e;
}

TEST(GraphError, DoubleWriter) {
  std::vector<PassDecl> g = {pass("a", {W("x")}), pass("b", {W("x")})};
  EXPECT_EQ(error_of(g, opts({"x"})), "pass 'b' writes 'x' but pass 'a' already writes it");
}

TEST(GraphError, RequestedOutputMissing) {
  std::vector<PassDecl> g = {pass("a", {W("x")})};
  EXPECT_EQ(error_of(g, opts({"final_color"})),
            "requested output 'final_color' is not written by any pass");
}

TEST(GraphError, DescMismatchBetweenWriters) {
  std::vector<PassDecl> g = {
      pass("a", {W("x", image(Format::rgba16_float))}),
      pass("b", {RW("x", image(Format::r32_float, SizeRule::half))}),
  };
  std::string e = error_of(g, opts({"x"}));
  EXPECT_NE(e.find("pass 'b'"), std::string::npos) << e;
  EXPECT_NE(e.find("'x'"), std::string::npos) << e;
  EXPECT_NE(e.find("'a'"), std::string::npos) << e;
}

TEST(GraphError, ReadPrevOfNonPersistent) {
  std::vector<PassDecl> g = {pass("a", {W("x")}), pass("b", {RP("x"), W("y")})};
  std::string e = error_of(g, opts({"y"}));
  EXPECT_NE(e.find("pass 'b'"), std::string::npos) << e;
  EXPECT_NE(e.find("not persistent"), std::string::npos) << e;
}

TEST(GraphError, SlotDeclaredTwice) {
  std::vector<PassDecl> g = {pass("a", {W("x"), R("x")})};
  EXPECT_NE(error_of(g, opts({"x"})).find("twice"), std::string::npos);
}

TEST(GraphError, ErrorsDoNotDependOnFeatures) {
  // A broken graph is broken whatever the scene: the cycle sits in culled passes.
  std::vector<PassDecl> g = {
      pass("a", {R("y"), W("x")}, Feature::translucent),
      pass("b", {R("x"), W("y")}, Feature::translucent),
      pass("c", {W("z")}),
  };
  EXPECT_THROW(compile(g, opts({"z"})), GraphError);
}

TEST(GraphResources, HalfQuarterRoundUpAndPingPong) {
  std::vector<PassDecl> g = {
      pass("full", {W("full", image(Format::rgba32_float))}),
      pass("half", {R("full"), W("half", image(Format::r32_float, SizeRule::half))}),
      pass("quarter", {R("half"), W("quarter", image(Format::rgba16_float, SizeRule::quarter))}),
      pass("temporal", {R("quarter"), RP("history"),
                        W("history", persistent(Format::rgba16_float))}),
      pass("accum", {R("history"), RW("accum", persistent(Format::rgba32_float))}),
      pass("fixed", {W("atlas", [] {
             ResourceDesc d = image(Format::e5b9g9r9_float, SizeRule::fixed);
             d.width = 100;
             d.height = 30;
             return d;
           }())}),
      pass("buf", {R("atlas"), R("accum"), W("cells", buffer(12345))}),
  };
  CompileOptions o = opts({"cells"});
  o.render_width = 257;
  o.render_height = 143;
  Plan p = compile(g, o);
  ASSERT_EQ(p.running().size(), 7u);
  const ResolvedResource* full = p.find("full");
  EXPECT_EQ(full->width, 257u);
  EXPECT_EQ(full->bytes, uint64_t(257) * 143 * 16);
  const ResolvedResource* half = p.find("half");
  EXPECT_EQ(half->width, 129u);
  EXPECT_EQ(half->height, 72u);
  EXPECT_EQ(half->bytes, uint64_t(129) * 72 * 4);
  const ResolvedResource* quarter = p.find("quarter");
  EXPECT_EQ(quarter->width, 65u);
  EXPECT_EQ(quarter->height, 36u);
  const ResolvedResource* history = p.find("history");
  EXPECT_EQ(history->copies, 2u);
  EXPECT_EQ(history->bytes, uint64_t(257) * 143 * 8 * 2);
  EXPECT_EQ(get(p, "temporal").bytes_written, uint64_t(257) * 143 * 8);  // one copy per frame
  const ResolvedResource* accum = p.find("accum");  // persistent but no read_prev: one copy
  EXPECT_EQ(accum->copies, 1u);
  EXPECT_EQ(accum->bytes, uint64_t(257) * 143 * 16);
  EXPECT_EQ(p.find("atlas")->bytes, 100u * 30 * 4);
  EXPECT_EQ(p.find("cells")->bytes, 12345u);
  uint64_t sum = 0;
  for (const ResolvedResource& r : p.resources) sum += r.bytes;
  EXPECT_EQ(p.total_bytes(), sum);
}

TEST(GraphBarriers, PlacedOnDependenciesOnly) {
  std::vector<PassDecl> g = {
      pass("visibility", {W("vbuffer", image(Format::rg32_uint))}, {}, PassKind::graphics),
      pass("sky", {W("sky_lut", image(Format::rgba16_float, SizeRule::quarter))}),
      pass("shade", {R("vbuffer"), R("sky_lut"), W("color")}),
      pass("shade2", {R("vbuffer"), W("color2")}),
      pass("add", {RW("color"), R("color2")}),
      pass("copy_out", {R("color"), W("final_color")}, {}, PassKind::transfer),
  };
  Plan p = compile(g, opts({"final_color"}));
  ASSERT_EQ(ran(p), (Names{"visibility", "sky", "shade", "shade2", "add", "copy_out"}));
  // Independent passes: none.
  EXPECT_TRUE(get(p, "visibility").barrier_before.resources.empty());
  EXPECT_TRUE(get(p, "sky").barrier_before.resources.empty());
  // RAW from a graphics and a compute writer.
  const Barrier& b = get(p, "shade").barrier_before;
  EXPECT_EQ(b.resources, (Names{"vbuffer", "sky_lut"}));
  EXPECT_EQ(b.src_kinds, (1u << uint32_t(PassKind::graphics)) | (1u << uint32_t(PassKind::compute)));
  EXPECT_EQ(b.dst_kind, 1u << uint32_t(PassKind::compute));
  // vbuffer already made visible to compute: no second barrier.
  EXPECT_TRUE(get(p, "shade2").barrier_before.resources.empty());
  // read_write after a write, plus a read.
  EXPECT_EQ(get(p, "add").barrier_before.resources, (Names{"color", "color2"}));
  const Barrier& t = get(p, "copy_out").barrier_before;
  EXPECT_EQ(t.resources, (Names{"color"}));
  EXPECT_EQ(t.src_kinds, 1u << uint32_t(PassKind::compute));
  EXPECT_EQ(t.dst_kind, 1u << uint32_t(PassKind::transfer));
}

TEST(GraphBarriers, WriteAfterReadAndReadPrev) {
  std::vector<PassDecl> g = {
      pass("init", {W("x")}),
      pass("reader", {R("x"), W("y")}, {}, PassKind::graphics),
      pass("acc", {RW("acc", persistent(Format::rgba32_float)), R("y")}),
      pass("acc2", {RW("acc", persistent(Format::rgba32_float)), RP("hist")}),
      pass("hist", {R("acc"), W("hist", persistent(Format::rgba16_float))}),
  };
  Plan p = compile(g, opts({"hist"}));
  ASSERT_EQ(ran(p), (Names{"init", "reader", "acc", "acc2", "hist"}));
  // First touch of a persistent resource in the frame needs nothing (y does).
  EXPECT_EQ(get(p, "acc").barrier_before.resources, (Names{"y"}));
  // WAW on the accumulator; read_prev of hist adds nothing.
  EXPECT_EQ(get(p, "acc2").barrier_before.resources, (Names{"acc"}));
  EXPECT_EQ(get(p, "hist").barrier_before.resources, (Names{"acc"}));

  // A reader declared before the modifier of a persistent buffer still runs after it (RAW).
  std::vector<PassDecl> counter = {
      pass("peek", {R("counter"), W("a")}, {}, PassKind::transfer),
      pass("count", {RW("counter", persistent(Format::buffer, SizeRule::buffer))}),
  };
  counter[1].slots[0].desc.bytes = 16;
  Plan q = compile(counter, opts({"a"}));
  ASSERT_EQ(ran(q), (Names{"count", "peek"}));
  EXPECT_EQ(get(q, "peek").barrier_before.src_kinds, 1u << uint32_t(PassKind::compute));
  EXPECT_EQ(get(q, "peek").barrier_before.dst_kind, 1u << uint32_t(PassKind::transfer));
  EXPECT_EQ(q.find("counter")->bytes, 16u);
}

// A mini "direct" technique: which passes run per feature mix.
std::vector<PassDecl> mini_direct() {
  return {
      pass("visibility", {W("vbuffer", image(Format::rg32_uint)), W("depth", image(Format::d32_float))},
           {}, PassKind::graphics),
      pass("alpha_mask", {RW("vbuffer"), RW("depth")}, Feature::alpha_tested, PassKind::graphics),
      pass("gbuffer", {R("vbuffer"), W("gbuffer_normal"), W("gbuffer_albedo", image(Format::rgba8_unorm))}),
      pass("light_grid", {R("depth"), W("light_grid", buffer(1 << 20))}, Feature::local_lights),
      pass("sun_shadow", {R("depth"), W("shadow", image(Format::r32_float))}, Feature::sun),
      pass("direct", {R("gbuffer_normal"), R("gbuffer_albedo"), W("final_color")}),
      pass("direct_local", {R("light_grid"), R("gbuffer_normal"), RW("final_color")}),
      pass("direct_sun", {R("shadow"), RW("final_color")}),
      pass("debug_normals", {R("gbuffer_normal"), W("debug_normals")}),
  };
}

TEST(GraphCull, FeatureMixTable) {
  struct Row {
    SceneFeatures features;
    Names runs;
  };
  const SceneFeatures ll = Feature::local_lights, at = Feature::alpha_tested, sun = Feature::sun;
  const std::vector<Row> table = {
      {{}, {"visibility", "gbuffer", "direct"}},
      {ll, {"visibility", "gbuffer", "light_grid", "direct", "direct_local"}},
      {at | ll,
       {"visibility", "alpha_mask", "gbuffer", "light_grid", "direct", "direct_local"}},
      {at | ll | sun,
       {"visibility", "alpha_mask", "gbuffer", "light_grid", "sun_shadow", "direct",
        "direct_local", "direct_sun"}},
  };
  for (const Row& row : table) {
    Plan p = compile(mini_direct(), opts({"final_color"}, row.features));
    EXPECT_EQ(ran(p), row.runs) << to_string(row.features);
    EXPECT_EQ(get(p, "debug_normals").reason, "outputs unused");
  }
  Plan none = compile(mini_direct(), opts({"final_color"}));
  EXPECT_EQ(get(none, "light_grid").reason, "scene lacks " + to_string(ll));
  EXPECT_EQ(get(none, "direct_local").reason,
            "input 'light_grid' has no producer (light_grid culled)");
  EXPECT_EQ(get(none, "alpha_mask").reason, "scene lacks " + to_string(at));
  EXPECT_EQ(get(none, "direct_sun").reason, "input 'shadow' has no producer (sun_shadow culled)");
}

TEST(GraphDump, TextListsEveryPassAndReason) {
  Plan p = compile(mini_direct(), opts({"final_color"}, Feature::local_lights));
  std::string t = p.to_text();
  for (const PlannedPass& pp : p.passes) {
    EXPECT_NE(t.find(pp.name), std::string::npos) << pp.name;
    if (!pp.runs) {
      EXPECT_NE(t.find(pp.reason), std::string::npos) << pp.reason;
    }
  }
  for (const ResolvedResource& r : p.resources) EXPECT_NE(t.find(r.name), std::string::npos);
  EXPECT_NE(t.find("culled"), std::string::npos);
  EXPECT_NE(t.find("ran"), std::string::npos);
  EXPECT_NE(t.find("vbuffer:write"), std::string::npos);
  EXPECT_NE(t.find("rg32_uint"), std::string::npos);
  EXPECT_NE(t.find("256x144"), std::string::npos);
  EXPECT_NE(t.find("total:"), std::string::npos);
  EXPECT_NE(t.find(" MiB"), std::string::npos);
}

TEST(GraphDump, DotIsADigraph) {
  Plan p = compile(mini_direct(), opts({"final_color"}, Feature::local_lights));
  std::string d = p.to_dot();
  EXPECT_EQ(d.rfind("digraph", 0), 0u);
  EXPECT_EQ(d.back(), '\n');
  EXPECT_EQ(d.substr(d.size() - 2), "}\n");
  EXPECT_EQ(std::count(d.begin(), d.end(), '{'), std::count(d.begin(), d.end(), '}'));
  EXPECT_EQ(std::count(d.begin(), d.end(), '"') % 2, 0);
  EXPECT_NE(d.find("\"pass:visibility\" [shape=box"), std::string::npos);
  EXPECT_NE(d.find("\"res:vbuffer\" [shape=ellipse"), std::string::npos);
  EXPECT_NE(d.find("\"pass:visibility\" -> \"res:vbuffer\""), std::string::npos);
  EXPECT_NE(d.find("\"res:vbuffer\" -> \"pass:gbuffer\""), std::string::npos);
  EXPECT_NE(d.find("style=dashed"), std::string::npos);  // culled passes
  EXPECT_NE(d.find("culled: scene lacks"), std::string::npos);

  std::vector<PassDecl> g = {
      pass("t", {RP("h"), W("h", persistent(Format::rgba16_float))}),
  };
  std::string h = compile(g, opts({"h"})).to_dot();
  EXPECT_NE(h.find("\"res:h\" -> \"pass:t\" [style=dashed, label=\"prev\"];"), std::string::npos)
      << h;
}

}  // namespace
}  // namespace gib
