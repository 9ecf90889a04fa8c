/* ballsim: runs a libball scene headless, prints its events and a summary,
 * and writes the trajectory as CSV or JSON Lines. See docs/scenes.md. */
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ball/ball.h"
#include "ball/scene.h"

#define TOOL_NAME "ballsim"
#include "args.h"

#define MAX_FRAMES 1000000000.0
#define EVENT_CAP (BALL_MAX_CONTACTS + BALL_MAX_RACKETS + 8)

typedef enum out_format { FORMAT_NONE = 0, FORMAT_CSV, FORMAT_JSONL } out_format;

typedef struct options {
  const char *scene_path;  /* NULL: the built-in tennis scene */
  double fps;              /* 0: the scene's frame time */
  double duration;         /* 0: the scene's duration */
  int scheme;              /* -1: the scene's scheme */
  const char *out_path;    /* NULL: no trajectory */
  out_format format;
} options;

static void print_help(FILE *f) {
  fprintf(f,
          "usage: ballsim [SCENE] [--fps N] [--duration S] [--scheme sampled|exact]\n"
          "               [--out FILE] [--format csv|jsonl]\n"
          "       ballsim --help\n"
          "\n"
          "Runs a libball scene headless: steps the ball at the scene's frame rate,\n"
          "prints every collision event as one line and a summary at the end.\n"
          "Scripted rackets (rackets[i].script) send their samples as the scene's\n"
          "network conditions deliver them; before each step every sample that has\n"
          "arrived by the end of the step goes to ball_racket_push.\n"
          "\n"
          "  SCENE               a YAML scene file (docs/scenes.md); without it the\n"
          "                      built-in tennis serve (the same as scenes/tennis.yaml)\n"
          "  --fps N             frames per second, N > 0; overrides the scene's time.frame_time\n"
          "  --duration S        sim seconds to run, S > 0; overrides the scene's duration.\n"
          "                      The run takes ceil(S / dt) frames of dt = frame_time * time_base\n"
          "                      sim seconds each.\n"
          "  --scheme MODE       static obstacle detection: sampled (the paper's per-frame\n"
          "                      tests) or exact (contact times in closed form)\n"
          "  --out FILE          write the trajectory, one record per frame including t = 0:\n"
          "                      t,px,py,pz,vx,vy,vz,sx,sy,sz (s, m, m/s, spin m/s)\n"
          "  --format FMT        csv (a header row, then one row per frame) or jsonl (one JSON\n"
          "                      object per line with the same names); default: from FILE's\n"
          "                      extension, .csv or .jsonl\n"
          "  -h, --help          this text\n"
          "\n"
          "Output lines:\n"
          "  scene: NAME (FILE) scheme=... fps=... dt=... frames=... effects=...\n"
          "  event t=T kind=floor|net|wall|racket index=I point=X,Y,Z v_in=X,Y,Z\n"
          "        v_out=X,Y,Z spin_out=X,Y,Z speed_in=S speed_out=S sound=0|1\n"
          "  summary: frames=N time=T events=N floor=N net=N wall=N racket=N sounds=N\n"
          "  samples: arrived=N accepted=N duplicate=N stale=N invalid=N\n"
          "  final: position=X,Y,Z velocity=X,Y,Z spin=X,Y,Z grounded=0|1\n"
          "  warnings: event_overflow=N contact_limit=N stale_racket=N\n"
          "\n"
          "Exit status: 0 on success, 1 for a scene or runtime error (printed as\n"
          "FILE:LINE:COLUMN: FIELD: MESSAGE), 2 for bad arguments.\n");
}

/* A finite number > 0, the whole text consumed. */
static int parse_positive(const char *text, double *out) {
  double v;
  if (!parse_number(text, &v) || !(v > 0.0)) return 0;
  *out = v;
  return 1;
}

static int ends_with(const char *s, const char *suffix) {
  size_t n = strlen(s), m = strlen(suffix);
  return n >= m && strcmp(s + n - m, suffix) == 0;
}

/* Returns -1 on success, else the exit status. */
static int parse_args(int argc, char **argv, options *o) {
  int i;
  memset(o, 0, sizeof *o);
  o->scheme = -1;
  for (i = 1; i < argc; ++i) {
    const char *a = argv[i];
    const char *value = NULL;
    char name[32];
    if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
      print_help(stdout);
      return 0;
    }
    if (a[0] != '-' || strcmp(a, "-") == 0) {
      if (o->scene_path) return usage_error("more than one scene given: %s and %s", o->scene_path, a);
      o->scene_path = a;
      continue;
    }
    if (strncmp(a, "--", 2) != 0) return usage_error("unknown option %s", a);
    {
      const char *eq = strchr(a, '=');
      size_t n = eq ? (size_t)(eq - a) : strlen(a);
      if (n >= sizeof name) return usage_error("unknown option %s", a);
      memcpy(name, a, n);
      name[n] = '\0';
      if (eq) value = eq + 1;
    }
    if (strcmp(name, "--fps") != 0 && strcmp(name, "--duration") != 0 && strcmp(name, "--scheme") != 0 &&
        strcmp(name, "--out") != 0 && strcmp(name, "--format") != 0)
      return usage_error("unknown option %s", name);
    if (!value) {
      if (i + 1 >= argc) return usage_error("%s needs a value", name);
      value = argv[++i];
    }
    if (strcmp(name, "--fps") == 0) {
      if (!parse_positive(value, &o->fps)) return usage_error("--fps: expected a number > 0, got \"%s\"", value);
    } else if (strcmp(name, "--duration") == 0) {
      if (!parse_positive(value, &o->duration))
        return usage_error("--duration: expected a number of seconds > 0, got \"%s\"", value);
    } else if (strcmp(name, "--scheme") == 0) {
      int s;
      for (s = 0; s < BALL_SCHEME_COUNT; ++s)
        if (strcmp(value, ball_scheme_name((ball_scheme)s)) == 0) break;
      if (s == BALL_SCHEME_COUNT) return usage_error("--scheme: expected sampled or exact, got \"%s\"", value);
      o->scheme = s;
    } else if (strcmp(name, "--out") == 0) {
      if (!*value) return usage_error("--out: empty file name");
      o->out_path = value;
    } else {
      if (strcmp(value, "csv") == 0) o->format = FORMAT_CSV;
      else if (strcmp(value, "jsonl") == 0) o->format = FORMAT_JSONL;
      else return usage_error("--format: expected csv or jsonl, got \"%s\"", value);
    }
  }
  if (o->format != FORMAT_NONE && !o->out_path) return usage_error("--format needs --out FILE");
  if (o->out_path && o->format == FORMAT_NONE) {
    if (ends_with(o->out_path, ".csv")) o->format = FORMAT_CSV;
    else if (ends_with(o->out_path, ".jsonl")) o->format = FORMAT_JSONL;
    else return usage_error("--out %s: cannot tell the format from the name; add --format csv|jsonl", o->out_path);
  }
  return -1;
}

static const char *kind_name(ball_event_kind k) {
  switch (k) {
    case BALL_EVENT_FLOOR: return "floor";
    case BALL_EVENT_NET: return "net";
    case BALL_EVENT_WALL: return "wall";
    case BALL_EVENT_RACKET: return "racket";
    case BALL_EVENT_KIND_COUNT: break;
  }
  return "unknown";
}

static double norm(ball_vec3 v) { return sqrt(v.x * v.x + v.y * v.y + v.z * v.z); }

static void write_record(FILE *f, out_format fmt, double t, const ball_state *s) {
  if (fmt == FORMAT_CSV) {
    fprintf(f, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", t, s->position.x, s->position.y,
            s->position.z, s->velocity.x, s->velocity.y, s->velocity.z, s->spin.x, s->spin.y, s->spin.z);
  } else {
    fprintf(f,
            "{\"t\":%.17g,\"px\":%.17g,\"py\":%.17g,\"pz\":%.17g,\"vx\":%.17g,\"vy\":%.17g,\"vz\":%.17g,"
            "\"sx\":%.17g,\"sy\":%.17g,\"sz\":%.17g}\n",
            t, s->position.x, s->position.y, s->position.z, s->velocity.x, s->velocity.y, s->velocity.z, s->spin.x,
            s->spin.y, s->spin.z);
  }
}

static void print_effects(unsigned effects) {
  unsigned bit;
  int first = 1;
  for (bit = 1u; bit & BALL_EFFECT_ALL; bit <<= 1) {
    if (effects & bit) {
      printf("%s%s", first ? "" : ",", ball_effect_name((ball_effect)bit));
      first = 0;
    }
  }
  if (first) printf("none");
}

static int runtime_error(const char *what, ball_status st) {
  fprintf(stderr, "ballsim: %s: %s\n", what, ball_strerror(st));
  return 1;
}

int main(int argc, char **argv) {
  options o;
  ball_scene scene;
  static ball_scene_run run; /* about 60 kB: kept off the stack */
  const ball_sim *sim = &run.sim;
  ball_state state;
  ball_event events[EVENT_CAP];
  unsigned long counts[BALL_EVENT_KIND_COUNT];
  unsigned long n_events = 0, n_sounds = 0;
  const char *field = NULL;
  double dt, duration, frames_d;
  unsigned long frames, k;
  FILE *out = NULL;
  ball_status st;
  int rc, i;

  rc = parse_args(argc, argv, &o);
  if (rc >= 0) return rc;

  if (o.scene_path) {
    if (!load_scene(o.scene_path, &scene)) return 1;
  } else {
    ball_scene_default(&scene);
  }

  if (o.fps > 0.0) scene.frame_time = 1.0 / o.fps;
  if (o.scheme >= 0) scene.model.scheme = (ball_scheme)o.scheme;
  duration = o.duration > 0.0 ? o.duration : scene.duration;
  st = ball_model_check(&scene.model, &field);
  if (st != BALL_OK) {
    fprintf(stderr, "ballsim: %s: %s: %s\n", o.scene_path ? o.scene_path : "built-in scene", field ? field : "model",
            ball_strerror(st));
    return 1;
  }
  dt = scene.frame_time * scene.time_base;
  frames_d = ceil(duration / dt * (1.0 - 1e-12));
  if (!(dt > 0.0) || !isfinite(dt) || !(frames_d <= MAX_FRAMES)) {
    fprintf(stderr, "ballsim: %g s at a step of %g s is more than %.0f frames\n", duration, dt, MAX_FRAMES);
    return 1;
  }
  frames = (unsigned long)frames_d;

  st = ball_scene_run_init(&run, &scene);
  if (st != BALL_OK) return runtime_error("cannot start the sim", st);

  if (o.out_path) {
    out = fopen(o.out_path, "w");
    if (!out) {
      fprintf(stderr, "ballsim: %s: %s\n", o.out_path, strerror(errno));
      return 1;
    }
    if (o.format == FORMAT_CSV) fprintf(out, "t,px,py,pz,vx,vy,vz,sx,sy,sz\n");
    st = ball_sim_state(&scene.model, sim, &state);
    if (st != BALL_OK) {
      fclose(out);
      return runtime_error("cannot read the state", st);
    }
    write_record(out, o.format, sim->time, &state);
  }

  printf("scene: %s (%s) scheme=%s fps=%.6g dt=%.9g frames=%lu effects=", scene.name[0] ? scene.name : "unnamed",
         o.scene_path ? o.scene_path : "built-in", ball_scheme_name(scene.model.scheme), 1.0 / scene.frame_time,
         dt, frames);
  print_effects(scene.model.effects);
  printf("\n");

  memset(counts, 0, sizeof counts);
  for (k = 0; k < frames; ++k) {
    int n = 0;
    /* the racket samples that have arrived by the end of the step, then the step */
    st = ball_scene_run_step(&run, &scene.model, events, EVENT_CAP, &n);
    if (st != BALL_OK) {
      if (out) fclose(out);
      fprintf(stderr, "ballsim: step %lu at t=%.9g: %s\n", k + 1, sim->time, ball_strerror(st));
      return 1;
    }
    for (i = 0; i < n; ++i) {
      const ball_event *e = &events[i];
      printf("event t=%.6f kind=%s index=%d point=%.6f,%.6f,%.6f v_in=%.4f,%.4f,%.4f v_out=%.4f,%.4f,%.4f "
             "spin_out=%.4f,%.4f,%.4f speed_in=%.4f speed_out=%.4f sound=%d\n",
             e->time, kind_name(e->kind), e->index, e->point.x, e->point.y, e->point.z, e->velocity_in.x,
             e->velocity_in.y, e->velocity_in.z, e->velocity_out.x, e->velocity_out.y, e->velocity_out.z,
             e->spin_out.x, e->spin_out.y, e->spin_out.z, norm(e->velocity_in), norm(e->velocity_out),
             e->sound ? 1 : 0);
      if ((unsigned)e->kind < BALL_EVENT_KIND_COUNT) counts[e->kind]++;
      n_events++;
      if (e->sound) n_sounds++;
    }
    if (out) {
      st = ball_sim_state(&scene.model, sim, &state);
      if (st != BALL_OK) {
        fclose(out);
        return runtime_error("cannot read the state", st);
      }
      write_record(out, o.format, sim->time, &state);
    }
  }

  if (out) {
    int bad = ferror(out);
    if (fclose(out) != 0 || bad) {
      fprintf(stderr, "ballsim: %s: write failed\n", o.out_path);
      return 1;
    }
  }

  st = ball_sim_state(&scene.model, sim, &state);
  if (st != BALL_OK) return runtime_error("cannot read the state", st);
  printf("summary: frames=%lu time=%.6f events=%lu floor=%lu net=%lu wall=%lu racket=%lu sounds=%lu\n", frames,
         sim->time, n_events, counts[BALL_EVENT_FLOOR], counts[BALL_EVENT_NET], counts[BALL_EVENT_WALL],
         counts[BALL_EVENT_RACKET], n_sounds);
  printf("samples: arrived=%lu accepted=%lu duplicate=%lu stale=%lu invalid=%lu\n", run.arrived, run.accepted,
         run.duplicate, run.stale, run.invalid);
  printf("final: position=%.6f,%.6f,%.6f velocity=%.6f,%.6f,%.6f spin=%.6f,%.6f,%.6f grounded=%d\n", state.position.x,
         state.position.y, state.position.z, state.velocity.x, state.velocity.y, state.velocity.z, state.spin.x,
         state.spin.y, state.spin.z, sim->seg.grounded);
  printf("warnings: event_overflow=%lu contact_limit=%lu stale_racket=%lu\n",
         sim->warnings[BALL_WARN_EVENT_OVERFLOW], sim->warnings[BALL_WARN_CONTACT_LIMIT],
         sim->warnings[BALL_WARN_STALE_RACKET]);
  if (fflush(stdout) != 0) return 1;
  return 0;
}
