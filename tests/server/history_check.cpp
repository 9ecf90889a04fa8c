// ball_history_check RECORD.jsonl...: the history checker (history.h) over
// watchers' records, each file a client of its own; prints what broke and
// exits 1 if anything did (2: a record that does not read).
#include <cstdio>
#include <string>

#include "history.h"

int main(int argc, char **argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: ball_history_check RECORD.jsonl...\n");
    return 2;
  }
  int status = 0;
  for (int a = 1; a < argc; ++a) {
    ballsrv::History h;
    std::string err;
    if (!h.take_file(argv[a], &err)) {
      std::fprintf(stderr, "ball_history_check: %s\n", err.c_str());
      return 2;
    }
    const ballsrv::HistoryCounts &c = h.counts();
    std::printf("%s: %ld lines, %ld checks, %ld changes of owner (%ld checked for continuity), %zu broken\n%s",
                argv[a], c.lines, c.checks, c.owner_changes, c.continuity, h.violations().size(), h.report().c_str());
    if (!h.violations().empty()) status = 1;
  }
  return status;
}
