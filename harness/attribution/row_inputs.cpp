#include "harness/attribution/row_inputs.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>

#include "harness/case_render.h"

namespace gib {

uint32_t reference_frame(const Case& c, uint32_t f) { return per_frame_references(c) ? f : 0; }

FloatImage read_reference(const GoldenStore& store, const Case& c, const std::string& aov, uint32_t frame) {
  const std::string stem = GoldenStore::reference_stem(aov, c.output, frame);
  const std::string path = store.find(stem, "");
  if (path.empty())
    throw std::runtime_error(fmt::format("attribute: {}: no reference '{}' in {} (gibench update-goldens --case {} "
                                         "--reference creates it)", c.name, stem, store.dir(), c.name));
  return store.read(path);
}

std::vector<double> reference_noise(Gpu& gpu, const Case& c, const std::string& aov, uint32_t spp,
                                    uint32_t committed_spp, const std::vector<attribution::NamedRoi>& rois,
                                    uint32_t frame) {
  TechniqueRun ref;
  ref.technique = "reference";
  ref.presets = {"ultra"};
  ref.spp = spp;
  ref.compare_aov = aov;
  const FloatImage a = render_case(gpu, c, ref, "ultra", 7001, frame).image;
  const FloatImage b = render_case(gpu, c, ref, "ultra", 7002, frame).image;
  std::vector<double> out;
  for (const attribution::NamedRoi& r : rois) {
    const attribution::RoiError e = attribution::roi_error({a}, b, metrics::roi_pixels(r.box, a.width, a.height));
    out.push_back(e.mse / 2.0 * double(spp) / double(std::max<uint32_t>(committed_spp, 1)));
  }
  return out;
}

OracleInputs oracle_inputs(const OracleRow& row, const std::vector<size_t>& game, uint32_t frozen,
                           const std::function<double()>& elapsed) {
  const Case& c = row.c;
  const Technique& t = row.t;
  OracleInputs in;
  in.width = c.width;
  in.height = c.height;
  const FloatImage constant(c.width, c.height, 4, float(c.analytic_value.value_or(0.0)));
  in.reference[row.aov] = row.analytic ? constant : read_reference(row.store, c, row.aov, frozen);
  RunHooks reads;
  reads.read_frames = row.st.oracle_frames;
  reads.frozen_frame = frozen;
  bool derive_indirect = false;  // analytic: indirect_diffuse = the value - the technique's direct
  for (size_t i : game) {
    for (const std::string& a : t.stages[i].reference_aovs) {
      if (in.reference.count(a)) continue;
      if (!row.analytic) {
        in.reference[a] = read_reference(row.store, c, a, frozen);
      } else if (!derive_indirect) {
        derive_indirect = true;
        reads.read.push_back(t.contract_aovs.at("direct"));
      }
    }
    for (const std::string& r : t.stages[i].seed_reads) reads.read.push_back(r);
  }
  for (uint32_t s = 0; s < row.st.oracle_seeds; ++s) {
    CaseRender r = render_case_hooked(row.gpu, c, row.run, row.preset, 1000 + s, reads);
    for (const std::string& name : reads.read) {
      const ResolvedResource* res = r.plan.find(name);
      in.formats[name] = res->desc.format;
      in.extents[name] = {res->width, res->height};
    }
    for (auto& before : r.read_before) in.seeds.push_back(std::move(before));
    in.seeds.push_back(std::move(r.read));
    if (row.verbose)
      fmt::print("  oracle seed render {}/{}{}, reads of its last {} frames ({:.0f} s)\n", s + 1, row.st.oracle_seeds,
                 frozen ? fmt::format(" of the scene frozen at frame {}", frozen) : "", r.read_before.size() + 1,
                 elapsed());
    std::fflush(stdout);
  }
  if (derive_indirect) {
    const std::string direct = t.contract_aovs.at("direct");
    FloatImage indirect = constant;
    for (const auto& seed : in.seeds) {
      const FloatImage d = decode_texels(in.formats.at(direct), c.width, c.height, seed.at(direct));
      for (size_t i = 0; i < indirect.pixels.size(); ++i) indirect.pixels[i] -= d.pixels[i] / float(in.seeds.size());
    }
    in.reference["indirect_diffuse"] = indirect;
    if (row.verbose)
      fmt::print("  analytic: indirect_diffuse reference = {} - the seeds' mean {}\n", *c.analytic_value, direct);
  }
  return in;
}

}  // namespace gib
