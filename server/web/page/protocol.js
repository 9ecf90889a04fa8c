// The ball server's protocol as a page needs it, written from
// docs/protocol.md and docs/rackets.md alone: the ball from a segment
// ("Evaluating the ball from segments", eq 3 and 4 of the paper), the
// segment in effect, the events a correction voids ("Corrections"), the
// sim clock estimate ("Time") and a racket's track
// (interpolated between samples, eq 15 past the newest). Another
// implementation beside libball's: the tests hold its numbers to libball's.
// Loads in a page (window.BallProtocol) and in Node (module.exports).
(function (root, factory) {
  if (typeof module === "object" && module.exports) module.exports = factory();
  else root.BallProtocol = factory();
})(typeof self !== "undefined" ? self : this, function () {
  "use strict";

  const LN2 = 0.69314718055994531;
  const EFFECT_DRAG = 1; // effects bit 0
  const EFFECT_SPIN = 2; // effects bit 1

  // The ball at sim time t on segment seg (t0, p0, v0, s0: [x, y, z], grounded)
  // with the flight model of MatchInfo (mass, air_friction, gravity,
  // spin_damping, effects): {position, velocity, spin}, each [x, y, z].
  function segmentEval(model, seg, t) {
    const tau = t - seg.t0;
    let d = tau; // b (1 - e^(-tau/b)), tau without drag
    let f = 1; //   e^(-tau/b), 1 without drag
    if ((model.effects & EFFECT_DRAG) && model.air_friction > 0 && tau !== 0) {
      const b = model.mass / model.air_friction; // eq 2: b = m / beta
      if (isFinite(b)) {
        const x = tau * (model.air_friction / model.mass);
        if (x < LN2) {
          const e = Math.expm1(-x); // no cancellation while e^(-x) >= 1/2
          d = -b * e;
          f = 1 + e;
        } else {
          f = Math.exp(-x);
          d = b * (1 - f);
        }
      }
    }
    const p0 = seg.p0, v0 = seg.v0, s0 = seg.s0;
    const g = model.gravity;
    const position = [p0[0] + v0[0] * d, 0, p0[2] + v0[2] * d];
    const velocity = [v0[0] * f, 0, v0[2] * f];
    if (seg.grounded) {
      position[1] = p0[1];
      velocity[1] = 0;
    } else {
      position[1] = p0[1] + v0[1] * tau - 0.5 * g * tau * tau;
      velocity[1] = v0[1] - g * tau;
    }
    let spin = [0, 0, 0];
    const sd = model.spin_damping;
    if ((model.effects & EFFECT_SPIN) && sd !== 0 && (s0[0] !== 0 || s0[1] !== 0 || s0[2] !== 0)) {
      const k = sd / (sd + tau); // eq 4
      spin = [s0[0] * k, s0[1] * k, s0[2] * k];
    }
    return { position: position, velocity: velocity, spin: spin };
  }

  // a after b in serial-number arithmetic (32-bit sequence numbers)
  function seqAfter(a, b) {
    const d = (a - b) >>> 0;
    return d !== 0 && d < 0x80000000;
  }

  // The segment in effect at sim time t: of those given, the one with the
  // highest seq whose t0 is not after t (null: none).
  function inEffect(segments, t) {
    let best = null;
    for (const s of segments)
      if (s.t0 <= t && (best === null || seqAfter(s.seq, best.seq))) best = s;
    return best;
  }

  // Whether a correction (a segment with `correction` set: {seq, t0}) voids
  // an event ({kind, time, segment_seq}), by "Corrections: hits found late":
  // a collision's or a point's event, written before the correction (the
  // segment in effect then is older: serial arithmetic) and after its t0.
  const VOIDABLE = ["racket", "floor", "net", "wall", "sound", "point"];
  function voids(correction, event) {
    return VOIDABLE.indexOf(event.kind) >= 0 && event.time > correction.t0 && seqAfter(correction.seq, event.segment_seq);
  }

  // The sim clock from (sim_time, server_time) pairs: the smallest
  // (local - server) difference over the last pairs is the offset plus the
  // smallest latency (the minimum filter); the newest pair is the anchor.
  class SimClock {
    constructor() {
      this.offsets = [];
      this.valid = false;
      this.simTime = 0;
      this.serverTime = 0;
      this.timeBase = 1;
      this.running = false;
    }
    observe(simTime, serverTime, timeBase, running, localNow) {
      const offset = localNow - serverTime;
      if (!isFinite(simTime) || !isFinite(offset) || !(timeBase >= 0.05 && timeBase <= 20)) return false;
      this.offsets.push(offset);
      if (this.offsets.length > SimClock.WINDOW) this.offsets.shift();
      if (!this.valid || serverTime >= this.serverTime) {
        this.simTime = simTime;
        this.serverTime = serverTime;
        this.timeBase = timeBase;
        this.running = running;
      }
      this.valid = true;
      return true;
    }
    offset() {
      return Math.min.apply(null, this.offsets);
    }
    simNow(localNow) {
      if (!this.valid) return 0;
      if (!this.running) return this.simTime;
      const ahead = Math.max(0, localNow - this.offset() - this.serverTime);
      return this.simTime + ahead * this.timeBase;
    }
  }
  SimClock.WINDOW = 128; // pairs

  function lerp3(a, b, u) {
    return [a[0] + (b[0] - a[0]) * u, a[1] + (b[1] - a[1]) * u, a[2] + (b[2] - a[2]) * u];
  }
  function unit3(v) {
    const n = Math.hypot(v[0], v[1], v[2]);
    return n > 0 ? [v[0] / n, v[1] / n, v[2] / n] : [0, 1, 0];
  }
  function velocityOf(a, b) {
    const dt = b.t - a.t;
    return dt > 0 ? [(b.center[0] - a.center[0]) / dt, (b.center[1] - a.center[1]) / dt, (b.center[2] - a.center[2]) / dt]
                  : [0, 0, 0];
  }

  // A racket's pose at sim time t from its samples ({t, center, normal},
  // oldest first): between two samples interpolated (the normal by
  // normalised lerp, the second turned into the first one's hemisphere);
  // before the oldest, the oldest; past the newest, eq 15 capped at
  // extrapolationTime. null without samples or when the newest is older
  // than staleTime at t.
  function racketEstimate(samples, t, extrapolationTime, staleTime) {
    const n = samples.length;
    if (n === 0) return null;
    const newest = samples[n - 1];
    if (t - newest.t > staleTime) return null;
    if (n === 1) return { center: newest.center.slice(), normal: unit3(newest.normal), velocity: [0, 0, 0] };
    if (t <= samples[0].t)
      return { center: samples[0].center.slice(), normal: unit3(samples[0].normal), velocity: velocityOf(samples[0], samples[1]) };
    for (let i = 1; i < n; ++i) {
      const a = samples[i - 1], b = samples[i];
      if (t > b.t) continue;
      const u = (t - a.t) / (b.t - a.t);
      const na = unit3(a.normal);
      let nb = unit3(b.normal);
      if (na[0] * nb[0] + na[1] * nb[1] + na[2] * nb[2] < 0) nb = [-nb[0], -nb[1], -nb[2]];
      return { center: lerp3(a.center, b.center, u), normal: unit3(lerp3(na, nb, u)), velocity: velocityOf(a, b) };
    }
    const v = velocityOf(samples[n - 2], newest);
    const ahead = Math.min(t - newest.t, extrapolationTime); // eq 15
    return {
      center: [newest.center[0] + v[0] * ahead, newest.center[1] + v[1] * ahead, newest.center[2] + v[2] * ahead],
      normal: unit3(newest.normal),
      velocity: v,
    };
  }

  return { segmentEval: segmentEval, seqAfter: seqAfter, inEffect: inEffect, voids: voids, SimClock: SimClock,
           racketEstimate: racketEstimate };
});
