#include <talus/base/exceptions.h>
#include <talus/contact/cell_space.h>
#include <talus/contact/contact_set.h>
#include <talus/io/block_vtu_writer.h>
#include <talus/io/checkpoint.h>
#include <talus/io/file_output.h>
#include <talus/io/history_file.h>
#include <talus/io/rank_checkpoint.h>
#include <talus/joint/continuously_yielding.h>
#include <talus/model/block_model.h>
#include <talus/run/rank_share.h>
#include <talus/scene/scene.h>
#include <talus/solver/damper.h>
#include <talus/solver/deformable_solver.h>
#include <talus/solver/rigid_solver.h>

#include <mpi.h>

#include <algorithm>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <regex>
#include <sstream>
#include <unistd.h>

namespace talus
{

namespace
{

constexpr char magic[8] = {'T', 'A', 'L', 'U', 'S', 'C', 'K', 'P'};
constexpr std::size_t header_size = 8 + 4 + 8 + 8;

volatile std::sig_atomic_t stop_signal = 0;

extern "C" void on_stop_signal(int signal)
{
  // A second signal ends the process at once: the first one is only seen
  // between steps, and a run stuck outside its cycle must still stop.
  if (stop_signal != 0)
    _exit(128 + signal);
  stop_signal = signal; // nothing else is safe in a handler
}

const char* signal_name(int signal)
{
  return signal == SIGINT ? "SIGINT" : signal == SIGTERM ? "SIGTERM" : "a signal";
}

template <typename T>
void put_header_value(std::string& s, const T& v)
{
  s.append(reinterpret_cast<const char*>(&v), sizeof(T));
}

} // namespace

CheckpointReader read_checkpoint(const std::string& file, unsigned int* rank, unsigned int* ranks)
{
  std::error_code ec;
  if (std::filesystem::is_directory(file, ec))
    throw InputError(file + ": a folder, not a checkpoint; allowed: a checkpoint file "
                            "(<Base name>_checkpoint.bin in the output folder)");
  if (std::filesystem::exists(file, ec) && !std::filesystem::is_regular_file(file, ec))
    throw InputError(file + ": not a regular file; allowed: a checkpoint written by talus");
  std::ifstream in(file, std::ios::binary);
  if (!in)
    throw InputError(file + ": cannot read the checkpoint (no such file, or not readable)");
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto refuse = [&](const std::string& why)
  { return InputError(file + ": " + why + "; allowed: a checkpoint written by talus"); };
  if (bytes.size() < sizeof magic || std::memcmp(bytes.data(), magic, sizeof magic) != 0)
    throw refuse("not a talus checkpoint (it does not start with TALUSCKP)");
  if (bytes.size() < header_size)
    throw refuse("the checkpoint is truncated (" + std::to_string(bytes.size()) +
                 " bytes, shorter than its header)");
  std::uint32_t version = 0;
  std::uint64_t size = 0, hash = 0;
  std::memcpy(&version, bytes.data() + 8, 4);
  std::memcpy(&size, bytes.data() + 12, 8);
  std::memcpy(&hash, bytes.data() + 20, 8);
  if (version != checkpoint_format_version)
    throw refuse("checkpoint format version " + std::to_string(version) +
                 "; this talus reads version " + std::to_string(checkpoint_format_version));
  if (bytes.size() - header_size != size)
    throw refuse(bytes.size() - header_size < size
                     ? "the checkpoint is truncated (" + std::to_string(bytes.size()) + " of " +
                           std::to_string(header_size + size) + " bytes)"
                     : "the checkpoint has " + std::to_string(bytes.size() - header_size - size) +
                           " bytes after its end");
  if (fnv1a(bytes.data() + header_size, size) != hash)
    throw refuse("the checkpoint is corrupt (its checksum does not match its content)");
  CheckpointReader reader(bytes.substr(header_size), file);
  reader.tag("talus checkpoint");
  unsigned int written_rank = 0, written_ranks = 1;
  reader.get(written_rank);
  reader.get(written_ranks);
  if (rank != nullptr)
    *rank = written_rank;
  if (ranks != nullptr)
    *ranks = written_ranks;
  return reader;
}

namespace
{

/// Fingerprint of the model's initial geometry (`blocks`:
/// ModelDigest::geometry_fingerprint) and of the zones' gridpoints.
std::uint64_t geometry_fingerprint(std::uint64_t blocks, const DeformableSolver* zones)
{
  std::uint64_t h = blocks;
  if (zones != nullptr && zones->share() != nullptr)
  {
    // Split among ranks: each gridpoint's number in the whole mesh and its
    // position as built, added over the ranks that own them, so that the
    // fingerprint does not depend on how the zones are split (deformable
    // blocks change rank). Collective.
    const GridpointShare& share = *zones->share();
    const std::vector<double>& x = zones->mesh().position;
    std::uint64_t sum = 0;
    for (unsigned int g = 0; g < share.n_owned; ++g)
      sum += fnv1a(&x[3 * std::size_t(g)], 3 * sizeof(double),
                   fnv1a(&share.whole_gridpoint[g], sizeof(unsigned int)));
    MPI_Allreduce(MPI_IN_PLACE, &sum, 1, MPI_UINT64_T, MPI_SUM, share.comm);
    h = fnv1a(&sum, sizeof sum, h);
  }
  else if (zones != nullptr)
  {
    const std::vector<double>& x = zones->mesh().position;
    h = fnv1a(x.data(), x.size() * sizeof(double), h);
  }
  return h;
}

} // namespace

// ---- Signals -----------------------------------------------------------------

RunInterrupted::RunInterrupted(int signal, unsigned long step, const std::string& checkpoint,
                               const std::string& restart_with)
    : std::runtime_error(std::string("stopped by ") + signal_name(signal) + " at step " +
                         std::to_string(step) + "; checkpoint written to " + checkpoint +
                         "; continue with: " +
                         (restart_with.empty() ? "talus --restart " + checkpoint : restart_with)),
      signal(signal), step(step), checkpoint(checkpoint)
{
}

void restore_default_signal_handlers()
{
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
}

void install_stop_signal_handlers()
{
  struct sigaction action = {};
  action.sa_handler = on_stop_signal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

int stop_signal_received()
{
  return stop_signal;
}

// ---- Scene -------------------------------------------------------------------

std::string checkpoint_parameter_file(const std::string& checkpoint)
{
  CheckpointReader in = read_checkpoint(checkpoint);
  std::string file;
  in.get(file);
  std::error_code ec;
  if (!std::filesystem::exists(file, ec))
    throw InputError(checkpoint + ": the parameter file it was written for, " + file +
                     ", is not there (a moved project?); allowed: name the parameter file: "
                     "talus --restart " +
                     checkpoint + " SCENE.prm");
  return file;
}

SceneFingerprint scene_fingerprint(const Scene& scene)
{
  SceneFingerprint f;
  f.base = fnv1a(nullptr, 0);
  std::map<std::string, std::uint64_t> stage_hash; // by "Stage N"
  std::istringstream lines(scene.used_parameters);
  int depth = 0;
  std::uint64_t* into = &f.base;
  for (std::string line; std::getline(lines, line);)
  {
    const std::size_t first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == '#')
      continue;
    line.erase(0, first);
    if (line.rfind("subsection ", 0) == 0)
    {
      // A top-level 'Stage N' and what it holds go to its own fingerprint.
      if (depth++ == 0 && std::regex_match(line.substr(11), std::regex("Stage [0-9]+")))
      {
        into = &stage_hash[line.substr(11)];
        *into = fnv1a(nullptr, 0);
      }
    }
    else if (line == "end" && --depth == 0)
    {
      *into = fnv1a(line.data(), line.size(), *into);
      into = &f.base;
      continue;
    }
    if (line.rfind("set Steps ", 0) == 0 || line.rfind("set Checkpoint interval ", 0) == 0)
      continue;
    *into = fnv1a(line.data(), line.size(), *into);
  }
  for (const StageSpec& stage : scene.stages)
    f.stages.push_back(stage_hash[stage.section]);
  return f;
}

namespace
{
/// The scene fingerprints of a checkpoint's header, with the stages begun.
struct WrittenFingerprint
{
  SceneFingerprint scene;
  std::uint64_t geometry = 0, step = 0;
  unsigned int stages_begun = 0;
};

WrittenFingerprint read_fingerprints(CheckpointReader& in)
{
  WrittenFingerprint w;
  std::string parameter_file;
  in.get(parameter_file);
  in.get(w.scene.base);
  in.get(w.scene.stages);
  in.get(w.stages_begun);
  in.get(w.geometry);
  in.get(w.step);
  return w;
}

/// Refuses a scene whose parameters outside the stages, or in the stages
/// the run has begun, differ from those the checkpoint was written with.
void compare_fingerprints(const std::string& checkpoint, const Scene& scene,
                          const WrittenFingerprint& written)
{
  const SceneFingerprint now = scene_fingerprint(scene);
  const std::string what = checkpoint + ": the parameter file " + scene.parameter_file;
  const std::string allowed = "the parameter file the checkpoint was written with; only 'Steps', "
                              "'Checkpoint interval', the stages the run has not begun, and "
                              "stages added after them may change";
  if (now.base != written.scene.base && written.scene.stages.empty())
    throw InputError(what + " has changed since the checkpoint was written (only 'Steps' and "
                            "'Checkpoint interval' may change); allowed: the parameter file the "
                            "checkpoint was written with");
  if (now.base != written.scene.base)
    throw InputError(what +
                     " has changed outside its stages since the checkpoint was written; "
                     "allowed: " +
                     allowed);
  if (written.scene.stages.empty() != now.stages.empty())
    throw InputError(what +
                     (now.stages.empty() ? " has no 'Stage N', and the run had stages"
                                         : " has 'Stage N', and the run had none") +
                     "; allowed: " + allowed);
  for (unsigned int k = 0; k < written.stages_begun && !now.stages.empty(); ++k)
  {
    if (k >= now.stages.size())
      throw InputError(what + " has " + std::to_string(now.stages.size()) +
                       " stages, and the run had begun " + std::to_string(written.stages_begun) +
                       "; allowed: " + allowed);
    if (now.stages[k] != written.scene.stages[k])
      throw InputError(what + ": '" + scene.stages[k].section +
                       "' has changed since the checkpoint was written, and the run had begun "
                       "it; allowed: " +
                       allowed);
  }
}
} // namespace

RankBlocks read_rank_blocks(const std::string& file, std::vector<unsigned int>* zone_surfaces)
{
  CheckpointReader in = read_checkpoint(file);
  read_fingerprints(in);
  RankBlocks blocks = get_rank_blocks(in);
  if (zone_surfaces)
    in.get(*zone_surfaces);
  return blocks;
}

void check_checkpoint_scene(const std::string& checkpoint, const Scene& scene)
{
  CheckpointReader in = read_checkpoint(checkpoint);
  const WrittenFingerprint written = read_fingerprints(in);
  compare_fingerprints(checkpoint, scene, written);
  const std::uint64_t step = written.step;
  // A staged run may take the step limits of all its stages.
  unsigned long limit = scene.stages.empty() ? scene.solver.steps : 0;
  for (const StageSpec& stage : scene.stages)
    limit += stage.steps;
  if (limit < step)
    throw InputError(checkpoint + ": the checkpoint is at step " + std::to_string(step) +
                     ", beyond 'Steps' = " + std::to_string(limit) + " of " + scene.parameter_file +
                     (scene.stages.empty() ? "" : " (the sum over its stages)") +
                     "; allowed: 'Steps' of at least " + std::to_string(step) +
                     " to continue the run");
}

void continue_in_checkpoint_folder(const std::string& checkpoint, Scene& scene)
{
  check_checkpoint_scene(checkpoint, scene);
  // The run goes on in the folder that holds its files: 'Directory' as
  // given, or else (a relative 'Directory' seen from another working
  // folder) the checkpoint's own folder. Restoring checks that the frames
  // the checkpoint names are there.
  const auto holds_run = [&](const std::string& folder)
  {
    std::error_code ec;
    return std::filesystem::exists(
        std::filesystem::path(folder) / (scene.output.base_name + "_history.csv"), ec);
  };
  const std::filesystem::path beside = std::filesystem::path(checkpoint).parent_path();
  const std::string checkpoint_folder = beside.empty() ? "." : beside.string();
  if (!holds_run(scene.output.directory) && holds_run(checkpoint_folder))
    scene.output.directory = checkpoint_folder;
  prepare_output_directory(scene.output.directory);
}

// ---- Checkpoint ----------------------------------------------------------------

Checkpoint::Checkpoint(const Scene& scene, std::uint64_t blocks_fingerprint, RigidSolver* rigid,
                       DeformableSolver* zones, const std::string& restart_from)
    : scene_(scene), rigid_(rigid), zones_(zones), scene_hash_(scene_fingerprint(scene)),
      geometry_hash_(geometry_fingerprint(blocks_fingerprint, zones)),
      interval_(scene.output.checkpoint_interval), rank_(static_cast<unsigned int>(world_rank())),
      ranks_(static_cast<unsigned int>(world_ranks())),
      set_(scene.output.directory + "/" + scene.output.base_name + "_checkpoint.bin"),
      path_(ranks_ > 1 ? rank_checkpoint_path(set_, rank_, ranks_) : set_)
{
  if (const char* at = std::getenv("TALUS_TEST_SIGNAL_AT_STEP"))
    signal_test_step_ = std::atol(at);
  if (!restart_from.empty())
  {
    CheckpointReader in = read_checkpoint(restart_from);
    check_fingerprints(in, restart_from);
  }
  install_stop_signal_handlers();
}

Checkpoint::~Checkpoint()
{
  // The cycle is over: a signal from now on ends the process as usual (a
  // finalization that hangs can still be stopped).
  restore_default_signal_handlers();
}

unsigned long Checkpoint::check_fingerprints(CheckpointReader& in, const std::string& file) const
{
  const WrittenFingerprint written = read_fingerprints(in);
  compare_fingerprints(file, scene_, written);
  if (written.geometry != geometry_hash_)
    throw InputError(file + ": the model built from " + scene_.parameter_file +
                     " differs from the one the checkpoint was written for (a changed mesh "
                     "file, or another version of talus); allowed: the same model");
  return written.step;
}

void Checkpoint::after_step(unsigned long step)
{
  if (signal_test_step_ >= 0 && step == static_cast<unsigned long>(signal_test_step_))
    std::raise(SIGTERM);
  int signal = stop_signal_received();
  if (ranks_ > 1)
  {
    // Every rank stops at the same step (a signal reaches the ranks at
    // different steps), so that the files of the set are of one step.
    int any = signal;
    MPI_Allreduce(&signal, &any, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
    signal = any;
  }
  if (signal != 0 || (interval_ > 0 && step % interval_ == 0))
    write(step);
  if (signal != 0 && ranks_ > 1)
    throw RunInterrupted(signal, step, rank_checkpoint_path(set_, -1, ranks_),
                         "mpirun -np " + std::to_string(ranks_) + " talus --restart " + set_);
  if (signal != 0)
    throw RunInterrupted(signal, step, path_);
}

DeformableSolver* Checkpoint::zone_solver() const
{
  if (rigid_ && rigid_->zone_solver())
    return rigid_->zone_solver();
  return zone_source_ ? zone_source_() : zones_;
}

void Checkpoint::write(unsigned long step) const
{
  CheckpointWriter out;
  out.tag("talus checkpoint");
  out.put(rank_);
  out.put(ranks_);
  out.put(std::filesystem::absolute(scene_.parameter_file).lexically_normal().string());
  out.put(scene_hash_.base);
  out.put(scene_hash_.stages);
  out.put(stages_begun_ != nullptr ? *stages_begun_ : 0u);
  out.put(geometry_hash_);
  out.put(static_cast<std::uint64_t>(step));
  if (share_ != nullptr)
    share_->save_state(out);
  out.tag("split");
  out.put(static_cast<unsigned char>(save_split_ != nullptr));
  if (save_split_)
    save_split_(out);
  out.tag("counters");
  out.put(static_cast<std::uint64_t>(counters_.size()));
  for (const unsigned int* c : counters_)
    out.put(*c);
  out.put(static_cast<std::uint64_t>(long_counters_.size()));
  for (const unsigned long* c : long_counters_)
    out.put(*c);
  out.put(static_cast<std::uint64_t>(real_values_.size()));
  for (const double* c : real_values_)
    out.put(*c);
  out.put(static_cast<unsigned char>(rigid_ != nullptr));
  if (rigid_ != nullptr)
    rigid_->save_state(out);
  // (The rigid solver's: on ranks its zones change with their blocks' ranks.)
  DeformableSolver* zones = zone_solver();
  out.put(static_cast<unsigned char>(zones != nullptr));
  if (zones != nullptr)
    zones->save_state(out);
  out.tag("output");
  out.put(static_cast<std::uint64_t>(histories_.size()));
  for (HistoryFile* h : histories_)
    h->save_state(out);
  out.put(static_cast<std::uint64_t>(series_.size()));
  for (const PvdSeries* s : series_)
    s->save_state(out);
  out.tag("end");

  const std::string& payload = out.bytes();
  std::string header(magic, sizeof magic);
  put_header_value(header, checkpoint_format_version);
  put_header_value(header, static_cast<std::uint64_t>(payload.size()));
  put_header_value(header, fnv1a(payload.data(), payload.size()));
  write_file_atomically(path_,
                        [&](std::ostream& file)
                        {
                          file.write(header.data(), header.size());
                          file.write(payload.data(), payload.size());
                        });
  // On ranks: the set whole (every rank's file of this step in place)
  // before the run goes on or stops.
  if (ranks_ > 1)
    MPI_Barrier(MPI_COMM_WORLD);
}

unsigned long Checkpoint::restore(const std::string& file)
{
  unsigned int rank = 0, ranks = 1;
  CheckpointReader in = read_checkpoint(file, &rank, &ranks);
  if (rank != rank_ || ranks != ranks_)
    throw InputError(file + ": written by rank " + std::to_string(rank) + " of " +
                     std::to_string(ranks) + ", read by rank " + std::to_string(rank_) + " of " +
                     std::to_string(ranks_) + "; allowed: " + restart_command(file, ranks));
  const unsigned long step = check_fingerprints(in, file);
  // Blocks split among ranks keep their share (RankShare); a deformable
  // body alone keeps its gridpoints' share in the zones' state.
  const bool split_blocks = ranks > 1 && rigid_ != nullptr;
  if ((share_ != nullptr) != split_blocks)
    in.mismatch("ranks' shares", split_blocks, share_ != nullptr);
  if (share_ != nullptr)
    share_->load_state(in, *rigid_);
  in.tag("split");
  unsigned char split = 0;
  in.get(split);
  if (split != (load_split_ != nullptr))
    in.mismatch("zones split again", split, load_split_ != nullptr);
  if (load_split_)
    load_split_(in);
  std::uint64_t n = 0;
  in.tag("counters");
  in.get(n);
  if (n != counters_.size())
    in.mismatch("output counters", n, counters_.size());
  for (unsigned int* c : counters_)
    in.get(*c);
  in.get(n);
  if (n != long_counters_.size())
    in.mismatch("output step counters", n, long_counters_.size());
  for (unsigned long* c : long_counters_)
    in.get(*c);
  in.get(n);
  if (n != real_values_.size())
    in.mismatch("run loop values", n, real_values_.size());
  for (double* c : real_values_)
    in.get(*c);
  unsigned char present = 0;
  in.get(present);
  if (present != (rigid_ != nullptr))
    in.mismatch("block solvers", present, rigid_ != nullptr);
  if (rigid_ != nullptr)
    rigid_->load_state(in);
  in.get(present);
  DeformableSolver* zones = zone_solver();
  if (present != (zones != nullptr))
    in.mismatch("zone solvers", present, zones != nullptr);
  if (zones != nullptr)
    zones->load_state(in);
  in.tag("output");
  in.get(n);
  if (n != histories_.size())
    in.mismatch("history files", n, histories_.size());
  for (HistoryFile* h : histories_)
    h->load_state(in);
  in.get(n);
  if (n != series_.size())
    in.mismatch("VTU series", n, series_.size());
  for (PvdSeries* s : series_)
    s->load_state(in);
  in.tag("end");
  // Only now, with the whole checkpoint read and checked, are files touched.
  for (HistoryFile* h : histories_)
    h->rewrite();
  for (PvdSeries* s : series_)
    s->rewrite();
  return step;
}

// ---- Hooks of the classes whose state is saved ---------------------------------

namespace
{
/// An exact sum by its words, normalized: not the object's bytes, whose
/// padding is whatever the memory held (checkpoints of one state are then
/// the same bytes).
void put_sum(CheckpointWriter& out, ExactSum sum)
{
  sum.normalize();
  out.put(sum.words());
  out.put(sum.special());
}

ExactSum get_sum(CheckpointReader& in)
{
  ExactSum sum;
  in.get(sum.words());
  in.get(sum.special());
  return sum;
}
} // namespace

void Damper::save_state(CheckpointWriter& out) const
{
  out.put(c_);
  put_sum(out, damping_power_);
  put_sum(out, force_power_);
}

void Damper::load_state(CheckpointReader& in)
{
  in.get(c_);
  damping_power_ = get_sum(in);
  force_power_ = get_sum(in);
}

void EnergyGrowthWatch::save_state(CheckpointWriter& out) const
{
  out.put(last_);
  out.put(growing_);
  out.put(largest_sources_);
}

void EnergyGrowthWatch::load_state(CheckpointReader& in)
{
  in.get(last_);
  in.get(growing_);
  in.get(largest_sources_);
}

void CellSpace::save_state(CheckpointWriter& out) const
{
  out.put(std::vector<Vec3>{bounds_.lo, bounds_.hi});
  out.put(regrowths_);
}

void CellSpace::load_state(CheckpointReader& in)
{
  std::vector<Vec3> corners;
  in.get(corners, 2, "cell space corners");
  in.get(regrowths_);
  bounds_ = Box{corners[0],
                corners[1]}; // the caller defines the grid on them, as map() does after growing
}

void ContactSet::save_state(CheckpointWriter& out) const
{
  out.tag("contacts");
  out.put(block_a);
  out.put(block_b);
  out.put(plane);
  out.put(gap);
  out.put(type);
  out.put(alive);
  out.put(material);
  out.put(path_at_update);
  out.put(sc_contact);
  out.put(sc_position);
  out.put(sc_area);
  out.put(sc_un);
  out.put(sc_fn);
  out.put(sc_fs);
  out.put(sc_dilation);
  out.put(sc_us);
  out.put(sc_yield);
  out.put(sc_state);
  out.put(sc_material);
  out.put(sc_fresh);
  out.put(sc_node);
  out.put(sc_weight);
  out.put(free_);
  out.put(n_alive_);
  // In the order of the pairs, not of the hash map, which differs between
  // a run and its restart: one state, the same bytes.
  std::vector<std::pair<std::uint64_t, unsigned int>> live(slot_of_pair_.begin(),
                                                           slot_of_pair_.end());
  std::sort(live.begin(), live.end());
  std::vector<std::uint64_t> pairs;
  std::vector<unsigned int> slots;
  for (const auto& [key, c] : live)
  {
    pairs.push_back(key);
    slots.push_back(c);
  }
  out.put(pairs);
  out.put(slots);
}

void ContactSet::load_state(CheckpointReader& in, unsigned int n_blocks)
{
  in.tag("contacts");
  in.get(block_a);
  const std::size_t ns = block_a.size();
  in.get(block_b, ns, "contact slots");
  in.get(plane, ns, "contact slots");
  in.get(gap, ns, "contact slots");
  in.get(type, ns, "contact slots");
  in.get(alive, ns, "contact slots");
  in.get(material, ns, "contact slots");
  in.get(path_at_update, ns, "contact slots");
  in.get(sc_contact);
  const std::size_t n = sc_contact.size();
  in.get(sc_position, n, "sub-contacts");
  in.get(sc_area, n, "sub-contacts");
  in.get(sc_un, n, "sub-contacts");
  in.get(sc_fn, n, "sub-contacts");
  in.get(sc_fs, 3 * n, "sub-contact shear force components");
  in.get(sc_dilation);
  if (!sc_dilation.empty() && sc_dilation.size() != n)
    in.mismatch("sub-contact offsets", sc_dilation.size(), n);
  in.get(sc_us, 3 * n, "sub-contact shear displacement components");
  in.get(sc_yield);
  if (!sc_yield.empty() && sc_yield.size() != yield_state_size * n)
    in.mismatch("sub-contact yield states", sc_yield.size(), yield_state_size * n);
  in.get(sc_state, n, "sub-contacts");
  in.get(sc_material, n, "sub-contacts");
  in.get(sc_fresh, n, "sub-contacts");
  in.get(sc_node);
  in.get(sc_weight, sc_node.size(), "sub-contact gridpoint weights");
  if (!sc_node.empty() && sc_node.size() != 6 * n)
    in.mismatch("sub-contact gridpoints", sc_node.size(), 6 * n);
  in.get(free_);
  in.get(n_alive_);
  std::vector<std::uint64_t> pairs;
  std::vector<unsigned int> slots;
  in.get(pairs, n_alive_, "live contacts");
  in.get(slots, n_alive_, "live contacts");
  for (std::size_t c = 0; c < ns; ++c)
    if (block_a[c] >= n_blocks || block_b[c] >= n_blocks)
      in.mismatch("blocks (a contact's block number)", std::max(block_a[c], block_b[c]) + 1ull,
                  n_blocks);
  for (unsigned int i : sc_contact)
    if (i >= ns)
      in.mismatch("contact slots (a sub-contact's)", i + 1ull, ns);
  for (unsigned int c : free_)
    if (c >= ns)
      in.mismatch("contact slots (a free one)", c + 1ull, ns);
  slot_of_pair_.clear();
  for (std::size_t k = 0; k < slots.size(); ++k)
  {
    if (slots[k] >= ns)
      in.mismatch("contact slots (a live one)", slots[k] + 1ull, ns);
    slot_of_pair_[pairs[k]] = slots[k];
  }
  // The block-pair order is that of these contacts, not of those the solver
  // was built with: sorted again at the next update.
  pair_order_.clear();
  pair_order_stale_ = true;
}

void RigidSolver::save_state(CheckpointWriter& out) const
{
  // What stages changed, first: loading sets the damper's kind from it.
  out.tag("stages");
  out.put(removed_);
  out.put(fixed);
  out.put(static_cast<unsigned char>(s_.dynamic));
  out.put(dt_);
  out.put(s_.joint_rule.of_joint_set);
  out.put(s_.joint_rule.of_joint);
  out.put(s_.joint_rule.n_groups);
  out.put(s_.joint_rule.of_group_pair);
  out.tag("model");
  out.put(m_.vertex);
  out.put(m_.face_normal);
  out.put(m_.centroid);
  out.tag("blocks");
  out.put(velocity);
  out.put(spin);
  out.put(force);
  out.put(moment);
  out.put(displacement);
  out.put(rotation);
  out.put(inertial_mass);
  out.put(applied_force);
  out.put(applied_force_rate);
  out.put(prescribed);
  out.put(moved);
  out.put(path);
  out.put(axes);
  out.put(last_force_);
  out.put(last_moment_);
  // The last motion the contacts take their increments from: a deformable
  // block's is its surface's move, which its velocity times the step gives
  // back only to round-off.
  out.put(motion_dx_);
  out.put(motion_dtheta_);
  damper_.save_state(out);
  cells_.save_state(out);
  contacts_.save_state(out);
  out.put(dt_);
  out.put(time_);
  out.put(ratio_);
  out.put(gravity_work_);
  out.put(friction_work_);
  out.put(damping_work_);
  out.put(boundary_work_);
  out.put(kinetic_whole_step_);
  out.put(moved_beyond_tolerance_);
  out.put(initial_stored_);
  out.put(energy_floor_);
  growth_watch_.save_state(out);
  out.put(step_);
  out.put(last_output_);
}

void RigidSolver::load_state(CheckpointReader& in)
{
  subcontacts_stale_ = true; // on every rank: all load together
  const std::size_t nb = m_.n_blocks();
  in.tag("stages");
  in.get(removed_, nb, "blocks");
  in.get(fixed, nb, "blocks");
  unsigned char dynamic = 0;
  in.get(dynamic);
  in.get(dt_);
  s_.dynamic = dynamic != 0;
  damper_ = damper_for(s_, dt_);
  in.get(s_.joint_rule.of_joint_set);
  in.get(s_.joint_rule.of_joint);
  in.get(s_.joint_rule.n_groups);
  in.get(s_.joint_rule.of_group_pair);
  if (!s_.joint_rule.trivial())
    s_.contact.materials = &s_.joint_rule;
  in.tag("model");
  in.get(m_.vertex, m_.vertex.size(), "block vertices");
  in.get(m_.face_normal, m_.face_normal.size(), "block faces");
  in.get(m_.centroid, nb, "blocks");
  in.tag("blocks");
  in.get(velocity, nb, "blocks");
  in.get(spin, nb, "blocks");
  in.get(force, nb, "blocks");
  in.get(moment, nb, "blocks");
  in.get(displacement, nb, "blocks");
  in.get(rotation, nb, "blocks");
  in.get(inertial_mass, nb, "blocks");
  in.get(applied_force, nb, "blocks");
  in.get(applied_force_rate, nb, "blocks");
  in.get(prescribed, nb, "blocks");
  in.get(moved, nb, "blocks");
  in.get(path, nb, "blocks");
  in.get(axes, axes.size(), "blocks with principal axes");
  in.get(last_force_, nb, "blocks");
  in.get(last_moment_, nb, "blocks");
  in.get(motion_dx_, nb, "blocks");
  in.get(motion_dtheta_, nb, "blocks");
  damper_.load_state(in);
  cells_.load_state(in);
  cells_.define(cells_.bounds(), static_cast<unsigned int>(nb));
  contacts_.load_state(in, static_cast<unsigned int>(nb));
  in.get(dt_);
  in.get(time_);
  in.get(ratio_);
  in.get(gravity_work_);
  in.get(friction_work_);
  in.get(damping_work_);
  in.get(boundary_work_);
  in.get(kinetic_whole_step_);
  in.get(moved_beyond_tolerance_);
  in.get(initial_stored_);
  in.get(energy_floor_);
  growth_watch_.load_state(in);
  in.get(step_);
  in.get(last_output_);
  // A checkpoint follows a step, whose motion the velocities still are.
  // The rotational inertia follows the density scaling of the masses.
  for (std::size_t b = 0; b < nb; ++b)
  {
    const double scale = mass[b] > 0.0 ? inertial_mass[b] / mass[b] : 1.0;
    inertia[b] = true_inertia_[b] * scale;
    if (s_.principal_inertia)
      principal_moments[b] = true_principal_[b] * scale;
  }
  resumed_ = true;
}

void HistoryFile::save_state(CheckpointWriter& out)
{
  // The history holds its whole text; the file gets it too, so that the
  // checkpoint and the file on disk agree.
  flush();
  out.tag("history");
  out.put(text_);
  out.put(rows_);
}

void HistoryFile::load_state(CheckpointReader& in)
{
  std::string text;
  in.tag("history");
  in.get(text);
  in.get(rows_);
  // The rows up to the checkpoint's step, exactly as they were; the rows of
  // the run beyond it (if it went on) are dropped and written again.
  text_ = std::move(text);
}

void PvdSeries::save_state(CheckpointWriter& out) const
{
  out.tag("series");
  out.put(static_cast<std::uint64_t>(entries_.size()));
  for (const auto& [time, file] : entries_)
  {
    out.put(time);
    out.put(file);
  }
}

void PvdSeries::load_state(CheckpointReader& in)
{
  in.tag("series");
  std::uint64_t n = 0;
  in.get(n);
  entries_.clear();
  for (std::uint64_t k = 0; k < n; ++k)
  {
    double time = 0.0;
    std::string file;
    in.get(time);
    in.get(file);
    entries_.emplace_back(time, file);
  }
  // The frames written before the checkpoint must be where the PVD file
  // will name them (a checkpoint copied away from its output folder).
  const std::filesystem::path folder = std::filesystem::path(path_).parent_path();
  std::error_code ec;
  for (const auto& entry : entries_)
    if (!std::filesystem::exists(folder / entry.second, ec))
      throw InputError(in.file() + ": the run it continues wrote " + entry.second +
                       ", which is not in " + (folder.empty() ? "." : folder.string()) +
                       "; allowed: a checkpoint in the output folder of its run, beside its "
                       "frames");
}

} // namespace talus
