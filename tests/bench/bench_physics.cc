// ODE grasp-stability test timing. Target (README): one grasp's full test — 0.5 s closing plus
// 6 gravity directions × 2 s at 1 kHz (12 500 steps) — in ≤ 2 s.
#include <benchmark/benchmark.h>

#include "planning/grasp/grasp_transfer.h"
#include "planning/physics/hand_builder.h"
#include "planning/physics/ode_runtime.h"
#include "planning/physics/stability.h"
#include "planning/robot/robot_io.h"
#include "tests/planning/physics/test_hands.h"

namespace {

planning::physics::OdeRuntime& Runtime() {
  static planning::physics::OdeRuntime runtime;
  return runtime;
}

// A stable grasp: every direction runs its full 2 s (no early exit), the worst case.
void BM_StabilityTestEnvelopingGrasp(benchmark::State& state) {
  const auto hand = testing_hands::ClawHand(1.3);
  const auto bottle = testing_hands::Bottle();
  planning::physics::StabilityOptions opt;
  opt.sim.stepper = state.range(0) == 0 ? planning::physics::Stepper::kQuickStep
                                        : planning::physics::Stepper::kWorldStep;
  long steps = 0;
  int passed = 0;
  for (auto _ : state) {
    const auto r = planning::physics::TestGraspStability(Runtime(), hand, bottle, opt);
    steps = r.total_steps;
    passed = r.directions_passed;
    benchmark::DoNotOptimize(r);
  }
  state.counters["steps"] = static_cast<double>(steps);
  state.counters["directions_passed"] = passed;
  state.counters["us_per_step"] = benchmark::Counter(
      static_cast<double>(steps) * 1e-6,
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.SetLabel(state.range(0) == 0 ? "quickstep-60" : "dWorldStep");
}
BENCHMARK(BM_StabilityTestEnvelopingGrasp)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// One simulation step of the closed grasp (16 hand links, ~20 contacts).
void BM_SingleStep(benchmark::State& state) {
  planning::physics::GraspSimulation sim(Runtime(), testing_hands::ClawHand(1.3),
                                         testing_hands::Bottle(), {});
  for (int k = 0; k < 500; ++k) sim.Step();
  for (auto _ : state) sim.Step();
  state.counters["contacts"] = static_cast<double>(sim.state().contacts.size());
}
BENCHMARK(BM_SingleStep)->Unit(benchmark::kMicrosecond);

// The SDH grasp transferred from the human power grasp of the bottle (9 bodies, ~6 contacts),
// as `grasp transfer` tests it. Transfer (AICO) timed separately.
void BM_StabilityTestSdhPowerGrasp(benchmark::State& state) {
  const std::string assets = std::string(TOPOPLAN_SOURCE_DIR) + "/assets/";
  const auto objects = planning::LoadGraspObjects(assets + "grasps/objects.json");
  const planning::GraspObject& bottle = planning::FindGraspObject(objects, "bottle");
  const planning::HumanGrasp g = planning::LoadHumanGrasp(assets + "grasps/power_bottle.json");
  const planning::TransferSetup setup =
      planning::MakeTransferSetup(planning::LoadRobot(assets + "robots/human_hand.urdf"),
                                  planning::LoadRobot(assets + "robots/lwr4_sdh.urdf"), bottle, g);
  const planning::TransferResult t =
      planning::TransferGrasp(setup, planning::TransferMethod::kWinding);
  const auto hand = planning::physics::BuildSimHand(setup.sdh, t.q, "sdh_palm");
  const auto body = planning::physics::BuildSimObject(bottle, g.world_from_object);
  int passed = 0;
  for (auto _ : state) {
    const auto r = planning::physics::TestGraspStability(Runtime(), hand, body, {});
    passed = r.directions_passed;
    benchmark::DoNotOptimize(r);
  }
  state.counters["directions_passed"] = passed;
}
BENCHMARK(BM_StabilityTestSdhPowerGrasp)->Unit(benchmark::kMillisecond);

void BM_WindingTransferPowerGrasp(benchmark::State& state) {
  const std::string assets = std::string(TOPOPLAN_SOURCE_DIR) + "/assets/";
  const auto objects = planning::LoadGraspObjects(assets + "grasps/objects.json");
  const planning::HumanGrasp g = planning::LoadHumanGrasp(assets + "grasps/power_bottle.json");
  const planning::TransferSetup setup =
      planning::MakeTransferSetup(planning::LoadRobot(assets + "robots/human_hand.urdf"),
                                  planning::LoadRobot(assets + "robots/lwr4_sdh.urdf"),
                                  planning::FindGraspObject(objects, "bottle"), g);
  for (auto _ : state) {
    benchmark::DoNotOptimize(planning::TransferGrasp(setup, planning::TransferMethod::kWinding));
  }
}
BENCHMARK(BM_WindingTransferPowerGrasp)->Unit(benchmark::kMillisecond);

}  // namespace
