#pragma once

#include <string>
#include <vector>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace talus
{

class CheckpointWriter;
class CheckpointReader;

/// The energy balance of a run (J), all terms since the start:
///   work of gravity + work of boundaries and loads + energy at the start
///     = kinetic + joint elastic + zone elastic
///       + frictional + plastic + damping dissipation.
/// Work increments are F(t) . (v(t - dt/2) + v(t + dt/2)) / 2 h, and the
/// kinetic term is 1/2 m v(t + dt/2)^2 less half the work of the contact
/// and zone forces over that half step: with these the central difference
/// scheme balances linear springs exactly, so the error measures what it
/// cannot account for: contacts that close part way through a step (at
/// most about (omega dt)^2 of the energy of an impact), sub-contacts
/// rebuilt at updates, large strains of hypoelastic zones. Masses are those
/// the cycle moves (scaled ones in statics with density scaling).
struct EnergyAccount
{
  double gravity_work = 0.0;
  double boundary_work = 0.0; ///< applied forces, pressures, prescribed velocities
  double kinetic = 0.0;       ///< at the last whole step (see above)
  double joint_elastic = 0.0;
  double zone_elastic = 0.0;
  double friction = 0.0;
  double plastic = 0.0;
  double damping = 0.0;
  /// The same stored terms at the start (initial velocities, initial stress).
  double initial_stored = 0.0;

  /// The history columns of a block cycle's account, in the order
  /// append_to() writes them (the error last).
  static std::vector<std::string> column_names()
  {
    return {"kinetic energy (J)",       "work of gravity (J)",     "joint elastic energy (J)",
            "friction dissipation (J)", "damping dissipation (J)", "work of boundaries (J)",
            "zone elastic energy (J)",  "plastic dissipation (J)", "energy balance error (J)"};
  }
  /// Appends the terms of column_names() to a history row.
  void append_to(std::vector<double>& row) const
  {
    row.insert(row.end(), {kinetic, gravity_work, joint_elastic, friction, damping, boundary_work,
                           zone_elastic, plastic, error()});
  }

  double stored() const { return kinetic + joint_elastic + zone_elastic; }
  /// Sources minus what they went into (J); zero for a perfect account.
  double error() const
  {
    return gravity_work + boundary_work + initial_stored - stored() - friction - plastic - damping;
  }
  /// The energy the balance is measured against (J): the largest of the
  /// terms, so that the relative error of a run means the same whatever
  /// happened in it.
  double scale() const;
};

/// A run that has become unstable: a non-finite force or stress, kinetic
/// energy growing geometrically with no source, or a block moving so far in
/// one step that it can pass through another. The message names the block
/// or zone, the step and the likely cause; the state is that of the last
/// good step (nothing moved after the fault was found).
class DivergenceError : public std::runtime_error
{
public:
  explicit DivergenceError(const std::string& message) : std::runtime_error(message) {}
};

/// Watches the kinetic energy of a run for growth without a source, every
/// step (an O(1) test: the kinetic term is summed in the motion loop
/// anyway). It reports when the kinetic energy exceeds what the sources
/// could have supplied a hundred times over (which a stable run never
/// does), or exceeds it four times over and has more than doubled at each
/// of `checks` checks `period` steps apart. What the sources could have
/// supplied is the most they ever came to: their net work returns to zero
/// whenever a body is back at its starting height (the top of a bounce, a
/// rocking or oscillating block), where the scheme's small energy error
/// would otherwise be judged against nothing.
class EnergyGrowthWatch
{
public:
  static constexpr unsigned int period = 5;
  static constexpr unsigned int checks = 3;

  /// True when the run diverges; `kinetic` and `sources` in J (sources: the
  /// stored energy at the start plus the work of gravity and boundaries, in
  /// absolute value), `floor` the energy below which nothing is judged.
  bool diverging(unsigned long step, double kinetic, double sources, double floor)
  {
    largest_sources_ = std::max(largest_sources_, sources);
    sources = largest_sources_;
    if (kinetic > 100.0 * (sources + floor))
      return true;
    if (step % period != 0)
      return false;
    const bool growing = kinetic > 2.0 * last_ && kinetic > 4.0 * sources + floor;
    last_ = kinetic;
    growing_ = growing ? growing_ + 1 : 0;
    return growing_ >= checks;
  }

  /// The most the sources have come to so far (J).
  double largest_sources() const { return largest_sources_; }

  /// For checkpoints (defined with the other hooks in checkpoint.cc).
  void save_state(CheckpointWriter& out) const;
  void load_state(CheckpointReader& in);

private:
  double last_ = 0.0;
  unsigned int growing_ = 0;
  double largest_sources_ = 0.0; ///< J
};

} // namespace talus
