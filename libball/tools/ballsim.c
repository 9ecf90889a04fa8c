/* ballsim: runs a libball scene headless, prints its events and a summary,
 * and writes the trajectory as CSV or JSON Lines. See docs/scenes.md. */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <getopt.h>
#include <signal.h>
#include <time.h>
#include <unistd.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ball/ball.h"
#include "ball/scene.h"
#include "ball/vec3.h"

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
  int keys;                /* --keys: print the scene keys table and stop */
} options;

static void print_help(FILE *f) {
  fprintf(f,
          "usage: ballsim [SCENE] [--fps N] [--duration S] [--scheme sampled|exact]\n"
          "               [--out FILE] [--format csv|jsonl]\n"
          "       ballsim --keys\n"
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
          "  --keys              print the model keys of a scene file (the field table of\n"
          "                      libball) as the Markdown table of docs/scenes.md, and stop\n"
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
          "Text in these lines (the scene's name, the file name) is printed with control\n"
          "characters escaped (\\n, \\t, \\xNN), so a scene cannot fake a line. Numbers\n"
          "print as %%.6f (speeds %%.4f) between 1e-3 and 1e9, and as %%.17g beyond.\n"
          "On a terminal a long run shows its progress on stderr; Ctrl-C stops it\n"
          "cleanly after the frame in hand (the summary says interrupted=1, exit 130).\n"
          "\n"
          "Exit status: 0 on success, 1 for a scene or runtime error (printed as\n"
          "FILE:LINE:COLUMN: FIELD: MESSAGE), 2 for bad arguments, 130 interrupted.\n");
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
  static const struct option longs[] = {
      {"fps", required_argument, NULL, 'f'},    {"duration", required_argument, NULL, 'd'},
      {"scheme", required_argument, NULL, 's'}, {"out", required_argument, NULL, 'o'},
      {"format", required_argument, NULL, 'F'}, {"keys", no_argument, NULL, 'k'},
      {"help", no_argument, NULL, 'h'},         {NULL, 0, NULL, 0}};
  int c;
  memset(o, 0, sizeof *o);
  o->scheme = -1;
  opterr = 0;
  while ((c = getopt_long(argc, argv, ":h", longs, NULL)) != -1) {
    const char *value = optarg;
    switch (c) {
      case 'h': print_help(stdout); return 0;
      case 'k': o->keys = 1; break;
      case 'f':
        if (!parse_positive(value, &o->fps)) return usage_error("--fps: expected a number > 0, got \"%s\"", value);
        break;
      case 'd':
        if (!parse_positive(value, &o->duration))
          return usage_error("--duration: expected a number of seconds > 0, got \"%s\"", value);
        break;
      case 's': {
        int sc;
        for (sc = 0; sc < BALL_SCHEME_COUNT; ++sc)
          if (strcmp(value, ball_scheme_name((ball_scheme)sc)) == 0) break;
        if (sc == BALL_SCHEME_COUNT) return usage_error("--scheme: expected sampled or exact, got \"%s\"", value);
        o->scheme = sc;
        break;
      }
      case 'o':
        if (!*value) return usage_error("--out: empty file name");
        o->out_path = value;
        break;
      case 'F':
        if (strcmp(value, "csv") == 0) o->format = FORMAT_CSV;
        else if (strcmp(value, "jsonl") == 0) o->format = FORMAT_JSONL;
        else return usage_error("--format: expected csv or jsonl, got \"%s\"", value);
        break;
      case ':': return usage_error("%s needs a value", argv[optind - 1]);
      default: {
        /* the option as given, without a value glued to it with = */
        const char *a = argv[optind - 1];
        size_t n = strcspn(a, "=");
        return usage_error("unknown option %.*s", (int)n, a);
      }
    }
  }
  if (optind < argc) o->scene_path = argv[optind++];
  if (optind < argc) return usage_error("more than one scene given: %s and %s", o->scene_path, argv[optind]);
  if (o->format != FORMAT_NONE && !o->out_path) return usage_error("--format needs --out FILE");
  if (o->out_path && o->format == FORMAT_NONE) {
    if (ends_with(o->out_path, ".csv")) o->format = FORMAT_CSV;
    else if (ends_with(o->out_path, ".jsonl")) o->format = FORMAT_JSONL;
    else return usage_error("--out %s: cannot tell the format from the name; add --format csv|jsonl", o->out_path);
  }
  return -1;
}

/* ---- text output ---- */

/* Text from a scene (its name, a file name) with control characters and
 * the backslash escaped, so that nothing in a scene can start a line of its
 * own or drive the terminal. */
static void put_text(FILE *f, const char *s) {
  for (; *s; ++s) {
    unsigned char c = (unsigned char)*s;
    if (c == '\\') fputs("\\\\", f);
    else if (c == '\n') fputs("\\n", f);
    else if (c == '\t') fputs("\\t", f);
    else if (c == '\r') fputs("\\r", f);
    else if (c < 0x20 || c == 0x7f) fprintf(f, "\\x%02x", c);
    else fputc(c, f);
  }
}

/* A number for the text lines: fixed point (digits decimals) in the usual
 * range, %.17g (all the digits, compactly) for the very large and small. */
static void put_num(FILE *f, double v, int digits) {
  double a = fabs(v);
  if (v == 0.0 || (a >= 1e-3 && a < 1e9)) fprintf(f, "%.*f", digits, v);
  else fprintf(f, "%.17g", v);
}

static void put_vec(FILE *f, ball_vec3 v, int digits) {
  put_num(f, v.x, digits);
  fputc(',', f);
  put_num(f, v.y, digits);
  fputc(',', f);
  put_num(f, v.z, digits);
}

/* ---- the key table (docs/scenes.md) ---- */

static const char *type_words(const ball_field *f, char *buf, size_t size) {
  int i;
  size_t used = 0;
  switch (f->type) {
    case BALL_FIELD_REAL: return "number";
    case BALL_FIELD_INT: return "integer";
    case BALL_FIELD_BOOL: return "boolean";
    case BALL_FIELD_AXIS: return "`x` or `z`";
    case BALL_FIELD_EFFECTS: return "list of names";
    case BALL_FIELD_VEC3: return "vector";
    case BALL_FIELD_PLANE: return "mapping or `none`";
    case BALL_FIELD_PLANES:
    case BALL_FIELD_RACKETS: return "list of mappings";
    case BALL_FIELD_ENUM:
      buf[0] = '\0';
      for (i = 0; i <= (int)f->hi && used < size; i++) {
        int w = snprintf(buf + used, size - used, "%s`%s`", i ? ", " : "", f->enum_name(i));
        if (w < 0) break;
        used += (size_t)w;
      }
      return buf;
    default: return "";
  }
}

static void put_default(const ball_field *f) {
  unsigned bit;
  int first = 1;
  switch (f->type) {
    case BALL_FIELD_REAL: printf("%.10g", f->def[0]); break;
    case BALL_FIELD_INT: printf("%d", (int)f->def[0]); break;
    case BALL_FIELD_BOOL: printf("`%s`", f->def[0] != 0.0 ? "true" : "false"); break;
    case BALL_FIELD_ENUM: printf("`%s`", f->enum_name((int)f->def[0])); break;
    case BALL_FIELD_AXIS: printf("`%s`", f->def[0] == 0.0 ? "x" : "z"); break;
    case BALL_FIELD_VEC3: printf("[%.10g, %.10g, %.10g]", f->def[0], f->def[1], f->def[2]); break;
    case BALL_FIELD_EFFECTS:
      printf("`[");
      for (bit = 1u; bit & BALL_EFFECT_ALL; bit <<= 1)
        if ((unsigned)f->def[0] & bit) {
          printf("%s%s", first ? "" : ", ", ball_effect_name((ball_effect)bit));
          first = 0;
        }
      printf("]`");
      break;
    default: break;
  }
}

static void key_row(const char *prefix, const ball_field *f, const char *def_override) {
  char types[160];
  printf("| `%s%s` | %s | %s | ", prefix, f->key, type_words(f, types, sizeof types), f->unit);
  if (def_override) printf("%s", def_override);
  else put_default(f);
  printf(" | %s%s%s", f->range, *f->range ? "; " : "", f->doc);
  if (*f->equation) printf(" (%s)", f->equation);
  printf(" |\n");
}

/* The model's keys as docs/scenes.md lists them: every field of the field
 * table under its scene key. */
static int print_keys(void) {
  int n, np, nr, i, j;
  const ball_field *f = ball_model_fields(&n);
  const ball_field *pf = ball_plane_fields(&np);
  const ball_field *rf = ball_racket_fields(&nr);
  printf("| key | type | unit | default | range and meaning |\n|---|---|---|---|---|\n");
  for (i = 0; i < n; i++) {
    if (f[i].type == BALL_FIELD_INT && (strcmp(f[i].key, "walls") == 0 || strcmp(f[i].key, "rackets") == 0))
      continue; /* the counts are the lists' lengths */
    if (f[i].type == BALL_FIELD_BOOL && strcmp(f[i].key, "net") == 0) continue; /* `net: none` */
    key_row("", &f[i], f[i].type == BALL_FIELD_PLANES || f[i].type == BALL_FIELD_RACKETS ? "`[]`" :
                      f[i].type == BALL_FIELD_PLANE ? "the court's net" : NULL);
    if (f[i].type == BALL_FIELD_PLANE)
      for (j = 0; j < np; j++) key_row("net.", &pf[j], NULL);
    if (f[i].type == BALL_FIELD_PLANES)
      for (j = 0; j < np; j++)
        key_row("walls[i].", &pf[j],
                strcmp(pf[j].key, "bottom") == 0 ? "`floor.level`" :
                strcmp(pf[j].key, "damping") == 0 ? "the default net's" : "required");
    if (f[i].type == BALL_FIELD_RACKETS)
      for (j = 0; j < nr; j++) key_row("rackets[i].", &rf[j], NULL);
  }
  return fflush(stdout) == 0 ? 0 : 1;
}

/* ---- Ctrl-C ---- */

static volatile sig_atomic_t g_interrupted = 0;
static void on_sigint(int sig) {
  (void)sig;
  g_interrupted = 1;
}

static double wall_now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
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
  int rc, i, show_progress;
  double last_progress;

  rc = parse_args(argc, argv, &o);
  if (rc >= 0) return rc;
  if (o.keys) return print_keys();

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
    st = ball_sim_state(sim, &state);
    if (st != BALL_OK) {
      fclose(out);
      return runtime_error("cannot read the state", st);
    }
    write_record(out, o.format, sim->time, &state);
  }

  printf("scene: ");
  put_text(stdout, scene.name[0] ? scene.name : "unnamed");
  printf(" (");
  put_text(stdout, o.scene_path ? o.scene_path : "built-in");
  printf(") scheme=%s fps=%.6g dt=%.9g frames=%lu effects=", ball_scheme_name(scene.model.scheme),
         1.0 / scene.frame_time, dt, frames);
  print_effects(scene.model.effects);
  printf("\n");
  show_progress = isatty(STDERR_FILENO) && frames > 100000;
  signal(SIGINT, on_sigint);
  last_progress = wall_now();

  memset(counts, 0, sizeof counts);
  for (k = 0; k < frames && !g_interrupted; ++k) {
    int n = 0;
    /* the racket samples that have arrived by the end of the step, then the step */
    st = ball_scene_run_step(&run, events, EVENT_CAP, &n);
    if (st != BALL_OK) {
      if (out) fclose(out);
      fprintf(stderr, "ballsim: step %lu at t=%.9g: %s\n", k + 1, sim->time, ball_strerror(st));
      return 1;
    }
    for (i = 0; i < n; ++i) {
      const ball_event *e = &events[i];
      printf("event t=");
      put_num(stdout, e->time, 6);
      printf(" kind=%s index=%d point=", kind_name(e->kind), e->index);
      put_vec(stdout, e->point, 6);
      printf(" v_in=");
      put_vec(stdout, e->velocity_in, 4);
      printf(" v_out=");
      put_vec(stdout, e->velocity_out, 4);
      printf(" spin_out=");
      put_vec(stdout, e->spin_out, 4);
      printf(" speed_in=");
      put_num(stdout, ball_v3_norm(e->velocity_in), 4);
      printf(" speed_out=");
      put_num(stdout, ball_v3_norm(e->velocity_out), 4);
      printf(" sound=%d\n", e->sound ? 1 : 0);
      if ((unsigned)e->kind < BALL_EVENT_KIND_COUNT) counts[e->kind]++;
      n_events++;
      if (e->sound) n_sounds++;
    }
    if (out) {
      st = ball_sim_state(sim, &state);
      if (st != BALL_OK) {
        fclose(out);
        return runtime_error("cannot read the state", st);
      }
      write_record(out, o.format, sim->time, &state);
    }
    if (show_progress && (k & 1023) == 0 && wall_now() - last_progress >= 1.0) {
      last_progress = wall_now();
      fprintf(stderr, "\rballsim: frame %lu of %lu (%.1f %%), sim time %.3f s ", k + 1, frames,
              100.0 * (double)(k + 1) / (double)frames, sim->time);
    }
  }
  if (show_progress) fprintf(stderr, "\n");
  frames = k; /* the frames run (fewer when interrupted) */

  if (out) {
    int bad = ferror(out);
    if (fclose(out) != 0 || bad) {
      fprintf(stderr, "ballsim: %s: write failed\n", o.out_path);
      return 1;
    }
  }

  st = ball_sim_state(sim, &state);
  if (st != BALL_OK) return runtime_error("cannot read the state", st);
  printf("summary: frames=%lu time=", frames);
  put_num(stdout, sim->time, 6);
  printf(" events=%lu floor=%lu net=%lu wall=%lu racket=%lu sounds=%lu%s\n", n_events, counts[BALL_EVENT_FLOOR],
         counts[BALL_EVENT_NET], counts[BALL_EVENT_WALL], counts[BALL_EVENT_RACKET], n_sounds,
         g_interrupted ? " interrupted=1" : "");
  printf("samples: arrived=%lu accepted=%lu duplicate=%lu stale=%lu invalid=%lu\n", run.arrived, run.accepted,
         run.duplicate, run.stale, run.invalid);
  printf("final: position=");
  put_vec(stdout, state.position, 6);
  printf(" velocity=");
  put_vec(stdout, state.velocity, 6);
  printf(" spin=");
  put_vec(stdout, state.spin, 6);
  printf(" grounded=%d\n", sim->seg.grounded);
  printf("warnings: event_overflow=%lu contact_limit=%lu stale_racket=%lu\n",
         sim->warnings[BALL_WARN_EVENT_OVERFLOW], sim->warnings[BALL_WARN_CONTACT_LIMIT],
         sim->warnings[BALL_WARN_STALE_RACKET]);
  if (fflush(stdout) != 0) return 1;
  return g_interrupted ? 130 : 0;
}
