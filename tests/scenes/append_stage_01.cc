// A stage appended to a finished run (tests/scenes/staged_cubes.prm: three
// cubes stacked on a fixed one; stage 1 settles them, stage 2 removes the
// top cube, stage 3 runs 0.005 s of dynamics):
//  - the scene with stages 1 and 2 runs to its end; its last checkpoint is
//    written at the end of stage 2;
//  - the same file with stage 3 added continues from that checkpoint
//    (talus --restart): its history is byte for byte that of the run of all
//    three stages at once (the stages ended by their target ratio are not
//    stepped again);
//  - continuing the finished three-stage run again adds nothing;
//  - a change in a stage the run had begun, or outside the stages, is
//    refused, naming what changed.

#include <talus/base/exceptions.h>
#include <talus/base/parallel_environment.h>

#include <fstream>
#include <iterator>

#include "../tests.h"
#include "stage_history.h"

namespace
{
/// Runs talus on `file` (continuing from `checkpoint` if given) with
/// standard output sent nowhere: the exit code, or -1 and the message of a
/// refusal.
int run_file(const std::string& file, const std::string& checkpoint, std::string& message)
{
  std::fflush(stdout);
  const int saved = dup(1);
  std::freopen("/dev/null", "w", stdout);
  int code = -1;
  try
  {
    code = Simulation(file, checkpoint, false).run();
  }
  catch (const talus::InputError& e)
  {
    message = e.what();
  }
  std::fflush(stdout);
  dup2(saved, 1);
  close(saved);
  return code;
}

std::string text_of(const std::string& file)
{
  std::ifstream in(file);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

void write(const std::string& file, const std::string& text)
{
  std::ofstream(file) << text;
}

std::string replaced(std::string text, const std::string& from, const std::string& to)
{
  text.replace(text.find(from), from.size(), to);
  return text;
}
} // namespace

int main(int argc, char** argv)
{
  talus::ParallelEnvironment env(argc, argv);
  const std::string three = replaced(text_of(std::string(SOURCE_DIR) + "/staged_cubes.prm"),
                                     "output_stages_01", "output_append_stage_01");
  const std::string two =
      three.substr(0, three.find("subsection Stage 3")) + three.substr(three.find("subsection Output"));
  write("append_two.prm", two);
  write("append_three.prm", three);
  write("append_full.prm", replaced(three, "output_append_stage_01", "output_append_stage_01_full"));
  std::string message;
  std::printf("stages 1 and 2: exit code %d\n", run_file("append_two.prm", "", message));
  const std::string checkpoint = "output_append_stage_01/stages_checkpoint.bin";
  std::printf("stage 3 appended, continued from the end of stage 2: exit code %d\n",
              run_file("append_three.prm", checkpoint, message));
  std::printf("all three stages at once: exit code %d\n", run_file("append_full.prm", "", message));
  const std::string history = text_of("output_append_stage_01/stages_history.csv");
  std::printf("the appended run's history is that of the run of all three stages: %s\n",
              talus_test::verdict(!history.empty() &&
                                  history == text_of("output_append_stage_01_full/stages_history.csv")));
  std::printf("continuing the finished run again: exit code %d\n",
              run_file("append_three.prm", checkpoint, message));
  std::printf("  and its history is unchanged: %s\n",
              talus_test::verdict(history == text_of("output_append_stage_01/stages_history.csv")));

  write("append_changed_stage.prm",
        replaced(three, "set Name = remove the top block", "set Name = remove the top cube"));
  message.clear();
  const int refused = run_file("append_changed_stage.prm", checkpoint, message);
  std::printf("a changed stage 2 (begun): exit code %d, refused naming it: %s\n", refused,
              talus_test::verdict(message.find("'Stage 2' has changed") != std::string::npos));
  std::fprintf(stderr, "%s\n", message.c_str());
  write("append_changed_base.prm", replaced(three, "set Spacing = 1", "set Spacing = 0.5"));
  message.clear();
  const int refused_base = run_file("append_changed_base.prm", checkpoint, message);
  std::printf("a changed joint set: exit code %d, refused: %s\n", refused_base,
              talus_test::verdict(message.find("has changed outside its stages") !=
                                  std::string::npos));
  std::fprintf(stderr, "%s\n", message.c_str());
}
