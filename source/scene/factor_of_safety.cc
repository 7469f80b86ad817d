#include <talus/base/archive.h>
#include <talus/scene/factor_of_safety.h>
#include <talus/solver/energy_account.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

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
  // Continuously yielding: phi_m runs from phi_i down to phi, both reduced
  // the same way (tan / F), so phi_i >= phi still holds.
  j.initial_friction_angle = reduced_angle(j.initial_friction_angle, factor);
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

/// Blocks whose displacement measures a trial: the free rigid ones.
std::vector<char> measured_blocks(const BlockSystem& system, const BlockModel& model)
{
  std::vector<char> measured(model.n_blocks(), 1);
  for (unsigned int b : system.deformable_blocks)
    measured[b] = 0;
  for (unsigned int b = 0; b < model.n_blocks(); ++b)
    measured[b] &= !system.solver->fixed[b];
  return measured;
}

/// Steps `view`'s system to the target ratio (after 10 steps, as
/// RigidSolver::run) or to 'Steps' steps after its start, and judges it.
StrengthReductionTrial run_to_target(const Scene& scene, const TrialView& view,
                                     const TrialHooks& hooks)
{
  RigidSolver& solver = *view.system.solver;
  const SolverSettings& s = scene.solver;
  const std::vector<char> measured = measured_blocks(view.system, view.model);
  const auto blocks_moved = [&]()
  {
    double d = 0.0;
    for (unsigned int b = 0; b < view.model.n_blocks(); ++b)
      if (measured[b])
        d = std::max(d, (solver.displacement[b] - view.start_displacement[b]).squaredNorm());
    return std::sqrt(d);
  };
  // The zones' part is a pass over the gridpoints: every history interval.
  double zones_moved = 0.0;
  DisplacementWatch watch;
  watch.add(0, 0.0);
  if (hooks.record)
    hooks.record(view);
  bool reached_target = false;
  std::string note;
  unsigned long n = 0;
  try
  {
    while (n < s.steps)
    {
      solver.step();
      ++n;
      const bool row = n % s.history_interval == 0;
      if (row && view.system.zones)
        zones_moved = view.largest_displacement();
      watch.add(n, std::max(blocks_moved(), zones_moved));
      if (row && hooks.record)
        hooks.record(view);
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
  StrengthReductionTrial t = judge_trial(view.factor, reached_target, n, solver.unbalanced_ratio(),
                                         watch, rest_fraction_of_tolerance * s.contact.tolerance);
  if (!note.empty())
  {
    t.stable = false;
    t.note = note;
  }
  if (hooks.record && n % s.history_interval != 0)
    hooks.record(view);
  if (hooks.finished)
    hooks.finished(view, t);
  return t;
}
} // namespace

double TrialView::largest_displacement() const
{
  double d = 0.0;
  const std::vector<char> measured = measured_blocks(system, model);
  for (unsigned int b = 0; b < model.n_blocks(); ++b)
    if (measured[b])
      d = std::max(d, (system.solver->displacement[b] - start_displacement[b]).squaredNorm());
  if (system.zones)
  {
    const std::vector<double> u = system.zones->displacements();
    const bool relative = start_gridpoint_displacement.size() == u.size();
    for (std::size_t g = 0; g + 2 < u.size(); g += 3)
    {
      double gd = 0.0;
      for (int k = 0; k < 3; ++k)
      {
        const double x = u[g + k] - (relative ? start_gridpoint_displacement[g + k] : 0.0);
        gd += x * x;
      }
      d = std::max(d, gd);
    }
  }
  return std::sqrt(d);
}

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

StrengthReductionTrials::StrengthReductionTrials(const Scene& scene, const BlockModel& model)
    : scene_(scene), model_(model)
{
  const double factor = scene.strength_reduction.smallest_factor;
  // Copies: build_block_system changes the model (zone surfaces), the
  // solver moves its blocks; both must outlive the system.
  Scene strong = scene;
  reduce_strengths(strong, factor);
  BlockModel copy = model;
  const BlockSystem system = build_block_system(strong, copy);
  const std::vector<Vec3> at_rest(copy.n_blocks(), Vec3::Zero());
  const std::vector<double> none;
  const TrialView view{factor, system, copy, 0, 0.0, at_rest, none};
  initial_ = run_to_target(strong, view, {});
  CheckpointWriter out;
  system.solver->save_state(out);
  if (system.zones)
  {
    system.zones->save_state(out);
    start_gridpoint_displacement_ = system.zones->displacements();
  }
  state_ = out.bytes();
  start_step_ = system.solver->steps_done();
  start_time_ = system.solver->time();
  start_displacement_ = system.solver->displacement;
}

StrengthReductionTrials::StrengthReductionTrials(
    const Scene& scene, const BlockModel& model, std::string state,
    std::function<void(const Scene& reduced, BlockSystem& system)> prepare,
    unsigned long start_step, double start_time, std::vector<Vec3> start_displacement,
    std::vector<double> start_gridpoint_displacement)
    : scene_(scene), model_(model), state_(std::move(state)), prepare_(std::move(prepare)),
      start_step_(start_step), start_time_(start_time),
      start_displacement_(std::move(start_displacement)),
      start_gridpoint_displacement_(std::move(start_gridpoint_displacement))
{
  initial_.stable = true;
  initial_.reached_target = true;
}

void StrengthReductionTrials::in_trial(
    double factor, const std::string& state, const std::string& what,
    const std::function<void(const Scene& reduced, const TrialView& view)>& use) const
{
  Scene reduced = scene_;
  reduce_strengths(reduced, factor);
  reduced.solver.dynamic = false;
  BlockModel copy = model_;
  BlockSystem system = build_block_system(reduced, copy);
  // The joint materials and zone strengths stay the reduced ones the
  // solvers were built with (they are not in the state).
  CheckpointReader in(state, what);
  system.solver->load_state(in);
  if (system.zones)
    system.zones->load_state(in);
  if (prepare_) // after the state, as a restart sets a stage's changes
    prepare_(reduced, system);
  system.solver->set_dynamic(false); // the trials are static
  use(reduced, TrialView{factor, system, copy, start_step_, start_time_, start_displacement_,
                         start_gridpoint_displacement_});
}

StrengthReductionTrial StrengthReductionTrials::run(double factor, const TrialHooks& hooks) const
{
  StrengthReductionTrial trial;
  in_trial(factor, state_, "the initial state of the strength reduction",
           [&](const Scene& reduced, const TrialView& view)
           { trial = run_to_target(reduced, view, hooks); });
  return trial;
}

void StrengthReductionTrials::show(double factor, const std::string& state,
                                   const std::function<void(const TrialView&)>& show) const
{
  in_trial(factor, state, "the end of a strength reduction trial from another rank",
           [&](const Scene&, const TrialView& view) { show(view); });
}

StrengthReductionResult
factor_of_safety(const Scene& scene, const BlockModel& model, const TrialHooks& hooks,
                 const std::function<void(const StrengthReductionTrial&)>& trial_done)
{
  return factor_of_safety(scene, model,
                          [&](const StrengthReductionTrials& trials)
                          {
                            return find_factor_of_safety(
                                [&](double factor)
                                {
                                  const StrengthReductionTrial t = trials.run(factor, hooks);
                                  if (trial_done)
                                    trial_done(t);
                                  return t;
                                },
                                scene.strength_reduction);
                          });
}

StrengthReductionResult factor_of_safety(
    const Scene& scene, const BlockModel& model,
    const std::function<StrengthReductionResult(const StrengthReductionTrials&)>& search)
{
  const StrengthReductionTrials trials(scene, model);
  if (!trials.initial().stable)
  {
    StrengthReductionResult r;
    char text[1000];
    const StrengthReductionTrial& t = trials.initial();
    std::snprintf(text, sizeof text,
                  "the model does not come to rest even with its strengths multiplied by %g "
                  "(the initial state of every trial; unbalanced-force ratio %.2g after %lu "
                  "steps%s%s): a block with no support, or 'Steps' too few to reach 'Target "
                  "ratio'",
                  1.0 / scene.strength_reduction.smallest_factor, t.ratio, t.steps,
                  t.reached_target ? ", its displacement still growing" : "",
                  t.note.empty() ? "" : ("; " + t.note).c_str());
    r.failure = text;
    return r;
  }
  return search(trials);
}

} // namespace talus
