// Running the real `nimbus` executable as a child process: arguments passed as an argv vector (no shell,
// so no quoting or injection issues), stdout and stderr captured through pipes, signals delivered by pid.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace nimbus::e2e {

struct ProcessResult {
  bool exited = false;  // exited normally (then exit_code is valid)
  int exit_code = -1;
  int signal = 0;          // the signal that ended the process, when !exited
  bool timed_out = false;  // killed by us because it ran past the deadline
  std::string out, err;

  // For assertion messages: how the process ended and what it printed on stderr.
  std::string describe() const;
};

class Process {
 public:
  // Starts `argv[0]` (a path, not looked up in PATH) with the other elements as its arguments, in the
  // working directory `cwd`, stdin from /dev/null. Throws std::runtime_error if it cannot be started.
  Process(const std::vector<std::string> &argv, const std::filesystem::path &cwd);
  ~Process();  // a child still running is killed and reaped, so a failing test never leaks one
  Process(const Process &) = delete;
  Process &operator=(const Process &) = delete;

  pid_t pid() const { return pid_; }
  void send_signal(int sig) const;
  // Collects output until `ready(stderr so far)` holds, the child closes its pipes, or `timeout` passes.
  // Returns whether `ready` held.
  bool wait_for_stderr(const std::function<bool(const std::string &)> &ready,
                       std::chrono::milliseconds timeout);
  // Collects the rest of the output and reaps the child; past `timeout` it is killed (timed_out = true).
  ProcessResult wait(std::chrono::seconds timeout = std::chrono::seconds(300));

 private:
  // Reads whatever the pipes have within `timeout_ms`; returns false once both are closed.
  bool pump(int timeout_ms);

  pid_t pid_ = -1;
  int out_fd_ = -1, err_fd_ = -1;
  std::string out_, err_;
};

// Runs the command to completion.
ProcessResult run_process(const std::vector<std::string> &argv, const std::filesystem::path &cwd);

}  // namespace nimbus::e2e
