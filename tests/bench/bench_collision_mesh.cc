// Collision on mesh robots and URDF loading limits. The robots are generated at start-up into a
// temporary folder (binary STL links, URDF): an 80-link tree (a torso with 8 arms of 10 links,
// like a mobile manipulator with two arms, a head and grippers) and a 9-link arm with two
// fingers, shaped like a Panda. Each link is a bumpy tube of ~1000 triangles (not convex).
//
//   BM_CheckProcess80        load URDF + meshes, build CollisionData, one boolean check and one
//                            minimum distance (what `topoplan check` does)
//   BM_Boolean80/hull|exact  one boolean query after loading (self + nothing else)
//   BM_MinDistance80/...     one minimum-distance query
//   BM_PandaSelf/hull|exact  one self-collision boolean query of the 9-link arm
//   BM_LoadChain10000        a 10000-link URDF without geometry
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "planning/collision/collision.h"
#include "planning/robot/kinematics.h"
#include "planning/robot/robot_io.h"

namespace {

namespace fs = std::filesystem;

// A closed tube along z from 0 to `length`, radius `radius` with bumps, as binary STL.
void WriteTube(const fs::path& path, double radius, double length, int around, int along) {
  std::vector<Eigen::Vector3f> v;
  for (int i = 0; i <= along; ++i) {
    for (int j = 0; j < around; ++j) {
      const double a = 2 * M_PI * j / around, z = length * i / along;
      const double r = radius * (1.0 + 0.15 * std::sin(5 * a) * std::sin(M_PI * i / along * 3));
      v.emplace_back(r * std::cos(a), r * std::sin(a), z);
    }
  }
  const int bottom = static_cast<int>(v.size());
  v.emplace_back(0, 0, 0);
  v.emplace_back(0, 0, length);
  std::vector<Eigen::Vector3i> t;
  for (int i = 0; i < along; ++i) {
    for (int j = 0; j < around; ++j) {
      const int a = i * around + j, b = i * around + (j + 1) % around;
      t.emplace_back(a, b, b + around);
      t.emplace_back(a, b + around, a + around);
    }
  }
  for (int j = 0; j < around; ++j) {
    t.emplace_back(bottom, (j + 1) % around, j);
    t.emplace_back(bottom + 1, along * around + j, along * around + (j + 1) % around);
  }
  std::ofstream out(path, std::ios::binary);
  char header[80] = {};
  out.write(header, 80);
  const std::uint32_t n = static_cast<std::uint32_t>(t.size());
  out.write(reinterpret_cast<const char*>(&n), 4);
  for (const Eigen::Vector3i& f : t) {
    const float normal[3] = {0, 0, 0};
    out.write(reinterpret_cast<const char*>(normal), 12);
    for (int k = 0; k < 3; ++k) out.write(reinterpret_cast<const char*>(v[f[k]].data()), 12);
    const std::uint16_t attr = 0;
    out.write(reinterpret_cast<const char*>(&attr), 2);
  }
}

std::string Link(const std::string& name, const std::string& mesh) {
  return "<link name=\"" + name + "\"><collision><geometry><mesh filename=\"" + mesh +
         "\"/></geometry></collision></link>\n";
}

std::string Joint(const std::string& name, const std::string& parent, const std::string& child,
                  const std::string& xyz, const std::string& axis) {
  return "<joint name=\"" + name + "\" type=\"revolute\"><parent link=\"" + parent +
         "\"/><child link=\"" + child + "\"/><origin xyz=\"" + xyz + "\"/><axis xyz=\"" + axis +
         "\"/><limit lower=\"-3\" upper=\"3\" effort=\"1\" velocity=\"1\"/></joint>\n";
}

const fs::path& Dir() {
  static const fs::path dir = [] {
    const fs::path d = fs::temp_directory_path() / "topoplan_bench_mesh";
    fs::create_directories(d);
    WriteTube(d / "tube.stl", 0.04, 0.12, 40, 12);  // 1040 triangles
    WriteTube(d / "torso.stl", 0.15, 0.6, 40, 12);
    // 80 links: torso + 8 arms of 10 links around it.
    std::string urdf = "<robot name=\"tree80\">\n" + Link("torso", "torso.stl");
    int links = 1;
    for (int arm = 0; arm < 8 && links < 80; ++arm) {
      const double a = 2 * M_PI * arm / 8;
      std::string parent = "torso";
      for (int k = 0; k < 10 && links < 80; ++k, ++links) {
        std::string name = std::to_string(arm);
        name.insert(0, 1, 'a');
        name += '_';
        name += std::to_string(k);
        urdf += Link(name, "tube.stl");
        const std::string xyz = k == 0 ? std::to_string(0.2 * std::cos(a)) + " " +
                                             std::to_string(0.2 * std::sin(a)) + " 0.45"
                                       : "0 0 0.13";
        urdf += Joint("j_" + name, parent, name, xyz, k % 2 ? "0 1 0" : "1 0 0");
        parent = name;
      }
    }
    std::ofstream(d / "tree80.urdf") << urdf << "</robot>\n";
    std::string panda = "<robot name=\"panda_like\">\n" + Link("link0", "tube.stl");
    for (int k = 1; k <= 7; ++k) {
      const std::string name = "link" + std::to_string(k);
      panda += Link(name, "tube.stl") + Joint("joint" + std::to_string(k),
                                              "link" + std::to_string(k - 1), name, "0 0 0.13",
                                              k % 2 ? "0 0 1" : "0 1 0");
    }
    panda += Link("finger_l", "tube.stl") +
             Joint("finger_l_joint", "link7", "finger_l", "0 0.05 0.13", "1 0 0");
    panda += Link("finger_r", "tube.stl") +
             Joint("finger_r_joint", "link7", "finger_r", "0 -0.05 0.13", "1 0 0");
    std::ofstream(d / "panda_like.urdf") << panda << "</robot>\n";
    std::string chain = "<robot name=\"long\">\n";
    for (int i = 0; i < 10000; ++i) chain += "<link name=\"l" + std::to_string(i) + "\"/>\n";
    for (int i = 1; i < 10000; ++i) {
      chain += "<joint name=\"j" + std::to_string(i) + "\" type=\"continuous\"><parent link=\"l" +
               std::to_string(i - 1) + "\"/><child link=\"l" + std::to_string(i) +
               "\"/><axis xyz=\"0 0 1\"/></joint>\n";
    }
    std::ofstream(d / "long.urdf") << chain << "</robot>\n";
    return d;
  }();
  return dir;
}

Eigen::VectorXd Bent(const planning::Robot& robot) {
  Eigen::VectorXd q(planning::num_dofs(robot));
  for (int k = 0; k < q.size(); ++k) q[k] = 0.3 * std::sin(1.7 * k);
  return q;
}

void BM_CheckProcess80(benchmark::State& state) {
  const std::string urdf = (Dir() / "tree80.urdf").string();
  for (auto _ : state) {
    const planning::Robot robot = planning::LoadRobot(urdf);
    planning::CollisionData coll(robot, planning::Environment{});
    planning::KinematicsData kin(robot);
    planning::ForwardKinematics(robot, Bent(robot), &kin);
    benchmark::DoNotOptimize(planning::InCollision(robot, kin, &coll));
    benchmark::DoNotOptimize(planning::MinDistance(robot, kin, &coll));
  }
}
BENCHMARK(BM_CheckProcess80)->Unit(benchmark::kMillisecond);

template <bool kDistance>
void Query(benchmark::State& state, const std::string& file) {
  const planning::Robot robot = planning::LoadRobot((Dir() / file).string());
  planning::CollisionOptions options;
  options.exact_meshes = state.range(0) != 0;
  planning::CollisionData coll(robot, planning::Environment{}, options);
  planning::KinematicsData kin(robot);
  planning::ForwardKinematics(robot, Bent(robot), &kin);
  for (auto _ : state) {
    if (kDistance) {
      benchmark::DoNotOptimize(planning::MinDistance(robot, kin, &coll));
    } else {
      benchmark::DoNotOptimize(planning::InCollision(robot, kin, &coll));
    }
  }
  state.SetLabel(options.exact_meshes ? "exact" : "hull");
}
void BM_Boolean80(benchmark::State& state) { Query<false>(state, "tree80.urdf"); }
void BM_MinDistance80(benchmark::State& state) { Query<true>(state, "tree80.urdf"); }
void BM_PandaSelf(benchmark::State& state) { Query<false>(state, "panda_like.urdf"); }
BENCHMARK(BM_Boolean80)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_MinDistance80)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_PandaSelf)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

void BM_LoadChain10000(benchmark::State& state) {
  const std::string urdf = (Dir() / "long.urdf").string();
  for (auto _ : state) benchmark::DoNotOptimize(planning::LoadRobot(urdf));
}
BENCHMARK(BM_LoadChain10000)->Unit(benchmark::kMillisecond);

}  // namespace
