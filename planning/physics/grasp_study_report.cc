// grasp.csv, paired statistics and tables of the grasp study (grasp_study_report.h).
#include "planning/physics/grasp_study_report.h"

#include <cstdio>
#include <map>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "base/str_cat.h"
#include "planning/grasp/grasp_quality.h"

namespace planning::physics {
namespace {

using base::StrCat;

std::string Format(const char* fmt, double v) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), fmt, v);
  return buf;
}

std::string Optional(const std::optional<double>& v) {
  return v ? Format("%.4f", *v) : std::string();
}

std::vector<std::string> SplitCsv(const std::string& line) {
  std::vector<std::string> out;
  std::string field;
  std::istringstream in(line);
  while (std::getline(in, field, ',')) out.push_back(field);
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

int ToInt(const std::string& s, const char* what) {
  try {
    size_t used = 0;
    const long v = std::stol(s, &used);
    if (used != s.size()) throw std::invalid_argument(what);
    return static_cast<int>(v);
  } catch (const std::exception&) {
    throw std::invalid_argument(StrCat("grasp.csv: bad ", what, " '", s, "'"));
  }
}

double ToDouble(const std::string& s, const char* what) {
  try {
    size_t used = 0;
    const double v = std::stod(s, &used);
    if (used != s.size()) throw std::invalid_argument(what);
    return v;
  } catch (const std::exception&) {
    throw std::invalid_argument(StrCat("grasp.csv: bad ", what, " '", s, "'"));
  }
}

bool InSubset(const StudyRow& r, StudySubset s) {
  return s == StudySubset::kAll || (s == StudySubset::kThreading) == r.threading;
}

std::string Count(int k, int n, const Eigen::Vector2d& ci) {
  if (n == 0) return "–";
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%d/%d (%.2f–%.2f)", k, n, ci[0], ci[1]);
  return buf;
}

}  // namespace

std::string StudyCsvHeader() {
  return "grasp,object,class,demo,seed,method,ode_stable,ode_directions,ode_status,"
         "mujoco_stable,mujoco_directions,mujoco_status,iou_thumb,iou_finger_1,iou_finger_2,"
         "iou_mean,demo_threads,threads_preserved,starts,task_evaluations,iterations,"
         "winding_error,min_clearance_m";
}

std::string StudyCsvRow(const StudyRow& r) {
  std::string s = StrCat(r.grasp, ",", r.object, ",", r.threading ? "threading" : "control", ",",
                         std::to_string(r.demo), ",", std::to_string(r.seed), ",",
                         ToString(r.method), ",", r.ode_stable ? "1" : "0", ",",
                         std::to_string(r.ode_directions), ",", ToString(r.ode_status), ",");
  if (r.mujoco_stable) {
    s.append(StrCat(*r.mujoco_stable ? "1" : "0", ",", std::to_string(r.mujoco_directions), ",",
                    ToString(r.mujoco_status)));
  } else {
    s.append(",,");
  }
  for (const std::optional<double>& v : r.iou) s.append(StrCat(",", Optional(v)));
  s.append(StrCat(",", Optional(r.MeanIoU()), ",", std::to_string(r.demo_threads), ",",
                  std::to_string(r.threads_preserved), ",", std::to_string(r.starts), ",",
                  std::to_string(r.task_evaluations), ",", std::to_string(r.iterations), ",",
                  Format("%.6g", r.winding_error), ",", Format("%.6g", r.min_clearance)));
  return s;
}

StudyRow ParseStudyCsvRow(const std::string& line) {
  const std::vector<std::string> f = SplitCsv(line);
  if (f.size() != 23) {
    throw std::invalid_argument(
        StrCat("grasp.csv: expected 23 columns, got ", std::to_string(f.size())));
  }
  StudyRow r;
  r.grasp = f[0];
  r.object = f[1];
  if (f[2] != "threading" && f[2] != "control") {
    throw std::invalid_argument(StrCat("grasp.csv: bad class '", f[2], "'"));
  }
  r.threading = f[2] == "threading";
  r.demo = ToInt(f[3], "demo");
  r.seed = static_cast<std::uint32_t>(std::stoul(f[4]));
  r.method = ParseTransferMethod(f[5]);
  r.ode_stable = ToInt(f[6], "ode_stable") != 0;
  r.ode_directions = ToInt(f[7], "ode_directions");
  r.ode_status = base::ParseEnum<StabilityStatus>(f[8], "stability status");
  if (!f[9].empty()) {
    r.mujoco_stable = ToInt(f[9], "mujoco_stable") != 0;
    r.mujoco_directions = ToInt(f[10], "mujoco_directions");
    r.mujoco_status = base::ParseEnum<StabilityStatus>(f[11], "stability status");
  }
  for (int k = 0; k < 3; ++k) {
    if (!f[12 + k].empty()) r.iou[k] = ToDouble(f[12 + k], "iou");
  }
  r.demo_threads = ToInt(f[16], "demo_threads");
  r.threads_preserved = ToInt(f[17], "threads_preserved");
  r.starts = ToInt(f[18], "starts");
  r.task_evaluations = ToInt(f[19], "task_evaluations");
  r.iterations = ToInt(f[20], "iterations");
  r.winding_error = ToDouble(f[21], "winding_error");
  r.min_clearance = ToDouble(f[22], "min_clearance_m");
  return r;
}

const char* ToString(StudySubset s) {
  switch (s) {
    case StudySubset::kAll:
      return "all";
    case StudySubset::kThreading:
      return "threading";
    case StudySubset::kControl:
      break;
  }
  return "control";
}

StudySummary SummariseStudy(const std::vector<StudyRow>& rows,
                            const std::vector<TransferMethod>& methods) {
  StudySummary out;
  out.methods = methods;
  // Outcomes per method keyed by (grasp, demo): (threading, ode, mujoco or −1).
  using Key = std::pair<std::string, int>;
  struct Outcome {
    bool threading, ode;
    int mujoco;
  };
  std::vector<std::map<Key, Outcome>> by_method(methods.size());
  std::map<Key, int> units;
  for (const StudyRow& r : rows) {
    for (size_t m = 0; m < methods.size(); ++m) {
      if (r.method != methods[m]) continue;
      const int mj = r.mujoco_stable ? (*r.mujoco_stable ? 1 : 0) : -1;
      by_method[m][{r.grasp, r.demo}] = {r.threading, r.ode_stable, mj};
      units[{r.grasp, r.demo}] = 1;
      if (r.mujoco_stable) {
        const bool o = r.ode_stable, j = *r.mujoco_stable;
        EngineAgreement& a = out.agreement;
        (o && j ? a.both_hold : !o && !j ? a.both_drop : o ? a.ode_only : a.mujoco_only) += 1;
      }
    }
  }
  out.units = static_cast<int>(units.size());
  const StudySubset subsets[3] = {StudySubset::kAll, StudySubset::kThreading,
                                  StudySubset::kControl};
  for (size_t m = 0; m < methods.size(); ++m) {
    for (StudySubset sub : subsets) {
      StudyMethodSummary s;
      s.method = methods[m];
      s.subset = sub;
      double iou = 0, starts = 0, evals = 0;
      for (const StudyRow& r : rows) {
        if (r.method != methods[m] || !InSubset(r, sub)) continue;
        ++s.trials;
        s.ode_stable += r.ode_stable ? 1 : 0;
        if (r.mujoco_stable) {
          ++s.mujoco_trials;
          s.mujoco_stable += *r.mujoco_stable ? 1 : 0;
        }
        if (const std::optional<double> v = r.MeanIoU()) {
          iou += *v;
          ++s.iou_rows;
        }
        s.demo_threads += r.demo_threads;
        s.threads_preserved += r.threads_preserved;
        starts += r.starts;
        evals += static_cast<double>(r.task_evaluations);
      }
      if (s.trials > 0) {
        s.ode_ci95 = WilsonInterval(s.ode_stable, s.trials);
        s.mean_starts = starts / s.trials;
        s.mean_task_evaluations = evals / s.trials;
      }
      if (s.mujoco_trials > 0) s.mujoco_ci95 = WilsonInterval(s.mujoco_stable, s.mujoco_trials);
      if (s.iou_rows > 0) s.mean_iou = iou / s.iou_rows;
      out.per_method.push_back(s);
    }
  }
  for (size_t a = 0; a < methods.size(); ++a) {
    for (size_t b = a + 1; b < methods.size(); ++b) {
      for (int engine = 0; engine < 2; ++engine) {
        for (StudySubset sub : subsets) {
          std::vector<bool> va, vb;
          for (const auto& [key, oa] : by_method[a]) {
            const auto it = by_method[b].find(key);
            if (it == by_method[b].end()) continue;
            const Outcome& ob = it->second;
            if (sub != StudySubset::kAll && (sub == StudySubset::kThreading) != oa.threading) {
              continue;
            }
            if (engine == 1 && (oa.mujoco < 0 || ob.mujoco < 0)) continue;
            va.push_back(engine == 0 ? oa.ode : oa.mujoco == 1);
            vb.push_back(engine == 0 ? ob.ode : ob.mujoco == 1);
          }
          if (engine == 1 && va.empty()) continue;
          StudyPairTest t;
          t.a = methods[a];
          t.b = methods[b];
          t.subset = sub;
          t.mujoco = engine == 1;
          t.table = MakePairedTable(va, vb);
          t.p = McNemarExactP(t.table);
          out.pairs.push_back(t);
        }
      }
    }
  }
  return out;
}

std::string StudyTableMarkdown(const StudySummary& s) {
  std::string md = StrCat("Stable trials per method (Wilson 95 % intervals), ",
                          std::to_string(s.units), " (grasp, demonstration) units:\n\n");
  md.append(
      "| method | ODE all | ODE threading | ODE control | MuJoCo all | MuJoCo threading | "
      "MuJoCo control | mean IoU | threads kept | AICO starts | task evaluations |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (size_t m = 0; m < s.methods.size(); ++m) {
    const StudyMethodSummary* row = &s.per_method[3 * m];
    md.append(StrCat("| ", ToString(s.methods[m])));
    for (int k = 0; k < 3; ++k) {
      md.append(StrCat(" | ", Count(row[k].ode_stable, row[k].trials, row[k].ode_ci95)));
    }
    for (int k = 0; k < 3; ++k) {
      md.append(
          StrCat(" | ", Count(row[k].mujoco_stable, row[k].mujoco_trials, row[k].mujoco_ci95)));
    }
    md.append(StrCat(" | ", row[0].iou_rows ? Format("%.3f", row[0].mean_iou) : std::string("–")));
    md.append(StrCat(" | ", row[0].demo_threads ? StrCat(std::to_string(row[0].threads_preserved),
                                                         "/", std::to_string(row[0].demo_threads))
                                                : std::string("–")));
    md.append(StrCat(" | ", Format("%.2f", row[0].mean_starts), " | ",
                     Format("%.0f", row[0].mean_task_evaluations), " |\n"));
  }
  for (int engine = 0; engine < 2; ++engine) {
    bool any = false;
    for (const StudyPairTest& t : s.pairs) any = any || (t.mujoco == (engine == 1));
    if (!any) continue;
    md.append(
        StrCat("\nMcNemar's exact test, ", engine ? "MuJoCo" : "ODE",
               " verdicts paired per (grasp, demonstration): A-only / B-only discordant pairs "
               "and two-sided p.\n\n| A vs B | all | threading | control |\n|---|---|---|---|\n"));
    for (size_t k = 0; k < s.pairs.size(); k += 1) {
      const StudyPairTest& t = s.pairs[k];
      if (t.mujoco != (engine == 1) || t.subset != StudySubset::kAll) continue;
      md.append(StrCat("| ", ToString(t.a), " vs ", ToString(t.b)));
      for (size_t j = k; j < k + 3 && j < s.pairs.size(); ++j) {
        const StudyPairTest& u = s.pairs[j];
        char buf[64];
        std::snprintf(buf, sizeof(buf), " | %d / %d, p = %.3g", u.table.only_a, u.table.only_b,
                      u.p);
        md.append(buf);
      }
      md.append(" |\n");
    }
  }
  const EngineAgreement& a = s.agreement;
  if (a.trials() > 0) {
    char buf[256];
    std::snprintf(buf, sizeof(buf),
                  "\nEngine agreement over %d trials: both hold %d, both drop %d, ODE only %d, "
                  "MuJoCo only %d (agree %.1f %%).\n",
                  a.trials(), a.both_hold, a.both_drop, a.ode_only, a.mujoco_only,
                  100.0 * (a.both_hold + a.both_drop) / a.trials());
    md.append(buf);
  }
  return md;
}

}  // namespace planning::physics
