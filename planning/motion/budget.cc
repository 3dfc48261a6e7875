// The budget functions of planner.h: parsing and printing a budget, reading a report against one.

#include <algorithm>
#include <ctime>
#include <iterator>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>

#include "base/enum_names.h"
#include "base/numbers.h"
#include "base/str_cat.h"
#include "planning/motion/planner.h"

namespace planning {

// The units' names in --budget (kNone has none: no budget is written as "").
inline constexpr base::EnumName<Budget::Unit> kBudgetUnitNames[] = {
    {Budget::Unit::kQueries, "queries"},
    {Budget::Unit::kCpuTime, "time"},
    {Budget::Unit::kPairTests, "pairs"},
};
constexpr std::span<const base::EnumName<Budget::Unit>> EnumNames(Budget::Unit) {
  return kBudgetUnitNames;
}

double CpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

Budget ParseBudget(const std::string& text, const std::string& flag) {
  const auto bad = [&] {
    return std::invalid_argument(flag +
                                 ": expected time=SECONDS (CPU, > 0), queries=N (N >= 1 "
                                 "state queries) or pairs=N (N >= 1 pair tests), got '" +
                                 text + "'");
  };
  const size_t eq = text.find('=');
  const std::string key = eq == std::string::npos ? "queries" : text.substr(0, eq);
  const std::string value = eq == std::string::npos ? text : text.substr(eq + 1);
  Budget b;
  const auto named = std::find_if(std::begin(kBudgetUnitNames), std::end(kBudgetUnitNames),
                                  [&](const auto& e) { return key == e.name; });
  if (named == std::end(kBudgetUnitNames)) throw bad();
  b.unit = named->value;
  if (b.unit == Budget::Unit::kCpuTime) {  // seconds: a finite decimal number > 0
    const std::optional<double> v = base::ParseFiniteDouble(value);
    if (!v.has_value() || !(*v > 0.0)) throw bad();
    b.value = *v;
    return b;
  }
  // A count: a whole decimal number in [1, 1e12] (no sign, exponent or "0x").
  const std::optional<long long> n = base::ParseInteger(value);
  if (!n.has_value() || *n < 1 || *n > 1000000000000LL || value[0] == '+') throw bad();
  b.value = static_cast<double>(*n);
  return b;
}

std::string BudgetText(const Budget& budget) {
  if (budget.unit == Budget::Unit::kNone) return "";
  return base::StrCat(base::ToName(budget.unit), "=",
                      budget.unit == Budget::Unit::kCpuTime
                          ? base::FormatShortest(budget.value)
                          : std::to_string(static_cast<long long>(budget.value)));
}

bool SolvedWithin(const PlanReport& report, const Budget& budget) {
  if (!report.success) return false;
  switch (budget.unit) {
    case Budget::Unit::kQueries:
      return static_cast<double>(report.counts.state_queries) <= budget.value;
    case Budget::Unit::kCpuTime:
      return report.cpu_time_s <= budget.value;
    case Budget::Unit::kPairTests:
      return static_cast<double>(report.counts.pair_tests()) <= budget.value;
    case Budget::Unit::kNone:
      break;
  }
  return true;
}

void EnforceBudget(const Budget& budget, PlanReport* report) {
  if (!report->success || SolvedWithin(*report, budget)) return;
  report->success = false;
  report->status = SolveStatus::kBudgetExhausted;
  report->failure_reason = FailureReason::kBudgetExhausted;
}

}  // namespace planning
