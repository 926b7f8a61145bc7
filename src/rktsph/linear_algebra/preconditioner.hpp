// What the conjugate-gradient solve asks of a preconditioner: z = M^{-1} r for a fixed symmetric
// positive-definite M (docs/theory.md §6.7).
#pragma once

namespace rktsph {

/// Preconditioner of the conjugate-gradient pore-pressure solve (docs/theory.md §6.7).
enum class PressurePreconditioner { Jacobi, IncompleteCholesky, Multigrid };

class Preconditioner {
 public:
  virtual ~Preconditioner() = default;
  /// z = M^{-1} r; r and z hold as many values as the matrix has rows and must not overlap.
  virtual void apply(const double* r, double* z) const = 0;
};

}  // namespace rktsph
