// libball and the client library's core in the page: the WebAssembly module
// the build makes (ball.wasm, cmake/BallWasm.cmake: libball's core, its
// camera presets and the client library's view of a match with the page's
// C shim, server/web/wasm/page_core.cpp) loaded and called. Every number
// about the ball, the sim clock and the rackets is the module's, to the
// bit; this file only copies numbers and names into the module's memory
// and out of it, at the places the module names. Loads in a page
// (window.BallWasm) and in Node (module.exports).
//
//   const ball = await BallWasm.load("ball.wasm");   // a URL, or the bytes
//   ball.segmentEval(model, seg, t)  -> {position, velocity, spin}, each [x, y, z]
//       ball_segment_eval itself (for the tests); model: ball_model fields by
//       name over libball's defaults; seg: {t0, p0, v0, s0, grounded}
//   const page = ball.pageCore();    // the page's core (page_core.cpp):
//       page.take(message, local)  an info, segment or event message of the
//                                  stream (JSON.parse's object); see take()
//       page.court(message), page.clock(message, local), page.racket(message)
//       page.simNow(match, local), page.ball(match, t), page.pose(match, slot, t),
//       page.trail(match, t, seconds, cap), page.markers(match, t, seconds, cap),
//       page.camera(match, preset, aspect), page.reset(match), page.forget(match),
//       page.clear(), page.presets (the camera presets' names)
//   ball.strerror(status), ball.exports (the module's own), ball.imports
//   (what it imports), ball.stubCalls (WASI stubs called, by name)
(function (root, factory) {
  if (typeof module === "object" && module.exports) module.exports = factory();
  else root.BallWasm = factory();
})(typeof self !== "undefined" ? self : this, function () {
  "use strict";

  // wasm32's layout (ILP32, double 8-aligned) of what is copied, from
  // ball/ball.h; tests/web/wasm_check.py holds each number to the
  // compiler's (page_core_layout of server/web/wasm/page_core.cpp)
  const layout = {
    model: 1408,
    segment: { size: 88, t0: 0, p0: 8, v0: 32, s0: 56, grounded: 80 },
    state: { size: 72, position: 0, velocity: 24, spin: 48 },
    field: { size: 88, name: 0, type: 8, offset: 12 },
    vec3: 24,
    plane: 56,
    racket: 48,
  };
  // ball_field_type: the kinds of field a model object may set
  const REAL = 0, INT = 1, BOOL = 2, ENUM = 3, AXIS = 4, EFFECTS = 5, VEC3 = 6, PLANE = 7, PLANES = 8, RACKETS = 9;
  const ENOSYS = 52; // WASI errno
  const BALL_OK = 0;

  // The library never prints, reads a clock or exits: a WASI function the
  // module imports all the same answers ENOSYS and is counted; any other
  // import is an error of the build.
  function importsFor(module, stubCalls) {
    const imports = {};
    for (const im of WebAssembly.Module.imports(module)) {
      if (im.module !== "wasi_snapshot_preview1" || im.kind !== "function")
        throw new Error("ballwasm: the module imports " + im.module + "." + im.name);
      imports[im.module] = imports[im.module] || {};
      imports[im.module][im.name] = function () {
        stubCalls[im.name] = (stubCalls[im.name] || 0) + 1;
        if (im.name === "proc_exit") throw new Error("ballwasm: the module exited");
        return ENOSYS;
      };
    }
    return imports;
  }

  async function load(source) {
    let bytes = source;
    if (typeof source === "string" || (typeof URL !== "undefined" && source instanceof URL)) {
      const r = await fetch(source);
      if (!r.ok) throw new Error("ballwasm: " + source + ": HTTP " + r.status);
      bytes = await r.arrayBuffer();
    }
    const module = await WebAssembly.compile(bytes);
    const stubCalls = {};
    const instance = await WebAssembly.instantiate(module, importsFor(module, stubCalls));
    return wrap(module, instance.exports, stubCalls);
  }

  // A value at a dotted path of a parsed message ("info.play.score.0"); undefined if absent.
  function at(object, path) {
    let o = object;
    for (const key of path.split(".")) {
      if (o === null || typeof o !== "object") return undefined;
      o = o[key];
    }
    return o;
  }

  // An object from dotted paths and their values ("position.0" -> o.position[0]).
  function build(paths, values) {
    const o = {};
    paths.forEach((path, i) => {
      const keys = path.split(".");
      let p = o;
      for (let k = 0; k < keys.length - 1; ++k) {
        if (!(keys[k] in p)) p[keys[k]] = /^\d+$/.test(keys[k + 1]) ? [] : {};
        p = p[keys[k]];
      }
      p[keys[keys.length - 1]] = values[i];
    });
    return o;
  }

  function wrap(module, e, stubCalls) {
    if (e._initialize) e._initialize(); // a reactor: C++ constructors, once
    const decoder = new TextDecoder(), encoder = new TextEncoder();
    // views are taken anew at each use: memory.grow replaces the buffer
    const bytesAt = () => new Uint8Array(e.memory.buffer);
    const view = () => new DataView(e.memory.buffer);
    function cString(ptr) {
      const m = bytesAt();
      let end = ptr;
      while (m[end] !== 0) ++end;
      return decoder.decode(m.subarray(ptr, end));
    }
    // the NUL-terminated strings f(0), f(1), ... up to the first NULL
    function names(f) {
      const out = [];
      for (let i = 0, p; (p = f(i)) !== 0; ++i) out.push(cString(p));
      return out;
    }

    // a struct's fields by name, from one of libball's field tables
    const block = e.malloc(2 * layout.model + layout.segment.size + layout.state.size);
    if (!block) throw new Error("ballwasm: out of memory");
    const modelAt = block, segAt = block + layout.model, stateAt = segAt + layout.segment.size;
    const courtAt = stateAt + layout.state.size; // the court message's model
    function table(get) {
      const fields = new Map();
      const t = get(stateAt); // the count into the state's place, for now
      const count = view().getInt32(stateAt, true);
      for (let i = 0; i < count; ++i) {
        const f = t + i * layout.field.size, dv = view();
        fields.set(cString(dv.getUint32(f + layout.field.name, true)),
                   { type: dv.getInt32(f + layout.field.type, true), offset: dv.getUint32(f + layout.field.offset, true) });
      }
      return fields;
    }
    const modelFields = table(e.ball_model_fields);
    const planeFields = table(e.ball_plane_fields), racketFields = table(e.ball_racket_fields);

    // a number of the JSON ("Infinity": JSON has none), as a double
    const real = (v) => (typeof v === "string" ? Number(v) : v);
    function setVec3(dv, where, v) {
      for (let i = 0; i < 3; ++i) dv.setFloat64(where + 8 * i, real(v[i]), true);
    }
    // the fields of `values` into the struct at `base` by `fields` (libball's table)
    function setFields(fields, base, values, what) {
      for (const name of Object.keys(values)) {
        const f = fields.get(name), v = values[name];
        if (!f) throw new Error("ballwasm: " + what + " has no field " + name);
        const where = base + f.offset, dv = view();
        if (f.type === REAL) dv.setFloat64(where, real(v), true);
        else if (f.type === INT || f.type === ENUM || f.type === AXIS) dv.setInt32(where, v, true);
        else if (f.type === BOOL) dv.setInt32(where, v ? 1 : 0, true);
        else if (f.type === EFFECTS) dv.setUint32(where, v, true);
        else if (f.type === VEC3) setVec3(dv, where, v);
        else if (f.type === PLANE) setFields(planeFields, where, v, name);
        else if (f.type === PLANES) v.forEach((p, i) => setFields(planeFields, where + i * layout.plane, p, name));
        else if (f.type === RACKETS) v.forEach((r, i) => setFields(racketFields, where + i * layout.racket, r, name));
        else throw new Error("ballwasm: " + name + " is of no type the glue knows");
      }
    }
    function setModel(at, model) {
      e.ball_model_default(at);
      setFields(modelFields, at, model, "ball_model");
    }

    function segmentEval(model, seg, t) {
      setModel(modelAt, model);
      const dv = view(), s = layout.segment;
      dv.setFloat64(segAt + s.t0, seg.t0, true);
      setVec3(dv, segAt + s.p0, seg.p0);
      setVec3(dv, segAt + s.v0, seg.v0);
      setVec3(dv, segAt + s.s0, seg.s0);
      dv.setInt32(segAt + s.grounded, seg.grounded ? 1 : 0, true);
      const status = e.ball_segment_eval(modelAt, segAt, t, stateAt);
      if (status !== BALL_OK) {
        const err = new Error("ballwasm: ball_segment_eval: " + strerror(status));
        err.status = status;
        throw err;
      }
      const o = new Float64Array(e.memory.buffer, stateAt, layout.state.size / 8);
      const vec = (where) => [o[where / 8], o[where / 8 + 1], o[where / 8 + 2]];
      return { position: vec(layout.state.position), velocity: vec(layout.state.velocity), spin: vec(layout.state.spin) };
    }

    function strerror(status) {
      return cString(e.ball_strerror(status));
    }

    // ---- the page's core (server/web/wasm/page_core.cpp) --------------------
    const kinds = names(e.page_core_kind_name);
    const paths = {}, textPaths = {};
    kinds.forEach((kind, k) => {
      paths[kind] = names((i) => e.page_core_path(k, i));
      textPaths[kind] = names((i) => e.page_core_text_path(k, i));
    });
    const kindOf = (name) => kinds.indexOf(name);
    const presets = names(e.ball_camera_preset_name);
    const markerKinds = names(e.page_core_marker_kind);
    const [SLOTS, , TEXT_LEN, OUT] = [0, 1, 2, 3].map(e.page_core_size);

    function pageCore() {
      const core = e.page_core_open();
      const numbers = () => new Float64Array(e.memory.buffer, e.page_core_numbers(core), SLOTS);
      const out = () => new Float64Array(e.memory.buffer, e.page_core_out(core), OUT);
      function setText(i, text) {
        const bytes = encoder.encode(text).subarray(0, TEXT_LEN - 1), m = bytesAt(), where = e.page_core_texts(core) + i * TEXT_LEN;
        m.set(bytes, where);
        m[where + bytes.length] = 0;
      }
      // a message's numbers and names into the slots, by its kind's paths
      function put(kind, message) {
        const n = numbers();
        paths[kind].forEach((path, i) => {
          const v = at(message, path);
          n[i] = typeof v === "number" ? v : typeof v === "boolean" ? (v ? 1 : 0) : NaN;
        });
        textPaths[kind].forEach((path, i) => {
          const v = at(message, path);
          setText(i, typeof v === "string" ? v : "");
        });
      }
      // an answer of `kind` from the slots (null unless status is BALL_OK)
      const answer = (kind, status) => (status === BALL_OK ? build(paths[kind], Array.from(numbers().subarray(0, paths[kind].length))) : null);
      return {
        presets: presets,
        // An info, segment or event message, at the page's clock `local` (s):
        // info 1 taken, 0 refused; segment: how many events it voided
        // (voided() names them), -1 refused or held; event: 1 given, 2 taken
        // back by a correction that came first, 0 refused or given already.
        take(message, local) {
          put(message.type, message);
          return e.page_core_take(core, kindOf(message.type), local);
        },
        voided() {
          const seqs = [];
          for (let i = 0, s; (s = e.page_core_voided(core, i)) >= 0; ++i) seqs.push(s);
          return seqs;
        },
        // The court message's model, copied by libball's field tables and
        // checked against its hash by the module: true when taken.
        court(message) {
          setModel(courtAt, message.model);
          setText(0, message.model_hash);
          return e.page_core_court(core, message.match, courtAt, e.page_core_texts(core)) === 1;
        },
        clock(message, local) {
          return e.page_core_clock(core, message.match, message.sim_time, message.real, message.time_base,
                                   message.running ? 1 : 0, local) === 1;
        },
        racket(message) {
          const c = message.center, n = message.normal;
          return e.page_core_racket(core, message.match, message.player, message.t, c[0], c[1], c[2], n[0], n[1], n[2]);
        },
        // the match's sim time at the page's clock `local`; null without a clock
        simNow(match, local) {
          const t = e.page_core_sim_now(core, match, local);
          return Number.isNaN(t) ? null : t;
        },
        ball: (match, t) => answer("ball", e.page_core_ball(core, match, t)),
        pose: (match, slot, t) => answer("pose", e.page_core_pose(core, match, slot, t)),
        camera: (match, preset, aspect) => answer("camera", e.page_core_camera(core, match, presets.indexOf(preset), aspect)),
        trail(match, t, seconds, cap) {
          const n = e.page_core_trail(core, match, t, seconds, cap), o = out(), points = [];
          for (let i = 0; i < n; ++i) points.push([o[3 * i], o[3 * i + 1], o[3 * i + 2]]);
          return points;
        },
        markers(match, t, seconds, cap) {
          const n = e.page_core_markers(core, match, t, seconds, cap), o = out(), w = paths.marker.length, list = [];
          for (let i = 0; i < n; ++i) {
            const m = build(paths.marker, Array.from(o.subarray(w * i, w * i + w)));
            m.kind = markerKinds[m.kind];
            list.push(m);
          }
          return list;
        },
        reset: (match) => e.page_core_reset(core, match),
        forget: (match) => e.page_core_forget(core, match),
        clear: () => e.page_core_clear(core),
        close: () => e.page_core_close(core),
      };
    }

    return {
      segmentEval: segmentEval,
      pageCore: pageCore,
      strerror: strerror,
      exports: e,
      imports: WebAssembly.Module.imports(module).map((im) => im.module + "." + im.name),
      stubCalls: stubCalls,
    };
  }

  return { load: load, layout: layout };
});
