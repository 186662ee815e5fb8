// The graph-level override of named resources (Executor::add_override): after a named pass
// writes a resource, the override's data replaces it, and every later reader sees the data.
// Synthetic transfer passes, no technique.
#include <gtest/gtest.h>

#include <cstring>

#include "renderer/graph/executor.h"
#include "renderer/scene/scene_loader.h"
#include "tests/gpu_fixture.h"

namespace gib {
namespace {

constexpr uint64_t kBufferBytes = 64;

ResourceDesc image_desc() { return ResourceDesc{Format::rgba32_float, SizeRule::render}; }
ResourceDesc buffer_desc() {
  ResourceDesc d;
  d.format = Format::buffer;
  d.size = SizeRule::buffer;
  d.bytes = kBufferBytes;
  return d;
}
PassDecl transfer_pass(const char* name, std::vector<Slot> slots) {
  PassDecl d;
  d.name = name;
  d.kind = PassKind::transfer;
  d.slots = std::move(slots);
  return d;
}

// "produce": clears image `a` to 1 and fills buffer `buf` with 0x01010101; "consume": copies
// them into `b` and `buf2`.
class Produce final : public Pass {
 public:
  PassDecl declare(const Scene&, const Settings&) const override {
    return transfer_pass("produce", {{"a", Access::write, image_desc()}, {"buf", Access::write, buffer_desc()}});
  }
  void record(RecordContext& ctx) override {
    const float one[4] = {1, 1, 1, 1};
    ctx.cmd.clear(ctx.image("a"), one);
    ctx.cmd.fill(ctx.buffer("buf"), 0x01010101u);
  }
};

class Consume final : public Pass {
 public:
  PassDecl declare(const Scene&, const Settings&) const override {
    return transfer_pass("consume", {{"a", Access::read},
                                     {"buf", Access::read},
                                     {"b", Access::write, image_desc()},
                                     {"buf2", Access::write, buffer_desc()}});
  }
  void record(RecordContext& ctx) override {
    ctx.cmd.copy(ctx.image("a"), ctx.image("b"));
    ctx.cmd.copy(ctx.buffer("buf"), ctx.buffer("buf2"));
  }
};

class ResourceOverrideTest : public test::GpuTest {
 protected:
  std::unique_ptr<Executor> make() {
    scene_ = load_scene(std::string(GIB_SOURCE_DIR) + "/cases/scenes/cornell.json");
    Settings s;
    s.width = 8;
    s.height = 4;
    std::vector<std::unique_ptr<Pass>> passes;
    passes.push_back(std::make_unique<Produce>());
    passes.push_back(std::make_unique<Consume>());
    return std::make_unique<Executor>(gpu(), scene_, s, std::move(passes), std::vector<std::string>{"b", "buf2"});
  }
  Scene scene_;
};

TEST_F(ResourceOverrideTest, LaterPassesReadTheOverride) {
  auto ex = make();
  // Without an override the consumer sees the producer's values.
  ex->run_frame();
  EXPECT_EQ(ex->read("b").at(3, 2, 0), 1.0f);
  std::vector<uint8_t> before = ex->read_buffer("buf2");
  EXPECT_EQ(before[0], 1);

  std::vector<float> texels(8 * 4 * 4);
  for (size_t i = 0; i < texels.size(); ++i) texels[i] = float(i) * 0.5f;
  ResourceOverride img{"produce", "a", std::vector<uint8_t>(texels.size() * 4)};
  std::memcpy(img.data.data(), texels.data(), img.data.size());
  ex->add_override(img);
  ResourceOverride buf{"produce", "buf", std::vector<uint8_t>(kBufferBytes)};
  for (size_t i = 0; i < buf.data.size(); ++i) buf.data[i] = uint8_t(200 - i);
  ex->add_override(buf);
  for (int f = 0; f < 2; ++f) {  // every frame, not only the first after adding it
    ex->run_frame();
    FloatImage b = ex->read("b");
    for (uint32_t y = 0; y < 4; ++y)
      for (uint32_t x = 0; x < 8; ++x)
        for (uint32_t c = 0; c < 4; ++c) ASSERT_EQ(b.at(x, y, c), texels[(y * 8 + x) * 4 + c]) << x << "," << y;
    EXPECT_EQ(ex->read_buffer("buf2"), buf.data);
    EXPECT_EQ(ex->read("a").at(1, 0, 0), 2.0f);  // the overridden resource itself holds the data
  }
}

TEST_F(ResourceOverrideTest, BadOverridesAreOneClearError) {
  auto ex = make();
  auto expect_error = [&](const ResourceOverride& o, const std::string& part) {
    try {
      ex->add_override(o);
      ADD_FAILURE() << "no error for " << o.after_pass << "/" << o.resource;
    } catch (const GraphError& e) {
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    }
  };
  expect_error({"nowhere", "a", std::vector<uint8_t>(8 * 4 * 16)}, "expected a running pass, got 'nowhere'");
  expect_error({"consume", "a", std::vector<uint8_t>(8 * 4 * 16)}, "expected a resource it writes, got 'a'");
  expect_error({"produce", "a", std::vector<uint8_t>(10)}, "expected 512 bytes (8x4 rgba32_float), got 10");
  expect_error({"produce", "buf", std::vector<uint8_t>(10)}, "expected 64 bytes (the buffer), got 10");
}

// Overrides over frame ranges: two of one resource, each over its own frames (a lag oracle
// that follows a moving scene), and none outside them.
TEST_F(ResourceOverrideTest, OverridesHoldOverTheirFramesOnly) {
  auto ex = make();
  auto filled = [](float v) {
    std::vector<float> texels(8 * 4 * 4, v);
    std::vector<uint8_t> bytes(texels.size() * 4);
    std::memcpy(bytes.data(), texels.data(), bytes.size());
    return bytes;
  };
  ex->add_override({"produce", "a", filled(2.0f), 1, 2});
  ex->add_override({"produce", "a", filled(3.0f), 3, UINT32_MAX});
  const float expected[] = {1.0f, 2.0f, 2.0f, 3.0f, 3.0f};
  for (float e : expected) {
    ex->run_frame();
    EXPECT_EQ(ex->read("b").at(5, 3, 1), e) << "frame " << ex->frames_run() - 1;
  }
  try {
    ex->add_override({"produce", "a", filled(1.0f), 4, 3});
    ADD_FAILURE();
  } catch (const GraphError& e) {
    EXPECT_NE(std::string(e.what()).find("expected first_frame <= last_frame, got 4 > 3"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace gib
