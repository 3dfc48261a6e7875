// The demo's HTML tables against the files written from the same result structs: every number in
// a table must equal the corresponding unwrap.csv / report.json value, with the columns in the
// planner / method order of the result.
#include "app/present/reports.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "app/present/ompl_log.h"
#include "planning/grasp/grasp_quality.h"

namespace app {
namespace {

using planning::Planner;

std::vector<std::vector<std::string>> TableCells(const std::string& html, bool* has_header,
                                                 std::vector<std::string>* header) {
  std::vector<std::vector<std::string>> rows;
  static const std::regex kRow("<tr>(.*?)</tr>");
  static const std::regex kCell("<t([hd])>(.*?)</t[hd]>");
  for (auto r = std::sregex_iterator(html.begin(), html.end(), kRow); r != std::sregex_iterator();
       ++r) {
    const std::string row = (*r)[1].str();
    std::vector<std::string> cells;
    bool th = false;
    for (auto c = std::sregex_iterator(row.begin(), row.end(), kCell); c != std::sregex_iterator();
         ++c) {
      th = (*c)[1].str() == "h";
      cells.push_back((*c)[2].str());
    }
    if (th) {
      *has_header = true;
      *header = cells;
    } else {
      rows.push_back(cells);
    }
  }
  return rows;
}

planning::UnwrapBenchmarkResult SyntheticUnwrap() {
  planning::UnwrapBenchmarkResult result;
  result.angles_deg = {0.0, 90.0, 180.0};
  // Not sorted by name, so a table ordered by name would swap columns.
  result.planners = {Planner::kAico, Planner::kRrt, Planner::kBiRrt};
  result.seeds = 3;
  long checks = 100;
  for (double angle : result.angles_deg) {
    for (Planner p : result.planners) {
      for (int seed = 0; seed < result.seeds; ++seed) {
        planning::UnwrapRun run;
        run.angle_deg = angle;
        run.planner = p;
        run.seed = seed;
        run.report.planner = planning::PlannerName(p);
        // rrt fails twice at 90 deg and always at 180 deg; failed runs have huge counts.
        const bool fail = p == Planner::kRrt && (angle == 180.0 || (angle == 90.0 && seed > 0));
        run.report.success = !fail;
        run.report.collision_checks = fail ? 100000 : (checks += 37 * (seed + 1));
        run.report.time_s = 0.01 * seed;
        result.runs.push_back(run);
      }
    }
  }
  result.summary = planning::SummarizeUnwrapRuns(result.runs, result.angles_deg, result.planners);
  return result;
}

TEST(ReportsTest, UnwrapTableMatchesCsv) {
  const planning::UnwrapBenchmarkResult result = SyntheticUnwrap();
  // Per (angle, planner) from the CSV: runs, successes, sum of checks of successful runs.
  struct Agg {
    int runs = 0, ok = 0;
    double sum = 0.0;
    std::vector<double> solved;  // collision checks of the solved runs
  };
  std::map<std::pair<std::string, std::string>, Agg> csv;
  std::istringstream in(planning::UnwrapCsv(result));
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line,
            "angle_deg,planner,seed,success,failure_reason,collision_checks,narrow_phase_calls,"
            "time_s,path_length,reach_error_m,pole_offset_m,state_queries,bool_pair_tests,"
            "distance_pair_tests,cpu_time_s,setup_time_s,goal_samples,goal_sampler_state_queries,"
            "goal_sampler_pair_tests,goal_sampler_cpu_time_s");
  while (std::getline(in, line)) {
    std::stringstream ss(line);
    std::string angle, planner, seed, success, reason, checks;
    std::getline(ss, angle, ',');
    std::getline(ss, planner, ',');
    std::getline(ss, seed, ',');
    std::getline(ss, success, ',');
    std::getline(ss, reason, ',');
    std::getline(ss, checks, ',');
    Agg& a = csv[{angle, planner}];
    ++a.runs;
    if (success == "1") {
      ++a.ok;
      a.sum += std::stod(checks);
      a.solved.push_back(std::stod(checks));
    }
  }
  bool has_header = false;
  std::vector<std::string> header;
  const auto rows = TableCells(UnwrapHtmlTable(result), &has_header, &header);
  ASSERT_TRUE(has_header);
  ASSERT_EQ(header.size(), 1 + result.planners.size());
  std::vector<std::string> planners;
  for (size_t i = 1; i < header.size(); ++i) {
    planners.push_back(header[i].substr(0, header[i].find(':')));
    EXPECT_EQ(planners.back(), planning::PlannerName(result.planners[i - 1]));
  }
  ASSERT_EQ(rows.size(), result.angles_deg.size());
  static const std::regex kCell(R"((\d+)/(\d+), (\d+|&ndash;))");
  int checked = 0;
  for (size_t a = 0; a < rows.size(); ++a) {
    ASSERT_EQ(rows[a].size(), header.size());
    const std::string angle = rows[a][0].substr(0, rows[a][0].find('&'));
    for (size_t p = 0; p < planners.size(); ++p) {
      std::smatch m;
      ASSERT_TRUE(std::regex_match(rows[a][p + 1], m, kCell)) << rows[a][p + 1];
      ASSERT_TRUE(csv.count({angle, planners[p]})) << angle << " " << planners[p];
      const Agg& agg = csv.at({angle, planners[p]});
      EXPECT_EQ(std::stoi(m[1].str()), agg.ok) << angle << " " << planners[p];
      EXPECT_EQ(std::stoi(m[2].str()), agg.runs);
      // The figure's value (summary) and the table's agree with the CSV: the median over solved
      // runs (the figure draws medians, so the table beside it does too).
      const planning::UnwrapCell& cell = planning::UnwrapSummaryCell(result, a, p);
      if (agg.ok == 0) {
        EXPECT_EQ(m[3].str(), "&ndash;");
        EXPECT_TRUE(std::isnan(cell.median_checks));
      } else {
        std::vector<double> v = agg.solved;
        std::sort(v.begin(), v.end());
        const size_t n = v.size();
        const double median = n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
        EXPECT_DOUBLE_EQ(cell.median_checks, median);
        EXPECT_EQ(std::stol(m[3].str()), std::lround(median));
      }
      ++checked;
    }
  }
  EXPECT_EQ(checked, 9);
}

TEST(ReportsTest, UnwrapSummaryMedianOfSolvedRuns) {
  const planning::UnwrapBenchmarkResult result = SyntheticUnwrap();
  const planning::UnwrapCell& rrt90 = planning::UnwrapSummaryCell(result, 1, 1);
  EXPECT_EQ(rrt90.planner, Planner::kRrt);
  EXPECT_EQ(rrt90.successes, 1);
  EXPECT_EQ(rrt90.runs, 3);
  EXPECT_EQ(rrt90.median_checks, rrt90.mean_checks);
  const planning::UnwrapCell& aico0 = planning::UnwrapSummaryCell(result, 0, 0);
  EXPECT_EQ(aico0.median_checks, static_cast<double>(result.runs[1].report.collision_checks));
}

TEST(ReportsTest, GraspTableMatchesReportJson) {
  namespace phys = planning::physics;
  phys::GraspTrialsResult result;
  result.methods = {planning::TransferMethod::kWinding, planning::TransferMethod::kJointMapping,
                    planning::TransferMethod::kFingertip};
  const int passed[3][3] = {{6, 4, 6}, {6, 0, 3}, {5, 6, 2}};
  for (int g = 0; g < 3; ++g) {
    planning::HumanGrasp grasp;
    grasp.name = "grasp_" + std::to_string(g);
    grasp.source = "/x/" + grasp.name + ".json";
    result.grasps.push_back(grasp);
    std::vector<phys::GraspTrial>& row = result.trials.emplace_back();
    for (int m = 0; m < 3; ++m) {
      phys::GraspTrial t;
      t.transfer.method = result.methods[m];
      t.stability.directions_passed = passed[g][m];
      t.stability.stable = passed[g][m] == 6;
      t.epsilon_quality = 0.01 * (3 * g + m);
      row.push_back(t);
    }
  }
  for (int m = 0; m < 3; ++m) {
    phys::GraspMethodSummary s;
    s.method = result.methods[m];
    s.grasps = 3;
    for (int g = 0; g < 3; ++g) s.stable += passed[g][m] == 6 ? 1 : 0;
    s.rate = s.stable / 3.0;
    s.ci95 = planning::WilsonInterval(s.stable, s.grasps);
    result.summary.push_back(s);
  }
  const nlohmann::json report = planning::physics::GraspReportJson(result);
  bool has_header = false;
  std::vector<std::string> header;
  const auto rows = TableCells(GraspHtmlTable(result), &has_header, &header);
  ASSERT_TRUE(has_header);
  ASSERT_EQ(header.size(), 4u);
  ASSERT_EQ(rows.size(), 4u);  // 3 grasps + success rate
  static const std::regex kCell(R"((\d+)/6( stable)?)");
  for (size_t g = 0; g < 3; ++g) {
    const nlohmann::json& gj = report["grasps"][g];
    EXPECT_EQ(rows[g][0], gj["name"].get<std::string>());
    for (size_t m = 1; m < header.size(); ++m) {
      const nlohmann::json& mj = gj["methods"][header[m]];
      std::smatch sm;
      ASSERT_TRUE(std::regex_match(rows[g][m], sm, kCell)) << rows[g][m];
      EXPECT_EQ(std::stoi(sm[1].str()), mj["directions_passed"].get<int>());
      EXPECT_EQ(sm[2].matched, mj["stable"].get<bool>());
      EXPECT_DOUBLE_EQ(mj["epsilon_quality"].get<double>(),
                       0.01 * static_cast<double>(3 * g + m - 1));
    }
  }
  // The success-rate row: "stable/grasps (lo-hi)" with the Wilson 95 % interval of the summary.
  for (size_t m = 1; m < header.size(); ++m) {
    const nlohmann::json& s = report["summary"][header[m]];
    char expected[64];
    std::snprintf(expected, sizeof expected, "%d/%d (%.2f-%.2f)", s["stable"].get<int>(),
                  s["grasps"].get<int>(), s["ci95"][0].get<double>(), s["ci95"][1].get<double>());
    EXPECT_EQ(rows[3][m], expected);
  }
  // Wilson(2, 3) = (0.2077, 0.9385), Wilson(1, 3) = (0.0615, 0.7923).
  EXPECT_NEAR(report["summary"]["winding"]["ci95"][0].get<double>(), 0.2077, 1e-4);
  EXPECT_NEAR(report["summary"]["winding"]["ci95"][1].get<double>(), 0.9385, 1e-4);
  // summary.md carries the same cells.
  const std::string md = planning::physics::GraspSummaryMarkdown(result);
  EXPECT_NE(md.find("| grasp_1 | 6/6 stable | 0/6 | 3/6 | 0.0300 | 0.0400 | 0.0500 |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| eps winding | eps joint | eps fingertip |"), std::string::npos) << md;
  EXPECT_NE(md.find("| **success rate (95 % CI)** | 2/3 (0.21-0.94) | 1/3 (0.06-0.79) | 1/3 "
                    "(0.06-0.79) |"),
            std::string::npos)
      << md;
  EXPECT_EQ(md.find("perturbed"), std::string::npos) << md;  // no --perturb: no perturbed row
  // The grip travel: in the protocol, and in the figure's title only when not the default.
  result.close_by = phys::HandBuildOptions{}.close_by;
  EXPECT_EQ(planning::physics::GraspReportJson(result)["protocol"]["close_by_rad"].get<double>(),
            0.15);
  EXPECT_EQ(visualize::GraspSummaryDataOf(result).title.find("grip"), std::string::npos);
  result.close_by = 0.05;
  EXPECT_EQ(planning::physics::GraspReportJson(result)["protocol"]["close_by_rad"].get<double>(),
            0.05);
  EXPECT_NE(visualize::GraspSummaryDataOf(result).title.find("grip \u03b4 = 0.05 rad"),
            std::string::npos)
      << visualize::GraspSummaryDataOf(result).title;
  EXPECT_NE(planning::physics::GraspSummaryMarkdown(result).find(
                "flexion set-points 0.05 rad past the grasp"),
            std::string::npos);
}

TEST(ReportsTest, GraspReportCarriesTheExtraCurveWindings) {
  // One grasp on an object with one extra reference curve (the plate's rim), one without.
  namespace phys = planning::physics;
  phys::GraspTrialsResult result;
  result.methods = {planning::TransferMethod::kWinding, planning::TransferMethod::kHuman};
  for (int g = 0; g < 2; ++g) {
    planning::HumanGrasp grasp;
    grasp.name = g == 0 ? "lateral_pinch_box" : "power_bottle";
    grasp.source = "/x/" + grasp.name + ".json";
    result.grasps.push_back(grasp);
    std::vector<phys::GraspTrial>& row = result.trials.emplace_back();
    for (int m = 0; m < 2; ++m) {
      phys::GraspTrial t;
      t.transfer.method = result.methods[m];
      if (g == 0) {
        t.transfer.target_extra_winding = Eigen::Vector2d(0.21, -0.34);
        t.transfer.robot_extra_winding =
            m == 0 ? Eigen::Vector2d(0.2134567, -0.19) : Eigen::Vector2d(0.21, -0.34);
      }
      row.push_back(t);
    }
  }
  const nlohmann::json report = planning::physics::GraspReportJson(result);
  const nlohmann::json& pinch = report["grasps"][0]["methods"];
  EXPECT_EQ(pinch["winding"]["target_extra_winding"], nlohmann::json({0.21, -0.34}));
  EXPECT_EQ(pinch["winding"]["robot_extra_winding"], nlohmann::json({0.213457, -0.19}));
  EXPECT_EQ(pinch["human"]["robot_extra_winding"], pinch["human"]["target_extra_winding"]);
  // Without extra curves: present and empty.
  const nlohmann::json& bottle = report["grasps"][1]["methods"]["winding"];
  ASSERT_TRUE(bottle.contains("target_extra_winding"));
  EXPECT_TRUE(bottle["target_extra_winding"].empty());
  EXPECT_TRUE(bottle["robot_extra_winding"].empty());
}

// --- OMPL benchmark logs (app/present/ompl_log.h)
// --------------------------------------------------------

std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

TEST(OmplLogTest, OneExperimentPerAngleWithEveryPlannerAndSeed) {
  const planning::UnwrapBenchmarkResult result = SyntheticUnwrap();
  OmplLogInfo info;
  info.version = "1.2.3";
  info.host = "testhost";
  info.start_time = "2026-12-01T00:00:00";
  info.setup = "synthetic";
  const std::vector<std::string> lines = Lines(OmplBenchmarkLog(result, 1, info));
  ASSERT_GT(lines.size(), 20u);
  // The header: the sum of the angle's run times is 3 planners x (0 + 0.01 + 0.02) s.
  const std::vector<std::string> header = {"topoplan version 1.2.3",
                                           "Experiment unwrap_90deg",
                                           "3 experiment properties",
                                           "angle_deg REAL = 90",
                                           "perturb_m REAL = 0",
                                           "seeds INTEGER = 3",
                                           "Running on testhost",
                                           "Starting at 2026-12-01T00:00:00",
                                           "<<<|",
                                           "synthetic",
                                           "|>>>",
                                           "0 is the random seed",
                                           "0 seconds per run",
                                           "0 MB per run",
                                           "3 runs per planner",
                                           "0.09 seconds spent to collect the data",
                                           "1 enum type"};
  EXPECT_EQ(std::vector<std::string>(lines.begin(), lines.begin() + 17), header);
  EXPECT_EQ(lines[17].rfind("failure_reason|none|joint_limits|", 0), 0u);
  EXPECT_EQ(lines[18], "3 planners");
  // Planner blocks in the result's order, each: name, common properties, 15 property names,
  // "3 runs", 3 run lines of 15 "; "-terminated values, ".".
  size_t k = 19;
  for (size_t p = 0; p < result.planners.size(); ++p) {
    EXPECT_EQ(lines[k++], planning::PlannerName(result.planners[p]));
    const int common = std::stoi(lines[k++]);
    k += static_cast<size_t>(common);
    ASSERT_EQ(lines[k++], "15 properties for each run");
    EXPECT_EQ(lines[k], "bool pair tests INTEGER");
    EXPECT_EQ(lines[k + 1], "collision checks INTEGER");
    EXPECT_EQ(lines[k + 12], "solved BOOLEAN");
    EXPECT_EQ(lines[k + 13], "state queries INTEGER");
    k += 15;
    ASSERT_EQ(lines[k++], "3 runs");
    for (int s = 0; s < 3; ++s) {
      const planning::UnwrapRun& run = result.runs[(1 * 3 + p) * 3 + static_cast<size_t>(s)];
      const std::string& line = lines[k++];
      EXPECT_EQ(line.rfind(std::to_string(run.report.counts.bool_pair_tests) + "; " +
                               std::to_string(run.report.collision_checks) + "; ",
                           0),
                0u)
          << line;
      // seed; setup time (0 here); solved; state queries
      EXPECT_NE(line.find("; " + std::to_string(s) + "; 0; " + (run.report.success ? "1" : "0") +
                          "; " + std::to_string(run.report.counts.state_queries) + "; "),
                std::string::npos)
          << line;
      EXPECT_EQ(std::count(line.begin(), line.end(), ';'), 15) << line;
    }
    EXPECT_EQ(lines[k++], ".");
  }
  EXPECT_EQ(k, lines.size());
  EXPECT_THROW(OmplBenchmarkLog(result, 3, info), std::invalid_argument);
}

TEST(OmplLogTest, LogPathPerAngle) {
  EXPECT_EQ(OmplLogPath("out/unwrap.log", 720.0), "out/unwrap_720deg.log");
  EXPECT_EQ(OmplLogPath("log", 22.5), "log_22.5deg");
}

}  // namespace
}  // namespace app
