/* ballsim: runs a libball scene headless, prints its events and a summary,
 * and writes the trajectory as CSV or JSON Lines (docs/scenes.md). The
 * work is ballsim_core's; this shell owns the process: Ctrl-C and the
 * terminal. */
#define _POSIX_C_SOURCE 200809L

#include <signal.h>
#include <stdio.h>
#include <unistd.h>

#include "ballsim_core.h"

static volatile sig_atomic_t g_interrupted = 0;

static void on_sigint(int sig) {
  (void)sig;
  g_interrupted = 1;
}

int main(int argc, char **argv) {
  ballsim_options o;
  int rc = ballsim_parse_args(argc, argv, &o, stdout, stderr);
  if (rc >= 0) return rc;
  if (o.keys) return ballsim_print_keys(stdout);
  o.progress = isatty(STDERR_FILENO);
  signal(SIGINT, on_sigint);
  return ballsim_run(&o, stdout, stderr, &g_interrupted);
}
