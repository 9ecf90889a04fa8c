// libball itself in the page: the WebAssembly module the build makes
// (ball.wasm, cmake/BallWasm.cmake: libball's core compiled with clang 14 for
// wasm32-wasi) loaded and called. The ball is ball_segment_eval's, to the bit;
// this file only copies numbers into the module's memory and out of it.
// Loads in a page (window.BallWasm) and in Node (module.exports).
//
//   const ball = await BallWasm.load("ball.wasm");   // a URL, or the bytes
//   ball.segmentEval(model, seg, t)  -> {position, velocity, spin}, each [x, y, z]
//       model: ball_model fields by name (MatchInfo's mass, air_friction,
//       gravity, spin_damping, effects), the rest libball's defaults;
//       seg: {t0, p0, v0, s0, grounded}; throws on a status other than BALL_OK
//   ball.strerror(status), ball.exports (the module's own), ball.imports
//   (what it imports), ball.stubCalls (WASI stubs called, by name)
(function (root, factory) {
  if (typeof module === "object" && module.exports) module.exports = factory();
  else root.BallWasm = factory();
})(typeof self !== "undefined" ? self : this, function () {
  "use strict";

  // wasm32's layout (ILP32, double 8-aligned) of what is copied, from
  // ball/ball.h; tests/web/wasm_check.py holds each number to the
  // compiler's (wasm_probe_layout of tests/web/wasm_probe.cpp)
  const layout = {
    model: 1408,
    segment: { size: 88, t0: 0, p0: 8, v0: 32, s0: 56, grounded: 80 },
    state: { size: 72, position: 0, velocity: 24, spin: 48 },
    field: { size: 88, name: 0, type: 8, offset: 12 },
    vec3: 24,
  };
  // ball_field_type: the kinds of field a model object may set
  const REAL = 0, INT = 1, BOOL = 2, ENUM = 3, AXIS = 4, EFFECTS = 5, VEC3 = 6;
  const ENOSYS = 52; // WASI errno

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

  function wrap(module, e, stubCalls) {
    if (e._initialize) e._initialize(); // a reactor: C++ constructors, once
    const decoder = new TextDecoder();
    // views are taken anew at each use: memory.grow replaces the buffer
    const bytesAt = () => new Uint8Array(e.memory.buffer);
    const view = () => new DataView(e.memory.buffer);
    function cString(ptr) {
      const m = bytesAt();
      let end = ptr;
      while (m[end] !== 0) ++end;
      return decoder.decode(m.subarray(ptr, end));
    }

    // the model's fields by name, from libball's field table
    const block = e.malloc(layout.model + layout.segment.size + layout.state.size);
    if (!block) throw new Error("ballwasm: out of memory");
    const modelAt = block, segAt = block + layout.model, stateAt = segAt + layout.segment.size;
    const fields = new Map();
    const table = e.ball_model_fields(stateAt); // the count into the state's place, for now
    const count = view().getInt32(stateAt, true);
    for (let i = 0; i < count; ++i) {
      const f = table + i * layout.field.size, dv = view();
      fields.set(cString(dv.getUint32(f + layout.field.name, true)),
                 { type: dv.getInt32(f + layout.field.type, true), offset: dv.getUint32(f + layout.field.offset, true) });
    }

    function setVec3(dv, at, v) {
      for (let i = 0; i < 3; ++i) dv.setFloat64(at + 8 * i, v[i], true);
    }

    function setModel(model) {
      e.ball_model_default(modelAt);
      const dv = view();
      for (const name of Object.keys(model)) {
        const f = fields.get(name), at = modelAt + (f ? f.offset : 0), v = model[name];
        if (!f) throw new Error("ballwasm: ball_model has no field " + name);
        if (f.type === REAL) dv.setFloat64(at, v, true);
        else if (f.type === INT || f.type === ENUM || f.type === AXIS) dv.setInt32(at, v, true);
        else if (f.type === BOOL) dv.setInt32(at, v ? 1 : 0, true);
        else if (f.type === EFFECTS) dv.setUint32(at, v, true);
        else if (f.type === VEC3) setVec3(dv, at, v);
        else throw new Error("ballwasm: " + name + " is not a number or a vector");
      }
    }

    function segmentEval(model, seg, t) {
      setModel(model);
      const dv = view(), s = layout.segment;
      dv.setFloat64(segAt + s.t0, seg.t0, true);
      setVec3(dv, segAt + s.p0, seg.p0);
      setVec3(dv, segAt + s.v0, seg.v0);
      setVec3(dv, segAt + s.s0, seg.s0);
      dv.setInt32(segAt + s.grounded, seg.grounded ? 1 : 0, true);
      const status = e.ball_segment_eval(modelAt, segAt, t, stateAt);
      if (status !== 0) {
        const err = new Error("ballwasm: ball_segment_eval: " + strerror(status));
        err.status = status;
        throw err;
      }
      const o = new Float64Array(e.memory.buffer, stateAt, layout.state.size / 8);
      const vec = at => [o[at / 8], o[at / 8 + 1], o[at / 8 + 2]];
      return { position: vec(layout.state.position), velocity: vec(layout.state.velocity), spin: vec(layout.state.spin) };
    }

    function strerror(status) {
      return cString(e.ball_strerror(status));
    }

    return {
      segmentEval: segmentEval,
      strerror: strerror,
      exports: e,
      imports: WebAssembly.Module.imports(module).map(im => im.module + "." + im.name),
      stubCalls: stubCalls,
    };
  }

  return { load: load, layout: layout };
});
