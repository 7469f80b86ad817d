// Runs `talus FILE` on an input that must be refused and prints what a user
// would see: the message (with FILE's folder removed so that the expected
// output does not depend on where the tests live) and how talus ended.
// Succeeds only if talus exited normally with code 1: not 0 (input accepted),
// not another code, not a signal (a crash). Directives in FILE's comments:
//   # expect exit code: N    another exit code that the run must end with
//   # arguments: A B         arguments put before FILE (e.g. --check)
//   # show new files         list what the run created in the working folder
//   # environment: NAME=VALUE   run talus with that environment variable set
//   # address space limit: N MB   run talus under that limit (ulimit -v)
//   # mask after: PHRASE     the word after each PHRASE shows as <masked> (a
//                            figure of the machine, such as its free memory)
// Under mpirun (a test named FILE.mpirun=N) only rank 0 prints.

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

int main(int argc, char** argv)
{
  if (argc != 2)
    return 2;
  const std::string file = argv[1];
  int expected_code = 1;
  bool show_new_files = false;
  double address_space_mb = 0.0;
  std::vector<std::string> masked_phrases;
  std::vector<std::string> arguments{"talus"};
  {
    std::ifstream in(file);
    for (std::string line; std::getline(in, line);)
    {
      const std::string code = "# expect exit code:", args = "# arguments:";
      if (line.rfind(code, 0) == 0)
        expected_code = std::stoi(line.substr(code.size()));
      else if (line.rfind("# address space limit:", 0) == 0)
        address_space_mb = std::stod(line.substr(22));
      else if (line.rfind("# mask after: ", 0) == 0)
        masked_phrases.push_back(line.substr(14));
      else if (line.rfind("# show new files", 0) == 0)
        show_new_files = true;
      else if (line.rfind("# environment: ", 0) == 0)
      {
        const std::string setting = line.substr(15);
        const std::size_t eq = setting.find('=');
        if (eq == std::string::npos)
          return 2;
        setenv(setting.substr(0, eq).c_str(), setting.substr(eq + 1).c_str(), 1);
      }
      else if (line.rfind(args, 0) == 0)
      {
        std::istringstream words(line.substr(args.size()));
        for (std::string w; words >> w;)
          arguments.push_back(w);
      }
    }
  }
  arguments.push_back(file);
  namespace fs = std::filesystem;
  const auto listing = []
  {
    std::set<std::string> names;
    for (const fs::directory_entry& e : fs::recursive_directory_iterator("."))
      names.insert(e.path().string());
    return names;
  };
  const std::set<std::string> before = show_new_files ? listing() : std::set<std::string>();
  int pipe_fd[2];
  if (pipe(pipe_fd) != 0)
    return 2;
  const pid_t child = fork();
  if (child == 0)
  {
    dup2(pipe_fd[1], 1);
    dup2(pipe_fd[1], 2);
    close(pipe_fd[0]);
    if (address_space_mb > 0.0)
    {
      const rlimit limit{static_cast<rlim_t>(address_space_mb * 1048576.0),
                         static_cast<rlim_t>(address_space_mb * 1048576.0)};
      setrlimit(RLIMIT_AS, &limit);
    }
    std::vector<char*> argv_child;
    for (std::string& a : arguments)
      argv_child.push_back(a.data());
    argv_child.push_back(nullptr);
    execv(TALUS_EXECUTABLE, argv_child.data());
    _exit(127);
  }
  close(pipe_fd[1]);
  std::string text;
  char buffer[4096];
  for (ssize_t n; (n = read(pipe_fd[0], buffer, sizeof buffer)) > 0;)
    text.append(buffer, static_cast<std::size_t>(n));
  int status = 0;
  waitpid(child, &status, 0);

  const std::string folder = file.substr(0, file.find_last_of('/') + 1);
  for (std::size_t at; !folder.empty() && (at = text.find(folder)) != std::string::npos;)
    text.erase(at, folder.size());
  for (const std::string& phrase : masked_phrases)
    for (std::size_t at = 0; (at = text.find(phrase, at)) != std::string::npos;)
    {
      at += phrase.size();
      const std::size_t begin = text.find_first_not_of(' ', at);
      const std::size_t end = text.find_first_of(" \n", begin);
      if (begin == std::string::npos || end == std::string::npos)
        break;
      text.replace(begin, end - begin, "<masked>");
    }
  // Under mpirun every rank runs this; rank 0 alone reports, so that the
  // output does not depend on how the ranks' lines interleave. Every rank
  // still judges its own talus's exit code.
  const char* rank = std::getenv("OMPI_COMM_WORLD_RANK");
  if (rank != nullptr && std::atoi(rank) != 0)
    std::freopen("/dev/null", "w", stdout);
  std::fputs(text.c_str(), stdout);
  if (WIFSIGNALED(status))
  {
    std::printf("talus was killed by signal %d\n", WTERMSIG(status));
    return 1;
  }
  if (show_new_files)
  {
    std::string created;
    for (const std::string& name : listing())
      if (before.count(name) == 0)
        created += " " + name;
    std::printf("new files in the working folder:%s\n",
                created.empty() ? " none" : created.c_str());
  }
  std::printf("exit code %d\n", WEXITSTATUS(status));
  return WEXITSTATUS(status) == expected_code ? 0 : 1;
}
