#include "terminal/run_program.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>

extern char** environ;

namespace eqhb::cli {

namespace fs = std::filesystem;

int runProgram(const std::vector<std::string>& argv) {
  if (argv.empty()) throw std::runtime_error("runProgram: empty argument vector");
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = 0;
  const int failed = posix_spawnp(&pid, args[0], nullptr, nullptr, args.data(), environ);
  if (failed != 0) throw std::runtime_error("cannot run " + argv[0] + ": " + std::strerror(failed));
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) throw std::runtime_error("waiting for " + argv[0] + ": " + std::strerror(errno));
  if (WIFSIGNALED(status))
    throw std::runtime_error(argv[0] + " was killed by signal " + std::to_string(WTERMSIG(status)));
  return WEXITSTATUS(status);
}

std::optional<std::string> programOutput(const std::vector<std::string>& argv) {
  if (argv.empty()) return std::nullopt;
  int pipe_ends[2];
  if (pipe(pipe_ends) != 0) return std::nullopt;
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, pipe_ends[1], STDOUT_FILENO);
  posix_spawn_file_actions_addclose(&actions, pipe_ends[0]);
  posix_spawn_file_actions_addclose(&actions, pipe_ends[1]);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = 0;
  const int failed = posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  close(pipe_ends[1]);
  std::string output;
  if (failed == 0) {
    char buffer[4096];
    ssize_t n;
    while ((n = read(pipe_ends[0], buffer, sizeof buffer)) > 0 || (n < 0 && errno == EINTR))
      if (n > 0) output.append(buffer, static_cast<size_t>(n));
  }
  close(pipe_ends[0]);
  if (failed != 0) return std::nullopt;
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return std::nullopt;
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) return std::nullopt;
  return output;
}

std::string findDataFile(const std::string& name) {
  std::error_code error;
  const fs::path exe = fs::read_symlink("/proc/self/exe", error);
  if (error) throw std::runtime_error("cannot locate the running program to find " + name + ": " + error.message());
  const fs::path dir = exe.parent_path();
  const fs::path candidates[] = {dir / ".." / "share" / "eqhb" / name, dir / "share" / "eqhb" / name};
  std::string looked;
  for (const auto& c : candidates) {
    if (fs::is_regular_file(c, error)) return fs::weakly_canonical(c).string();
    looked += (looked.empty() ? "" : ", ") + c.lexically_normal().string();
  }
  throw std::runtime_error(name + " not found (looked at " + looked + ")");
}

std::string python3() {
  return access("/usr/bin/python3", X_OK) == 0 ? "/usr/bin/python3" : "python3";
}

}  // namespace eqhb::cli
