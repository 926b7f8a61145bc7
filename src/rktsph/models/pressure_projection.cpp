#include "rktsph/models/pressure_projection.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>

#include "rktsph/core/parallel.hpp"
#include "rktsph/sph/cell_laplacian.hpp"

namespace rktsph {

struct PressureProjection::Solvers {
  Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper,
                           Eigen::DiagonalPreconditioner<double>>
      jacobi;
  Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper,
                           Eigen::IncompleteCholesky<double>>
      cholesky;
};

namespace {
double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}
}  // namespace

PressureProjection::~PressureProjection() = default;

PressureProjection::PressureProjection(const SaturatedVpw& model, const NodeSets& nodes,
                                       const OperatorOptions& options,
                                       const BoundaryConditions& conditions,
                                       const PressureSolveOptions& solve, double dt)
    : model_(model),
      nodes_(nodes),
      conditions_(conditions),
      alpha_(model.fluid().biot_coefficient),
      storage_(model.fluid().storage),
      permeability_(model.fluid().permeability),
      beta_(solve.projection_beta),
      tolerance_(solve.tolerance),
      checkerboard_theta_(solve.checkerboard_theta),
      max_iterations_(solve.max_iterations),
      preconditioner_(solve.preconditioner),
      solvers_(std::make_unique<Solvers>()) {
  const auto start = std::chrono::steady_clock::now();
  const std::size_t n = nodes.sph_nodes.size();
  const int d = nodes.dimension;
  build_operators(nodes, options, solve.laplacian_scale);
  density_.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    density_[i] = model.material(nodes.node_material[i]).density();
  drained_.assign(n, 0);
  for (std::int32_t node : conditions.drained_nodes())
    drained_[static_cast<std::size_t>(node)] = 1;
  if (max_iterations_ <= 0) max_iterations_ = 2 * static_cast<long>(n) + 10;

  rhs_.resize(static_cast<Eigen::Index>(n));
  pressure_.resize(static_cast<Eigen::Index>(n));
  previous_.resize(static_cast<Eigen::Index>(n));
  older_.resize(static_cast<Eigen::Index>(n));
  guess_.resize(static_cast<Eigen::Index>(n));
  scratch_.resize(static_cast<Eigen::Index>(n));
  boundary_values_ = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(n));
  velocity_ = FieldArray(d, n);
  velocity_gradient_ = FieldArray(d * d, n);
  pressure_increment_ = FieldArray(1, n);
  pressure_gradient_ = FieldArray(d, n);
  for (int a = 0; a < d; ++a)
    velocity_parity_.push_back(vector_parity(a));
  assemble(dt);
  statistics_.assembly_seconds = seconds_since(start);
}

void PressureProjection::build_operators(const NodeSets& nodes, const OperatorOptions& options,
                                         double laplacian_scale) {
  // Off a lattice the Morris scale does not fit (docs/theory.md §6.3): the cells' P1 Laplacian and
  // the lumped cell gradient (eqs. 6.6, 6.7) take its place, and the lattice's checkerboard
  // stabilisation has nothing to act on (§6.6, refused on triangles at pore_fluid).
  if (!nodes.on_lattice()) {
    gradient_ = build_cell_node_gradient(nodes.cells, nodes.sph_nodes);
    laplacian_ = build_cell_laplacian(nodes.cells, nodes.sph_nodes, laplacian_scale);
    statistics_.laplacian_scale = laplacian_.scale;
    return;
  }
  const CellList cells(nodes.sph_nodes, options.kernel.support_radius(options.smoothing_length));
  StencilReport report;
  gradient_ = build_collocated_gradient(nodes.sph_nodes, cells, options, {}, &report);
  if (!report.degenerate_rows.empty())
    throw RunError(fmt::format(
        "the pore-pressure gradient cannot be formed at the SPH node at {}: the nodes around it "
        "lie on one line or are too few (a strip of soil one node wide, or a lone node at a "
        "corner), so the pressure solve has no stencil there; make every part of the soil at "
        "least two spacings wide",
        describe_point(nodes.sph_nodes, static_cast<std::size_t>(report.degenerate_rows.front()))));
  laplacian_ = build_laplacian(nodes.sph_nodes, cells, options, nodes.spacing, laplacian_scale);
  statistics_.laplacian_scale = laplacian_.scale;
  checkerboard_rate_ = laplacian_checkerboard_rate(
      options.kernel, options.smoothing_length, nodes.spacing, nodes.dimension, laplacian_.scale);
}

void PressureProjection::assemble(double dt) {
  // K = diag(V_eff)/(Q dt) - (alpha^2 dt/rho_IJ + k_bar) Ltilde with rho_IJ the pair mean, so that
  // K stays symmetric with several materials; diagonals are rebuilt from the scaled off-diagonals
  // so that every row of the Laplacian part still sums to zero (eq. 6.3).
  const auto n = static_cast<Eigen::Index>(nodes_.sph_nodes.size());
  std::vector<Eigen::Triplet<double>> system, projection, coupling;
  std::vector<double> system_diagonal(static_cast<std::size_t>(n)),
      projection_diagonal(static_cast<std::size_t>(n));
  // An entry of K: drained rows keep only their diagonal (added below); in free rows, drained
  // columns go to the coupling that moves the prescribed values to the right-hand side.
  auto add_entry = [&](Eigen::Index i, Eigen::Index j, double value) {
    if (drained_[static_cast<std::size_t>(i)]) return;
    (drained_[static_cast<std::size_t>(j)] ? coupling : system).emplace_back(i, j, value);
  };
  const auto& ltilde = laplacian_.weighted;
  for (Eigen::Index i = 0; i < n; ++i) {
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(ltilde, i); it; ++it) {
      const Eigen::Index j = it.col();
      if (j == i) continue;
      const double rho =
          0.5 * (density_[static_cast<std::size_t>(i)] + density_[static_cast<std::size_t>(j)]);
      const double projection_value = alpha_ * alpha_ * dt / rho * it.value();
      const double system_value = -(projection_value + permeability_ * it.value());
      projection.emplace_back(i, j, projection_value);
      projection_diagonal[static_cast<std::size_t>(i)] -= projection_value;
      system_diagonal[static_cast<std::size_t>(i)] -= system_value;
      add_entry(i, j, system_value);
    }
  }
  // Checkerboard stabilisation S (eq. 6.5), added to K like the Laplacian part.
  const std::vector<Eigen::Triplet<double>> stabilisation = checkerboard_stabilisation(dt);
  for (const Eigen::Triplet<double>& entry : stabilisation)
    add_entry(entry.row(), entry.col(), entry.value());
  stabilisation_.resize(n, n);
  stabilisation_.setFromTriplets(stabilisation.begin(), stabilisation.end());

  for (Eigen::Index i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const double storage = laplacian_.effective_volume[k] * storage_ / dt;
    // Drained rows keep only their diagonal: K_II p_I = K_II p_bar.
    system.emplace_back(
        i, i, drained_[k] ? laplacian_.effective_volume[k] / dt : storage + system_diagonal[k]);
    projection.emplace_back(i, i, projection_diagonal[k]);
  }
  // K is kept once: by rows for the multigrid path, by columns for Eigen's solvers.
  if (preconditioner_ == PressurePreconditioner::Multigrid) {
    system_rows_.resize(n, n);
    system_rows_.setFromTriplets(system.begin(), system.end());
    system_rows_.makeCompressed();
  } else {
    system_.resize(n, n);
    system_.setFromTriplets(system.begin(), system.end());
  }
  system.clear();
  system.shrink_to_fit();
  projection_term_.resize(n, n);
  projection_term_.setFromTriplets(projection.begin(), projection.end());
  projection_term_.makeCompressed();
  drained_coupling_.resize(n, n);
  drained_coupling_.setFromTriplets(coupling.begin(), coupling.end());
  drained_coupling_.makeCompressed();
  assembled_dt_ = dt;

  Solvers& s = *solvers_;
  if (preconditioner_ == PressurePreconditioner::Multigrid) {
    multigrid_ = std::make_unique<SmoothedAggregation>(system_rows_);
    conjugate_gradient_ =
        std::make_unique<ConjugateGradient>(static_cast<std::size_t>(system_rows_.rows()));
    statistics_.multigrid_levels = multigrid_->levels();
    statistics_.multigrid_complexity = multigrid_->operator_complexity();
  } else if (preconditioner_ == PressurePreconditioner::IncompleteCholesky) {
    s.cholesky.setTolerance(tolerance_);
    s.cholesky.setMaxIterations(max_iterations_);
    s.cholesky.compute(system_);
    if (s.cholesky.info() != Eigen::Success)
      throw RunError(
          "the incomplete Cholesky factorisation of the pore-pressure matrix failed (a pivot "
          "vanished: the matrix is not positive definite enough for it, as with a very low "
          "permeability beside a drained face); set pore_fluid.preconditioner to multigrid (the "
          "default) or jacobi");
  } else {
    s.jacobi.setTolerance(tolerance_);
    s.jacobi.setMaxIterations(max_iterations_);
    s.jacobi.compute(system_);
  }
}

std::vector<Eigen::Triplet<double>> PressureProjection::checkerboard_stabilisation(
    double dt) const {
  // w_c b_c b_c^T per quadrilateral cell, b_c = (+1, -1, +1, -1) the twist of its corners
  // (counter-clockwise). The cells are those of the stress points; mirrored cells are left out,
  // which is the V_eff weighting of Ltilde (docs/theory.md §6.6).
  std::vector<Eigen::Triplet<double>> entries;
  if (nodes_.dimension != 2 || checkerboard_theta_ <= 0.0) return entries;
  // The corners in lattice order (lower row, then upper row), the order the sums were written in.
  constexpr std::array<std::size_t, 4> kRowOrder{0, 1, 3, 2};
  constexpr std::array<double, 4> kTwist{1.0, -1.0, 1.0, -1.0};
  const CellComplex& cells = nodes_.cells;
  for (std::size_t p = 0; p < cells.cell_count(); ++p) {
    if (cells.kind(p) != CellKind::Quadrilateral) continue;
    const auto corners = cells.corners(p);
    double density = 0.0, volume = 0.0;
    for (const std::size_t k : kRowOrder) {
      const auto node = static_cast<std::size_t>(corners[k]);
      density += 0.25 * density_[node];
      volume += 0.25 * nodes_.sph_nodes.volume[node];
    }
    const double weight =
        checkerboard_theta_ * alpha_ * alpha_ * dt / density * volume * checkerboard_rate_ / 16.0;
    for (const std::size_t a : kRowOrder)
      for (const std::size_t b : kRowOrder)
        entries.emplace_back(corners[a], corners[b], weight * kTwist[a] * kTwist[b]);
  }
  return entries;
}

void PressureProjection::solve(double time) {
  const auto start = std::chrono::steady_clock::now();
  Solvers& s = *solvers_;
  long iterations;
  double error;
  bool converged;
  if (preconditioner_ == PressurePreconditioner::Multigrid) {
    parallel_copy(guess_.data(), static_cast<std::size_t>(guess_.size()), pressure_.data());
    const ConjugateGradientResult result = conjugate_gradient_->solve(
        system_rows_, *multigrid_, rhs_.data(), pressure_.data(), tolerance_, max_iterations_);
    iterations = result.iterations;
    error = result.relative_residual;
    converged = result.converged;
  } else if (preconditioner_ == PressurePreconditioner::IncompleteCholesky) {
    pressure_ = s.cholesky.solveWithGuess(rhs_, guess_);
    iterations = s.cholesky.iterations();
    error = s.cholesky.error();
    converged = s.cholesky.info() == Eigen::Success;
  } else {
    pressure_ = s.jacobi.solveWithGuess(rhs_, guess_);
    iterations = s.jacobi.iterations();
    error = s.jacobi.error();
    converged = s.jacobi.info() == Eigen::Success;
  }
  statistics_.solve_seconds += seconds_since(start);
  ++statistics_.solves;
  statistics_.total_iterations += iterations;
  statistics_.max_iterations = std::max(statistics_.max_iterations, iterations);
  statistics_.last_residual = error;
  if (!converged || !std::isfinite(error))
    throw RunError(fmt::format(
        "the pore-pressure solve did not converge at t = {:.6g} s: relative residual {:.3g} after "
        "{} iterations (tolerance {:.3g}, limit {}); try another pore_fluid.preconditioner, a "
        "larger solver_max_iterations, or check the drained boundaries",
        time, error, iterations, tolerance_, max_iterations_));
}

void PressureProjection::project(State& state, double time, double dt) {
  const auto start = std::chrono::steady_clock::now();
  // The last step of a run is end - t, which differs from dt in its last bits even when end is a
  // multiple of dt: reassembling (and, with multigrid, rebuilding the hierarchy) for a relative
  // change below 1e-9 would cost seconds at 10^6 nodes for a change in p_w far below the solver
  // tolerance.
  if (std::abs(dt - assembled_dt_) > 1e-9 * assembled_dt_) assemble(dt);
  const std::size_t n = nodes_.sph_nodes.size();
  const int d = nodes_.dimension;
  const int pw = model_.pore_pressure_field();

  // div v* with the collocated gradient (velocity components are odd under their mirror).
  for (int a = 0; a < d; ++a)
    parallel_copy(state.fields.field(model_.velocity_field(a)), n, velocity_.field(a));
  apply_operator(gradient_, velocity_, velocity_parity_, nullptr, &velocity_gradient_);
  const double* pressure_now = state.fields.field(pw);
  parallel_copy(pressure_now, n, previous_.data());

  // Right-hand side of eq. 6.3, then the drained values moved to it.
  multiply(projection_term_, previous_.data(), scratch_.data());
  const auto nodes = static_cast<std::int64_t>(n);
#pragma omp parallel for schedule(static) if (nodes > kParallelThreshold)
  for (std::int64_t i = 0; i < nodes; ++i) {
    const auto k = static_cast<std::size_t>(i);
    double divergence = 0.0;
    for (int a = 0; a < d; ++a)
      divergence += velocity_gradient_(a * d + a, k);
    rhs_[i] =
        laplacian_.effective_volume[k] * (storage_ / dt * previous_[i] - alpha_ * divergence) -
        beta_ * scratch_[i];
  }
  const auto& drained = conditions_.drained_nodes();
  for (std::size_t k = 0; k < drained.size(); ++k)
    boundary_values_[drained[k]] = conditions_.drained_pressure(k, time);
  if (!drained.empty()) {
    residual(drained_coupling_, boundary_values_.data(), rhs_.data(), rhs_.data());
    for (std::int32_t node : drained)
      rhs_[node] =
          laplacian_.effective_volume[static_cast<std::size_t>(node)] / dt * boundary_values_[node];
  }
  // Initial guess: p_w^n + (p_w^n - p_w^{n-1}). With a relative tolerance, a guess that is O(dt^2)
  // rather than O(dt) off saves the iterations that only recover the trend (theory §6.4).
#pragma omp parallel for schedule(static) if (nodes > kParallelThreshold)
  for (std::int64_t i = 0; i < nodes; ++i)
    guess_[i] = has_older_ ? 2.0 * previous_[i] - older_[i] : previous_[i];
  solve(time);
  parallel_copy(previous_.data(), n, older_.data());
  has_older_ = true;

  // Velocity correction, eq. 6.4.
#pragma omp parallel for schedule(static) if (nodes > kParallelThreshold)
  for (std::int64_t i = 0; i < nodes; ++i)
    pressure_increment_(0, static_cast<std::size_t>(i)) = pressure_[i] - beta_ * previous_[i];
  const Parity even[] = {kEven};
  apply_operator(gradient_, pressure_increment_, even, nullptr, &pressure_gradient_);
#pragma omp parallel for schedule(static) if (nodes > kParallelThreshold)
  for (std::int64_t i = 0; i < nodes; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const double factor = alpha_ * dt / density_[k];
    for (int a = 0; a < d; ++a)
      state.fields(model_.velocity_field(a), k) -= factor * pressure_gradient_(a, k);
    state.fields(pw, k) = pressure_[i];
  }
  conditions_.apply(time, state.fields);
  statistics_.projection_seconds += seconds_since(start);
}

void PressureProjection::save_checkpoint(CheckpointOut& out) const {
  out.put_u32(has_older_ ? 1 : 0);
  out.put_doubles(older_.data(), static_cast<std::size_t>(older_.size()));
  out.put_i64(statistics_.solves);
  out.put_i64(statistics_.total_iterations);
  out.put_i64(statistics_.max_iterations);
  out.put_f64(statistics_.last_residual);
  out.put_f64(statistics_.solve_seconds);
  out.put_f64(statistics_.projection_seconds);
}

void PressureProjection::restore_checkpoint(CheckpointIn& in) {
  has_older_ = in.get_u32() != 0;
  in.get_doubles_into(older_.data(), static_cast<std::size_t>(older_.size()));
  statistics_.solves = in.get_i64();
  statistics_.total_iterations = in.get_i64();
  statistics_.max_iterations = in.get_i64();
  statistics_.last_residual = in.get_f64();
  statistics_.solve_seconds = in.get_f64();
  statistics_.projection_seconds = in.get_f64();
}

}  // namespace rktsph
