// Running the sgnlf binary from a test as a child process: its stdout and stderr appended to a
// log file, environment variables set or removed, and optionally a real SIGKILL after a time
// (what the kill/resume tests need; no shell involved).
#pragma once
#include <string>
#include <vector>

namespace sgnlf::test {

struct ProcessOutcome {
  bool exited = false;  // exited normally (then `code`), else killed by `signal`
  int code = -1;
  int signal = 0;
  double seconds = 0.0;
};

// `args[0]` is the program. `env`: "NAME=VALUE" entries that replace the variable, "NAME=" ones
// that remove it. `kill_after_s` >= 0 sends SIGKILL after that many seconds if still running.
ProcessOutcome run_process(const std::vector<std::string>& args, const std::string& log_path,
                           const std::vector<std::string>& env = {}, double kill_after_s = -1.0);

}  // namespace sgnlf::test
