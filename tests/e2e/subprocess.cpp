#include "subprocess.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <thread>

extern char **environ;

namespace nimbus::e2e {
namespace {

using Clock = std::chrono::steady_clock;

// The parent environment minus NIMBUS_PLUGIN_PATH: the CLI must find the plugins of the build tree it
// belongs to, not whatever a developer's shell points at (a stray refused library would change exit codes).
std::vector<std::string> child_environment() {
  std::vector<std::string> env;
  for (char **e = environ; *e; ++e)
    if (std::strncmp(*e, "NIMBUS_PLUGIN_PATH=", 19) != 0) env.emplace_back(*e);
  return env;
}

std::vector<char *> c_strings(std::vector<std::string> &strings) {
  std::vector<char *> out;
  for (std::string &s : strings) out.push_back(s.data());
  out.push_back(nullptr);
  return out;
}

void check(int rc, const char *what) {
  if (rc != 0) throw std::runtime_error(std::string(what) + ": " + std::strerror(rc));
}

}  // namespace

std::string ProcessResult::describe() const {
  std::string how = timed_out ? "timed out and was killed"
                    : exited  ? "exited with " + std::to_string(exit_code)
                              : "was killed by signal " + std::to_string(signal);
  return "the process " + how + "; stderr:\n" + err + (out.empty() ? "" : "stdout:\n" + out);
}

Process::Process(const std::vector<std::string> &argv, const std::filesystem::path &cwd) {
  int out_pipe[2], err_pipe[2];
  // O_CLOEXEC: only the dup2'ed ends survive into the child, so EOF arrives when the child exits.
  if (pipe2(out_pipe, O_CLOEXEC) != 0) throw std::runtime_error("pipe2 failed");
  if (pipe2(err_pipe, O_CLOEXEC) != 0) {
    close(out_pipe[0]), close(out_pipe[1]);
    throw std::runtime_error("pipe2 failed");
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, out_pipe[1], STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, err_pipe[1], STDERR_FILENO);
  posix_spawn_file_actions_addchdir_np(&actions, cwd.c_str());
  // The child starts with default SIGINT handling whatever the test runner inherited, as from a shell.
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  sigset_t defaults, empty;
  sigemptyset(&defaults);
  sigaddset(&defaults, SIGINT);
  sigemptyset(&empty);
  posix_spawnattr_setsigdefault(&attr, &defaults);
  posix_spawnattr_setsigmask(&attr, &empty);
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSIGDEF | POSIX_SPAWN_SETSIGMASK);

  std::vector<std::string> args = argv, env = child_environment();
  const int rc =
      posix_spawn(&pid_, args.at(0).c_str(), &actions, &attr, c_strings(args).data(), c_strings(env).data());
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attr);
  close(out_pipe[1]);
  close(err_pipe[1]);
  out_fd_ = out_pipe[0];
  err_fd_ = err_pipe[0];
  if (rc != 0) {
    close(out_fd_), close(err_fd_);
    out_fd_ = err_fd_ = -1;
    pid_ = -1;
    check(rc, ("posix_spawn " + argv.at(0)).c_str());
  }
}

Process::~Process() {
  if (pid_ > 0) {
    kill(pid_, SIGKILL);
    waitpid(pid_, nullptr, 0);
  }
  if (out_fd_ >= 0) close(out_fd_);
  if (err_fd_ >= 0) close(err_fd_);
}

void Process::send_signal(int sig) const {
  if (pid_ > 0) kill(pid_, sig);
}

bool Process::pump(int timeout_ms) {
  pollfd fds[2] = {{out_fd_, POLLIN, 0}, {err_fd_, POLLIN, 0}};
  if (out_fd_ < 0 && err_fd_ < 0) return false;
  const int n = poll(fds, 2, timeout_ms);  // negative fds are ignored by poll
  if (n < 0 && errno != EINTR) throw std::runtime_error("poll failed");
  if (n <= 0) return true;
  int *fd_of[2] = {&out_fd_, &err_fd_};
  std::string *text_of[2] = {&out_, &err_};
  for (int i = 0; i < 2; ++i) {
    if (!(fds[i].revents & (POLLIN | POLLHUP | POLLERR))) continue;
    char buf[4096];
    const ssize_t got = read(*fd_of[i], buf, sizeof buf);
    if (got > 0) {
      text_of[i]->append(buf, size_t(got));
    } else if (got == 0 || errno != EINTR) {
      close(*fd_of[i]);
      *fd_of[i] = -1;
    }
  }
  return out_fd_ >= 0 || err_fd_ >= 0;
}

bool Process::wait_for_stderr(const std::function<bool(const std::string &)> &ready,
                              std::chrono::milliseconds timeout) {
  const auto deadline = Clock::now() + timeout;
  while (!ready(err_)) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now());
    if (left.count() <= 0) return false;
    if (!pump(int(std::min<long long>(left.count(), 50)))) return ready(err_);
  }
  return true;
}

ProcessResult Process::wait(std::chrono::seconds timeout) {
  ProcessResult r;
  const auto deadline = Clock::now() + timeout;
  while (Clock::now() < deadline && pump(100)) {
  }
  // Past the deadline, whether still writing or hung with its pipes closed, the child is killed: a test
  // must fail, not hang the suite.
  int status = 0;
  for (;;) {
    const pid_t got = waitpid(pid_, &status, WNOHANG);
    if (got == pid_ || (got < 0 && errno != EINTR)) break;
    if (got != 0) continue;
    if (Clock::now() >= deadline && !r.timed_out) {
      kill(pid_, SIGKILL);
      r.timed_out = true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  pid_ = -1;
  r.exited = WIFEXITED(status);
  r.exit_code = r.exited ? WEXITSTATUS(status) : -1;
  r.signal = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
  r.out = std::move(out_);
  r.err = std::move(err_);
  return r;
}

ProcessResult run_process(const std::vector<std::string> &argv, const std::filesystem::path &cwd) {
  return Process(argv, cwd).wait();
}

}  // namespace nimbus::e2e
