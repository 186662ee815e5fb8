// gibench: the command line. Every error becomes one line on stderr and a non-zero exit.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <exception>

#include "harness/render.h"

int main(int argc, char** argv) {
  CLI::App app{"gibench: rendering test and benchmark harness for real-time GI"};
  app.require_subcommand(1);

  app.add_subcommand("devices", "list Vulkan devices and which one is the default");

  gib::RenderOptions ro;
  auto* render = app.add_subcommand("render", "render a scene with a technique");
  render->add_option("--scene", ro.scene, "scene JSON file")->required();
  render->add_option("--technique", ro.technique, "direct | reference");
  render->add_option("--preset", ro.preset, "low | medium | high | ultra");
  render->add_option("--spp", ro.spp, "reference: samples per pixel in total (default 64)");
  render->add_option("--frames", ro.frames, "frames to run (temporal techniques, timing)");
  std::string size = "256x144";
  render->add_option("--size", size, "render size WxH");
  render->add_option("--seed", ro.seed, "random seed");
  render->add_option("--device", ro.device, "device index or name substring");
  render->add_flag("--validate", ro.validate, "enable Vulkan validation; messages fail the run");
  render->add_flag("--plan", ro.plan_only, "print the plan (ran / culled and why) and exit");
  render->add_option("--dump-graph", ro.dot, "write the graph as graphviz .dot");
  render->add_option("--dump", ro.dumps, "also write this resource as EXR (repeatable)");
  render->add_option("--out", ro.out, "output EXR (a PNG preview is written beside it)");
  render->add_option("--json", ro.json, "write device, plan and timings as JSON");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  try {
    if (app.got_subcommand("devices")) return gib::cmd_devices();
    if (app.got_subcommand("render")) {
      unsigned w = 0, h = 0;
      char x = 0;
      if (std::sscanf(size.c_str(), "%u%c%u", &w, &x, &h) != 3 || x != 'x' || w == 0 || h == 0 || w > 16384 || h > 16384)
        throw std::invalid_argument(fmt::format("--size: expected WxH like 256x144, got '{}'", size));
      ro.width = w;
      ro.height = h;
      return gib::cmd_render(ro);
    }
  } catch (const std::exception& e) {
    fmt::print(stderr, "gibench: error: {}\n", e.what());
    return 2;
  }
  return 0;
}
