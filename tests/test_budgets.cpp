// Per-category GPU budgets (perf/budgets.h, data/budgets.json): the tree on known inputs, the
// loader's errors, and the shipped file against the seed's figures.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "perf/budgets.h"
#include "perf/profiles.h"
#include "renderer/techniques/technique.h"

namespace gib::perf {
namespace {

using nlohmann::json;

json small_budgets() {
  return json::parse(R"({
    "source": "test",
    "order": ["art", "shadows"],
    "categories": {"art": "Art", "shadows": "Lighting"},
    "profiles": {"ps4": {"art": 2.0, "shadows": 1.0}},
    "passes": {"visibility": "art", "gbuffer": "art", "shadow_maps": "shadows"}
  })");
}

TEST(Budgets, TreeSumsPassesPerCategoryAndFlagsWhatIsOver) {
  Budgets b = parse_budgets(small_budgets(), "test.json");
  BudgetTree t = budget_tree(b, "ps4", {{"visibility", 0.5}, {"shadow_maps", 1.25}, {"gbuffer", 1.0}, {"mystery", 0.1}});
  ASSERT_EQ(t.categories.size(), 3u);
  EXPECT_EQ(t.categories[0].name, "art");
  EXPECT_DOUBLE_EQ(t.categories[0].total_ms, 1.5);
  EXPECT_DOUBLE_EQ(t.categories[0].budget_ms, 2.0);
  EXPECT_FALSE(t.categories[0].over);
  EXPECT_EQ(t.categories[0].passes.size(), 2u);
  EXPECT_EQ(t.categories[1].name, "shadows");
  EXPECT_DOUBLE_EQ(t.categories[1].total_ms, 1.25);
  EXPECT_TRUE(t.categories[1].over);
  EXPECT_EQ(t.categories[2].name, "uncategorised");
  EXPECT_DOUBLE_EQ(t.categories[2].budget_ms, 0.0);
  EXPECT_FALSE(t.categories[2].over);  // no budget, never over
  EXPECT_DOUBLE_EQ(t.total_ms, 2.85);
  EXPECT_DOUBLE_EQ(t.budget_ms, 3.0);
  EXPECT_FALSE(t.over);
  // At exactly the budget: not over; a frame over the total: over.
  EXPECT_FALSE(budget_tree(b, "ps4", {{"shadow_maps", 1.0}}).categories[1].over);
  EXPECT_TRUE(budget_tree(b, "ps4", {{"visibility", 2.5}, {"shadow_maps", 1.0}}).over);
  // A profile without budgets: sums, no budget, nothing over.
  BudgetTree none = budget_tree(b, "ps5", {{"visibility", 9.0}});
  EXPECT_DOUBLE_EQ(none.total_ms, 9.0);
  EXPECT_FALSE(none.over);
  const std::string text = format_budget_tree(t);
  EXPECT_NE(text.find("OVER by 0.250 ms"), std::string::npos) << text;
  EXPECT_NE(budget_html({{"t", t}}).find("class=\"cat over\""), std::string::npos);
  EXPECT_EQ(to_json(t)["categories"][1]["over"], true);
}

TEST(Budgets, BadFilesNameTheField) {
  auto message = [](json doc) {
    try {
      parse_budgets(doc, "b.json");
    } catch (const PerfError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  json d = small_budgets();
  d["passes"]["visibility"] = "arts";
  EXPECT_NE(message(d).find("b.json: passes/visibility: expected one of the categories"), std::string::npos) << message(d);
  d = small_budgets();
  d["profiles"]["ps4"]["art"] = -1;
  EXPECT_NE(message(d).find("profiles/ps4/art: expected a positive number"), std::string::npos) << message(d);
  d = small_budgets();
  d["profiles"]["ps4"]["hud"] = 1;
  EXPECT_NE(message(d).find("profiles/ps4/hud"), std::string::npos) << message(d);
  d = small_budgets();
  d.erase("source");
  EXPECT_NE(message(d).find("b.json: source"), std::string::npos) << message(d);
}

// The shipped file: the PS4 budgets are the seed's (data/seed-timings.json ps4_budgets_ms, whose
// total is the talk's 33.25 ms), and every pass it names exists.
TEST(Budgets, ShippedFileMatchesTheSeed) {
  const std::string dir = std::string(GIB_SOURCE_DIR) + "/data";
  Budgets b = load_budgets(dir + "/budgets.json");
  std::ifstream in(dir + "/seed-timings.json");
  json seed = json::parse(in)["god_of_war_ragnarok"]["ps4_budgets_ms"];
  double sum = 0;
  for (auto& [cat, ms] : b.profiles.at("ps4")) {
    EXPECT_DOUBLE_EQ(ms, seed.at(cat).get<double>()) << cat;
    sum += ms;
  }
  EXPECT_EQ(b.profiles.at("ps4").size(), 6u);
  EXPECT_DOUBLE_EQ(sum, seed.at("total").get<double>());
  const std::vector<std::string> known = pass_names();
  for (auto& [pass, cat] : b.pass_category)
    EXPECT_NE(std::find(known.begin(), known.end(), pass), known.end()) << pass << " is no pass";
  // Every gow-ragnarok pass has its category from the talk's tree (bench times the reflection
  // passes too, now that it plans every contract AOV): shadow-map rendering and its min/max
  // are Shadows; the filtered shadow resolve ("DeferredShadows"), SSDO/SSGI and the
  // reflections (SSR and the environment maps are Lighting in the talk) are Lighting.
  for (const char* pass : {"shadow_maps", "shadow_minmax"}) EXPECT_EQ(b.pass_category.at(pass), "shadows") << pass;
  for (const char* pass : {"shadows_pcf", "shadows_contact_hardening", "ssdo_ssgi", "ssdo", "ssgi", "direct_aov", "direct_lighting",
                           "cubemap_capture", "reflections_rt_cubemap", "reflections_resolve"})
    EXPECT_EQ(b.pass_category.at(pass), "lighting") << pass;
  for (const char* pass : {"visibility", "gbuffer"}) EXPECT_EQ(b.pass_category.at(pass), "art") << pass;
}

}  // namespace
}  // namespace gib::perf
