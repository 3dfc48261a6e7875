// Raw bytes between processes of one build: a writer that appends values in native layout and a
// reader that takes them back in the same order, refusing counts larger than the bytes left and
// reads past the end. For results a forked worker returns to its parent (the same binary, so the
// same layout); not a file format: nothing is versioned or portable across machines.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace base {

// Appends values: a count is a uint64; a string or vector is its count, then its bytes; a matrix
// its rows and columns, then its column-major doubles; a 3-vector 3 doubles; a pose the 16 doubles
// of its 4 × 4 matrix.
class ByteWriter {
 public:
  template <typename T>
  void Pod(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    out_.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  void Size(size_t n) { Pod(static_cast<std::uint64_t>(n)); }
  void String(const std::string& s) {
    Size(s.size());
    out_.append(s);
  }
  void Doubles(const std::vector<double>& v) {
    Size(v.size());
    Raw(v.data(), v.size());
  }
  void Vector(const Eigen::VectorXd& v) {
    Size(static_cast<size_t>(v.size()));
    Raw(v.data(), static_cast<size_t>(v.size()));
  }
  void Vectors(const std::vector<Eigen::VectorXd>& vs) {
    Size(vs.size());
    for (const Eigen::VectorXd& v : vs) Vector(v);
  }
  void Matrix(const Eigen::MatrixXd& m) {
    Size(static_cast<size_t>(m.rows()));
    Size(static_cast<size_t>(m.cols()));
    Raw(m.data(), static_cast<size_t>(m.size()));
  }
  void Vec3(const Eigen::Vector3d& v) { Raw(v.data(), 3); }
  void Pose(const Eigen::Isometry3d& p) { Raw(p.matrix().data(), 16); }
  // The bytes written so far (the writer is empty afterwards).
  std::string Take() { return std::move(out_); }

 private:
  void Raw(const double* d, size_t n) {
    if (n > 0) out_.append(reinterpret_cast<const char*>(d), sizeof(double) * n);
  }
  std::string out_;
};

// Reads what ByteWriter wrote, in the same order. Any read past the end, or a count larger than
// the bytes left could hold, throws std::runtime_error "<what>: bytes not written by this build's
// writer". `in` must outlive the reader.
class ByteReader {
 public:
  ByteReader(const std::string& in, std::string what) : in_(in), what_(std::move(what)) {}
  template <typename T>
  T Pod() {
    static_assert(std::is_trivially_copyable_v<T>);
    T v;
    std::memcpy(&v, Bytes(sizeof v), sizeof v);
    return v;
  }
  // A count of items of `unit` bytes each that the bytes left can hold.
  size_t Size(size_t unit = 1) {
    const std::uint64_t n = Pod<std::uint64_t>();
    if (n > (in_.size() - pos_) / unit) Fail();
    return static_cast<size_t>(n);
  }
  std::string String() {
    const size_t n = Size();
    return std::string(Bytes(n), n);
  }
  std::vector<double> Doubles() {
    std::vector<double> v(Size(sizeof(double)));
    Raw(v.data(), v.size());
    return v;
  }
  Eigen::VectorXd Vector() {
    Eigen::VectorXd v(static_cast<Eigen::Index>(Size(sizeof(double))));
    Raw(v.data(), static_cast<size_t>(v.size()));
    return v;
  }
  std::vector<Eigen::VectorXd> Vectors() {
    std::vector<Eigen::VectorXd> vs(Size(sizeof(std::uint64_t)));
    for (Eigen::VectorXd& v : vs) v = Vector();
    return vs;
  }
  Eigen::MatrixXd Matrix() {
    const size_t rows = Pod<std::uint64_t>(), cols = Pod<std::uint64_t>();
    if (cols != 0 && rows > (in_.size() - pos_) / sizeof(double) / cols) Fail();
    Eigen::MatrixXd m(static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(cols));
    Raw(m.data(), rows * cols);
    return m;
  }
  Eigen::Vector3d Vec3() {
    Eigen::Vector3d v;
    Raw(v.data(), 3);
    return v;
  }
  Eigen::Isometry3d Pose() {
    Eigen::Isometry3d p;
    Raw(p.matrix().data(), 16);
    return p;
  }
  bool at_end() const { return pos_ == in_.size(); }
  [[noreturn]] void Fail() const {
    throw std::runtime_error(what_ + ": bytes not written by this build's writer");
  }

 private:
  const char* Bytes(size_t n) {
    if (n > in_.size() - pos_) Fail();
    const char* p = in_.data() + pos_;
    pos_ += n;
    return p;
  }
  void Raw(double* d, size_t n) {
    const char* p = Bytes(sizeof(double) * n);
    if (n > 0) std::memcpy(d, p, sizeof(double) * n);
  }
  const std::string& in_;
  std::string what_;
  size_t pos_ = 0;
};

}  // namespace base
