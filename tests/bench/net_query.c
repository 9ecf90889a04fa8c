/* What the client library's ball query costs (docs/client.md, "What it
 * costs"): a spectator client of a match being played follows it through
 * ball/net.h, takes N times spread over the next second of its clock and
 * times, in interleaved rounds, ball_net_ball_at at those times against
 * ball_segment_eval of the same segments (the ones ball_net_ball_at said
 * were in effect) at the same sim times, with the model from the wire.
 * Both must give the same bits; it prints each round's ns per call and the
 * ratio's min and median.
 *
 *   net_query --domain D [--match M] [--calls N] [--rounds R]
 *
 * Exit status 1 when no ball came within 15 s, or the two disagree. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <ball/net.h>

static double now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int by_value(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

int main(int argc, char **argv) {
  ball_net_config config;
  ball_net_client *c = NULL;
  ball_net_event ev[64];
  ball_model model;
  char why[256];
  uint32_t match = 0;
  int calls = 200000, rounds = 9, i, r, n;
  double *times, *sims, *ratio, start, sink = 0.0;
  ball_segment *flights;
  ball_net_ball b;
  ball_state s;

  ball_net_config_default(&config);
  for (i = 1; i + 1 < argc; i += 2) {
    if (strcmp(argv[i], "--domain") == 0) config.domain = atoi(argv[i + 1]);
    else if (strcmp(argv[i], "--match") == 0) match = (uint32_t)atol(argv[i + 1]);
    else if (strcmp(argv[i], "--calls") == 0) calls = atoi(argv[i + 1]);
    else if (strcmp(argv[i], "--rounds") == 0) rounds = atoi(argv[i + 1]);
  }
  if (calls < 1 || rounds < 1) return 2;
  if (ball_net_open(&config, &c, why, sizeof why) != BALL_OK) {
    fprintf(stderr, "net_query: %s\n", why);
    return 1;
  }
  ball_net_watch(c, match);
  for (start = now(); now() - start < 15.0; ) {
    ball_net_poll(c, ev, 64, &n);
    if (ball_net_ball_at(c, match, now(), &b) == BALL_OK && ball_net_model(c, match, &model) == BALL_OK) break;
    nanosleep(&(struct timespec){0, 20000000}, NULL);
  }
  if (ball_net_model(c, match, &model) != BALL_OK) {
    fprintf(stderr, "net_query: no ball of match %u within 15 s\n", match);
    ball_net_free(c);
    return 1;
  }
  times = malloc(sizeof *times * (size_t)calls);
  sims = malloc(sizeof *sims * (size_t)calls);
  flights = malloc(sizeof *flights * (size_t)calls);
  ratio = malloc(sizeof *ratio * (size_t)rounds);
  if (!times || !sims || !flights || !ratio) return 1;
  /* times over the next second; the segments in effect then, as the library says */
  start = now();
  for (i = 0; i < calls; i++) {
    times[i] = start + (double)i / calls;
    if (ball_net_ball_at(c, match, times[i], &b) != BALL_OK) return 1;
    sims[i] = b.sim_time;
    flights[i] = b.flight;
    if (ball_segment_eval(&model, &flights[i], sims[i], &s) != BALL_OK ||
        memcmp(&s.position, &b.state.position, sizeof s.position) != 0) {
      fprintf(stderr, "net_query: call %d: ball_net_ball_at and ball_segment_eval differ\n", i);
      return 1;
    }
  }
  printf("net_query: match %u, %d calls a round, %d rounds\n", match, calls, rounds);
  for (r = 0; r < rounds; r++) {
    double t0 = now(), q, e;
    for (i = 0; i < calls; i++) {
      ball_net_ball_at(c, match, times[i], &b);
      sink += b.state.position.x;
    }
    q = now() - t0;
    t0 = now();
    for (i = 0; i < calls; i++) {
      ball_segment_eval(&model, &flights[i], sims[i], &s);
      sink += s.position.x;
    }
    e = now() - t0;
    ratio[r] = q / e;
    printf("net_query: round %d: ball_net_ball_at %.1f ns, ball_segment_eval %.1f ns, ratio %.3f\n", r,
           1e9 * q / calls, 1e9 * e / calls, ratio[r]);
  }
  qsort(ratio, (size_t)rounds, sizeof *ratio, by_value);
  printf("net_query: ratio ball_net_ball_at / ball_segment_eval: min %.3f, median %.3f (checksum %g)\n", ratio[0],
         ratio[rounds / 2], sink);
  free(times);
  free(sims);
  free(flights);
  free(ratio);
  ball_net_free(c);
  return 0;
}
