// Effects and the whole step: the cost of a frame as the effects are switched
// on one by one, each against the model without what the effects still off
// would act on (a disabled effect must cost nothing); a whole frame of a rally
// and the 6 s prediction a bot asks for, with ball_bench's own measurements
// (bench_kit.h), against docs/benchmarks.md's targets.
#include <cstring>

#include "accuracy.h"
#include "bench_kit.h"
#include "common.h"

namespace acc {

namespace {

const ball_effect kOrder[] = {BALL_EFFECT_DRAG,  BALL_EFFECT_SPIN,    BALL_EFFECT_FLOOR, BALL_EFFECT_NET,
                              BALL_EFFECT_WALLS, BALL_EFFECT_RACKETS, BALL_EFFECT_SOUND};
const long kFrames = 420;  // the serve's 7 s at 60 Hz

// bench_full_scene with two rackets standing clear of the ball's path
// (tracked every frame while the rackets effect is on).
void effects_scene(ball_model *m) {
  bench_full_scene(m);
  m->n_rackets = 2;
  m->rackets[0].radius = m->rackets[1].radius = 0.15;
  m->rackets[0].partner = 1;
  m->rackets[1].partner = 0;
}

const ball_vec3 kRacket[2] = {{1.0, 1.0, 9.0}, {22.0, 1.0, 9.0}};

// One pass of the scene; the final state in *end.
void pass(const ball_model &m, ball_state *end) {
  ball_sim sim;
  ball_event ev[BALL_MAX_CONTACTS + BALL_MAX_RACKETS];
  bool tracked = (m.effects & BALL_EFFECT_RACKETS) && m.n_rackets > 0;
  ball_sim_init(&sim, &m);
  for (long k = 0; k < kFrames; k++) {
    if (tracked)
      for (int r = 0; r < 2; r++) {
        ball_racket_sample s;
        s.t = sim.time;
        s.center = kRacket[r];
        s.normal = ball_v3(r == 0 ? 1.0 : -1.0, 0.0, 0.0);
        ball_racket_push(&sim, r, &s);
      }
    ball_step(&sim, 1.0 / 60.0, ev, BALL_MAX_CONTACTS + BALL_MAX_RACKETS, NULL);
  }
  ball_sim_state(&sim, end);
}

double pass_cost(const ball_model &m, long passes) {
  ball_state end;
  double t0 = bench_now();
  for (long p = 0; p < passes; p++) pass(m, &end);
  bench_sink = end.position.x;
  return 1e9 * (bench_now() - t0) / static_cast<double>(passes * kFrames);
}

}  // namespace

void run_step(const Options &opt, Report &rep) {
  StepResults &out = rep.step;
  bench_eval_result ev;
  bench_eval_run(opt.rounds, opt.quick ? 20000 : 2000000, &ev);
  out.lean_ns = Stat{ev.lean.min, ev.lean.median};

  // effects on one by one: the full model with the rest off in the mask,
  // against the model without what the rest acts on
  ball_model full;
  effects_scene(&full);
  const int stages = 1 + static_cast<int>(sizeof kOrder / sizeof kOrder[0]);
  std::vector<ball_model> off(stages), without(stages);
  int same_path = 0;
  for (int k = 0; k < stages; k++) {
    unsigned mask = 0;
    std::string on;
    for (int j = 0; j < k; j++) {
      mask |= kOrder[j];
      on += std::string(on.empty() ? "" : "+") + ball_effect_name(kOrder[j]);
    }
    off[k] = full;
    off[k].effects = mask;
    without[k] = off[k];
    for (int j = k; j < stages - 1; j++) bench_without(&without[k], kOrder[j]);
    EffectRow row;
    row.on = on.empty() ? "none" : on;
    row.mask = mask;
    out.effects.push_back(row);
    ball_state a, b;
    pass(off[k], &a);
    pass(without[k], &b);
    same_path += std::memcmp(&a, &b, sizeof a) == 0;
  }
  // a frame here is short (40-200 ns): twice the rounds, for the least disturbed
  long passes = opt.quick ? 1 : 60;
  std::vector<std::vector<double>> t_off(stages), t_without(stages);
  for (int r = 0; r < 2 * opt.rounds + 1; r++)
    for (int k = 0; k < stages; k++) {  // interleaved: a disturbance hits both
      t_off[k].push_back(pass_cost(off[k], passes));
      t_without[k].push_back(pass_cost(without[k], passes));
    }
  for (int k = 0; k < stages; k++) {
    out.effects[k].ns_off = stat_of(t_off[k]);
    out.effects[k].ns_without = stat_of(t_without[k]);
  }
  check(rep, "an effect off in the mask gives the path of the model without it", same_path == stages,
        bv::fmt("%d of %d stages end in the same state, to the bit", same_path, stages));

  // a whole frame of rally_advanced.yaml (ball, floor, net, two rackets with
  // their samples, physical response) with each test
  bench_run rn;
  std::string path = opt.scenes + "/rally_advanced.yaml";
  if (!bench_run_prepare(&rn, path.c_str())) {
    check(rep, "the rally scene loads", false, path);
  } else {
    for (ball_detect d : {BALL_DETECT_SPHERE, BALL_DETECT_DISC, BALL_DETECT_SWEPT}) {
      bench_rally_result ra;
      FrameRow row;
      row.what = ball_detect_name(d);
      if (!bench_rally_run(&rn, d, opt.rounds, opt.quick ? 1 : 40, opt.quick ? 1 : 15, &ra)) {
        check(rep, "the rally scene steps", false, row.what);
        continue;
      }
      row.mean_ns = Stat{ra.mean.min, ra.mean.median};
      row.median_ns = ra.frame_median;
      row.worst_ns = ra.worst;
      row.hits = ra.hits;
      row.frames = ra.frames;
      out.frames.push_back(row);
      std::printf("  rally frame, %-6s: mean %.0f / %.0f ns, median frame %.0f ns, worst %.0f ns\n", row.what.c_str(),
                  row.mean_ns.min, row.mean_ns.median, row.median_ns, row.worst_ns);
    }
    bench_run_free(&rn);
  }

  // the 6 s prediction at 120 Hz
  bench_predict_result pr;
  bench_predict_run(opt.rounds, opt.quick ? 20 : 2000, &pr);
  out.predict_us = Stat{pr.predict.min, pr.predict.median};
  out.steps_us = Stat{pr.steps.min, pr.steps.median};
  out.predict_contacts = pr.contacts;

  FILE *f = open_data(opt, "effects.dat");
  std::fprintf(f, "# ball_accuracy effects on one by one (ns per frame, min of interleaved rounds)\n"
                  "# stage effects_on ns_rest_off_in_mask ns_rest_removed_from_model\n");
  for (size_t k = 0; k < out.effects.size(); k++) {
    const EffectRow &e = out.effects[k];
    std::string label = k == 0 ? std::string("none") : std::string("+") + ball_effect_name(kOrder[k - 1]);
    std::fprintf(f, "%zu \"%s\" %.2f %.2f\n", k, label.c_str(), e.ns_off.min, e.ns_without.min);
  }
  std::fclose(f);
}

}  // namespace acc
