#include <talus/base/exceptions.h>
#include <talus/base/memory.h>
#include <talus/io/scene_checks.h>
#include <talus/run/run_summary.h>
#include <talus/zone/tet10_mesh.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

namespace talus
{

/// Writes the zones of deformable blocks at their current state as frame
/// `frame` of the zone series.
/// After a divergence (`with_stress` false) non-finite stresses are written
/// as 0.
void write_zone_frame(const Scene& scene, const TetMesh& mesh, const DeformableSolver& solver,
                      ZoneWriter& writer, PvdSeries& series, unsigned int frame, bool with_stress)
{
  char file[64];
  std::snprintf(file, sizeof file, "_zones_%05u.vtu", frame);
  const std::string vtu = scene.output.base_name + file;
  write_zone_file(scene.output.directory + "/" + vtu, mesh, solver, writer, with_stress);
  series.add(solver.time(), vtu);
}

void write_zone_file(const std::string& path, const TetMesh& mesh, const DeformableSolver& solver,
                     ZoneWriter& writer, bool with_stress, const std::vector<unsigned int>* zones)
{
  // One cell per shown tetrahedron: a hexahedral zone shows its averaged
  // stress on its first overlay; a 10-node zone is eight sub-tetrahedra
  // with the Gauss-point stresses and states carried over (tet10_mesh.h).
  const std::vector<double> x = solver.positions();
  std::vector<double> stress;
  std::vector<unsigned char> state;
  // A piece: each of its zones the solver's zones[k], with its stress points.
  std::vector<double> piece_stress;
  std::vector<unsigned char> piece_state;
  if (zones != nullptr)
  {
    const unsigned int p = solver.stress_points_per_zone();
    for (unsigned int z : *zones)
    {
      piece_stress.insert(piece_stress.end(), &solver.stress()[6 * p * std::size_t(z)],
                          &solver.stress()[6 * p * (std::size_t(z) + 1)]);
      piece_state.insert(piece_state.end(), &solver.plastic_state()[p * std::size_t(z)],
                         &solver.plastic_state()[p * (std::size_t(z) + 1)]);
    }
  }
  const std::vector<double>& zone_stress = zones ? piece_stress : solver.stress();
  const std::vector<unsigned char>& zone_state = zones ? piece_state : solver.plastic_state();
  if (mesh.quadratic())
  {
    stress = tet10_subcell_values(zone_stress, 6);
    state = tet10_subcell_flags(zone_state);
  }
  else
    shown_zone_values(mesh, x, zone_stress, zone_state, stress, state);
  // After a divergence the stresses may hold the non-finite values found:
  // those are written as 0, so that the frame keeps the fields of the others.
  if (!with_stress)
    for (double& s : stress)
      s = std::isfinite(s) ? s : 0.0;
  std::vector<ZoneField> cells{
      {"stress", 6, stress}, {"principal_stress", 3, {}}, {"plastic_state", 1, {}}};
  cells[1].values.resize(3 * state.size());
  for (std::size_t c = 0; c < state.size(); ++c)
  {
    principal_stresses(&stress[6 * c], &cells[1].values[3 * c]);
    cells[2].values.push_back(state[c]);
  }
  writer.write(path, x,
               {{"displacement", 3, solver.displacements()}, {"velocity", 3, solver.velocities()}},
               cells, solver.time());
}

void print_added_mass(const SolverSettings& s, const AddedMass& added, const char* indent)
{
  if (!s.dynamic || !s.raises_mass())
    return;
  // Two significant digits (whole percents from 100 %): the figures a test
  // compares.
  const auto percent = [](double fraction)
  {
    char p[32];
    std::snprintf(p, sizeof p, fraction < 1.0 ? "%.2g %%" : "%.0f %%", 100.0 * fraction);
    return std::string(p);
  };
  std::printf("%s%-*s%u gridpoints and %u blocks raised to the %.6g s step; %s of the total "
              "mass, largest factor %.2g (partial density scaling)\n",
              indent, int(14 - std::strlen(indent)), "Added mass:", added.gridpoints, added.blocks,
              s.time_step, percent(added.fraction()).c_str(), added.largest_factor);
  if (added.fraction() <= s.added_mass_limit)
    return;
  const std::string text = "partial density scaling to the 'Time step' " + number(s.time_step) +
                           " s adds " + percent(added.fraction()) +
                           " of the total mass, above the limit of " + percent(s.added_mass_limit);
  if (!s.added_mass_warn)
    throw InputError::at(s.source, 0, "Solver", "Added mass limit", text,
                         "a larger limit (at most 1), a smaller 'Time step', or 'Added mass over "
                         "limit = warn' to run anyway");
  std::printf("%sWarning: %s (the motion of the scaled parts is slower than true)\n", indent,
              text.c_str());
}

/// The largest displacement of a gridpoint (m).
void print_dynamic_damping(const SolverSettings& s, double dt, double dt_without,
                           const char* indent)
{
  if (!s.dynamic)
    return;
  if (s.rayleigh_alpha > 0.0 || s.rayleigh_beta > 0.0)
    std::printf("%sRayleigh damping: alpha %.3g 1/s, beta %.3g s; time step %.3g s (%.3g s "
                "without the stiffness term)\n",
                indent, s.rayleigh_alpha, s.rayleigh_beta, dt, dt_without);
  if (s.dynamic_local_damping > 0.0)
    std::printf("%sLocal damping: alpha %g (eqs. 78-79), in dynamics\n", indent,
                s.dynamic_local_damping);
}

double largest_gridpoint_displacement(const DeformableSolver& solver)
{
  const std::vector<double> u = solver.displacements();
  double largest = 0.0;
  for (std::size_t g = 0; g < solver.owned_gridpoints(); ++g) // split: each rank its own
    largest = std::max(largest, std::sqrt(u[3 * g] * u[3 * g] + u[3 * g + 1] * u[3 * g + 1] +
                                          u[3 * g + 2] * u[3 * g + 2]));
  if (const GridpointShare* share = solver.share())
    MPI_Allreduce(MPI_IN_PLACE, &largest, 1, MPI_DOUBLE, MPI_MAX, share->comm);
  return largest;
}

/// How the zones' edge length was asked for, for the summary.
std::string edge_length_text(const EdgeLengthField& f)
{
  if (!f.graded())
    return "edge length " + number(f.coarse) + " m";
  return "edge length " + number(f.fine) + " m at the fine region, growing to " + number(f.coarse) +
         " m at " + number(f.distance) + " m from it";
}

/// The summary's lines on the zones' shapes: the radius ratio (1 for a
/// regular tetrahedron), where the poor zones are, and the gridpoint that
/// sets the stable step of eq. 84 with its worst zone.
void print_mesh_quality(const MeshReport& r, const TetMesh& mesh, unsigned int g,
                        const BlockModel& model)
{
  if (r.zones == 0)
    return;
  std::printf("Quality:      radius ratio min %.2g (a zone of block %u), 1 %% %.2g, median %.2g; "
              "%u zones below 0.1",
              r.quality_min, r.worst_block, r.quality_1, r.quality_median, r.poor_zones);
  if (!r.poor_blocks.empty())
  {
    std::printf(" in block");
    for (std::size_t i = 0; i < r.poor_blocks.size(); ++i)
      std::printf("%s %u (%u)", i == 0 ? "" : ",", r.poor_blocks[i].first, r.poor_blocks[i].second);
  }
  std::printf("\n");
  double worst = 2.0, height = 1e300;
  const auto P = [&](unsigned int i)
  { return Vec3(mesh.position[3 * i], mesh.position[3 * i + 1], mesh.position[3 * i + 2]); };
  for (const auto& t : mesh.zone_gridpoint)
    if (std::find(t.begin(), t.end(), g) != t.end())
    {
      worst = std::min(worst, radius_ratio(P(t[0]), P(t[1]), P(t[2]), P(t[3])));
      const double v =
          std::abs((P(t[1]) - P(t[0])).dot((P(t[2]) - P(t[0])).cross(P(t[3]) - P(t[0]))));
      for (int k = 0; k < 4; ++k)
      {
        const Vec3 a = P(t[(k + 1) % 4]), b = P(t[(k + 2) % 4]), c = P(t[(k + 3) % 4]);
        height = std::min(height, v / (b - a).cross(c - a).norm());
      }
    }
  // The block's own shape: an edge or a thickness much below the zone size
  // forces thin zones, whatever the mesher does.
  const unsigned int b = mesh.gridpoint_block[g];
  double shortest = 1e300, thickness = 1e300;
  for (unsigned int f = model.face_start[b]; f < model.face_start[b + 1]; ++f)
  {
    const unsigned int first = model.face_loop_start[f], n = model.face_loop_start[f + 1] - first;
    for (unsigned int k = 0; k < n; ++k)
      shortest = std::min(shortest, (model.vertex[model.face_vertex[first + k]] -
                                     model.vertex[model.face_vertex[first + (k + 1) % n]])
                                        .norm());
    double across = 0.0;
    for (unsigned int v = model.vertex_start[b]; v < model.vertex_start[b + 1]; ++v)
      across = std::max(across, -model.face_normal[f].dot(model.vertex[v] -
                                                          model.vertex[model.face_vertex[first]]));
    thickness = std::min(thickness, across);
  }
  std::printf("Step set by:  the gridpoint at (%.4g, %.4g, %.4g) m of block %u (eq. 84): its "
              "zones' worst radius ratio %.2g, smallest height %.3g m; the block's shortest edge "
              "%.3g m, thickness %.3g m\n",
              P(g).x(), P(g).y(), P(g).z(), b, worst, height, shortest, thickness);
}

/// The summary's line on the zones about to be meshed: how many and how much
/// memory, estimated before meshing (after the checks, which refuse a scene
/// that does not fit).
void print_zone_estimate(const Scene& scene, const BlockModel& model)
{
  const ZoneEstimate e = estimate_zones(scene, model);
  if (e.blocks == 0 || e.zones == 0.0)
    return;
  std::printf("Meshing:      about %.3g %s in %zu deformable block%s, about %s of memory\n",
              e.zones, e.quadratic ? "10-node zones" : "zones", e.blocks, e.blocks == 1 ? "" : "s",
              memory_text(e.bytes).c_str());
  std::fflush(stdout);
}

/// The summary's line on nodal mixed discretization, when some zones have
/// it.
void print_nodal_mixed(const DeformableSolver& solver)
{
  if (const auto [mixed, all] = solver.whole_nodal_mixed_zones(); mixed > 0)
    std::printf("Nodal mixed:  %lu of %lu zones (eqs. 68-76)\n", mixed, all);
}

/// The summary's lines on the history blocks: which block each is (so that
/// an id can be checked, and a point's block known), and a warning for a
/// fixed one, whose history holds only zeros.
void print_history_blocks(const Scene& scene, const ModelDigest& model)
{
  for (unsigned int b : scene.solver.history_blocks)
  {
    const std::string& group = model.group_name(b);
    const Vec3& c = model.centroid()[b];
    std::printf("History block %u: group %s, centroid %.6g, %.6g, %.6g m\n", b, group.c_str(), c[0],
                c[1], c[2]);
    if (std::find(scene.fixed_groups.begin(), scene.fixed_groups.end(), group) !=
        scene.fixed_groups.end())
      std::printf("Warning: history block %u is in the fixed group %s: its displacement and "
                  "velocity stay zero\n",
                  b, group.c_str());
  }
}

PointHistory::PointHistory(const TetMesh& mesh, const std::vector<Vec3>& points)
{
  for (const Vec3& p : points)
  {
    unsigned int best_g = 0, best_z = 0;
    double dg = 1e300, dz = 1e300;
    for (unsigned int g = 0; g < mesh.n_gridpoints(); ++g)
    {
      const double d =
          (Vec3(mesh.position[3 * g], mesh.position[3 * g + 1], mesh.position[3 * g + 2]) - p)
              .squaredNorm();
      if (d < dg)
      {
        dg = d;
        best_g = g;
      }
    }
    for (unsigned int z = 0; z < mesh.n_zones(); ++z)
    {
      Vec3 c = Vec3::Zero();
      for (unsigned int g : mesh.zone_gridpoint[z])
        c += 0.25 * Vec3(mesh.position[3 * g], mesh.position[3 * g + 1], mesh.position[3 * g + 2]);
      if ((c - p).squaredNorm() < dz)
      {
        dz = (c - p).squaredNorm();
        best_z = z;
      }
    }
    gridpoint.push_back(best_g);
    zone.push_back(best_z);
  }
}

void PointHistory::add_columns(std::vector<std::string>& columns) const
{
  for (std::size_t k = 0; k < gridpoint.size(); ++k)
  {
    const std::string at = "point " + std::to_string(k) + " ";
    for (const char* q : {"ux (m)", "uy (m)", "uz (m)", "vx (m/s)", "vy (m/s)", "vz (m/s)",
                          "sxx (Pa)", "syy (Pa)", "szz (Pa)", "sxy (Pa)", "syz (Pa)", "szx (Pa)"})
      columns.push_back(at + q);
    if (water)
      columns.push_back(at + "pore pressure (Pa)");
  }
}

void PointHistory::add_values(std::vector<double>& row, const DeformableSolver& zones) const
{
  if (gridpoint.empty())
    return;
  const std::vector<double> u = zones.displacements(), v = zones.velocities();
  for (std::size_t k = 0; k < gridpoint.size(); ++k)
  {
    for (const std::vector<double>* q : {&u, &v})
      for (int d = 0; d < 3; ++d)
        row.push_back((*q)[3 * gridpoint[k] + d]);
    // The zone's mean over its stress points (Gauss points of 10-node zones).
    const unsigned int p = zones.stress_points_per_zone();
    for (int c = 0; c < 6; ++c)
    {
      double sum = 0.0;
      for (unsigned int q = 0; q < p; ++q)
        sum += zones.stress()[6 * (p * zone[k] + q) + c];
      row.push_back(sum / p);
    }
    if (water)
    {
      const std::vector<double> x = zones.positions();
      const unsigned int g = gridpoint[k];
      row.push_back(
          pore_pressure(zones.water(), gravity, Vec3(x[3 * g], x[3 * g + 1], x[3 * g + 2])));
    }
  }
}

bool has_water(const Scene& scene)
{
  bool any = scene.solver.water.active();
  for (const StageSpec& stage : scene.stages)
    any |= stage.changes_water && stage.water.active();
  return any;
}

double pore_pressure(const WaterSpec& water, double gravity, const Vec3& x)
{
  if (water.table.empty())
    return 0.0;
  return std::max(0.0, water.density * gravity * (water.table.height(x[0], x[1]) - x[2]));
}

} // namespace talus
