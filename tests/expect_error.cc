// Runs `talus FILE` on an input that must be refused and prints what a user
// would see: the message (with FILE's folder removed so that the expected
// output does not depend on where the tests live) and how talus ended.
// Succeeds only if talus exited normally with code 1: not 0 (input accepted),
// not another code, not a signal (a crash). A file with the line
// "# expected exit code N" expects N instead (3: a run that diverges).

#include <cstdio>
#include <fstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

int main(int argc, char** argv)
{
  if (argc != 2)
    return 2;
  const std::string file = argv[1];
  int expected = 1;
  {
    std::ifstream in(file);
    const std::string marker = "# expected exit code ";
    for (std::string line; std::getline(in, line);)
      if (line.rfind(marker, 0) == 0)
        expected = std::stoi(line.substr(marker.size()));
  }
  int pipe_fd[2];
  if (pipe(pipe_fd) != 0)
    return 2;
  const pid_t child = fork();
  if (child == 0)
  {
    dup2(pipe_fd[1], 1);
    dup2(pipe_fd[1], 2);
    close(pipe_fd[0]);
    execl(TALUS_EXECUTABLE, "talus", file.c_str(), static_cast<char*>(nullptr));
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
  std::fputs(text.c_str(), stdout);
  if (WIFSIGNALED(status))
  {
    std::printf("talus was killed by signal %d\n", WTERMSIG(status));
    return 1;
  }
  std::printf("exit code %d\n", WEXITSTATUS(status));
  return WEXITSTATUS(status) == expected ? 0 : 1;
}
