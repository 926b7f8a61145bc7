// Method-of-characteristics reference for the 1D Perzyna Von Mises bar (docs/theory.md
// §8.3) and the analytical decay law of a viscoplastic front.
//
// Model (tension positive, F = |σ|):
//   ρ v_t = σ_x,   σ_t = E (v_x − ε̇_vp),   ε̇_vp = γ ⟨(|σ| − Y)/Y⟩^N sign(σ),
//   Y_t = H |ε̇_vp| (H < 0 softens), Y ≥ Y_res.
// Along dx/dt = ±c the invariants σ ∓ Zv change only through the plastic source:
// d(σ ∓ Zv) = −E ε̇_vp dt. The grid has Δx = cΔt, so every characteristic joins two nodes and
// elastic fronts travel without smearing. The source is integrated by the trapezoidal rule, which
// makes the update implicit in the new rate at each node; that scalar equation is solved exactly
// (safeguarded Newton), so the scheme is second order where the solution is smooth.
//
// With Section::PlaneStressLateralRollers the bar is a 2D plane-stress strip whose lateral faces
// are on rollers (ε_yy = 0, σ_zz = 0; docs/theory.md §9.9): the long wave is then exactly 1D with
// the plane-stress modulus M = E/(1 − ν²) and c = √(M/ρ), and each node also carries the lateral
// stress σ_yy = νσ_xx + τ, where τ changes only by plastic flow, τ_t = −E ε̇_yy (eq. 9.10). The
// Von Mises flow of (σ_xx, σ_yy, 0) gives ε̇_xx and ε̇_yy; the invariants change by
// −M(ε̇_xx + ν ε̇_yy) dt. A node's new equivalent rate is bracketed and solved by regula falsi,
// with the new stress for each trial rate by Newton on two unknowns. "plastic_strain" is then
// ε_xx of the flow, and plastic_strain_rate() the source rate ε̇_xx + ν ε̇_yy.
#pragma once

#include <functional>
#include <vector>

namespace rktsph::references {

struct ViscoplasticBarParameters {
  enum class LeftEnd { Fixed, Free };
  enum class Section { UniaxialStress, PlaneStressLateralRollers };

  double length = 0.0;                ///< L [m]
  double young_modulus = 0.0;         ///< E [Pa]
  double density = 0.0;               ///< ρ [kg/m³]
  double initial_yield_stress = 0.0;  ///< Y0 [Pa]
  double fluidity = 0.0;              ///< γ [1/s]
  double exponent = 1.0;              ///< N
  double hardening_modulus = 0.0;     ///< H = dY/d|ε_vp| [Pa]
  /// Y never drops below this fraction of Y0; docs/theory.md §8.3 uses 0.05.
  double residual_yield_fraction = 0.05;
  LeftEnd left_end = LeftEnd::Fixed;
  Section section = Section::UniaxialStress;
  double poisson_ratio = 0.0;  ///< ν, used by Section::PlaneStressLateralRollers only
  /// Imposed velocity of the right end x = L [m/s] against time; called for t > 0.
  std::function<double(double)> right_velocity;
  int cells = 400;
};

/// Values at one point, linearly interpolated between grid nodes.
struct ViscoplasticBarPoint {
  double stress = 0.0;          ///< [Pa]
  double velocity = 0.0;        ///< [m/s]
  double plastic_strain = 0.0;  ///< ε_vp
};

struct ViscoplasticBarSample {
  double time = 0.0;
  ViscoplasticBarPoint values;
};

class ViscoplasticBar {
 public:
  /// Throws std::invalid_argument if a parameter is out of range or right_velocity is missing.
  explicit ViscoplasticBar(ViscoplasticBarParameters parameters);

  double wave_speed() const { return wave_speed_; }  ///< c = √(E/ρ), or √(M/ρ) with rollers
  double impedance() const { return impedance_; }    ///< Z = ρc
  double grid_spacing() const { return grid_spacing_; }
  double time_step() const { return time_step_; }  ///< Δt = Δx/c
  int node_count() const { return static_cast<int>(stress_.size()); }
  double node_position(int node) const { return node * grid_spacing_; }
  long step_count() const { return steps_; }
  double time() const { return static_cast<double>(steps_) * time_step_; }

  /// One step of Δt along the characteristics.
  void step();
  /// Steps until the grid time nearest to `end_time` (never backwards).
  void advance_to(double end_time);

  // Nodal fields at time(); node i sits at x = iΔx.
  const std::vector<double>& stress() const { return stress_; }
  const std::vector<double>& velocity() const { return velocity_; }
  const std::vector<double>& plastic_strain() const { return plastic_strain_; }
  const std::vector<double>& plastic_strain_rate() const { return plastic_rate_; }
  const std::vector<double>& yield_stress() const { return yield_; }
  /// σ_yy of each node (zero in uniaxial stress).
  std::vector<double> lateral_stress() const;

  /// Fields at 0 ≤ x ≤ L, linear between nodes.
  ViscoplasticBarPoint at(double x) const;

 private:
  /// Solves e = ε̇_vp(σ_trial − k e) at `node` and returns the new plastic strain rate.
  double plastic_rate(int node, double trial_stress) const;
  /// The same with lateral rollers: the new ε̇_xx + ν ε̇_yy at `node`; the node's new ε̇_xx, ε̇_yy
  /// and equivalent rate are left in next_axial_rate_, next_lateral_rate_, next_equivalent_rate_.
  double roller_plastic_rate(int node, double trial_stress);
  /// The new-time source rate of `node` for the invariants, after either solve.
  double new_source_rate(int node, double trial_stress);

  ViscoplasticBarParameters parameters_;
  double wave_speed_;
  double impedance_;
  double grid_spacing_;
  double time_step_;
  double source_weight_;  ///< k = EΔt/2, the trapezoidal weight of a plastic rate
  double residual_yield_;
  long steps_ = 0;
  std::vector<double> stress_, velocity_, plastic_strain_, plastic_rate_, yield_;
  std::vector<double> next_stress_, next_velocity_, next_rate_;
  // Lateral rollers only: ε̇_xx, ε̇_yy, the equivalent rate γφ and τ = σ_yy − νσ_xx of each node.
  double lateral_weight_ = 0.0;  ///< EΔt/2, the trapezoidal weight of ε̇_yy in τ
  std::vector<double> axial_rate_, lateral_rate_, equivalent_rate_, lateral_offset_;
  std::vector<double> next_axial_rate_, next_lateral_rate_, next_equivalent_rate_;
};

/// Runs a fresh bar to `end_time` and records the fields at x after every step.
std::vector<ViscoplasticBarSample> viscoplastic_bar_history(
    const ViscoplasticBarParameters& parameters, double x, double end_time);

/// Stress just behind a front entering material at rest, N = 1 (docs/theory.md eq. 8.1):
/// |σ_f| − Y0 = (|σ0| − Y0) exp(−Eγt/(2Y0)), with the sign of σ0. H does not enter because
/// ε_vp = 0 at the front. A front with |σ0| ≤ Y0 is elastic and keeps σ0.
double viscoplastic_front_stress(double initial_front_stress, double initial_yield_stress,
                                 double young_modulus, double fluidity, double time);

/// Distance over which the front overstress decays by e: ℓ = 2cY0/(Eγ).
double viscoplastic_decay_length(double young_modulus, double density, double initial_yield_stress,
                                 double fluidity);

}  // namespace rktsph::references
