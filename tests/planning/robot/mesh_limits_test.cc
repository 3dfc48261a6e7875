// planning/mesh_io limits: files that are not regular files (a named pipe, /dev/zero), huge sparse
// files, non-finite vertices and hostile files an OBJ refers to are refused or skipped quickly,
// with the file named.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "planning/robot/mesh_io.h"

namespace planning {
namespace {

namespace fs = std::filesystem;

// A fresh folder for one test, removed afterwards.
class MeshLimits : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("topoplan-mesh-limits-" + std::to_string(getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string Write(const std::string& name, const std::string& text) const {
    const std::string path = (dir_ / name).string();
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }
  fs::path dir_;
};

// LoadMesh's message for `path`; fails the test when it loads, or takes more than 5 s.
std::string Refusal(const std::string& path) {
  const auto start = std::chrono::steady_clock::now();
  try {
    LoadMesh(path);
  } catch (const std::invalid_argument& e) {
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5)) << path;
    return e.what();
  }
  ADD_FAILURE() << path << " loaded";
  return "";
}

constexpr char kTetObj[] =
    "v 0 0 0\nv 0.1 0 0\nv 0 0.2 0\nv 0 0 0.3\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";

TEST_F(MeshLimits, PipesDevicesAndFoldersAreNotRead) {
  const std::string fifo = (dir_ / "pipe.stl").string();
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_EQ(Refusal(fifo), fifo + ": mesh is not a regular file (a folder, pipe or device)");
  const std::string zero = (dir_ / "zero.stl").string();
  fs::create_symlink("/dev/zero", zero);
  EXPECT_EQ(Refusal(zero), zero + ": mesh is not a regular file (a folder, pipe or device)");
  EXPECT_EQ(Refusal(dir_.string()),
            dir_.string() + ": mesh is not a regular file (a folder, pipe or device)");
}

TEST_F(MeshLimits, HugeSparseFileIsRefusedOnItsSize) {
  const std::string huge = (dir_ / "huge.stl").string();
  std::ofstream(huge).close();
  fs::resize_file(huge, std::uintmax_t{100} << 30);  // 100 GB, sparse
  EXPECT_EQ(Refusal(huge),
            huge + ": mesh file of 107374182400 bytes is larger than 67108864 " + "bytes (limit)");
  fs::resize_file(huge, kMaxMeshFileBytes + 1);
  EXPECT_NE(Refusal(huge).find("larger than 67108864 bytes (limit)"), std::string::npos);
}

TEST_F(MeshLimits, NonFiniteVerticesAreRefused) {
  const std::string bad = Write("inf.obj", "v 0 0 0\nv 1e39 0 0\nv 0 1 0\nf 1 2 3\n");
  EXPECT_EQ(Refusal(bad), bad + ": mesh vertex 1 of mesh 0 is not finite");
}

TEST_F(MeshLimits, OnlyStlObjAndColladaAreRead) {
  const std::string ply = Write("tet.ply", "ply\nformat ascii 1.0\nx 4\n");
  EXPECT_EQ(Refusal(ply),
            ply + ": mesh format '.ply' is not supported (expected .stl, .obj or .dae)");
  // A COLLADA source naming no element (assimp 5.2 would allocate gigabytes).
  const std::string dae =
      Write("dangling.dae",
            "<COLLADA><library_geometries><geometry id='g'><mesh><source id='p'/>"
            "<vertices id='v'><input semantic='POSITION' source='#q'/></vertices></mesh></geometry>"
            "</library_geometries></COLLADA>");
  EXPECT_EQ(Refusal(dae), dae + ": COLLADA source '#q' names no element of the file");
}

TEST_F(MeshLimits, ReferencedPipesAndDevicesAreSkipped) {
  // An OBJ whose material libraries are a named pipe and /dev/zero: both are skipped (opening the
  // pipe would block, /dev/zero has no end), the geometry loads.
  ASSERT_EQ(mkfifo((dir_ / "pipe.mtl").c_str(), 0600), 0);
  fs::create_symlink("/dev/zero", dir_ / "zero.mtl");
  const std::string obj =
      Write("tet.obj", std::string("mtllib pipe.mtl\nmtllib zero.mtl\nusemtl a\n") + kTetObj);
  const auto start = std::chrono::steady_clock::now();
  const Mesh mesh = LoadMesh(obj);
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5));
  EXPECT_EQ(mesh.triangles.size(), 4u);
  EXPECT_EQ(mesh.vertices.size(), mesh.normals.size());
}

}  // namespace
}  // namespace planning
