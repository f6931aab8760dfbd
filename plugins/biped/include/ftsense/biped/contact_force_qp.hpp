#pragma once
// Contact-point normal force distribution for one foot (method.md section 4).
//
// Model
// -----
// A foot touches the ground at n contact points c_l = (x_l, y_l) [m], l = 1..n, given in the foot
// frame, 1 <= n <= kMaxContactPoints (= 8; the biped uses 3..8). Given the foot's normal force
// F_z [N] and its centre of pressure r [m] (2-vector, foot frame), find the n point normal forces
// N [N]:
//
//     minimise    || C N - d ||^2 + N^T W N
//     subject to  1^T N = F_z ,   N_l >= 0 for every l
//
//     C = [x_1 .. x_n ; y_1 .. y_n]   (2 x n, m)
//     d = F_z r                        (2,     N m)   moments about the foot-frame origin
//     W = diag(w_1 .. w_n)             (n x n, m^2)   w_l > 0; the paper uses W = 0.01 I
//
// Standard form (what the KKT checker uses):  1/2 N^T H N + g^T N  with
//     H = 2 (C^T C + W)   (SPD because W > 0),     g = -2 C^T d.
// Lagrangian  L = 1/2 N^T H N + g^T N - lambda (1^T N - F_z) - mu^T N; the KKT conditions are
//     stationarity       H N + g - lambda 1 - mu = 0
//     primal feasibility 1^T N = F_z,  N >= 0
//     dual feasibility   mu >= 0
//     complementarity    mu_l N_l = 0.
// The objective is in N^2 m^2, so gradients, lambda and mu are in N m^2. lambda is the marginal
// cost of load; mu_l > 0 marks a point that would like to pull (it is held at zero).
//
// Note on W: W is in m^2 and competes with C^T C (for a 0.24 x 0.15 m foot, sum x_l^2 = 0.058
// m^2). With W = 0.01 I the moment equations C N = d are therefore NOT met exactly even for a CoP
// well inside the polygon: for a symmetric rectangle the realised CoP is
// r_x sum x^2 / (sum x^2 + w) (85 % of r_x for the foot above; 69 % of r_y). For any r inside
// the polygon ||C N - d|| <= sqrt(max_l w_l) F_z, so method.md's "met exactly" holds only in the
// limit w << sum x^2 (e.g. w = 1e-9 m^2, or the paper's 0.01 with coordinates in mm).
//
// Reduced (3 x 3) form used by the active-set solver
// --------------------------------------------------
// Fix a set A of points at zero and let F be the others. Writing a_l = (1, x_l, y_l) and
// p = (nu, q) with nu = lambda / 2 and q = d - C N (the unmet moment), stationarity on F gives
//     N_l = a_l^T p / w_l  (l in F),        mu_l = -2 a_l^T p  (l in A),
// and the equality and moment definitions become the 3 x 3 SPD system
//     K_F p = F_z (1, r_x, r_y),    K_F = sum_{l in F} a_l a_l^T / w_l + diag(0, 1, 1).
// K_F is positive definite for any non-empty F and any geometry (collinear or repeated points
// included), and its condition number is bounded by the geometry, not by F_z. So each
// equality-constrained subproblem costs O(n) to assemble plus one 3 x 3 Cholesky solve; no n x n
// factorisation is needed. At the optimum N_l = max(a_l^T p, 0) / w_l for every l.
//
// Algorithm (ActiveSetContactQp): primal active-set method (Nocedal & Wright, Alg. 16.3) on the
// bounds N_l >= 0, with the sum constraint always in the working set:
//   1. Start from the feasible point N = F_z / |F| on F, 0 on A (A = previous optimal active set
//      when warm starting, else empty).
//   2. Solve the subproblem on F (above) -> x. If some x_l < 0, step to the first bound hit
//      (ratio test), fix every point that reached zero, repeat.
//   3. Otherwise N = x; if every mu_l (l in A) >= -tol, N is optimal; else free the point with the
//      most negative mu_l and repeat.
// Termination: the objective never increases; a point is released only if mu_l < -1e-10 *
// (gradient scale), and then the new subproblem moves it up, so the step after a release is
// blocked at zero length only by another free point sitting exactly at zero (a degenerate tie;
// points that reach zero in a blocked step are fixed together to make that rare). Without such
// ties each release is followed by a strict decrease of the strictly convex objective, so no
// working set repeats and the loop is finite (at most 2^n working sets; in tests <= 2n
// iterations cold). Ties or rounding are caught by Options::max_iterations (cycle guard,
// status iteration_limit, forces still primal feasible).
// Cost: O(n) per iteration plus a 3 x 3 Cholesky. Measured on the dev machine (GCC 12 -O2, gait
// trajectory at 1 kHz, warm start): ~1.03 iterations and ~85 ns per loaded solve for n = 4,
// ~105 ns for n = 8; a cold start needs 1-4 iterations (<= 200 ns for n = 8). No heap
// allocation after construction; solve() is noexcept.
//
// Threading: a solver object holds warm-start state; use one object per thread (per foot).

#include <Eigen/Core>

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace ftsense::biped {

inline constexpr int kMaxContactPoints = 8;

/// 2 x n contact point coordinates [m], foot frame, n <= 8 (no heap allocation).
using ContactPoints = Eigen::Matrix<double, 2, Eigen::Dynamic, Eigen::ColMajor, 2, kMaxContactPoints>;
/// n-vector (forces [N], weights [m^2], multipliers), n <= 8 (no heap allocation).
using ContactVector = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, kMaxContactPoints, 1>;
/// n x n matrix, n <= 8.
using ContactMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor,
                                    kMaxContactPoints, kMaxContactPoints>;

/// Constant per foot: the contact points and the regularisation weights (diagonal of W).
struct ContactGeometry {
  ContactPoints points;  ///< 2 x n [m]
  ContactVector weights; ///< n, diagonal of W [m^2], each > 0 and finite

  int size() const noexcept { return static_cast<int>(points.cols()); }

  /// Throws std::invalid_argument naming the field, the value and the violated constraint
  /// (1 <= n <= 8, weights.size() == n, finite coordinates, 0 < w_l < inf).
  void validate() const;

  /// Four corner points of a length x width [m] rectangle centred at the origin (x forward),
  /// counter-clockwise from the front-left corner, all weights = weight [m^2].
  static ContactGeometry rectangle(double length, double width, double weight = 0.01);
};

/// One QP instance: geometry plus the load.
struct ContactQpProblem {
  ContactGeometry geometry;
  double fz = 0.0;                             ///< foot normal force [N]
  Eigen::Vector2d cop = Eigen::Vector2d::Zero(); ///< centre of pressure, foot frame [m]

  /// H = 2 (C^T C + W), n x n.
  ContactMatrix hessian() const;
  /// g = -2 C^T (fz cop), n.
  ContactVector linear_term() const;
  /// || C N - d ||^2 + N^T W N  (the unscaled objective of method.md).
  double objective(const Eigen::Ref<const Eigen::VectorXd>& forces) const;
};

enum class ContactQpStatus : std::uint8_t {
  optimal,         ///< KKT point found (F_z > 0)
  zero_load,       ///< F_z == 0: all forces zero (this is the exact optimum)
  invalid_input,   ///< F_z < 0, NaN/inf in F_z or cop, or F_z * cop overflows: forces zero
  iteration_limit, ///< cycle guard hit: forces primal feasible but maybe not optimal
  solver_failure,  ///< inner solver reported failure (Ceres only): forces zero
};

std::string_view to_string(ContactQpStatus status) noexcept;
/// Inverse of to_string; std::nullopt for unknown names.
std::optional<ContactQpStatus> contact_qp_status_from_string(std::string_view name) noexcept;
/// "optimal, zero_load, ..." for error messages.
std::string contact_qp_status_choices();

struct ContactQpSolution {
  ContactVector forces;  ///< N [N], n; always finite (zeros unless optimal/iteration_limit)
  ContactVector bound_multipliers; ///< mu, n, >= 0 at optimum; 0 for points with N_l > 0
  double sum_multiplier = 0.0;     ///< lambda of 1^T N = F_z (standard-form units)
  ContactQpStatus status = ContactQpStatus::invalid_input;
  int iterations = 0;              ///< subproblem solves
  std::uint32_t active_set = 0;    ///< bit l set <=> point l held at zero

  bool ok() const noexcept {
    return status == ContactQpStatus::optimal || status == ContactQpStatus::zero_load;
  }
};

/// Interface shared by the solvers. Geometry and weights are fixed at construction; solve() takes
/// the per-sample load. solve() never throws and never writes NaN into `out`.
class ContactForceQpSolver {
public:
  virtual ~ContactForceQpSolver() = default;
  virtual void solve(double fz, const Eigen::Vector2d& cop, ContactQpSolution& out) noexcept = 0;
  /// Forget warm-start state (next solve is a cold start).
  virtual void reset() noexcept = 0;
  virtual const ContactGeometry& geometry() const noexcept = 0;

  ContactQpProblem problem(double fz, const Eigen::Vector2d& cop) const {
    return ContactQpProblem{geometry(), fz, cop};
  }

protected:
  ContactForceQpSolver() = default;
  ContactForceQpSolver(const ContactForceQpSolver&) = default;
  ContactForceQpSolver& operator=(const ContactForceQpSolver&) = default;
};

/// KKT residuals, each relative:
///   stationarity       max_l |H N + g - lambda - mu_l|           / gradient_scale
///   primal_feasibility max(|1^T N - F_z|, max_l max(-N_l, 0))      / force_scale
///   dual_feasibility   max_l max(-mu_l, 0)                         / gradient_scale
///   complementarity    max_l |mu_l| |N_l|                          / (gradient_scale force_scale)
/// force_scale = max(1, |F_z|) [N];
/// gradient_scale = max(1, ||g||_inf, ||H||_inf ||N||_inf, |lambda|) (objective units per N).
struct ContactQpKkt {
  double sum_multiplier = 0.0; ///< lambda
  ContactVector bound_multipliers; ///< mu
  double stationarity = 0.0;
  double primal_feasibility = 0.0;
  double dual_feasibility = 0.0;
  double complementarity = 0.0;
  double force_scale = 1.0;
  double gradient_scale = 1.0;
  double tolerance = 0.0;

  double max_residual() const noexcept;
  bool satisfied() const noexcept { return max_residual() <= tolerance; } // false on NaN
  std::string describe() const; ///< one line, for test failure messages
};

/// Independent KKT check of forces N. Multipliers are estimated from N alone: the free set is
/// {l : N_l > tolerance * force_scale}; lambda is the mean of (H N + g)_l over it (min over all l
/// if it is empty), mu_l = (H N + g)_l - lambda off it and 0 on it. This does not trust any
/// solver output. Throws std::invalid_argument if forces.size() != n or the geometry is invalid.
ContactQpKkt check_kkt(const ContactQpProblem& problem, const Eigen::Ref<const Eigen::VectorXd>& forces,
                       double tolerance);

/// KKT check with given multipliers (e.g. ContactQpSolution's).
ContactQpKkt check_kkt(const ContactQpProblem& problem, const Eigen::Ref<const Eigen::VectorXd>& forces,
                       double sum_multiplier, const Eigen::Ref<const Eigen::VectorXd>& bound_multipliers,
                       double tolerance);

namespace detail {
/// The bit of contact point l in an active set's bitmask (l < 32; at most kMaxContactPoints).
constexpr std::uint32_t contact_bit(int l) noexcept { return std::uint32_t{1} << l; }

/// Equality-constrained subproblem oracle for the shared active-set loop: minimise the QP with
/// the points in `fixed` (bitmask) held at zero and 1^T N = F_z. `start` is feasible for it.
/// Writes x (0 on fixed points), lambda, and mu_l for fixed points (0 on free ones).
class EqualityQpSubproblem {
public:
  virtual bool solve(std::uint32_t fixed, const ContactVector& start, ContactVector& x, double& lambda,
                     ContactVector& mu) noexcept = 0;

protected:
  ~EqualityQpSubproblem() = default;
};

/// Primal active-set loop described in the header comment. Requires fz > 0 finite, n >= 1.
/// `out.active_set` is the initial working set on entry (must leave a point free).
/// `gradient_scale` sets the release tolerance on mu (relative 1e-10). Allocation-free.
void run_primal_active_set(int n, double fz, double gradient_scale, int max_iterations,
                           EqualityQpSubproblem& subproblem, ContactQpSolution& out) noexcept;

/// Validity of the per-sample input (finite, fz >= 0, fz * cop finite).
bool load_is_valid(double fz, const Eigen::Vector2d& cop) noexcept;
/// Sets out to n zeros with the given status (and zero multipliers).
void set_zero_solution(int n, ContactQpStatus status, ContactQpSolution& out) noexcept;
} // namespace detail

/// Exact primal active-set solver (see the header comment). Allocation-free after construction.
class ActiveSetContactQp final : public ContactForceQpSolver {
public:
  struct Options {
    bool warm_start = true;  ///< start from the previous optimal active set
    int max_iterations = 64; ///< cycle guard (> 0); n <= 8 needs at most ~2n in practice
    /// Throws std::invalid_argument naming the field on violation.
    void validate() const;
  };

  /// Throws std::invalid_argument if geometry or options are invalid.
  explicit ActiveSetContactQp(ContactGeometry geometry);
  ActiveSetContactQp(ContactGeometry geometry, Options options);

  void solve(double fz, const Eigen::Vector2d& cop, ContactQpSolution& out) noexcept override;
  void reset() noexcept override { warm_active_set_ = 0; }
  const ContactGeometry& geometry() const noexcept override { return geometry_; }
  const Options& options() const noexcept { return options_; }

private:
  class Subproblem final : public detail::EqualityQpSubproblem {
  public:
    explicit Subproblem(const ContactGeometry& geometry);
    bool solve(std::uint32_t fixed, const ContactVector& start, ContactVector& x, double& lambda,
               ContactVector& mu) noexcept override;
    Eigen::Vector3d rhs = Eigen::Vector3d::Zero(); ///< F_z (1, r_x, r_y), set per solve

  private:
    int n_;
    // Per point: the 6 distinct entries of a_l a_l^T / w_l (00, 01, 02, 11, 12, 22).
    Eigen::Matrix<double, 6, Eigen::Dynamic, Eigen::ColMajor, 6, kMaxContactPoints> outer_;
    ContactPoints points_;
    ContactVector weights_;
  };

  ContactGeometry geometry_;
  Options options_;
  Subproblem subproblem_;
  double hessian_norm_ = 0.0; ///< ||H||_inf, for the release tolerance
  double moment_norm_ = 0.0;  ///< max_l ||c_l||_1
  std::uint32_t warm_active_set_ = 0;
};

} // namespace ftsense::biped
