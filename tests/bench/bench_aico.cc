// AICO vs the RRT baselines on the unwrap scenario (thesis Fig. 4.5 set-up), plus the AICO
// building blocks. Counters: collision_checks (configuration-level collision queries, the thesis
// unit), narrow_phase (FCL shape-pair calls), success (1/0).
//   ./bench_aico --benchmark_filter=Unwrap720
#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <string>

#include "planning/motion/aico.h"
#include "planning/motion/planner.h"
#include "planning/motion/scenario.h"

namespace {

const planning::Scenario& Unwrap(double wrap_deg) {
  static std::map<double, std::unique_ptr<planning::Scenario>> cache;
  auto& s = cache[wrap_deg];
  if (!s) {
    planning::ScenarioOverrides o;
    o.start_wrap_deg = wrap_deg;
    s = planning::LoadScenario(TOPOPLAN_SOURCE_DIR "/assets/scenarios/unwrap.json", o);
  }
  return *s;
}

void RunPlanner(benchmark::State& state, planning::Planner planner, double wrap) {
  const planning::Scenario& s = Unwrap(wrap);
  planning::PlanReport last;
  unsigned seed = 0;
  for (auto _ : state) {
    last = planning::RunPlanner(s, planner, seed++).report;
    benchmark::DoNotOptimize(last.cost);
  }
  state.counters["collision_checks"] = static_cast<double>(last.collision_checks);
  state.counters["narrow_phase"] = static_cast<double>(last.narrow_phase_calls);
  state.counters["success"] = last.success ? 1.0 : 0.0;
  state.counters["final_writhe"] = last.final_writhe_total;
}

void BM_AicoUnwrap(benchmark::State& state) {
  RunPlanner(state, planning::Planner::kAico, static_cast<double>(state.range(0)));
}
BENCHMARK(BM_AicoUnwrap)->Arg(360)->Arg(540)->Arg(720)->Unit(benchmark::kMillisecond);

void BM_BiRrtUnwrap(benchmark::State& state) {
  RunPlanner(state, planning::Planner::kBiRrt, static_cast<double>(state.range(0)));
}
BENCHMARK(BM_BiRrtUnwrap)
    ->Arg(360)
    ->Arg(540)
    ->Arg(720)
    ->Iterations(3)
    ->Unit(benchmark::kMillisecond);

void BM_RrtUnwrap(benchmark::State& state) {
  RunPlanner(state, planning::Planner::kRrt, static_cast<double>(state.range(0)));
}
BENCHMARK(BM_RrtUnwrap)->Arg(720)->Iterations(1)->Unit(benchmark::kMillisecond);

// One AICO solve without the validation and reporting around it.
void BM_AicoSolveOnly720(benchmark::State& state) {
  const planning::Scenario& s = Unwrap(720);
  planning::AicoWorkspace ws(s.initial.problem);
  for (auto _ : state) {
    const planning::AicoResult r = planning::SolveAico(s.initial.problem, s.aico, &ws);
    benchmark::DoNotOptimize(r.cost);
  }
}
BENCHMARK(BM_AicoSolveOnly720)->Unit(benchmark::kMillisecond);

// One full AICO solve (AicoSolver: rollout start, sweeps to convergence) at 360° and 720°.
void BM_AicoSolverUnwrap(benchmark::State& state) {
  const planning::Scenario& s = Unwrap(static_cast<double>(state.range(0)));
  planning::AicoResult r;
  for (auto _ : state) {
    planning::AicoSolver solver(s.initial.problem, s.aico);
    r = solver.Solve();
    benchmark::DoNotOptimize(r.cost);
  }
  state.counters["sweeps"] = r.iterations;
  state.counters["task_evaluations"] = static_cast<double>(r.task_evaluations);
}
BENCHMARK(BM_AicoSolverUnwrap)->Arg(360)->Arg(720)->Unit(benchmark::kMillisecond);

// One sweep (message passing, relocation, cost at the beliefs) at 720°: the k-th sweep of a solve,
// k = 0, 1, ... (a fresh solver, set up untimed, once the previous one is done).
void BM_AicoOneSweep720(benchmark::State& state) {
  const planning::Scenario& s = Unwrap(720);
  std::unique_ptr<planning::AicoSolver> solver;
  for (auto _ : state) {
    if (!solver || solver->done()) {
      state.PauseTiming();
      solver = std::make_unique<planning::AicoSolver>(s.initial.problem, s.aico);
      state.ResumeTiming();
    }
    const planning::AicoStep step = solver->Step();
    benchmark::DoNotOptimize(step.cost);
  }
}
BENCHMARK(BM_AicoOneSweep720)->Unit(benchmark::kMillisecond);

// The writhe-continuation start and final-pose estimate (scenario loading).
void BM_LoadUnwrap720(benchmark::State& state) {
  planning::ScenarioOverrides o;
  o.start_wrap_deg = 720;
  for (auto _ : state) {
    auto s = planning::LoadScenario(TOPOPLAN_SOURCE_DIR "/assets/scenarios/unwrap.json", o);
    benchmark::DoNotOptimize(s.get());
  }
}
BENCHMARK(BM_LoadUnwrap720)->Unit(benchmark::kMillisecond);

}  // namespace
