// Analytic grasp quality from contact points: the Ferrari–Canny ε (L1 metric) and the Wilson
// score interval for success rates of repeated trials.
//
// ε (Ferrari & Canny 1992, "Planning optimal grasps"): every contact i at point p_i ∈ ℝ³ with
// unit inward normal n_i (pointing into the object) and Coulomb friction μ gets a friction cone
// linearised as a pyramid of m edges (m = 8 by default),
//   f_ik = n_i + μ (cos θ_k t1_i + sin θ_k t2_i),  θ_k = 2πk/m,  k = 0..m−1,
// with (t1_i, t2_i, n_i) an orthonormal frame, so every edge carries a unit normal force. Its
// primitive wrench (6-vector, force [N] then torque / ρ [N]) about the object centre c is
//   w_ik = ( f_ik ; (p_i − c) × f_ik / ρ ),
// ρ [m] = the object's radius of gyration, which makes torques commensurate with forces. L1:
// W = conv{w_ik} (the wrenches reachable with Σ_i normal force ≤ 1), and
//   ε = min over the facets of W of the distance of the origin to the facet hyperplane
// = the radius of the largest origin-centred ball inside W, or 0 when the origin is not
// strictly inside W (no force closure). ε is dimensionless (wrench per unit total normal
// force), invariant to the order of the contacts and to a common rigid motion of contacts and
// centre; scaling the contacts, centre and ρ by s leaves it unchanged. The 6-D hull is computed
// with qhull (libqhull_r).
#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

namespace planning {

// One contact: world-frame point [m] and unit normal pointing into the object.
struct GraspContact {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
};

struct EpsilonOptions {
  int friction_edges = 8;           // pyramid edges m per contact, >= 3
  double radius_of_gyration = 0.0;  // ρ [m], > 0 (required)
};

// Ferrari–Canny ε (see the file comment) of `contacts` about `centre` with friction μ >= 0.
// Returns 0 for fewer than 2 contacts, when the primitive wrenches do not span ℝ⁶ (e.g. all
// normals parallel and no friction, a single contact, contacts on one line) or the origin is not
// strictly inside their hull. Throws std::invalid_argument for μ < 0, non-finite input, a
// normal of zero length, friction_edges < 3 or radius_of_gyration <= 0.
double EpsilonQuality(const std::vector<GraspContact>& contacts, const Eigen::Vector3d& centre,
                      double mu, const EpsilonOptions& options);

// The primitive wrenches w_ik (6 × (contacts·m), column i·m + k), as used by EpsilonQuality.
// Same argument checks.
Eigen::Matrix<double, 6, Eigen::Dynamic> PrimitiveWrenches(
    const std::vector<GraspContact>& contacts, const Eigen::Vector3d& centre, double mu,
    const EpsilonOptions& options);

// Wilson score interval [lo, hi] ⊂ [0, 1] for a binomial proportion p̂ = successes / trials:
//   centre = (p̂ + z²/2n) / (1 + z²/n),  half = z/(1 + z²/n) · sqrt(p̂(1 − p̂)/n + z²/4n²),
// [lo, hi] = [centre − half, centre + half] (clamped to [0, 1]); z = 1.959964 gives 95 %.
// Throws std::invalid_argument unless 0 <= successes <= trials, trials >= 1 and z > 0.
Eigen::Vector2d WilsonInterval(int successes, int trials, double z = 1.959964);

// Spearman's rank correlation of paired samples x, y (same length n): the Pearson correlation of
// their ranks, ties given their average rank, in [−1, 1]. Used to ask how well a fast measure
// (ε) orders the outcomes of the slow one (the ODE test: stable 0/1 or directions held). Returns
// nullopt when it is undefined: n < 2 or all x (or all y) equal. Throws std::invalid_argument for
// different lengths or a non-finite value.
std::optional<double> SpearmanCorrelation(const std::vector<double>& x,
                                          const std::vector<double>& y);

}  // namespace planning
