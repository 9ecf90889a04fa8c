// dds::run_bounded, the guard a Domain deletes its entities under (Fast DDS
// 2.9 can deadlock there: server/dds/domain.h): work that returns is left
// alone, work that sticks ends the process after the limit, with the
// status the program set and a sentence on stderr; a real participant with
// endpoints, on the domain cmake/dds_domains.cmake gives this test, writes
// and reads a message and goes inside the limit.
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <string>
#include <thread>

#include "check.hpp"
#include "common.h"
#include "domain.h"

using namespace ballsrv;

namespace {

double now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

struct Child {
  int status = -1;  // exit status; -1: killed or still running after the wait
  double seconds = 0.0;
  std::string err;
};

// Runs body in a child process, its stderr captured; waits up to `wait` s.
Child in_child(const std::function<void()> &body, double wait) {
  Child c;
  int fds[2];
  if (pipe(fds) != 0) return c;
  std::fflush(nullptr);  // the child must not print this process's buffered output again
  double t0 = now();
  pid_t pid = fork();
  if (pid == 0) {
    dup2(fds[1], 2);
    close(fds[0]);
    body();
    std::fflush(nullptr);
    _exit(0);
  }
  close(fds[1]);
  fcntl(fds[0], F_SETFL, O_NONBLOCK);
  int st = 0;
  bool reaped = false;
  while (now() - t0 < wait) {
    char buf[512];
    ssize_t n;
    while ((n = read(fds[0], buf, sizeof buf)) > 0) c.err.append(buf, static_cast<size_t>(n));
    if (waitpid(pid, &st, WNOHANG) == pid) {
      reaped = true;
      break;
    }
    usleep(10000);
  }
  c.seconds = now() - t0;
  if (!reaped) {
    kill(pid, SIGKILL);
    waitpid(pid, &st, 0);
  } else if (WIFEXITED(st)) {
    c.status = WEXITSTATUS(st);
  }
  char buf[512];
  ssize_t n;
  while ((n = read(fds[0], buf, sizeof buf)) > 0) c.err.append(buf, static_cast<size_t>(n));
  close(fds[0]);
  return c;
}

}  // namespace

TEST(work_that_returns_is_left_alone) {
  // in this process: a guard that fired would end the test run
  int calls = 0;
  for (int i = 0; i < 50; ++i) dds::run_bounded([&] { calls++; }, 0.05, "quick work");
  CHECK_EQ(calls, 50);
  // work slower than nothing but inside the limit returns, and its effect is there
  dds::run_bounded([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(30));
    calls++;
  }, 2.0, "30 ms of work");
  CHECK_EQ(calls, 51);
}

TEST(stuck_work_ends_the_process_with_the_status_set) {
  Child c = in_child(
      [] {
        dds::set_exit_status_if_stuck(7);
        dds::run_bounded([] { std::this_thread::sleep_for(std::chrono::seconds(30)); }, 0.3, "sleeping work");
        _exit(0);  // not reached
      },
      10.0);
  // the child ended by itself (not killed after the 10 s wait), with the status it set
  CHECK_MSG(c.status == 7, "exit status %d; its stderr: %s", c.status, c.err.c_str());
  CHECK_MSG(c.seconds >= 0.3, "ended after %.3f s, before its limit", c.seconds);  // it waited the limit out
  CHECK_MSG(c.err.find("sleeping work did not finish within 0.3 s") != std::string::npos, "its stderr: %s",
            c.err.c_str());
  CHECK_MSG(c.err.find("exiting with status 7") != std::string::npos, "its stderr: %s", c.err.c_str());
}

TEST(stuck_work_exits_1_unless_a_program_said_otherwise) {
  Child c = in_child(
      [] { dds::run_bounded([] { std::this_thread::sleep_for(std::chrono::seconds(30)); }, 0.2, "stuck"); }, 10.0);
  CHECK_MSG(c.status == 1, "exit status %d; its stderr: %s", c.status, c.err.c_str());
}

TEST(a_participant_goes_inside_the_limit) {
  // a child: the participant's threads stay out of this process. It must
  // open the domain, match its own reader, write a message and read it
  // back before its entities go; each failure has its own exit status.
  Child c = in_child(
      [] {
        std::string err;
        {
          auto d = dds::Domain::open(BALL_TEST_DOMAIN, app::find_profile(""), "loopback", {}, "teardown test", &err);
          if (!d) {
            std::fprintf(stderr, "open: %s\n", err.c_str());
            _exit(3);
          }
          auto w = d->writer<ControlIn>(dds::kControlTopic, dds::kControlProfile, {1}, &err);
          auto r = d->reader<ControlIn>(dds::kControlTopic, dds::kControlProfile, {1}, &err);
          if (!w.valid() || !r.valid()) _exit(4);
          for (int i = 0; i < 100 && (r.matched() == 0 || w.matched() == 0); ++i)
            std::this_thread::sleep_for(std::chrono::milliseconds(50));
          if (r.matched() == 0 || w.matched() == 0) _exit(5);
          ControlIn msg;
          msg.seq = 77;
          if (!w.write(msg)) _exit(6);
          ControlIn got;
          bool read = false;
          for (int i = 0; i < 100 && !read; ++i) {
            read = r.take(&got, nullptr);
            if (!read) std::this_thread::sleep_for(std::chrono::milliseconds(20));
          }
          if (!read || got.seq != 77) _exit(7);
          // the Domain deletes its entities here, under the guard: past the
          // limit the guard ends this child with status 1
        }
        _exit(0);
      },
      30.0);
  CHECK_MSG(c.status == 0, "exit status %d (3 open, 4 endpoints, 5 no match, 6 write, 7 not read back, 1 stuck); "
            "its stderr: %s", c.status, c.err.c_str());
}

CHECK_MAIN
