#include "program_runner.h"

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <thread>
#include <vector>

namespace fibrecheck {

namespace fs = std::filesystem;

namespace {

/// `root` and every process descended from it, found by their parents in /proc.
std::vector<pid_t> process_tree(pid_t root) {
  std::multimap<pid_t, pid_t> children;
  std::error_code error;
  for (const fs::directory_entry& entry : fs::directory_iterator("/proc", error)) {
    const std::string name = entry.path().filename().string();
    if (name.empty() || name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream in(entry.path() / "stat");
    std::string stat;
    std::getline(in, stat);
    // The parent is the second field after the command name, which ends at the last ')'.
    const std::size_t end = stat.rfind(')');
    if (end == std::string::npos) continue;
    std::istringstream fields(stat.substr(end + 1));
    char state = 0;
    pid_t parent = 0;
    if (fields >> state >> parent) children.emplace(parent, static_cast<pid_t>(std::stol(name)));
  }
  std::vector<pid_t> tree{root};
  for (std::size_t k = 0; k < tree.size(); ++k) {
    const auto [first, last] = children.equal_range(tree[k]);
    for (auto it = first; it != last; ++it) tree.push_back(it->second);
  }
  return tree;
}

/// A process's proportional set size in kB (its resident pages, each page it shares divided
/// among the processes that map it), or 0 once it has gone.
double proportional_set_kb(pid_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/smaps_rollup");
  std::string key;
  double kb = 0.0;
  while (in >> key) {
    if (key == "Pss:") return in >> kb ? kb : 0.0;
    in.ignore(1 << 20, '\n');
  }
  return 0.0;
}

}  // namespace

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
    // Resident memory's peak comes from the kernel; the proportional set size has none, so the
    // process tree is sampled while it runs, every tenth of a second.
    int status = 0;
    struct rusage usage {};
    std::map<pid_t, double> peak_kb;
    for (;;) {
      const pid_t done = wait4(pid, &status, WNOHANG, &usage);
      if (done != 0 && !(done < 0 && errno == EINTR)) break;
      for (const pid_t p : process_tree(pid))
        peak_kb[p] = std::max(peak_kb[p], proportional_set_kb(p));
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    for (const auto& [p, kb] : peak_kb)
      run.peak_proportional_memory_mb = std::max(run.peak_proportional_memory_mb, kb / 1024.0);
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
