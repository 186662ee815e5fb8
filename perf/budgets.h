// Per-category GPU budgets (data/budgets.json): which category each pass belongs to (art,
// lighting, shadows, system, ui, vfx, after God of War Ragnarök's budget table) and each
// profile's budget per category. `gibench bench` sums every run's console-scaled pass times
// into a tree per category against its budget and flags what is over (the talk's in-game
// "GPU Performance" tree view).
#pragma once
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace gib::perf {

struct BudgetCategory {
  std::string name;
  std::string owners;  // the teams the seed names for it
};
struct Budgets {
  std::string source;                                             // where the numbers come from
  std::vector<BudgetCategory> categories;                         // in the file's order
  std::map<std::string, std::string> pass_category;              // pass -> category
  std::map<std::string, std::map<std::string, double>> profiles;  // profile -> category -> ms
};
// Throws PerfError naming the file and the field on malformed input (unknown category of a
// pass or a budget, a budget not a positive number, a missing key).
Budgets parse_budgets(const nlohmann::json& doc, const std::string& file);
Budgets load_budgets(const std::string& path);

// One category of a frame: its passes' scaled times, their sum, its budget (0: none for the
// profile) and whether the sum is over it. Passes the file does not map go to "uncategorised",
// which has no budget.
struct CategoryCost {
  std::string name;
  double budget_ms = 0;
  double total_ms = 0;
  bool over = false;
  std::vector<std::pair<std::string, double>> passes;  // in the order given
};
struct BudgetTree {
  std::string profile;
  double total_ms = 0, budget_ms = 0;  // budget_ms: the profile's categories summed
  bool over = false;                   // the frame over the total budget
  std::vector<CategoryCost> categories;  // the file's order, then uncategorised (when any)
};
BudgetTree budget_tree(const Budgets& b, const std::string& profile,
                       const std::vector<std::pair<std::string, double>>& pass_ms);
std::string format_budget_tree(const BudgetTree& t);  // the text tree `bench` prints
nlohmann::json to_json(const BudgetTree& t);
// A self-contained HTML page with one tree per entry (bars against the budget, over in red).
std::string budget_html(const std::vector<std::pair<std::string, BudgetTree>>& trees);

}  // namespace gib::perf
