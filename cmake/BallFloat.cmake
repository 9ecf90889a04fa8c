# The floating point of libball's core, stated once: BALL_C_FLOAT, for the
# sources of libball/src natively (libball/CMakeLists.txt) and on WebAssembly
# (BallWasm.cmake). Used as target_compile_options(<target> PRIVATE ${BALL_C_FLOAT}).
#
# -ffp-contract=off: no a * b + c fused into one fma. GCC fuses by default in
# its GNU dialects (-ffp-contract=fast) and clang 14 within an expression
# (-ffp-contract=on) wherever the target has an fma (aarch64; x86_64 with
# -march=haswell or later), and a fused result differs from the two
# rounded operations in the last bits. With it off, and libball's own exp,
# expm1, log and log1p (libball/src/elementary.c), every build of libball
# gives the same bits for the same inputs (docs/model.md, "The same bits on
# every platform"); wasm32 has no fma anyway.
include_guard(GLOBAL)
set(BALL_C_FLOAT -ffp-contract=off)
