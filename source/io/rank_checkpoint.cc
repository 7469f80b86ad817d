#include <talus/base/exceptions.h>
#include <talus/io/checkpoint.h>
#include <talus/io/rank_checkpoint.h>
#include <talus/run/rank_share.h>
#include <talus/solver/block_migration.h>

#include <filesystem>
#include <regex>
#include <set>

namespace talus
{

namespace
{
const std::regex rank_suffix("(.*)\\.rank-([0-9]+)-of-([0-9]+)");

/// The set a file names: itself, or the file less `.rank-R-of-N`.
std::string set_of(const std::string& file)
{
  std::smatch m;
  return std::regex_match(file, m, rank_suffix) ? m[1].str() : file;
}

/// The numbers of ranks of the sets `set.rank-0-of-N` in its folder.
std::set<unsigned int> sets_beside(const std::string& set)
{
  std::set<unsigned int> found;
  const std::filesystem::path p(set);
  const std::filesystem::path folder = p.parent_path().empty() ? "." : p.parent_path();
  const std::string name = p.filename().string();
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(folder, ec))
  {
    std::smatch m;
    const std::string f = e.path().filename().string();
    if (std::regex_match(f, m, rank_suffix) && m[1].str() == name && m[2].str() == "0")
      found.insert(static_cast<unsigned int>(std::stoul(m[3].str())));
  }
  return found;
}

std::string text(const std::set<unsigned int>& counts)
{
  std::string s;
  for (unsigned int n : counts)
    s += (s.empty() ? "" : ", ") + std::to_string(n);
  return s;
}

/// This rank's file of the set `given` names, checked (header, rank count).
std::string resolve(const std::string& given, unsigned int rank, unsigned int ranks)
{
  const std::string set = set_of(given);
  std::error_code ec;
  const auto exists = [&](const std::string& f) { return std::filesystem::exists(f, ec); };
  unsigned int written_rank = 0, written_ranks = 1;
  if (ranks == 1)
  {
    if (!exists(given) && given == set && !sets_beside(set).empty())
    {
      const unsigned int n = *sets_beside(set).begin();
      throw InputError(
          given + ": not there, but the checkpoint set " + rank_checkpoint_path(set, -1, n) +
          " of a run on " + std::to_string(n) +
          " MPI ranks is; allowed: continue it on as many ranks: " + restart_command(set, n));
    }
    if (!exists(given))
      return given; // read_checkpoint says what is wrong
    read_checkpoint(given, &written_rank, &written_ranks);
    if (written_ranks != 1)
      throw InputError(given + ": a file of the checkpoint set of a run on " +
                       std::to_string(written_ranks) +
                       " MPI ranks, and this run is on one; allowed: continue it on as many "
                       "ranks: " +
                       restart_command(given, written_ranks));
    return given;
  }
  const std::string mine = rank_checkpoint_path(set, static_cast<int>(rank), ranks);
  if (!exists(mine))
  {
    const std::set<unsigned int> others = sets_beside(set);
    if (!others.empty() && others.count(ranks) == 0)
      throw InputError(set + ": the checkpoint set was written on " + text(others) +
                       " MPI ranks (" + rank_checkpoint_path(set, -1, *others.begin()) +
                       "), and this run is on " + std::to_string(ranks) +
                       "; allowed: a restart on the number of ranks it was written on: " +
                       restart_command(set, *others.begin()));
    if (others.count(ranks) != 0)
      throw InputError(set + ": the checkpoint set of " + std::to_string(ranks) +
                       " ranks lacks rank " + std::to_string(rank) + "'s file " + mine +
                       "; allowed: a whole set, every file written by one run");
    if (exists(set) && !std::filesystem::is_directory(set, ec))
    {
      read_checkpoint(set, &written_rank, &written_ranks);
      throw InputError(set + ": a checkpoint of a run on " +
                       (written_ranks == 1 ? std::string("one rank")
                                           : std::to_string(written_ranks) + " ranks") +
                       ", and this run is on " + std::to_string(ranks) +
                       " MPI ranks; allowed: continue it as it was written: " +
                       restart_command(set, written_ranks));
    }
    throw InputError(set + ": no checkpoint set " + rank_checkpoint_path(set, -1, ranks) +
                     " of a run on " + std::to_string(ranks) +
                     " ranks; allowed: <Base name>_checkpoint.bin of a run on as many ranks");
  }
  read_checkpoint(mine, &written_rank, &written_ranks);
  if (written_rank != rank || written_ranks != ranks)
    throw InputError(mine + ": written by rank " + std::to_string(written_rank) + " of " +
                     std::to_string(written_ranks) + " (a renamed file?); allowed: the files of " +
                     "a set as talus wrote them");
  return mine;
}

/// The step a checkpoint is at (after its header's fingerprints).
unsigned long step_of(const std::string& file)
{
  CheckpointReader in = read_checkpoint(file);
  std::string parameter_file;
  std::uint64_t hash = 0, step = 0;
  std::vector<std::uint64_t> stages;
  unsigned int begun = 0;
  in.get(parameter_file);
  in.get(hash);
  in.get(stages);
  in.get(begun);
  in.get(hash);
  in.get(step);
  return step;
}
} // namespace

std::string rank_checkpoint_path(const std::string& set, int rank, unsigned int ranks)
{
  return set + ".rank-" + (rank < 0 ? std::string("*") : std::to_string(rank)) + "-of-" +
         std::to_string(ranks);
}

std::string restart_command(const std::string& file, unsigned int ranks)
{
  const std::string command = "talus --restart " + set_of(file);
  return ranks > 1 ? "mpirun -np " + std::to_string(ranks) + " " + command
                   : command + " (without mpirun)";
}

std::string checkpoint_of_this_rank(const std::string& given)
{
  const unsigned int rank = static_cast<unsigned int>(world_rank());
  const unsigned int ranks = static_cast<unsigned int>(world_ranks());
  std::string mine;
  agree_on_input_errors([&]() { mine = resolve(given, rank, ranks); });
  if (ranks == 1)
    return mine;
  // The files of a set are of one step, unless a run stopped while it
  // wrote them (each file is whole: written atomically).
  unsigned long step = 0;
  agree_on_input_errors([&]() { step = step_of(mine); });
  unsigned long least = step, most = step;
  MPI_Allreduce(&step, &least, 1, MPI_UNSIGNED_LONG, MPI_MIN, MPI_COMM_WORLD);
  MPI_Allreduce(&step, &most, 1, MPI_UNSIGNED_LONG, MPI_MAX, MPI_COMM_WORLD);
  if (least != most)
    throw InputError(set_of(given) + ": the files of the checkpoint set are of steps " +
                     std::to_string(least) + " to " + std::to_string(most) +
                     " (a run stopped while it wrote them); allowed: a set whose files are of "
                     "one step");
  return mine;
}

void put_rank_blocks(CheckpointWriter& out, const RankBlocks& blocks)
{
  out.tag("ranks");
  out.put(blocks.rank);
  out.put(blocks.local);
  out.put(blocks.owned);
  for (const auto* lists : {&blocks.send, &blocks.receive})
  {
    out.put(static_cast<std::uint64_t>(lists->size()));
    for (const auto& [other, list] : *lists)
    {
      out.put(other);
      out.put(list);
    }
  }
}

RankBlocks get_rank_blocks(CheckpointReader& in)
{
  RankBlocks blocks;
  in.tag("ranks");
  in.get(blocks.rank);
  in.get(blocks.local);
  in.get(blocks.owned, blocks.local.size(), "blocks this rank holds");
  for (auto* lists : {&blocks.send, &blocks.receive})
  {
    std::uint64_t n = 0;
    in.get(n);
    for (std::uint64_t k = 0; k < n; ++k)
    {
      unsigned int other = 0;
      std::vector<unsigned int> list;
      in.get(other);
      in.get(list);
      for (unsigned int i : list)
        if (i >= blocks.local.size())
          in.mismatch("blocks this rank holds (a ghost list's)", i + 1ull, blocks.local.size());
      lists->emplace_back(other, std::move(list));
    }
  }
  return blocks;
}

void BlockMigration::save_state(CheckpointWriter& out) const
{
  out.tag("migration");
  out.put(path_at_choice_);
  out.put(events_);
  out.put(owner_changes_);
  out.put(received_);
  out.put(dropped_);
  out.put(zone_moves_);
}

void BlockMigration::load_state(CheckpointReader& in)
{
  in.tag("migration");
  in.get(path_at_choice_, path_at_choice_.size(), "blocks this rank holds");
  in.get(events_);
  in.get(owner_changes_);
  in.get(received_);
  in.get(dropped_);
  in.get(zone_moves_);
}

void RankShare::save_state(CheckpointWriter& out) const
{
  put_rank_blocks(out, blocks_);
  out.put(zone_surfaces_);
  out.put(static_cast<unsigned char>(migration_ != nullptr));
  if (migration_)
    migration_->save_state(out);
  out.put(event_steps_);
  // The regions a rebalance chose (the ones made at the start otherwise).
  out.tag("regions");
  out.put(partition_->numbers());
  out.put(balance_->numbers());
}

void RankShare::load_state(CheckpointReader& in, const RigidSolver& solver)
{
  const RankBlocks saved = get_rank_blocks(in);
  // The share was made with the blocks of this file (read_rank_blocks).
  if (saved.rank != blocks_.rank || saved.local != blocks_.local || saved.owned != blocks_.owned)
    in.mismatch("blocks this rank holds", saved.local.size(), blocks_.local.size());
  std::vector<unsigned int> surfaces;
  in.get(surfaces);
  if (surfaces != zone_surfaces_)
    in.mismatch("deformable blocks whose surfaces this rank holds", surfaces.size(),
                zone_surfaces_.size());
  unsigned char migrating = 0;
  in.get(migrating);
  migration_.reset();
  if (migrating)
  {
    make_migration(solver);
    migration_->load_state(in);
  }
  in.get(event_steps_);
  in.tag("regions");
  std::vector<double> numbers;
  in.get(numbers);
  try
  {
    *partition_ = CellPartition::from_numbers(numbers); // in place: the migration refers to it
    in.get(numbers);
    balance_->set_numbers(numbers);
  }
  catch (const std::invalid_argument&)
  {
    in.mismatch("numbers of the ranks' regions", numbers.size(), numbers.size());
  }
  if (partition_->n_ranks() != static_cast<unsigned int>(ranks_))
    in.mismatch("ranks of the regions", partition_->n_ranks(), ranks_);
}

} // namespace talus
