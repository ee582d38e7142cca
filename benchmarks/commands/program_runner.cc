#include "program_runner.h"

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

namespace fibrecheck {

namespace fs = std::filesystem;

ProgramRun run_program(const std::vector<std::string>& arguments) {
  ProgramRun run;
  if (arguments.empty()) return run;
  char error_name[] = "/tmp/fibrecheck-run-XXXXXX";
  const int error_fd = mkstemp(error_name);
  std::vector<char*> argv;
  for (const std::string& a : arguments) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = fork();
  if (pid == 0) {
    const int null_fd = open("/dev/null", O_WRONLY);
    if (null_fd >= 0) dup2(null_fd, STDOUT_FILENO);
    if (error_fd >= 0) dup2(error_fd, STDERR_FILENO);
    if (geteuid() == 0) {
      setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 0);
      setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 0);
    }
    execvp(argv[0], argv.data());
    _exit(127);
  }
  if (pid < 0) {
    run.error = "could not start " + arguments[0];
  } else {
    int status = 0;
    struct rusage usage {};
    wait4(pid, &status, 0, &usage);
    run.wall_time_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    run.peak_memory_mb = static_cast<double>(usage.ru_maxrss) / 1024.0;  // kB on Linux
  }
  if (error_fd >= 0) {
    close(error_fd);
    std::ifstream in(error_name);
    std::ostringstream text;
    text << in.rdbuf();
    std::string all = text.str();
    run.error = all.size() > 2000 ? all.substr(all.size() - 2000) : all;
    std::remove(error_name);
  }
  return run;
}

std::string this_program() {
  std::error_code error;
  const fs::path self = fs::read_symlink("/proc/self/exe", error);
  return error ? std::string("fibrecheck") : self.string();
}

std::string program_beside_this(const std::string& name) {
  const fs::path beside = fs::path(this_program()).parent_path() / name;
  return fs::exists(beside) ? beside.string() : std::string();
}

std::string find_on_path(const std::string& name) {
  const char* path = std::getenv("PATH");
  if (!path) return "";
  std::stringstream folders(path);
  std::string folder;
  while (std::getline(folders, folder, ':')) {
    const fs::path candidate = fs::path(folder) / name;
    if (!folder.empty() && access(candidate.c_str(), X_OK) == 0) return candidate.string();
  }
  return "";
}

}  // namespace fibrecheck
