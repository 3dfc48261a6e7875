// Shared by the binding files of the topoplan Python module (python/bind/*.cc): NumPy argument
// conversion with the argument's name in every ValueError, images as arrays, JSON as Python
// objects, and the offscreen render of a scene.
#pragma once

#include <pybind11/eigen.h>
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "render/image.h"
#include "render/offscreen_context.h"
#include "render/renderer.h"

namespace topoplan_py {

namespace py = pybind11;
namespace fs = std::filesystem;

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

[[noreturn]] inline void ThrowPy(PyObject* type, const std::string& message) {
  PyErr_SetString(type, message.c_str());
  throw py::error_already_set();
}

[[noreturn]] inline void ThrowValue(const std::string& message) {
  ThrowPy(PyExc_ValueError, message);
}

// An old keyword, kept working for one release: a DeprecationWarning naming the new one.
inline void WarnDeprecated(const char* old_name, const char* new_name) {
  PyErr_WarnFormat(PyExc_DeprecationWarning, 2, "%s= is deprecated; use %s=", old_name, new_name);
}

// f(), with a std::invalid_argument it throws raised as `type` "arg: <message>".
template <typename F>
auto Named(const std::string& arg, F f, PyObject* type = PyExc_ValueError) -> decltype(f()) {
  try {
    return f();
  } catch (const std::invalid_argument& e) {
    // The shared app code names its command-line flag or positional ("--grasp: ", "SCENARIO: "):
    // here the Python argument is named instead.
    std::string what = e.what();
    const size_t colon = what.find(": ");
    if (colon != std::string::npos &&
        (what.rfind("--", 0) == 0 || what.rfind("SCENARIO", 0) == 0) && what.find(' ') > colon) {
      what.erase(0, colon + 2);
    }
    ThrowPy(type, arg + ": " + what);
  }
}

// A float64 array from any array-like; ValueError naming `arg` when it is not numeric.
// Most numbers an array argument may hold (2^27 doubles, 1 GiB): checked before any copy.
constexpr py::ssize_t kMaxArrayElements = py::ssize_t{1} << 27;

inline Array ToArray(const py::handle& obj, const std::string& arg) {
  // What it is before it is converted: real numbers only (a complex array would lose its
  // imaginary part, strings and objects are not numbers), and of a size that can be copied.
  py::array raw;
  try {
    raw = py::array::ensure(obj);
  } catch (const py::error_already_set&) {
    ThrowValue(arg + ": expected an array of numbers");
  }
  if (!raw) ThrowValue(arg + ": expected an array of numbers");
  const char kind = raw.dtype().kind();
  if (kind == 'c') {
    ThrowValue(arg + ": complex numbers are not accepted (the imaginary part would be lost)");
  }
  if (kind != 'f' && kind != 'i' && kind != 'u' && kind != 'b') {
    ThrowValue(arg + ": expected real numbers, got dtype " +
               py::str(raw.dtype()).cast<std::string>());
  }
  if (raw.size() > kMaxArrayElements) {
    ThrowValue(arg + ": " + std::to_string(raw.size()) + " numbers, more than the limit of " +
               std::to_string(kMaxArrayElements));
  }
  Array a;
  try {
    a = py::cast<Array>(raw);
  } catch (const py::cast_error&) {
    ThrowValue(arg + ": expected an array of numbers");
  } catch (const py::error_already_set&) {
    ThrowValue(arg + ": expected an array of numbers");
  }
  if (!a) ThrowValue(arg + ": expected an array of numbers");
  for (py::ssize_t i = 0; i < a.size(); ++i) {
    if (!std::isfinite(a.data()[i])) ThrowValue(arg + ": non-finite value (NaN or Inf)");
  }
  return a;
}

// An N×3 point array as a 3×N Eigen matrix (N >= min_points).
inline Eigen::Matrix3Xd ToPoints(const py::handle& obj, const std::string& arg,
                                 int min_points = 2) {
  const Array a = ToArray(obj, arg);
  if (a.ndim() != 2 || a.shape(1) != 3) {
    std::string shape = "(";
    for (py::ssize_t d = 0; d < a.ndim(); ++d)
      shape += (d ? ", " : "") + std::to_string(a.shape(d));
    ThrowValue(arg + ": expected shape (N, 3), got " + shape + (a.ndim() == 1 ? ",)" : ")"));
  }
  if (a.shape(0) < min_points) {
    ThrowValue(arg + ": needs at least " + std::to_string(min_points) + " points, got " +
               std::to_string(a.shape(0)));
  }
  Eigen::Matrix3Xd p(3, a.shape(0));
  for (py::ssize_t i = 0; i < a.shape(0); ++i) {
    for (int k = 0; k < 3; ++k) p(k, i) = a.at(i, k);
  }
  return p;
}

// A vector of exactly `size` entries (size < 0: any).
inline Eigen::VectorXd ToVector(const py::handle& obj, const std::string& arg, int size) {
  const Array a = ToArray(obj, arg);
  if (a.ndim() != 1 || (size >= 0 && a.shape(0) != size)) {
    ThrowValue(arg + ": expected shape (" + std::to_string(size) + ",), got " +
               std::to_string(a.size()) + " values in " + std::to_string(a.ndim()) + " dims");
  }
  return Eigen::Map<const Eigen::VectorXd>(a.data(), a.shape(0));
}

inline Eigen::MatrixXd ToMatrix(const py::handle& obj, const std::string& arg) {
  const Array a = ToArray(obj, arg);
  if (a.ndim() != 2 || a.shape(0) < 1 || a.shape(1) < 1) {
    ThrowValue(arg + ": expected a non-empty 2-D array");
  }
  Eigen::MatrixXd m(a.shape(0), a.shape(1));
  for (py::ssize_t i = 0; i < a.shape(0); ++i) {
    for (py::ssize_t j = 0; j < a.shape(1); ++j) m(i, j) = a.at(i, j);
  }
  return m;
}

// Points 3×N as an N×3 array.
inline Eigen::MatrixXd Rows(const Eigen::Matrix3Xd& p) { return p.transpose(); }

inline void RequireFile(const std::string& path, const std::string& arg) {
  if (!std::filesystem::is_regular_file(path)) {
    ThrowPy(PyExc_FileNotFoundError, arg + ": no such file: " + path);
  }
}

template <typename T>
std::vector<std::string> Names(const std::vector<T>& items) {
  std::vector<std::string> names;
  for (const T& item : items) names.push_back(item.name);
  return names;
}

inline std::string Join(const std::vector<std::string>& names) {
  std::string s;
  for (const std::string& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

// An H×W×3 uint8 array of an RGBA image (alpha dropped; row 0 is the top row).
inline py::array_t<std::uint8_t> ImageArray(const render::Image& image) {
  py::array_t<std::uint8_t> out({image.height, image.width, 3});
  auto m = out.mutable_unchecked<3>();
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      for (int c = 0; c < 3; ++c) m(y, x, c) = image.rgba[(size_t(y) * image.width + x) * 4 + c];
    }
  }
  return out;
}

inline py::object JsonToPython(const nlohmann::json& j) {
  return py::module_::import("json").attr("loads")(j.dump());
}

inline std::pair<int, int> CheckSize(const std::pair<int, int>& size) {
  if (size.first < 16 || size.second < 16 || size.first > 8192 || size.second > 8192) {
    ThrowValue("size: width and height must be in [16, 8192]");
  }
  return size;
}

inline render::Image RenderScene(const render::Scene& scene, const render::Camera& camera,
                                 int width, int height) {
  render::OffscreenContext context(render::GlBackend::kAuto);
  render::Renderer renderer(context.proc_loader());
  return renderer.Render(scene, camera, width, height, render::RenderOptions{});
}

// Binds each layer's functions and classes into `m`.
void BindTopology(py::module_& m);
void BindPlanning(py::module_& m);
void BindScenarioLoading(py::module_& m);  // scenario_loading.cc, called by BindPlanning
void BindRender(py::module_& m);

}  // namespace topoplan_py
