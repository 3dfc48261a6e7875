// The topology layer in Python: writhe matrices and their Jacobians, winding numbers.
#include "python/bind/common.h"
#include "base/enum_names.h"
#include "topology/linking_crossings.h"
#include "topology/winding.h"
#include "topology/writhe.h"
#include "topology/writhe_stream.h"

namespace topoplan_py {
namespace {

// --- topology --------------------------------------------------------------------------------

// Largest dense Jacobian writhe_jacobian returns: (N_A−1)(N_B−1)(N_A+N_B)·3 doubles ≤ 2^27 (1 GiB).
constexpr double kMaxDenseJacobianEntries = double(1 << 27);

Eigen::MatrixXd WritheMatrixPy(const py::handle& a_obj, const py::handle& b_obj,
                               bool unsigned_variant) {
  topology::WritheOptions options;
  if (unsigned_variant) options.variant = topology::WritheVariant::kUnsignedSolidAngle;
  const Eigen::Matrix3Xd a = ToPoints(a_obj, "A"), b = ToPoints(b_obj, "B");
  py::gil_scoped_release release;  // O(N_A N_B); other Python threads run meanwhile
  return topology::WritheMatrix(a, b, options);
}

py::tuple WritheJacobianPy(const py::handle& a_obj, const py::handle& b_obj) {
  const Eigen::Matrix3Xd a = ToPoints(a_obj, "A"), b = ToPoints(b_obj, "B");
  const double entries =
      double(a.cols() - 1) * double(b.cols() - 1) * double(a.cols() + b.cols()) * 3.0;
  if (entries > kMaxDenseJacobianEntries) {
    char msg[256];
    std::snprintf(msg, sizeof msg,
                  "A, B: the dense Jacobians of %ld x %ld points would hold %.3g numbers "
                  "(%.3g GB), more than the limit of %.3g (1 GiB); use fewer points, or "
                  "writhe_matrix for W alone",
                  long(a.cols()), long(b.cols()), entries, entries * 8e-9,
                  kMaxDenseJacobianEntries);
    ThrowValue(msg);
  }
  Eigen::MatrixXd w;
  topology::WritheJacobian jac;
  {
    py::gil_scoped_release release;
    topology::WritheWorkspace ws;
    topology::WritheMatrixWithJacobian(a, b, {}, &w, &jac, &ws);
  }
  const py::ssize_t rows = jac.rows, cols = jac.cols, na = a.cols(), nb = b.cols();
  py::array_t<double> da({rows, cols, na, py::ssize_t(3)}), db({rows, cols, nb, py::ssize_t(3)});
  std::fill(da.mutable_data(), da.mutable_data() + da.size(), 0.0);
  std::fill(db.mutable_data(), db.mutable_data() + db.size(), 0.0);
  auto ma = da.mutable_unchecked<4>();
  auto mb = db.mutable_unchecked<4>();
  for (py::ssize_t i = 0; i < rows; ++i) {
    for (py::ssize_t j = 0; j < cols; ++j) {
      const auto col = jac.pair.col(i * cols + j);
      for (int k = 0; k < 3; ++k) {
        ma(i, j, i, k) = col(k);
        ma(i, j, i + 1, k) = col(3 + k);
        mb(i, j, j, k) = col(6 + k);
        mb(i, j, j + 1, k) = col(9 + k);
      }
    }
  }
  return py::make_tuple(w, da, db);
}

py::dict LinkingNumberPy(const py::handle& a_obj, const py::handle& b_obj, int threads,
                         const std::string& method_name) {
  const topology::LinkingMethod method = base::ParseEnum<topology::LinkingMethod>(method_name, "linking method");
  const Eigen::Matrix3Xd a = ToPoints(a_obj, "A"), b = ToPoints(b_obj, "B");
  topology::WritheStreamOptions options;
  options.threads = threads;
  topology::LinkingResult r;
  {
    py::gil_scoped_release release;  // crossings: near-linear; gauss: O(N_A N_B), streamed
    r = topology::LinkingNumberAuto(a, b, method, options);
  }
  py::dict d;
  const bool ok = r.status == topology::LinkingStatus::kCertified;
  const bool crossings = r.method == topology::LinkingMethod::kCrossings;
  d["linking_number"] = ok ? py::object(py::int_(r.linking_number)) : py::object(py::none());
  d["status"] = topology::LinkingStatusName(r.status);
  d["method"] = base::ToName(r.method);
  d["crossings"] = r.crossings;
  d["gauss_integral"] = crossings ? py::object(py::none()) : py::object(py::float_(r.gauss_integral));
  d["error_bound"] = r.error_bound;
  d["distance"] = r.distance;
  d["degenerate_pairs"] = r.degenerate_pairs;
  return d;
}

py::object WritheTotalPy(const py::handle& a_obj, const py::handle& b_obj, bool row_sums,
                         int threads) {
  const Eigen::Matrix3Xd a = ToPoints(a_obj, "A"), b = ToPoints(b_obj, "B");
  topology::WritheStreamOptions options;
  options.threads = threads;
  options.row_sums = row_sums;
  topology::WritheSums s;
  {
    py::gil_scoped_release release;
    s = topology::StreamWritheSums(a, b, options);
  }
  if (!row_sums) return py::float_(s.total);
  return py::make_tuple(s.total, Eigen::VectorXd(s.row_sums));
}

py::object WindingPy(const py::handle& chain, const py::handle& point, const py::handle& dir,
                     bool gradient, bool unsigned_variant) {
  topology::Axis axis;
  axis.point = ToVector(point, "axis_point", 3);
  axis.direction = ToVector(dir, "axis_dir", 3);
  if (axis.direction.norm() == 0.0) ThrowValue("axis_dir: must be non-zero");
  topology::WindingOptions options;
  if (unsigned_variant) options.variant = topology::WindingVariant::kUnsignedArccos;
  const Eigen::Matrix3Xd p = ToPoints(chain, "chain");
  if (!gradient) return py::float_(topology::WindingNumber(p, axis, options));
  Eigen::Matrix3Xd grad;
  const double w = topology::WindingNumber(p, axis, options, &grad);
  return py::make_tuple(w, Rows(grad));
}

}  // namespace

void BindTopology(py::module_& m) {
  // topology
  m.def("writhe_matrix", &WritheMatrixPy, py::arg("A"), py::arg("B"), py::arg("unsigned") = false,
        "Writhe matrix of chains A (N_A x 3) and B (N_B x 3): W[i, j] = Gauss linking integral of\n"
        "segment i of A with segment j of B, shape (N_A-1, N_B-1). Its sum over two closed\n"
        "polygons is their linking number. unsigned=True gives |solid angle| in [0, 2 pi)\n"
        "(no 1/(4 pi)).");
  m.def(
      "writhe_jacobian", &WritheJacobianPy, py::arg("A"), py::arg("B"),
      "(W, dW_dA, dW_dB): the signed writhe matrix and its derivatives with respect to every\n"
      "chain point, dW_dA of shape (N_A-1, N_B-1, N_A, 3), dW_dB of shape (N_A-1, N_B-1, N_B, 3)\n"
      "(dW_dA[i, j, p, k] = dW[i, j]/dA[p, k]; nonzero only for p in {i, i+1}). The arrays are\n"
      "dense: sizes whose two Jacobians would exceed 2^27 numbers (1 GiB) raise ValueError.");
  m.def("linking_number", &LinkingNumberPy, py::arg("A"), py::arg("B"), py::arg("threads") = 0,
        py::arg("method") = "auto",
        "Linking number of two closed chains (N x 3; last point = first, up to 1e-9 of the\n"
        "size). method 'crossings': half the signed crossings of a projection, every sign\n"
        "certified (near-linear time); 'gauss': the Gauss integral, streamed in O(N) memory on\n"
        "`threads` threads (0: all cores), rounded when its error bound allows; 'auto' (default):\n"
        "crossings, else gauss. Returns a dict: linking_number (int, or None unless status ==\n"
        "'certified'), status ('certified', 'not_integer', 'touching', 'uncertain'), method (the\n"
        "one used), crossings, gauss_integral (None for crossings), error_bound (a bound on the\n"
        "float error of gauss_integral), distance (to the nearest integer), degenerate_pairs.\n"
        "Raises ValueError for an open chain.");
  m.def("writhe_total", &WritheTotalPy, py::arg("A"), py::arg("B"), py::arg("row_sums") = false,
        py::arg("threads") = 0,
        "Sum of the writhe matrix of A and B without forming it (O(N) memory, any length).\n"
        "row_sums=True returns (total, row_sums) with row_sums of length N_A-1.");
  m.def("winding", &WindingPy, py::arg("chain"), py::arg("axis_point"), py::arg("axis_dir"),
        py::arg("gradient") = false, py::arg("unsigned") = false,
        "Winding number (turns) of chain (N x 3) about the oriented axis through axis_point along\n"
        "axis_dir (right-hand rule). gradient=True returns (w, dw_dchain) with dw_dchain N x 3.\n"
        "unsigned=True uses the arccos variant of Ivan et al. (2013).");
}

}  // namespace topoplan_py
