// Rows, paired statistics and tables of the grasp-transfer study (`bench grasp`, issue 36):
// grasp.csv (one row per grasp × demonstration × method, resumable), per method the stable
// count with a Wilson 95 % interval (all objects, threading objects, controls), McNemar's exact
// test for every method pair on the outcomes paired per (grasp, demonstration), the similarity
// measures and the agreement of the two physics engines.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "planning/grasp/grasp_stats.h"
#include "planning/physics/grasp_study.h"

namespace planning::physics {

// grasp.csv: the header line (no newline) and one row (no newline). Columns: grasp, object,
// class (threading | control), demo, seed, method, ode_stable (0/1), ode_directions, ode_status,
// mujoco_stable (0/1, empty without MuJoCo), mujoco_directions, mujoco_status, iou_thumb,
// iou_finger_1, iou_finger_2 (4 decimals, empty when undefined), iou_mean, demo_threads,
// threads_preserved, starts, task_evaluations, iterations, winding_error (turns, 6 digits),
// min_clearance_m (6 digits).
std::string StudyCsvHeader();
std::string StudyCsvRow(const StudyRow& row);
// Parses a row written by StudyCsvRow (numbers as written). Throws std::invalid_argument for a
// wrong column count or an unparsable field.
StudyRow ParseStudyCsvRow(const std::string& line);

// Subsets of the trials the summaries split by.
enum class StudySubset { kAll, kThreading, kControl };
const char* ToString(StudySubset subset);

struct StudyMethodSummary {
  TransferMethod method = TransferMethod::kWinding;
  StudySubset subset = StudySubset::kAll;
  int trials = 0;
  int ode_stable = 0;
  Eigen::Vector2d ode_ci95 = Eigen::Vector2d(0, 1);  // Wilson 95 % (0, 1 without trials)
  int mujoco_trials = 0;                             // rows with a MuJoCo verdict
  int mujoco_stable = 0;
  Eigen::Vector2d mujoco_ci95 = Eigen::Vector2d(0, 1);
  double mean_iou = 0.0;  // mean of StudyRow::MeanIoU over the rows where it is defined
  int iou_rows = 0;
  int demo_threads = 0;       // threading fingers of the demonstrations (summed)
  int threads_preserved = 0;  // of those, threading in the transfers
  double mean_starts = 0.0;
  double mean_task_evaluations = 0.0;
};

// McNemar's exact test of methods a and b on the trials both ran, paired per (grasp, demo).
struct StudyPairTest {
  TransferMethod a = TransferMethod::kWinding, b = TransferMethod::kWinding;
  StudySubset subset = StudySubset::kAll;
  bool mujoco = false;  // verdicts of MuJoCo instead of ODE
  PairedTable table;
  double p = 1.0;
};

// Agreement of ODE and MuJoCo over the rows with both verdicts.
struct EngineAgreement {
  int both_hold = 0, both_drop = 0, ode_only = 0, mujoco_only = 0;
  int trials() const { return both_hold + both_drop + ode_only + mujoco_only; }
};

struct StudySummary {
  std::vector<TransferMethod> methods;
  std::vector<StudyMethodSummary> per_method;  // methods × {all, threading, control}
  std::vector<StudyPairTest> pairs;  // every method pair × subset × engine (MuJoCo if present)
  EngineAgreement agreement;
  int units = 0;  // distinct (grasp, demo)
};

// Summarises rows (any order) of `methods`; rows of other methods are ignored.
StudySummary SummariseStudy(const std::vector<StudyRow>& rows,
                            const std::vector<TransferMethod>& methods);

// Markdown: the per-method table (stable/trials and Wilson interval per engine and subset, mean
// IoU, threads preserved, AICO starts and evaluations), the McNemar p-values (ODE; MuJoCo
// below when present) and the engine agreement.
std::string StudyTableMarkdown(const StudySummary& summary);

}  // namespace planning::physics
