/* A small game on the client library (docs/client.md): it lists the
 * matches a ball server serves, joins one, moves its racket on a scripted
 * path (to meet the ball where the server's segments say it will be, on
 * its own half), prints the rally as it happens and leaves.
 *
 *   rally [--domain D] [--match M] [--points N] [--hits H] [--seconds S] [--log 1] [--states 1]
 *
 * With --log 1 it also prints every event of the server as it comes:
 * "event SEQ KIND server ID". With --states 1 it reads the server's ball
 * states too (ball_net_config.ball_states).
 * It returns H balls a rally (default 3), then lets the next one go, so
 * that points are played. Exit status 0 when it played N points (default
 * 3) with at least one hit of its own, 1 otherwise. */
#define _POSIX_C_SOURCE 200809L /* clock_gettime, nanosleep */
#include <math.h>
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

static void sleep_until(double t) {
  struct timespec ts;
  double left = t - now();
  if (left <= 0.0) return;
  ts.tv_sec = (time_t)left;
  ts.tv_nsec = (long)((left - (double)ts.tv_sec) * 1e9);
  nanosleep(&ts, NULL);
}

/* Where the racket wants to be at `t`: onto the ball 0.05 s ahead while the
 * ball is on this side of the net, coming in, and not yet 2 m past the
 * baseline or a sideline (a racket far off the court is refused: the
 * server's racket_margin), and this rally has not had its `hits` of ours
 * yet; else waiting 1 m inside its baseline. */
static ball_vec3 target(const ball_net_client *c, uint32_t match, const ball_net_match *m, int side, double t,
                        int chase) {
  ball_net_ball b;
  double toward = side == 0 ? 1.0 : -1.0; /* the net is toward +x from side 0 */
  ball_vec3 ready;
  ready.x = side == 0 ? m->court_x[0] + 1.0 : m->court_x[1] - 1.0;
  ready.y = 1.0;
  ready.z = 0.5 * (m->court_z[0] + m->court_z[1]);
  if (!chase || ball_net_ball_at(c, match, t + 0.05, &b) != BALL_OK) return ready;
  if ((b.state.position.x - m->net_x) * toward < 0.0 && b.state.velocity.x * toward < 0.0 &&
      (b.state.position.x - (side == 0 ? m->court_x[0] : m->court_x[1])) * toward > -2.0 &&
      b.state.position.z > m->court_z[0] - 2.0 && b.state.position.z < m->court_z[1] + 2.0 && b.state.position.y < 3.0)
    return b.state.position;
  return ready;
}

/* A step from `at` toward `to`, at most `reach` long: a racket is a body (the
 * server refuses one faster than its max_racket_speed, 50 m/s by default). */
static ball_vec3 toward(ball_vec3 at, ball_vec3 to, double reach) {
  double dx = to.x - at.x, dy = to.y - at.y, dz = to.z - at.z;
  double d = sqrt(dx * dx + dy * dy + dz * dz);
  if (d > reach) {
    at.x += dx * reach / d;
    at.y += dy * reach / d;
    at.z += dz * reach / d;
    return at;
  }
  return to;
}

int main(int argc, char **argv) {
  ball_net_config config;
  ball_net_client *client = NULL;
  ball_net_match m;
  ball_net_event events[32];
  char why[256];
  long match = -1;
  int points = 3, hits = 3, log = 0, played = 0, mine = 0, rally_hits = 0, slot = -1, placed = 0, n, i;
  ball_vec3 racket = {0.0, 1.0, 0.0};
  double seconds = 60.0, start, next_pose;
  ball_status st;

  setvbuf(stdout, NULL, _IOLBF, 0); /* the rally as it happens, also into a file */
  ball_net_config_default(&config);
  for (i = 1; i + 1 < argc; i += 2) {
    if (strcmp(argv[i], "--domain") == 0) config.domain = atoi(argv[i + 1]);
    else if (strcmp(argv[i], "--match") == 0) match = atol(argv[i + 1]);
    else if (strcmp(argv[i], "--points") == 0) points = atoi(argv[i + 1]);
    else if (strcmp(argv[i], "--hits") == 0) hits = atoi(argv[i + 1]);
    else if (strcmp(argv[i], "--log") == 0) log = atoi(argv[i + 1]);
    else if (strcmp(argv[i], "--states") == 0) config.ball_states = atoi(argv[i + 1]);
    else if (strcmp(argv[i], "--seconds") == 0) seconds = atof(argv[i + 1]);
  }
  st = ball_net_open(&config, &client, why, sizeof why);
  if (st != BALL_OK) {
    fprintf(stderr, "rally: %s: %s\n", ball_strerror(st), why);
    return 1;
  }
  start = now();
  /* the matches the domain serves: the one asked for, or the first with a free slot */
  while (match < 0 || ball_net_match_info(client, (uint32_t)match, &m) != BALL_OK) {
    ball_net_match list[16];
    ball_net_poll(client, events, 32, &n);
    if (ball_net_matches(client, list, 16, &n) == BALL_OK) {
      for (i = 0; i < n && i < 16 && match < 0; i++) {
        int k, free_slot = 0;
        for (k = 0; k < list[i].players; k++) free_slot += !list[i].slots[k].held;
        if (free_slot) match = list[i].id;
      }
    }
    if (now() - start > 10.0) {
      fprintf(stderr, "rally: no match with a free slot within 10 s\n");
      ball_net_free(client);
      return 1;
    }
    sleep_until(now() + 0.05);
  }
  printf("rally: match %ld, scene %s, %d players, score %d-%d\n", match, m.scene, m.players, m.score[0], m.score[1]);
  ball_net_join(client, (uint32_t)match, -1);
  next_pose = now();
  while (played < points && now() - start < seconds) {
    double t = now();
    st = ball_net_poll(client, events, 32, &n);
    if (st != BALL_OK) {
      fprintf(stderr, "rally: %s\n", ball_net_message(client));
      break;
    }
    for (i = 0; i < n; i++) {
      const ball_net_event *e = &events[i];
      if (log && e->seq > 0) printf("rally: event %u %s server %u\n", e->seq, ball_net_event_kind_name(e->kind), e->server);
      switch (e->kind) {
        case BALL_NET_EVENT_SLOT:
          if (e->value > 0.0) slot = e->index;
          printf("rally: %s slot %d\n", e->value > 0.0 ? "holds" : "lost", e->index);
          break;
        case BALL_NET_EVENT_SERVE: printf("rally: serve by slot %d\n", e->index); break;
        case BALL_NET_EVENT_RACKET:
          if (e->in_play) {
            mine += e->index == slot;
            rally_hits += e->index == slot;
            printf("rally: hit by slot %d%s at (%.2f, %.2f, %.2f)\n", e->index, e->index == slot ? " (me)" : "",
                   e->point.x, e->point.y, e->point.z);
          }
          break;
        case BALL_NET_EVENT_FLOOR:
          if (e->in_play) printf("rally: bounce at (%.2f, %.2f)\n", e->point.x, e->point.z);
          break;
        case BALL_NET_EVENT_POINT:
          played++;
          rally_hits = 0;
          printf("rally: point to side %d (%s), score %d-%d\n", e->side, ball_net_reason_name(e->reason), e->score[0],
                 e->score[1]);
          break;
        case BALL_NET_EVENT_SERVER: printf("rally: now served by server %u\n", e->server); break;
        default: break;
      }
    }
    /* what a game draws every frame: the ball now */
    {
      ball_net_ball b;
      ball_net_ball_at(client, (uint32_t)match, t, &b);
    }
    /* the racket's pose, 30 a second */
    if (slot >= 0 && t >= next_pose && ball_net_match_info(client, (uint32_t)match, &m) == BALL_OK) {
      ball_vec3 to = target(client, (uint32_t)match, &m, slot % 2, t, rally_hits < hits), normal;
      racket = placed ? toward(racket, to, 30.0 / 30.0) : to; /* 30 m/s at most */
      placed = 1;
      normal.x = slot % 2 == 0 ? 1.0 : -1.0;
      normal.y = 0.0;
      normal.z = 0.0;
      st = ball_net_push(client, (uint32_t)match, slot, t, racket, normal);
      if (st != BALL_OK && st != BALL_EAGAIN) fprintf(stderr, "rally: push: %s\n", ball_net_message(client));
      next_pose += 1.0 / 30.0;
      if (next_pose < t) next_pose = t + 1.0 / 30.0;
    }
    sleep_until(t + 1.0 / 60.0);
  }
  {
    ball_net_status s;
    if (ball_net_status_of(client, (uint32_t)match, &s) == BALL_OK)
      printf("rally: %.1f s: %lu poses, %lu segments, %lu events taken; bytes in %lu, out %lu; term %u\n",
             now() - start, (unsigned long)s.samples, (unsigned long)s.segments, (unsigned long)s.events,
             (unsigned long)s.bytes_in, (unsigned long)s.bytes_out, s.term);
  }
  printf("rally: %d points played, %d hits of mine; leaving\n", played, mine);
  fflush(stdout);
  ball_net_leave(client, (uint32_t)match, -1);
  st = ball_net_close(client);
  if (st != BALL_OK) fprintf(stderr, "rally: close: %s\n", ball_net_message(client));
  ball_net_free(client);
  return played >= points && mine > 0 ? 0 : 1;
}
