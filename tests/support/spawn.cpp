// run_process (see spawn.hpp).
#include "support/spawn.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <stdexcept>
#include <thread>

extern char** environ;

namespace sgnlf::test {

ProcessOutcome run_process(const std::vector<std::string>& args, const std::string& log_path,
                           const std::vector<std::string>& env, double kill_after_s) {
  if (args.empty()) throw std::invalid_argument("run_process: no program");
  std::vector<std::string> a = args;
  std::vector<char*> argv;
  for (auto& s : a) argv.push_back(s.data());
  argv.push_back(nullptr);
  auto name_of = [](const std::string& e) { return e.substr(0, e.find('=')); };
  std::vector<std::string> env_s;
  for (char** e = environ; *e; ++e) {
    bool replaced = false;
    for (const auto& x : env) replaced = replaced || name_of(x) == name_of(*e);
    if (!replaced) env_s.emplace_back(*e);
  }
  for (const auto& x : env)
    if (x.size() > name_of(x).size() + 1) env_s.push_back(x);
  std::vector<char*> envp;
  for (auto& e : env_s) envp.push_back(e.data());
  envp.push_back(nullptr);

  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 1, log_path.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
  posix_spawn_file_actions_adddup2(&fa, 1, 2);
  pid_t pid = 0;
  const auto t0 = std::chrono::steady_clock::now();
  const int rc = posix_spawn(&pid, argv[0], &fa, nullptr, argv.data(), envp.data());
  posix_spawn_file_actions_destroy(&fa);
  if (rc != 0) throw std::runtime_error("run_process: cannot start " + args[0]);
  int status = 0;
  bool reaped = false;
  if (kill_after_s >= 0) {
    const auto deadline = t0 + std::chrono::duration<double>(kill_after_s);
    while (!reaped && std::chrono::steady_clock::now() < deadline) {
      reaped = waitpid(pid, &status, WNOHANG) == pid;
      if (!reaped) std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    if (!reaped) kill(pid, SIGKILL);
  }
  if (!reaped && waitpid(pid, &status, 0) != pid) throw std::runtime_error("run_process: waitpid failed");
  ProcessOutcome o;
  o.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  o.exited = WIFEXITED(status);
  o.code = o.exited ? WEXITSTATUS(status) : -1;
  o.signal = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
  return o;
}

}  // namespace sgnlf::test
