#include <talus/solver/energy_account.h>
#include <talus/solver/factor_of_safety.h>

#include <algorithm>
#include <cmath>

namespace talus
{

namespace
{
constexpr double degree = M_PI / 180.0;

/// atan(tan(phi) / F) in degrees.
double reduced_angle(double phi_degrees, double factor)
{
  return std::atan(std::tan(phi_degrees * degree) / factor) / degree;
}

void reduce(JointProperties& j, double factor)
{
  j.friction_angle = reduced_angle(j.friction_angle, factor);
  j.dilation_angle = std::min(j.dilation_angle, j.friction_angle);
  j.cohesion /= factor;
  j.tensile_strength /= factor;
}

void reduce(ZoneMaterial& z, double factor)
{
  if (z.model != ZoneModel::mohr_coulomb)
    return;
  z.friction_angle = reduced_angle(z.friction_angle, factor);
  z.dilation_angle = std::min(z.dilation_angle, z.friction_angle);
  z.cohesion /= factor;
  z.tensile_strength /= factor;
}

/// The largest displacement of a gridpoint (m).
double largest_gridpoint_displacement(const DeformableSolver& zones)
{
  const std::vector<double> u = zones.displacements();
  double largest = 0.0;
  for (std::size_t g = 0; g + 2 < u.size(); g += 3)
    largest = std::max(largest, u[g] * u[g] + u[g + 1] * u[g + 1] + u[g + 2] * u[g + 2]);
  return std::sqrt(largest);
}
} // namespace

void reduce_strengths(Scene& scene, double factor)
{
  reduce(scene.solver.joint, factor);
  for (JointProperties& j : scene.solver.joint_materials)
    reduce(j, factor);
  if (!scene.strength_reduction.reduce_zone_strength)
    return;
  reduce(scene.deformable.material, factor);
  for (RockMaterialSpec& r : scene.rock_materials)
    reduce(r.zone, factor);
}

StrengthReductionTrial run_strength_reduction_trial(const Scene& scene, const BlockModel& model,
                                                    double factor, const TrialHooks& hooks)
{
  // A copy of each: build_block_system changes the model (zone surfaces)
  // and the solver moves its blocks; both must outlive the system.
  Scene trial_scene = scene;
  reduce_strengths(trial_scene, factor);
  BlockModel trial_model = model;
  const BlockSystem system = build_block_system(trial_scene, trial_model);
  RigidSolver& solver = *system.solver;
  const SolverSettings& s = trial_scene.solver;
  std::vector<char> measured(trial_model.n_blocks(), 1); // free rigid blocks
  for (unsigned int b : system.deformable_blocks)
    measured[b] = 0;
  for (unsigned int b = 0; b < trial_model.n_blocks(); ++b)
    measured[b] &= !solver.fixed[b];
  double zone_displacement = 0.0; // refreshed every history interval (a pass over the gridpoints)
  const auto largest_displacement = [&](bool with_zones)
  {
    double d = 0.0;
    for (unsigned int b = 0; b < trial_model.n_blocks(); ++b)
      if (measured[b])
        d = std::max(d, solver.displacement[b].squaredNorm());
    if (with_zones && system.zones)
      zone_displacement = largest_gridpoint_displacement(*system.zones);
    return std::max(std::sqrt(d), zone_displacement);
  };
  DisplacementWatch watch;
  watch.add(0, 0.0);
  if (hooks.record)
    hooks.record(system);
  bool reached_target = false;
  std::string note;
  try
  {
    while (solver.steps_done() < s.steps)
    {
      solver.step();
      const unsigned long n = solver.steps_done();
      const bool row = n % s.history_interval == 0;
      watch.add(n, largest_displacement(row));
      if (row && hooks.record)
        hooks.record(system);
      // As RigidSolver::run: not in the first steps, before the contacts carry load.
      if (n > 10 && solver.unbalanced_ratio() < s.target_ratio)
      {
        reached_target = true;
        break;
      }
    }
  }
  catch (const DivergenceError& e)
  {
    note = std::string("diverged (") + e.what() + ")";
  }
  StrengthReductionTrial t =
      judge_trial(factor, reached_target, solver.steps_done(), solver.unbalanced_ratio(), watch);
  if (!note.empty())
  {
    t.stable = false;
    t.note = note;
  }
  if (hooks.record && solver.steps_done() % s.history_interval != 0)
    hooks.record(system);
  if (hooks.finished)
    hooks.finished(system, trial_model, t);
  return t;
}

StrengthReductionResult
factor_of_safety(const Scene& scene, const BlockModel& model, const TrialHooks& hooks,
                 const std::function<void(const StrengthReductionTrial&)>& trial_done)
{
  return find_factor_of_safety(
      [&](double factor)
      {
        const StrengthReductionTrial t = run_strength_reduction_trial(scene, model, factor, hooks);
        if (trial_done)
          trial_done(t);
        return t;
      },
      scene.strength_reduction);
}

} // namespace talus
