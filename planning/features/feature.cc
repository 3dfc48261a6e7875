#include "planning/features/feature.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <stdexcept>
#include <string>

#include "topology/writhe.h"

namespace planning {

std::unique_ptr<FeatureData> Feature::CreateData(const Robot&) const { return nullptr; }
long Feature::collision_queries(const FeatureData*) const { return 0; }
long Feature::narrow_phase_calls(const FeatureData*) const { return 0; }

namespace {

void CheckLink(const Robot& robot, int link, const char* what) {
  if (link < 0 || link >= static_cast<int>(robot.links.size())) {
    throw std::invalid_argument(std::string(what) + ": link index " + std::to_string(link) +
                                " out of range (robot has " + std::to_string(robot.links.size()) +
                                " links)");
  }
}

void CheckChain(const Robot& robot, int chain, const char* what) {
  if (chain < 0 || chain >= static_cast<int>(robot.chains.size())) {
    throw std::invalid_argument(std::string(what) + ": chain index " + std::to_string(chain) +
                                " out of range (robot has " + std::to_string(robot.chains.size()) +
                                " chains)");
  }
}

// Buffers holding one 3 × n point Jacobian or a 6 × n frame Jacobian.
struct JacobianData : FeatureData {
  explicit JacobianData(int rows, int n) : jac(rows, n) {}
  Eigen::MatrixXd jac;
};

// --- position ------------------------------------------------------------------------------------
class PositionFeature : public Feature {
 public:
  PositionFeature(int link, const Eigen::Vector3d& offset) : link_(link), offset_(offset) {}
  int dim() const override { return 3; }
  std::string name() const override { return "position"; }
  void Eval(const Robot& robot, const KinematicsData& kin, FeatureData*,
            Eigen::Ref<Eigen::VectorXd> y, Eigen::MatrixXd* J) const override {
    y = kin.world_from_link[link_] * offset_;
    if (J != nullptr) PointJacobian(robot, kin, link_, offset_, *J);
  }

 private:
  int link_;
  Eigen::Vector3d offset_;
};

// --- axis alignment ------------------------------------------------------------------------------
class AxisAlignmentFeature : public Feature {
 public:
  AxisAlignmentFeature(int link, const Eigen::Vector3d& axis, const Eigen::Vector3d& dir)
      : link_(link), axis_(axis.normalized()), dir_(dir.normalized()) {}
  int dim() const override { return 1; }
  std::string name() const override { return "axis_alignment"; }
  std::unique_ptr<FeatureData> CreateData(const Robot& robot) const override {
    return std::make_unique<JacobianData>(6, num_dofs(robot));
  }
  void Eval(const Robot& robot, const KinematicsData& kin, FeatureData* data,
            Eigen::Ref<Eigen::VectorXd> y, Eigen::MatrixXd* J) const override {
    const Eigen::Vector3d a = kin.world_from_link[link_].linear() * axis_;
    y[0] = a.dot(dir_);
    if (J != nullptr) {
      auto* d = static_cast<JacobianData*>(data);
      FrameJacobian(robot, kin, link_, d->jac);
      J->noalias() = a.cross(dir_).transpose() * d->jac.bottomRows<3>();
    }
  }

 private:
  int link_;
  Eigen::Vector3d axis_, dir_;
};

// --- joint limits --------------------------------------------------------------------------------
class JointLimitFeature : public Feature {
 public:
  JointLimitFeature(const Robot& robot, double margin)
      : lower_(LowerLimits(robot)), upper_(UpperLimits(robot)), margin_(margin) {}
  int dim() const override { return static_cast<int>(lower_.size()); }
  std::string name() const override { return "joint_limits"; }
  void Eval(const Robot&, const KinematicsData& kin, FeatureData*, Eigen::Ref<Eigen::VectorXd> y,
            Eigen::MatrixXd* J) const override {
    if (J != nullptr) J->setZero();
    for (int k = 0; k < dim(); ++k) {
      const double q = kin.q[k];
      const double lo = lower_[k] + margin_, hi = upper_[k] - margin_;
      y[k] = 0.0;
      if (q < lo) {
        y[k] = lo - q;
        if (J != nullptr) (*J)(k, k) = -1.0;
      } else if (q > hi) {
        y[k] = -(q - hi);
        if (J != nullptr) (*J)(k, k) = -1.0;
      }
    }
  }

 private:
  Eigen::VectorXd lower_, upper_;
  double margin_;
};

// --- q itself
// --------------------------------------------------------------------------------------
class JointPositionFeature : public Feature {
 public:
  explicit JointPositionFeature(int n) : n_(n) {}
  int dim() const override { return n_; }
  std::string name() const override { return "joint_position"; }
  void Eval(const Robot&, const KinematicsData& kin, FeatureData*, Eigen::Ref<Eigen::VectorXd> y,
            Eigen::MatrixXd* J) const override {
    y = kin.q;
    if (J != nullptr) J->setIdentity();
  }

 private:
  int n_;
};

// --- box
// -------------------------------------------------------------------------------------------
class BoxFeature : public Feature {
 public:
  BoxFeature(int link, const Eigen::Vector3d& offset, const Eigen::Vector3d& c,
             const Eigen::Vector3d& h, double margin)
      : link_(link),
        offset_(offset),
        lo_(c - h + Eigen::Vector3d::Constant(margin)),
        hi_(c + h - Eigen::Vector3d::Constant(margin)) {}
  int dim() const override { return 3; }
  std::string name() const override { return "box"; }
  std::unique_ptr<FeatureData> CreateData(const Robot& robot) const override {
    return std::make_unique<JacobianData>(3, num_dofs(robot));
  }
  void Eval(const Robot& robot, const KinematicsData& kin, FeatureData* data,
            Eigen::Ref<Eigen::VectorXd> y, Eigen::MatrixXd* J) const override {
    const Eigen::Vector3d p = kin.world_from_link[link_] * offset_;
    auto* d = static_cast<JacobianData*>(data);
    if (J != nullptr) {
      PointJacobian(robot, kin, link_, offset_, d->jac);
      J->setZero();
    }
    for (int k = 0; k < 3; ++k) {
      y[k] = std::max(0.0, p[k] - hi_[k]) - std::max(0.0, lo_[k] - p[k]);
      if (J != nullptr && (p[k] > hi_[k] || p[k] < lo_[k])) J->row(k) = d->jac.row(k);
    }
  }

 private:
  int link_;
  Eigen::Vector3d offset_, lo_, hi_;
};

// --- writhe
// ----------------------------------------------------------------------------------------
struct ChainData : FeatureData {
  ChainData(int points, int n) : P(3, points), dP(3 * points, n) {}
  Eigen::Matrix3Xd P;
  Eigen::MatrixXd dP;
  Eigen::MatrixXd W, dW;
  topology::WritheJacobian wjac;
  topology::WritheWorkspace ws;
  Eigen::Matrix3Xd grad, grad_object;
};

class WritheFeature : public Feature {
 public:
  WritheFeature(const Robot& robot, int chain, const Eigen::Matrix3Xd& object, WritheOutput out)
      : chain_(chain),
        object_(object),
        output_(out),
        rows_(ChainSize(robot, chain) - 1),
        cols_(static_cast<int>(object.cols()) - 1) {}
  int dim() const override { return output_ == WritheOutput::kTotal ? 1 : rows_ * cols_; }
  std::string name() const override {
    return output_ == WritheOutput::kTotal ? "writhe_total" : "writhe";
  }
  std::unique_ptr<FeatureData> CreateData(const Robot& robot) const override {
    auto d = std::make_unique<ChainData>(rows_ + 1, num_dofs(robot));
    d->W.resize(rows_, cols_);
    d->dW.resize(rows_ * cols_, num_dofs(robot));
    return d;
  }
  void Eval(const Robot& robot, const KinematicsData& kin, FeatureData* data,
            Eigen::Ref<Eigen::VectorXd> y, Eigen::MatrixXd* J) const override {
    auto* d = static_cast<ChainData*>(data);
    ChainPoints(robot, kin, chain_, &d->P);
    topology::WritheOptions options;
    if (J == nullptr) {
      topology::WritheMatrix(d->P, object_, options, &d->W, &d->ws);
    } else {
      topology::WritheMatrixWithJacobian(d->P, object_, options, &d->W, &d->wjac, &d->ws);
      ChainJacobian(robot, kin, chain_, d->dP);
    }
    if (output_ == WritheOutput::kTotal) {
      y[0] = d->W.sum();
      if (J != nullptr) {
        // ∂Σ/∂q = Σ_k (∂Σ/∂p_k)ᵀ ∂p_k/∂q.
        topology::WeightedWritheGradient(d->wjac, Eigen::MatrixXd(), &d->grad, &d->grad_object);
        J->noalias() = Eigen::Map<const Eigen::RowVectorXd>(d->grad.data(), d->grad.size()) * d->dP;
      }
    } else {
      for (int i = 0; i < rows_; ++i) {
        for (int j = 0; j < cols_; ++j) y[i * cols_ + j] = d->W(i, j);
      }
      if (J != nullptr) {
        topology::ChainWritheJacobian(d->wjac, d->dP, Eigen::MatrixXd(), J);
      }
    }
  }

 private:
  int chain_;
  Eigen::Matrix3Xd object_;
  WritheOutput output_;
  int rows_, cols_;
};

// --- winding
// ---------------------------------------------------------------------------------------
class WindingFeature : public Feature {
 public:
  WindingFeature(const Robot& robot, int chain, const topology::Axis& axis)
      : chain_(chain), axis_(axis), points_(ChainSize(robot, chain)) {}
  int dim() const override { return 1; }
  std::string name() const override { return "winding"; }
  std::unique_ptr<FeatureData> CreateData(const Robot& robot) const override {
    auto d = std::make_unique<ChainData>(points_, num_dofs(robot));
    d->grad.resize(3, points_);
    return d;
  }
  void Eval(const Robot& robot, const KinematicsData& kin, FeatureData* data,
            Eigen::Ref<Eigen::VectorXd> y, Eigen::MatrixXd* J) const override {
    auto* d = static_cast<ChainData*>(data);
    ChainPoints(robot, kin, chain_, &d->P);
    y[0] = topology::WindingNumber(d->P, axis_, {}, J != nullptr ? &d->grad : nullptr);
    if (J != nullptr) {
      ChainJacobian(robot, kin, chain_, d->dP);
      J->noalias() = Eigen::Map<const Eigen::RowVectorXd>(d->grad.data(), d->grad.size()) * d->dP;
    }
  }

 private:
  int chain_;
  topology::Axis axis_;
  int points_;
};

// --- line clearance
// ----------------------------------------------------------------------------
class LineClearanceFeature : public Feature {
 public:
  LineClearanceFeature(const Robot& robot, int chain, const topology::Axis& line, double margin)
      : chain_(chain),
        point_(line.point),
        dir_(line.direction.normalized()),
        margin_(margin),
        points_(ChainSize(robot, chain)) {}
  int dim() const override { return points_ - 1; }
  std::string name() const override { return "line_clearance"; }
  std::unique_ptr<FeatureData> CreateData(const Robot& robot) const override {
    return std::make_unique<ChainData>(points_, num_dofs(robot));
  }
  void Eval(const Robot& robot, const KinematicsData& kin, FeatureData* data,
            Eigen::Ref<Eigen::VectorXd> y, Eigen::MatrixXd* J) const override {
    auto* d = static_cast<ChainData*>(data);
    ChainPoints(robot, kin, chain_, &d->P);
    y.setZero();
    if (J != nullptr) {
      J->setZero();
      ChainJacobian(robot, kin, chain_, d->dP);
    }
    const Eigen::Matrix3d perp = Eigen::Matrix3d::Identity() - dir_ * dir_.transpose();
    for (int s = 0; s + 1 < points_; ++s) {
      // Components perpendicular to the line: a(σ) = a0 + σ·v, σ ∈ [0, 1]; d = min_σ |a(σ)|.
      const Eigen::Vector3d a0 = perp * (d->P.col(s) - point_);
      const Eigen::Vector3d v = perp * (d->P.col(s + 1) - d->P.col(s));
      const double vv = v.squaredNorm();
      const double sigma = vv > 1e-18 ? std::clamp(-a0.dot(v) / vv, 0.0, 1.0) : 0.5;
      const Eigen::Vector3d a = a0 + sigma * v;
      const double dist = a.norm();
      if (dist >= margin_) continue;
      y[s] = 1.0 - dist / margin_;
      if (J == nullptr || dist < 1e-12) continue;
      // ∂d/∂p_s = (1 − σ) nᵀ, ∂d/∂p_{s+1} = σ nᵀ (n = a/d ⊥ line; σ is stationary or clamped).
      const Eigen::RowVector3d n = a.transpose() / dist;
      J->row(s).noalias() -= ((1.0 - sigma) / margin_) * n * d->dP.middleRows<3>(3 * s);
      J->row(s).noalias() -= (sigma / margin_) * n * d->dP.middleRows<3>(3 * s + 3);
    }
  }

 private:
  int chain_;
  Eigen::Vector3d point_, dir_;
  double margin_;
  int points_;
};

}  // namespace

std::unique_ptr<Feature> MakePositionFeature(const Robot& robot, int link,
                                             const Eigen::Vector3d& offset) {
  CheckLink(robot, link, "position feature");
  return std::make_unique<PositionFeature>(link, offset);
}

std::unique_ptr<Feature> MakeAxisAlignmentFeature(const Robot& robot, int link,
                                                  const Eigen::Vector3d& axis_link,
                                                  const Eigen::Vector3d& direction_world) {
  CheckLink(robot, link, "axis_alignment feature");
  if (axis_link.norm() < 1e-12 || direction_world.norm() < 1e-12 || !axis_link.allFinite() ||
      !direction_world.allFinite()) {
    throw std::invalid_argument("axis_alignment feature: axis and direction must be non-zero");
  }
  return std::make_unique<AxisAlignmentFeature>(link, axis_link, direction_world);
}

std::unique_ptr<Feature> MakeJointLimitFeature(const Robot& robot, double margin) {
  if (!(margin >= 0.0)) throw std::invalid_argument("joint_limits feature: margin must be >= 0");
  return std::make_unique<JointLimitFeature>(robot, margin);
}

std::unique_ptr<Feature> MakeJointPositionFeature(const Robot& robot) {
  return std::make_unique<JointPositionFeature>(num_dofs(robot));
}

std::unique_ptr<Feature> MakeBoxFeature(const Robot& robot, int link, const Eigen::Vector3d& offset,
                                        const Eigen::Vector3d& center,
                                        const Eigen::Vector3d& half_extent, double margin) {
  CheckLink(robot, link, "box feature");
  if (!(half_extent.minCoeff() > margin) || !(margin >= 0.0)) {
    throw std::invalid_argument("box feature: half extents must exceed the margin (>= 0)");
  }
  return std::make_unique<BoxFeature>(link, offset, center, half_extent, margin);
}

std::unique_ptr<Feature> MakeWritheFeature(const Robot& robot, int chain,
                                           const Eigen::Matrix3Xd& object_chain,
                                           WritheOutput output) {
  CheckChain(robot, chain, "writhe feature");
  if (object_chain.cols() < 2 || !object_chain.allFinite()) {
    throw std::invalid_argument("writhe feature: the object chain needs >= 2 finite points");
  }
  return std::make_unique<WritheFeature>(robot, chain, object_chain, output);
}

std::unique_ptr<Feature> MakeWindingFeature(const Robot& robot, int chain,
                                            const topology::Axis& axis) {
  CheckChain(robot, chain, "winding feature");
  if (axis.direction.norm() < 1e-12) {
    throw std::invalid_argument("winding feature: zero axis direction");
  }
  return std::make_unique<WindingFeature>(robot, chain, axis);
}

std::unique_ptr<Feature> MakeLineClearanceFeature(const Robot& robot, int chain,
                                                  const topology::Axis& line, double margin) {
  CheckChain(robot, chain, "line_clearance feature");
  if (!(line.direction.norm() > 1e-12) || !line.direction.allFinite() || !line.point.allFinite()) {
    throw std::invalid_argument(
        "line_clearance feature: the line needs a finite non-zero direction");
  }
  if (!(margin > 0.0)) throw std::invalid_argument("line_clearance feature: margin must be > 0");
  return std::make_unique<LineClearanceFeature>(robot, chain, line, margin);
}

}  // namespace planning
