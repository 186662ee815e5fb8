#include "perf/budgets.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "perf/profiles.h"

namespace gib::perf {
namespace {

const char* kUncategorised = "uncategorised";

std::string html_escape(const std::string& s) {
  std::string o;
  for (char c : s) {
    if (c == '<') o += "&lt;";
    else if (c == '>') o += "&gt;";
    else if (c == '&') o += "&amp;";
    else if (c == '"') o += "&quot;";
    else o += c;
  }
  return o;
}

}  // namespace

Budgets parse_budgets(const nlohmann::json& doc, const std::string& file) {
  auto fail = [&](const std::string& field, const std::string& what) {
    throw PerfError(fmt::format("{}: {}: expected {}", file, field, what));
  };
  if (!doc.is_object()) fail("(top level)", "an object");
  Budgets b;
  if (!doc.contains("source") || !doc["source"].is_string()) fail("source", "a string naming where the budgets come from");
  b.source = doc["source"].get<std::string>();
  if (!doc.contains("categories") || !doc["categories"].is_object() || doc["categories"].empty())
    fail("categories", "an object of category -> owners (string)");
  std::set<std::string> names;
  // nlohmann::json objects iterate sorted; the file's order is kept in "order" when given.
  std::vector<std::string> order;
  if (doc.contains("order")) {
    if (!doc["order"].is_array()) fail("order", "an array of category names");
    for (auto& n : doc["order"]) {
      if (!n.is_string() || !doc["categories"].contains(n.get<std::string>()))
        fail("order", "names of categories");
      order.push_back(n.get<std::string>());
    }
  }
  for (auto& [name, owners] : doc["categories"].items()) {
    if (!owners.is_string()) fail("categories/" + name, "a string (the owning teams)");
    names.insert(name);
    if (std::find(order.begin(), order.end(), name) == order.end()) order.push_back(name);
  }
  for (auto& n : order) b.categories.push_back({n, doc["categories"][n].get<std::string>()});
  if (!doc.contains("passes") || !doc["passes"].is_object()) fail("passes", "an object of pass -> category");
  for (auto& [pass, cat] : doc["passes"].items()) {
    if (!cat.is_string() || !names.count(cat.get<std::string>()))
      fail("passes/" + pass, fmt::format("one of the categories, got {}", cat.dump()));
    b.pass_category[pass] = cat.get<std::string>();
  }
  if (!doc.contains("profiles") || !doc["profiles"].is_object()) fail("profiles", "an object of profile -> budgets");
  for (auto& [profile, cats] : doc["profiles"].items()) {
    if (!cats.is_object()) fail("profiles/" + profile, "an object of category -> ms");
    for (auto& [cat, ms] : cats.items()) {
      if (!names.count(cat)) fail("profiles/" + profile + "/" + cat, "a category of `categories`");
      if (!ms.is_number() || !(ms.get<double>() > 0) || !std::isfinite(ms.get<double>()))
        fail("profiles/" + profile + "/" + cat, fmt::format("a positive number of ms, got {}", ms.dump()));
      b.profiles[profile][cat] = ms.get<double>();
    }
  }
  return b;
}

Budgets load_budgets(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw PerfError(fmt::format("{}: cannot open the budgets file", path));
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw PerfError(fmt::format("{}: not JSON: {}", path, e.what()));
  }
  return parse_budgets(doc, path);
}

BudgetTree budget_tree(const Budgets& b, const std::string& profile,
                       const std::vector<std::pair<std::string, double>>& pass_ms) {
  BudgetTree t;
  t.profile = profile;
  auto budgets = b.profiles.find(profile);
  for (auto& c : b.categories) {
    CategoryCost cc;
    cc.name = c.name;
    if (budgets != b.profiles.end() && budgets->second.count(c.name)) cc.budget_ms = budgets->second.at(c.name);
    t.categories.push_back(cc);
  }
  CategoryCost other;
  other.name = kUncategorised;
  for (auto& [pass, ms] : pass_ms) {
    auto it = b.pass_category.find(pass);
    CategoryCost* cc = &other;
    if (it != b.pass_category.end())
      for (auto& c : t.categories)
        if (c.name == it->second) cc = &c;
    cc->passes.push_back({pass, ms});
    cc->total_ms += ms;
  }
  if (!other.passes.empty()) t.categories.push_back(other);
  for (auto& c : t.categories) {
    c.over = c.budget_ms > 0 && c.total_ms > c.budget_ms;
    t.total_ms += c.total_ms;
    t.budget_ms += c.budget_ms;
  }
  t.over = t.budget_ms > 0 && t.total_ms > t.budget_ms;
  return t;
}

std::string format_budget_tree(const BudgetTree& t) {
  std::string out = fmt::format("{:<34} {:>10} {:>10}\n", fmt::format("{} (total)", t.profile), "ms", "budget");
  auto budget = [](double ms) { return ms > 0 ? fmt::format("{:.2f}", ms) : std::string("-"); };
  out += fmt::format("{:<34} {:>10.3f} {:>10}{}\n", "frame", t.total_ms, budget(t.budget_ms), t.over ? "  OVER" : "");
  for (auto& c : t.categories) {
    out += fmt::format("  {:<32} {:>10.3f} {:>10}{}\n", c.name, c.total_ms, budget(c.budget_ms),
                       c.over ? fmt::format("  OVER by {:.3f} ms", c.total_ms - c.budget_ms) : "");
    for (auto& [pass, ms] : c.passes) out += fmt::format("    {:<30} {:>10.3f}\n", pass, ms);
  }
  return out;
}

nlohmann::json to_json(const BudgetTree& t) {
  nlohmann::json j{{"profile", t.profile}, {"total_ms", t.total_ms}, {"budget_ms", t.budget_ms}, {"over", t.over}};
  auto& cats = j["categories"] = nlohmann::json::array();
  for (auto& c : t.categories) {
    nlohmann::json jc{{"name", c.name}, {"total_ms", c.total_ms}, {"budget_ms", c.budget_ms}, {"over", c.over}};
    for (auto& [pass, ms] : c.passes) jc["passes"].push_back({{"pass", pass}, {"ms", ms}});
    cats.push_back(jc);
  }
  return j;
}

std::string budget_html(const std::vector<std::pair<std::string, BudgetTree>>& trees) {
  std::ostringstream o;
  o << "<!doctype html><meta charset=utf-8><title>GPU budgets</title><style>"
       "body{font:13px system-ui,sans-serif;margin:2em}table{border-collapse:collapse;margin:0 0 2em}"
       "td,th{padding:2px 8px;text-align:left}td.n{text-align:right;font-variant-numeric:tabular-nums}"
       "tr.cat td{font-weight:600;border-top:1px solid #ccc}tr.pass td:first-child{padding-left:2em;color:#444}"
       ".bar{background:#9bc;height:10px}.over .bar{background:#d44}.over td{color:#b00}</style>"
       "<h1>GPU budgets (console-scaled pass times)</h1>";
  for (auto& [title, t] : trees) {
    o << "<h2>" << html_escape(title) << "</h2><table><tr><th>name</th><th>ms</th><th>budget</th><th></th></tr>";
    o << fmt::format("<tr class=\"cat{}\"><td>frame</td><td class=n>{:.3f}</td><td class=n>{}</td><td></td></tr>",
                     t.over ? " over" : "", t.total_ms, t.budget_ms > 0 ? fmt::format("{:.2f}", t.budget_ms) : "-");
    for (auto& c : t.categories) {
      const double scale = c.budget_ms > 0 ? c.budget_ms : std::max(c.total_ms, 1e-9);
      const double width = std::min(200.0, 100.0 * c.total_ms / scale);
      o << fmt::format(
          "<tr class=\"cat{}\"><td>{}</td><td class=n>{:.3f}</td><td class=n>{}</td><td><div class=bar "
          "style=\"width:{:.0f}px\"></div></td></tr>",
          c.over ? " over" : "", html_escape(c.name), c.total_ms,
          c.budget_ms > 0 ? fmt::format("{:.2f}", c.budget_ms) : "-", width);
      for (auto& [pass, ms] : c.passes)
        o << fmt::format("<tr class=pass><td>{}</td><td class=n>{:.3f}</td><td></td><td></td></tr>", html_escape(pass), ms);
    }
    o << "</table>";
  }
  return o.str();
}

}  // namespace gib::perf
