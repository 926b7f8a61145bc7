// The fractional step of the saturated v-pw model (docs/theory.md §6.1-6.4): after the RK-TSPH
// pass has given v* with the pore pressure frozen, solve
//   [V/(Q dt) - (alpha^2 dt/rho) Ltilde - k_bar Ltilde] p^{n+1}
//       = V p^n/(Q dt) - alpha V div v* - beta (alpha^2 dt/rho) Ltilde p^n          (6.3)
// by preconditioned conjugate gradients (warm start from p^n), then correct the velocity,
//   v^{n+1} = v* - (alpha dt/rho) grad(p^{n+1} - beta p^n),                          (6.4)
// and impose the boundary conditions again. The matrix is assembled once (dt is constant).
// On a lattice the Laplacian is Morris's and the gradient the corrected collocated one (radius
// search); off a lattice both come from the cells (cell_laplacian.hpp, docs/theory.md §6.3).
//
// In 2D the left-hand side also carries the checkerboard stabilisation S p^{n+1}
// (docs/theory.md §6.6): S = sum over lattice cells c of w_c b_c b_c^T, b_c = (+1, -1, -1, +1) on
// the cell's corners (the discrete twist dx^2 d2p/dxdy), w_c = theta (alpha^2 dt/rho_c) V lambda/16
// with lambda the checkerboard rate of the Laplacian. S is symmetric positive semi-definite and
// conservative (rows sum to zero), vanishes on every field f(x) + g(y) (linear fields, the 1D
// drained-face boundary layer, the undrained column), and removes the p_w checkerboard, which
// both gradient operators miss, at the rate theta/(1 + theta) per step in the undrained limit.
#pragma once

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCore>
#include <memory>
#include <vector>

#include "rktsph/boundary/boundary_conditions.hpp"
#include "rktsph/core/checkpoint.hpp"
#include "rktsph/geometry/node_sets.hpp"
#include "rktsph/linear_algebra/conjugate_gradient.hpp"
#include "rktsph/linear_algebra/smoothed_aggregation.hpp"
#include "rktsph/models/saturated_vpw.hpp"
#include "rktsph/sph/laplacian.hpp"
#include "rktsph/time/rk_taylor_step.hpp"

namespace rktsph {

struct SolverStatistics {
  long solves = 0;
  long total_iterations = 0;
  long max_iterations = 0;
  double last_residual = 0.0;       ///< relative residual of the last solve
  double assembly_seconds = 0.0;    ///< matrix assembly (once)
  double solve_seconds = 0.0;       ///< conjugate gradients, all steps
  double projection_seconds = 0.0;  ///< the whole projection (right-hand side, solve, correction)
  double laplacian_scale = 1.0;
  std::size_t multigrid_levels = 0;   ///< 0 unless the multigrid preconditioner is used
  double multigrid_complexity = 0.0;  ///< entries of all levels over those of the matrix
};

/// How the pore pressure is solved for (docs/theory.md §6.2-§6.7); the case's `pore_fluid` keys
/// of the same names.
struct PressureSolveOptions {
  double projection_beta = 1.0;  ///< incremental projection (1) or not (0), §6.2
  double tolerance = 1e-8;       ///< relative residual of the conjugate gradients
  long max_iterations = 0;       ///< 0: twice the number of nodes
  PressurePreconditioner preconditioner = PressurePreconditioner::Multigrid;
  double laplacian_scale = 0.0;     ///< 0: the consistency scale (§6.3)
  double checkerboard_theta = 0.0;  ///< theta of the checkerboard term, §6.6
};

class PressureProjection final : public StepProjection {
 public:
  PressureProjection(const SaturatedVpw& model, const NodeSets& nodes,
                     const OperatorOptions& options, const BoundaryConditions& conditions,
                     const PressureSolveOptions& solve, double dt);
  ~PressureProjection() override;

  void project(State& state, double time, double dt) override;
  const SolverStatistics& statistics() const { return statistics_; }
  /// The values a restarted run needs to solve as this one would: the previous pressure of the
  /// warm start (which changes the iterates, so the last bits of the result) and the statistics.
  void save_checkpoint(CheckpointOut& out) const override;
  void restore_checkpoint(CheckpointIn& in) override;
  const LaplacianMatrix& laplacian() const { return laplacian_; }
  /// A copy of the assembled system matrix (Dirichlet rows decoupled), for tests.
  Eigen::SparseMatrix<double> system() const {
    return preconditioner_ == PressurePreconditioner::Multigrid
               ? Eigen::SparseMatrix<double>(system_rows_)
               : system_;
  }
  /// The checkerboard stabilisation S (all rows and columns, before the drained rows are
  /// decoupled); empty unless 2D with theta > 0.
  const Eigen::SparseMatrix<double>& stabilisation() const { return stabilisation_; }

 private:
  /// The gradient, the Laplacian and its checkerboard rate: from a radius search on a lattice
  /// (Morris, eq. 6.3), from the cells otherwise (eqs. 6.6, 6.7).
  void build_operators(const NodeSets& nodes, const OperatorOptions& options,
                       double laplacian_scale);
  void assemble(double dt);
  /// The entries of S (eq. 6.5) for this dt, every row and column; empty unless 2D and theta > 0.
  std::vector<Eigen::Triplet<double>> checkerboard_stabilisation(double dt) const;
  void solve(double time);

  const SaturatedVpw& model_;
  const NodeSets& nodes_;
  const BoundaryConditions& conditions_;
  double alpha_, storage_, permeability_, beta_, tolerance_, checkerboard_theta_;
  long max_iterations_;
  PressurePreconditioner preconditioner_;
  double assembled_dt_ = 0.0;

  WeightTable gradient_;  // collocated gradient on the SPH nodes, mirror images folded in
  LaplacianMatrix laplacian_;
  Eigen::SparseMatrix<double> system_;  // K, drained rows and columns decoupled (Eigen's solvers)
  SparseRows projection_term_;          // (alpha^2 dt / rho) Ltilde, for the RHS
  SparseRows drained_coupling_;         // K(free rows, drained columns)
  Eigen::SparseMatrix<double> stabilisation_;  // S, theory §6.6
  double checkerboard_rate_ = 0.0;             // -lambda of L on the checkerboard
  std::vector<char> drained_;
  std::vector<double> density_;

  struct Solvers;
  std::unique_ptr<Solvers> solvers_;
  // The multigrid path: K by rows (the products split over the threads; system_ stays empty), its
  // hierarchy, and the
  // conjugate gradients' vectors (docs/theory.md §6.7).
  SparseRows system_rows_;
  std::unique_ptr<SmoothedAggregation> multigrid_;
  std::unique_ptr<ConjugateGradient> conjugate_gradient_;

  Eigen::VectorXd rhs_, pressure_, previous_, boundary_values_, scratch_;
  // Initial guess of the solve: p_w extrapolated linearly from the last two steps (theory §6.4).
  Eigen::VectorXd older_, guess_;
  bool has_older_ = false;
  FieldArray velocity_, velocity_gradient_, pressure_increment_, pressure_gradient_;
  std::vector<Parity> velocity_parity_;
  SolverStatistics statistics_;
};

}  // namespace rktsph
