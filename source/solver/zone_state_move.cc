#include "block_arrays.h"

#include <talus/base/gather.h>

#include <talus/solver/deformable_solver.h>
#include <talus/solver/zone_migration.h>

#include <algorithm>
#include <stdexcept>
#include <unordered_map>

namespace talus
{

using block_records::Bytes;
using block_records::Reader;

namespace
{
/// Doubles of a gridpoint's record: position, velocity, force, inertial
/// mass, reference position, held velocity and the last step's force (3
/// each), the joints' stiffness (1); then its held components (a byte).
constexpr std::size_t gridpoint_doubles = 7 * 3 + 1;
} // namespace

std::size_t DeformableSolver::gridpoint_record_size()
{
  return gridpoint_doubles * sizeof(double) + 1;
}

std::size_t DeformableSolver::zone_record_size() const
{
  return 6 * points_per_zone_ * sizeof(double) + points_per_zone_ + 1;
}

void DeformableSolver::put_gridpoint_records(const std::vector<unsigned int>& which,
                                             std::vector<char>& out) const
{
  const std::array<std::vector<double>, 4> vectors = local_vectors();
  Bytes b;
  b.data.reserve(which.size() * gridpoint_record_size());
  for (unsigned int g : which)
  {
    for (const std::vector<double>* v :
         {&vectors[0], &vectors[1], &vectors[2], &vectors[3], &reference_, &held_velocity_})
      for (int d = 0; d < 3; ++d)
        b.put((*v)[3 * std::size_t(g) + d]);
    for (int d = 0; d < 3; ++d) // (combined damping only)
      b.put(last_force_.empty() ? 0.0 : last_force_[3 * std::size_t(g) + d]);
    b.put(joint_stiffness_.empty() ? 0.0 : joint_stiffness_[g]);
    b.put(held_[g]);
  }
  out.insert(out.end(), b.data.begin(), b.data.end());
}

void DeformableSolver::put_zone_records(const std::vector<unsigned int>& which,
                                        std::vector<char>& out) const
{
  Bytes b;
  b.data.reserve(which.size() * zone_record_size());
  for (unsigned int z : which)
  {
    for (std::size_t i = 6 * points_per_zone_ * std::size_t(z);
         i < 6 * points_per_zone_ * (std::size_t(z) + 1); ++i)
      b.put(stress_[i]);
    for (unsigned int q = 0; q < points_per_zone_; ++q)
      b.put(state_[points_per_zone_ * std::size_t(z) + q]);
    b.put<char>(removed_zone_.empty() ? 0 : removed_zone_[z]);
  }
  out.insert(out.end(), b.data.begin(), b.data.end());
}

void DeformableSolver::take_moved_state(const DeformableSolver& before,
                                        const std::vector<const char*>& gridpoint_record,
                                        const std::vector<const char*>& zone_record)
{
  const std::size_t ng = mesh_.n_gridpoints(), nz = mesh_.n_zones();
  if (gridpoint_record.size() != ng || zone_record.size() != nz)
    throw std::logic_error("DeformableSolver::take_moved_state: a record per gridpoint and zone");
  // As load_state: the mode and the settings the stages left, the zones
  // removed, then the values.
  s_ = before.s_;
  dt_ = before.dt_;
  step_from_blocks_ = before.step_from_blocks_;
  std::vector<char> removed(nz, 0);
  bool any_removed = false;
  for (std::size_t z = 0; z < nz; ++z)
  {
    Reader in{zone_record[z] + zone_record_size() - 1};
    removed[z] = in.get<char>();
    any_removed |= removed[z] != 0;
  }
  if (any_removed)
    null_zones(removed);
  std::array<std::vector<double>, 4> vectors;
  for (auto& v : vectors)
    v.resize(3 * ng);
  joint_stiffness_.assign(ng, 0.0);
  // Combined damping's last forces, where the mode the stages left uses
  // them (as set_inertial_masses sizes them).
  if (!s_.dynamic && s_.damping == Damping::combined)
    last_force_.assign(3 * ng, 0.0);
  else
    last_force_.clear();
  for (std::size_t g = 0; g < ng; ++g)
  {
    Reader in{gridpoint_record[g]};
    for (std::vector<double>* v :
         {&vectors[0], &vectors[1], &vectors[2], &vectors[3], &reference_, &held_velocity_})
      for (int d = 0; d < 3; ++d)
        (*v)[3 * g + d] = in.get<double>();
    for (int d = 0; d < 3; ++d)
    {
      const double f = in.get<double>();
      if (!last_force_.empty())
        last_force_[3 * g + d] = f;
    }
    joint_stiffness_[g] = in.get<double>();
    held_[g] = in.get<unsigned char>();
  }
  set_local_vectors(vectors);
  for (std::size_t z = 0; z < nz; ++z)
  {
    Reader in{zone_record[z]};
    for (std::size_t i = 6 * points_per_zone_ * z; i < 6 * points_per_zone_ * (z + 1); ++i)
      stress_[i] = in.get<double>();
    for (unsigned int q = 0; q < points_per_zone_; ++q)
      state_[points_per_zone_ * z + q] = in.get<unsigned char>();
  }
  // What this rank kept of the run: its shares of the sums over the ranks
  // (the energy account's works, the added mass) stay its own, so that the
  // sums stay the whole model's.
  damper_ = before.damper_;
  added_mass_ = before.added_mass_;
  time_ = before.time_;
  ratio_ = before.ratio_;
  ratio_whole_gridpoint_ = before.ratio_whole_gridpoint_;
  if (!share_) // the whole model's solver: its gridpoints are the whole mesh's
    ratio_gridpoint_ = before.share_ ? before.ratio_whole_gridpoint_ : before.ratio_gridpoint_;
  step_ = before.step_;
  motion_dt_ = before.motion_dt_;
  rest_at_next_motion_ = before.rest_at_next_motion_;
  last_step_yielded_ = before.last_step_yielded_;
  gravity_work_ = before.gravity_work_;
  boundary_work_ = before.boundary_work_;
  damping_work_ = before.damping_work_;
  kinetic_whole_step_ = before.kinetic_whole_step_;
  plastic_stress_work_ = before.plastic_stress_work_;
  nodal_mixed_work_ = before.nodal_mixed_work_;
  quiet_work_ = before.quiet_work_;
  initial_elastic_ = before.initial_elastic_;
  initial_plastic_elastic_ = before.initial_plastic_elastic_;
  growth_watch_ = before.growth_watch_;
  seconds_zones_ = before.seconds_zones_;
  seconds_gridpoints_ = before.seconds_gridpoints_;
}

void move_zone_state(const DeformableSolver& from, const std::vector<unsigned int>& from_zone,
                     DeformableSolver& to, const std::vector<unsigned int>& to_zone,
                     const std::function<int(unsigned int)>& old_owner_of_gridpoint,
                     const std::function<int(unsigned int)>& old_owner_of_zone, MPI_Comm comm)
{
  int ranks = 1;
  MPI_Comm_size(comm, &ranks);
  const GridpointShare* before = from.share();
  const GridpointShare* after = to.share();
  if (before == nullptr || after == nullptr)
    throw std::logic_error("move_zone_state: zones not split among the ranks");
  // 1. Requests: the whole numbers of the gridpoints, then of the zones,
  // this rank holds from now on, to the ranks that owned them.
  std::vector<std::vector<unsigned int>> want_gridpoints(ranks), want_zones(ranks);
  std::vector<std::pair<int, std::size_t>> gridpoint_source(after->whole_gridpoint.size()),
      zone_source(to_zone.size()); // (rank, place in its reply)
  for (std::size_t g = 0; g < after->whole_gridpoint.size(); ++g)
  {
    const unsigned int w = after->whole_gridpoint[g];
    const int r = old_owner_of_gridpoint(w);
    gridpoint_source[g] = {r, want_gridpoints[r].size()};
    want_gridpoints[r].push_back(w);
  }
  for (std::size_t z = 0; z < to_zone.size(); ++z)
  {
    const int r = old_owner_of_zone(to_zone[z]);
    zone_source[z] = {r, want_zones[r].size()};
    want_zones[r].push_back(to_zone[z]);
  }
  std::vector<std::vector<char>> request(ranks);
  for (int r = 0; r < ranks; ++r)
  {
    Bytes b;
    b.put(static_cast<unsigned int>(want_gridpoints[r].size()));
    for (unsigned int w : want_gridpoints[r])
      b.put(w);
    for (unsigned int w : want_zones[r])
      b.put(w);
    if (!want_gridpoints[r].empty() || !want_zones[r].empty())
      request[r] = std::move(b.data);
  }
  const std::vector<std::vector<char>> asked = block_records::trade(request, comm, 2421);

  // 2. Replies: the records asked for, in the order asked. An owned
  // gridpoint is among the first n_owned, ascending by whole number; the
  // zones held are ascending too.
  const auto owned_begin = before->whole_gridpoint.begin();
  const auto owned_end = owned_begin + before->n_owned;
  std::vector<std::vector<char>> reply(ranks);
  for (int r = 0; r < ranks; ++r)
  {
    if (asked[r].empty())
      continue;
    Reader in{asked[r].data()};
    const unsigned int n_g = in.get<unsigned int>();
    const std::size_t n_z = (asked[r].size() - sizeof(unsigned int)) / sizeof(unsigned int) - n_g;
    std::vector<unsigned int> gridpoints(n_g), zones(n_z);
    for (unsigned int& g : gridpoints)
    {
      const unsigned int w = in.get<unsigned int>();
      const auto it = std::lower_bound(owned_begin, owned_end, w);
      if (it == owned_end || *it != w)
        throw std::logic_error("move_zone_state: asked for a gridpoint this rank did not own");
      g = static_cast<unsigned int>(it - owned_begin);
    }
    for (unsigned int& z : zones)
    {
      const unsigned int w = in.get<unsigned int>();
      const auto it = std::lower_bound(from_zone.begin(), from_zone.end(), w);
      if (it == from_zone.end() || *it != w)
        throw std::logic_error("move_zone_state: asked for a zone this rank did not hold");
      z = static_cast<unsigned int>(it - from_zone.begin());
    }
    from.put_gridpoint_records(gridpoints, reply[r]);
    from.put_zone_records(zones, reply[r]);
  }
  const std::vector<std::vector<char>> got = block_records::trade(reply, comm, 2422);

  // 3. Each local gridpoint and zone with its record.
  const std::size_t gsize = DeformableSolver::gridpoint_record_size(),
                    zsize = to.zone_record_size();
  std::vector<const char*> gridpoint_record(gridpoint_source.size()),
      zone_record(zone_source.size());
  for (std::size_t g = 0; g < gridpoint_source.size(); ++g)
    gridpoint_record[g] =
        got[gridpoint_source[g].first].data() + gridpoint_source[g].second * gsize;
  for (std::size_t z = 0; z < zone_source.size(); ++z)
  {
    const int r = zone_source[z].first;
    zone_record[z] =
        got[r].data() + want_gridpoints[r].size() * gsize + zone_source[z].second * zsize;
  }
  to.take_moved_state(from, gridpoint_record, zone_record);
}

void gather_whole_zones(const DeformableSolver& split, const std::vector<unsigned int>& split_zone,
                        DeformableSolver& whole, MPI_Comm comm)
{
  const GridpointShare* share = split.share();
  if (share == nullptr || whole.share() != nullptr)
    throw std::logic_error("gather_whole_zones: a split solver into a whole one");
  // This rank's owned gridpoints and the zones it counts (each zone on one
  // rank: by the owner of its first corner), each with its whole number.
  std::vector<unsigned int> gridpoints(share->n_owned), zones;
  for (unsigned int g = 0; g < share->n_owned; ++g)
    gridpoints[g] = g;
  const TetMesh& mesh = split.mesh();
  for (unsigned int z = 0; z < mesh.n_zones(); ++z)
    if (share->counts(mesh.zone_gridpoint[z][0]))
      zones.push_back(z);
  std::vector<char> gridpoint_records, zone_records;
  split.put_gridpoint_records(gridpoints, gridpoint_records);
  split.put_zone_records(zones, zone_records);
  const std::size_t gsize = DeformableSolver::gridpoint_record_size(),
                    zsize = split.zone_record_size();
  Bytes out;
  out.put(static_cast<unsigned int>(gridpoints.size()));
  out.put(static_cast<unsigned int>(zones.size()));
  for (unsigned int g : gridpoints)
    out.put(share->whole_gridpoint[g]);
  for (unsigned int z : zones)
    out.put(split_zone[z]);
  out.data.insert(out.data.end(), gridpoint_records.begin(), gridpoint_records.end());
  out.data.insert(out.data.end(), zone_records.begin(), zone_records.end());
  const std::vector<char> all = gathered_on_every_rank(out.data, comm);

  const std::size_t ng = whole.mesh().n_gridpoints(), nz = whole.mesh().n_zones();
  std::vector<const char*> gridpoint_record(ng, nullptr), zone_record(nz, nullptr);
  for (const char* at = all.data(); at != all.data() + all.size();)
  {
    Reader in{at};
    const unsigned int n_g = in.get<unsigned int>(), n_z = in.get<unsigned int>();
    const char* numbers = in.at;
    const char* records = numbers + (std::size_t(n_g) + n_z) * sizeof(unsigned int);
    for (unsigned int k = 0; k < n_g + n_z; ++k)
    {
      const unsigned int w = in.get<unsigned int>();
      const bool gridpoint = k < n_g;
      if (w >= (gridpoint ? ng : nz) || (gridpoint ? gridpoint_record[w] : zone_record[w]))
        throw std::logic_error("gather_whole_zones: a gridpoint or zone not of the whole mesh, "
                               "or sent twice");
      (gridpoint ? gridpoint_record[w] : zone_record[w]) =
          gridpoint ? records + k * gsize : records + n_g * gsize + (k - n_g) * zsize;
    }
    at = records + n_g * gsize + std::size_t(n_z) * zsize;
  }
  if (std::count(gridpoint_record.begin(), gridpoint_record.end(), nullptr) != 0 ||
      std::count(zone_record.begin(), zone_record.end(), nullptr) != 0)
    throw std::logic_error(
        "gather_whole_zones: a gridpoint or zone of the whole mesh was not sent");
  whole.take_moved_state(split, gridpoint_record, zone_record);
  // The energy account's terms, which each rank keeps for its own
  // gridpoints and zones, as the whole model's.
  double terms[9] = {
      whole.gravity_work_,     whole.boundary_work_,      whole.damping_work_,
      whole.quiet_work_,       whole.kinetic_whole_step_, whole.plastic_stress_work_,
      whole.nodal_mixed_work_, whole.initial_elastic_,    whole.initial_plastic_elastic_};
  MPI_Allreduce(MPI_IN_PLACE, terms, 9, MPI_DOUBLE, MPI_SUM, comm);
  whole.gravity_work_ = terms[0];
  whole.boundary_work_ = terms[1];
  whole.damping_work_ = terms[2];
  whole.quiet_work_ = terms[3];
  whole.kinetic_whole_step_ = terms[4];
  whole.plastic_stress_work_ = terms[5];
  whole.nodal_mixed_work_ = terms[6];
  whole.initial_elastic_ = terms[7];
  whole.initial_plastic_elastic_ = terms[8];
}

} // namespace talus
