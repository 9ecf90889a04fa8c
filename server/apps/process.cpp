#include "process.h"

#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstring>
#include <mutex>
#include <set>

#include "common.h"

namespace ballsrv {
namespace app {

namespace {
// the groups of the children still running, for kill_all
std::mutex &groups_mutex() {
  static std::mutex m;
  return m;
}
std::set<pid_t> &groups() {
  static std::set<pid_t> g;
  return g;
}
}  // namespace

void Process::kill_all() {
  std::lock_guard<std::mutex> lock(groups_mutex());
  for (pid_t g : groups()) kill(-g, SIGKILL);
}

Process Process::start(const std::vector<std::string> &argv, const std::string &out_file,
                       const std::string &err_file) {
  Process p;
  if (argv.empty()) return p;
  // everything the child needs is prepared before fork: after it, only
  // async-signal-safe calls
  std::vector<char *> args;
  for (const auto &a : argv) args.push_back(const_cast<char *>(a.c_str()));
  args.push_back(nullptr);
  pid_t parent = getpid();
  pid_t pid = fork();
  if (pid < 0) return p;
  if (pid == 0) {
    setpgid(0, 0);
    prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (getppid() != parent) _exit(127);  // the parent died before prctl
    if (!out_file.empty()) {
      int fd = open(out_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      if (fd >= 0) dup2(fd, 1);
    }
    if (!err_file.empty()) {
      int fd = open(err_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      if (fd >= 0) dup2(fd, 2);
    }
    execv(args[0], args.data());
    _exit(127);
  }
  setpgid(pid, pid);  // also here: no race with a signal sent right away
  p.pid_ = pid;
  std::lock_guard<std::mutex> lock(groups_mutex());
  groups().insert(pid);
  return p;
}

Process::Process(Process &&o) noexcept : pid_(o.pid_), status_(o.status_) { o.pid_ = -1; }

Process &Process::operator=(Process &&o) noexcept {
  if (this != &o) {
    stop();
    pid_ = o.pid_;
    status_ = o.status_;
    o.pid_ = -1;
  }
  return *this;
}

bool Process::reap(bool block) {
  if (pid_ <= 0) return true;
  int st = 0;
  pid_t r = waitpid(pid_, &st, block ? 0 : WNOHANG);
  if (r == pid_) {
    status_ = WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
    std::lock_guard<std::mutex> lock(groups_mutex());
    groups().erase(pid_);
    pid_ = -1;
    return true;
  }
  return false;
}

bool Process::running() { return pid_ > 0 && !reap(false); }

int Process::wait(double timeout) {
  double end = mono_now() + timeout;
  while (pid_ > 0) {
    if (reap(false)) break;
    if (mono_now() >= end) return -1;
    usleep(10000);
  }
  return status_;
}

void Process::signal(int sig) {
  if (pid_ > 0) kill(-pid_, sig);
}

int Process::stop(double grace) {
  if (pid_ <= 0) return status_;
  pid_t group = pid_;
  kill(-group, SIGTERM);
  if (wait(grace) < 0) {
    kill(-group, SIGKILL);
    reap(true);
  }
  kill(-group, SIGKILL);  // anything the child left in its group
  return status_;
}

std::vector<std::string> dds_shm_files() {
  std::vector<std::string> out;
  DIR *d = opendir("/dev/shm");
  if (!d) return out;
  while (dirent *e = readdir(d)) {
    const char *n = e->d_name;
    if (std::strncmp(n, "fastrtps_", 9) == 0 || std::strncmp(n, "fast_datasharing", 16) == 0 ||
        std::strncmp(n, "sem.fastrtps_", 13) == 0 || std::strncmp(n, "sem.fast_datasharing", 20) == 0)
      out.push_back(n);
  }
  closedir(d);
  return out;
}

}  // namespace app
}  // namespace ballsrv
