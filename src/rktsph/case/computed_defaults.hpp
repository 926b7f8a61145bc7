// Defaults that follow from other keys of the case (docs/input-reference.md, "numerics" and
// "pore_fluid"), computed here so that the resolved case a run writes has every value filled in.
#pragma once

#include "rktsph/case/case_description.hpp"

namespace rktsph {

/// numerics.stress_update when unset: the mean-velocity update in 2D, the thesis' half-step
/// update in 1D (docs/theory.md §2.2).
StressUpdate default_stress_update(int dimension);

/// True if a stress point's stencil reaches beyond its cell's corners on a full interior lattice:
/// the nearest other node, (1.5, 0.5) spacings from a cell centre, lies within the kernel's
/// support (h_over_dx >= 0.79 with the cubic spline, >= 0.53 with the others, in 2D).
bool has_wide_stencils(const NumericsSpec& numerics, int dimension);

/// numerics.hourglass.fields when unset: the velocity only on compact stencils, every field on
/// wider ones, where the velocity-only filter is unstable (docs/theory.md §3.3).
HourglassFields default_hourglass_fields(const NumericsSpec& numerics, int dimension);

/// pore_fluid.laplacian_scale when unset: c such that the Laplacian of |x|^2 is 2d on a full
/// interior stencil (docs/theory.md §6.3), for the case's kernel, h and spacing; 1 on triangles,
/// whose cell Laplacian needs no factor (eq. 6.6).
double default_laplacian_scale(const CaseDescription& description);

}  // namespace rktsph
