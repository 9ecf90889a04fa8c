// Child processes for ball-demo and the integration tests: each in a
// process group of its own, stopped with the whole group (SIGTERM, then
// SIGKILL after a grace period) when its owner stops it or goes out of
// scope, and sent SIGTERM by the kernel if its parent dies first.
#pragma once

#include <sys/types.h>

#include <string>
#include <vector>

namespace ballsrv {
namespace app {

class Process {
 public:
  Process() = default;
  // Starts argv (argv[0] a path) with stdout and stderr to the given files
  // ("": inherited). Check running() or pid() > 0.
  static Process start(const std::vector<std::string> &argv, const std::string &out_file = "",
                       const std::string &err_file = "");
  ~Process() { stop(); }
  Process(Process &&other) noexcept;
  Process &operator=(Process &&other) noexcept;
  Process(const Process &) = delete;
  Process &operator=(const Process &) = delete;

  pid_t pid() const { return pid_; }
  bool running();
  // Waits up to timeout s; the exit status (128 + signal when killed), or -1 if still running.
  int wait(double timeout);
  void signal(int sig);  // to the whole group
  // SIGTERM to the group, up to grace s, then SIGKILL; the exit status.
  int stop(double grace = 3.0);
  int status() const { return status_; }
  // SIGKILL to the group of every Process still running (a watchdog's last word).
  static void kill_all();

 private:
  pid_t pid_ = -1;
  int status_ = -1;
  bool reap(bool block);
};

// Fast DDS shared-memory files in /dev/shm (fastrtps_*, fast_datasharing_*, sem.fastrtps_*).
std::vector<std::string> dds_shm_files();

}  // namespace app
}  // namespace ballsrv
