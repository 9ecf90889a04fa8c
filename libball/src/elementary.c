/* libball's own exp, expm1, log and log1p (docs/model.md, "The same bits on
 * every platform"): fdlibm's algorithms, as FreeBSD's msun has them
 * (e_exp.c, s_expm1.c, e_log.c, s_log1p.c), in portable C99, so that every
 * build of libball (x86_64 with or without FMA, aarch64, wasm32) gives the
 * same bits for the same inputs. The C libraries do not: glibc's exp and log
 * are other algorithms than musl's (the WebAssembly build's), and glibc picks
 * FMA code at run time by CPU. With IEEE double arithmetic, round to
 * nearest, FLT_EVAL_METHOD 0 and no contraction (-ffp-contract=off,
 * libball/CMakeLists.txt) each of these is a fixed sequence of correctly
 * rounded operations, hence the same everywhere. Each is within 1 ulp of
 * the true value (fdlibm's error analysis; libball/src/tests/
 * test_elementary.c holds them to glibc's within 1 ulp).
 *
 * What changed from fdlibm: the words of a double are read and written
 * through memcpy into a uint64_t (no unions, no int32 conversions of
 * unsigned words: sign_high() below); the constants are written as
 * hexadecimal floating literals (the exact bits fdlibm states); the tricks
 * that raise the inexact, overflow and underflow flags are left out (the
 * library reads no flags and sets no errno): an overflow returns +Inf, an
 * underflow +0, a domain error a quiet NaN (0x7ff8000000000000 on every
 * platform), a NaN argument itself quieted (x + x). Otherwise the
 * operations are fdlibm's, in fdlibm's order.
 *
 * fdlibm's notice, which its permission requires to be kept:
 *
 * ====================================================
 * Copyright (C) 1993 by Sun Microsystems, Inc. All rights reserved.
 *
 * Developed at SunPro, a Sun Microsystems, Inc. business.
 * Permission to use, copy, modify, and distribute this
 * software is freely granted, provided that this notice
 * is preserved.
 * ====================================================
 *
 * and for e_exp.c (1.6 04/04/22):
 *
 * ====================================================
 * Copyright (C) 2004 by Sun Microsystems, Inc. All rights reserved.
 *
 * Permission to use, copy, modify, and distribute this
 * software is freely granted, provided that this notice
 * is preserved.
 * ====================================================
 */
#include <stdint.h>
#include <string.h>

#include "internal.h"

/* ---- the words of a double ---- */

static uint64_t bits_of(double x) {
  uint64_t u;
  memcpy(&u, &x, sizeof u);
  return u;
}
static double double_of(uint64_t u) {
  double x;
  memcpy(&x, &u, sizeof x);
  return x;
}
/* The high word (sign, exponent, top 20 bits of the mantissa). */
static uint32_t high_word(double x) { return (uint32_t)(bits_of(x) >> 32); }
static uint32_t low_word(double x) { return (uint32_t)bits_of(x); }
/* The high word as fdlibm's int32_t reads it (negative for a negative x):
 * two's complement spelled out, since converting a uint32_t above
 * INT32_MAX to int32_t is implementation-defined in C99. */
static int32_t sign_high(double x) {
  uint32_t h = high_word(x);
  return (h & 0x80000000u) ? -(int32_t)(~h & 0x7fffffffu) - 1 : (int32_t)h;
}
/* x with its high word replaced by h, its low word kept. */
static double with_high(double x, uint32_t h) {
  return double_of(((uint64_t)h << 32) | (bits_of(x) & 0xffffffffu));
}
/* 2^k for -1022 <= k <= 1023: the exponent field alone (fdlibm's
 * INSERT_WORDS(twopk, 0x3ff00000 + (k << 20), 0) without shifting a
 * negative int). */
static double pow2(int k) { return double_of((uint64_t)(0x3ff + k) << 52); }
static int is_nan(double x) { return (bits_of(x) << 1) > (UINT64_C(0x7ff) << 53); }
static double quiet_nan(void) { return double_of(UINT64_C(0x7ff8000000000000)); }

/* ---- the constants (fdlibm's hexadecimal words; decimal in the comments) ---- */

static const double ln2_hi = 0x1.62e42fee00000p-1;       /* 6.93147180369123816490e-01: k ln2_hi exact, |k| < 2000 */
static const double ln2_lo = 0x1.a39ef35793c76p-33;      /* 1.90821492927058770002e-10 */
static const double invln2 = 0x1.71547652b82fep+0;       /* 1.44269504088896338700e+00 */
static const double o_threshold = 0x1.62e42fefa39efp+9;  /* 7.09782712893383973096e+02: e^x overflows above */
static const double u_threshold = -0x1.74910d52d3051p+9; /* -7.45133219101941108420e+02: e^x underflows below */
static const double two54 = 0x1p54;                      /* 1.80143985094819840000e+16 */

/* exp: R(z) = r (e^r + 1) / (e^r - 1) ~ 2 + P1 z + ... + P5 z^5, z = r^2 (error <= 2^-59) */
static const double P1 = 0x1.555555555553ep-3;  /* 1.66666666666666019037e-01 */
static const double P2 = -0x1.6c16c16bebd93p-9; /* -2.77777777770155933842e-03 */
static const double P3 = 0x1.1566aaf25de2cp-14; /* 6.61375632143793436117e-05 */
static const double P4 = -0x1.bbd41c5d26bf1p-20; /* -1.65339022054652515390e-06 */
static const double P5 = 0x1.6376972bea4d0p-25; /* 4.13813679705723846039e-08 */

/* expm1: R1 ~ 1 + Q1 z + ... + Q5 z^5 with z = r^2 / 2 (fdlibm's Qn scaled by 2^n; error <= 2^-61) */
static const double Q1 = -0x1.11111111110f4p-5;  /* -3.33333333333331316428e-02 */
static const double Q2 = 0x1.a01a019fe5585p-10;  /* 1.58730158725481460165e-03 */
static const double Q3 = -0x1.4ce199eaadbb7p-14; /* -7.93650757867487942473e-05 */
static const double Q4 = 0x1.0cfca86e65239p-18; /* 4.00821782732936239552e-06 */
static const double Q5 = -0x1.afdb76e09c32dp-23; /* -2.01099218183624371326e-07 */

/* log and log1p: log(1 + f) = 2s + s R(s^2), s = f / (2 + f), R(z) ~ Lg1 z + ... + Lg7 z^7
 * (error <= 2^-58.45); s_log1p.c's Lp1..Lp7 are the same numbers */
static const double Lg1 = 0x1.5555555555593p-1; /* 6.666666666666735130e-01 */
static const double Lg2 = 0x1.999999997fa04p-2; /* 3.999999999940941908e-01 */
static const double Lg3 = 0x1.2492494229359p-2; /* 2.857142874366239149e-01 */
static const double Lg4 = 0x1.c71c51d8e78afp-3; /* 2.222219843214978396e-01 */
static const double Lg5 = 0x1.7466496cb03dep-3; /* 1.818357216161805012e-01 */
static const double Lg6 = 0x1.39a09d078c69fp-3; /* 1.531383769920937332e-01 */
static const double Lg7 = 0x1.2f112df3e5244p-3; /* 1.479819860511658591e-01 */

/* ---- exp (e_exp.c) ----
 * 1. x = k ln2 + r, |r| <= ln2 / 2, r as hi - lo;
 * 2. e^r = 1 + r + r c / (2 - c), c = r - (P1 r^2 + ... + P5 r^10);
 * 3. e^x = 2^k e^r. */
double ball__exp(double x) {
  static const double ln2HI[2] = {0x1.62e42fee00000p-1, -0x1.62e42fee00000p-1}; /* +-ln2_hi */
  static const double ln2LO[2] = {0x1.a39ef35793c76p-33, -0x1.a39ef35793c76p-33}; /* +-ln2_lo */
  static const double halF[2] = {0.5, -0.5};
  double y, hi = 0.0, lo = 0.0, c, t;
  int k = 0, xsb;
  uint32_t hx = high_word(x);
  xsb = (int)(hx >> 31); /* sign bit of x */
  hx &= 0x7fffffffu;     /* high word of |x| */

  /* non-finite or huge arguments */
  if (hx >= 0x40862E42u) { /* |x| >= 709.78... */
    if (hx >= 0x7ff00000u) {
      if (((hx & 0xfffffu) | low_word(x)) != 0) return x + x; /* NaN */
      return xsb == 0 ? x : 0.0;                              /* exp(+Inf) = +Inf, exp(-Inf) = +0 */
    }
    if (x > o_threshold) return INFINITY; /* overflow */
    if (x < u_threshold) return 0.0;      /* underflow */
  }

  /* argument reduction */
  if (hx > 0x3fd62e42u) {   /* |x| > ln2 / 2 */
    if (hx < 0x3FF0A2B2u) { /* and |x| < 1.5 ln2 */
      hi = x - ln2HI[xsb];
      lo = ln2LO[xsb];
      k = 1 - xsb - xsb;
    } else {
      k = (int)(invln2 * x + halF[xsb]);
      t = k;
      hi = x - t * ln2HI[0]; /* t ln2HI is exact here */
      lo = t * ln2LO[0];
    }
    x = hi - lo;
  } else if (hx < 0x3e300000u) { /* |x| < 2^-28 */
    return 1.0 + x;
  } else {
    k = 0;
  }

  /* x is now in the primary range */
  t = x * x;
  c = x - t * (P1 + t * (P2 + t * (P3 + t * (P4 + t * P5))));
  if (k == 0) return 1.0 - ((x * c) / (c - 2.0) - x);
  y = 1.0 - ((lo - (x * c) / (2.0 - c)) - hi);
  if (k >= -1021) {
    if (k == 1024) return y * 2.0 * 0x1p1023;
    return y * pow2(k);
  }
  return y * pow2(k + 1000) * 0x1p-1000; /* a subnormal result: rounded once, by the last product */
}

/* ---- expm1 (s_expm1.c) ----
 * 1. x = k ln2 + r, |r| <= ln2 / 2, with c the rounding error of r;
 * 2. expm1(r) = r + r^2 / 2 + r^3 / 2 [3 - (R1 + R1 r / 2)] / [6 - r (3 - R1 r / 2)];
 * 3. expm1(x) = 2^k [expm1(r) + 1] - 1, or 2^k [expm1(r) + (1 - 2^-k)]. */
double ball__expm1(double x) {
  double y, hi, lo, c = 0.0, t, e, hxs, hfx, r1;
  int k;
  uint32_t hx = high_word(x), xsb = hx & 0x80000000u; /* sign bit of x */
  hx &= 0x7fffffffu;                                   /* high word of |x| */

  /* huge and non-finite arguments */
  if (hx >= 0x4043687Au) {   /* |x| >= 56 ln2 */
    if (hx >= 0x40862E42u) { /* |x| >= 709.78... */
      if (hx >= 0x7ff00000u) {
        if (((hx & 0xfffffu) | low_word(x)) != 0) return x + x; /* NaN */
        return xsb == 0 ? x : -1.0;                             /* expm1(+Inf) = +Inf, expm1(-Inf) = -1 */
      }
      if (x > o_threshold) return INFINITY; /* overflow */
    }
    if (xsb != 0) return -1.0; /* x < -56 ln2: e^x < 2^-56, -1 is the nearest double */
  }

  /* argument reduction */
  if (hx > 0x3fd62e42u) {   /* |x| > ln2 / 2 */
    if (hx < 0x3FF0A2B2u) { /* and |x| < 1.5 ln2 */
      if (xsb == 0) {
        hi = x - ln2_hi;
        lo = ln2_lo;
        k = 1;
      } else {
        hi = x + ln2_hi;
        lo = -ln2_lo;
        k = -1;
      }
    } else {
      k = (int)(invln2 * x + (xsb == 0 ? 0.5 : -0.5));
      t = k;
      hi = x - t * ln2_hi; /* t ln2_hi is exact here */
      lo = t * ln2_lo;
    }
    x = hi - lo;
    c = (hi - x) - lo;
  } else if (hx < 0x3c900000u) { /* |x| < 2^-54: x itself, -0 and subnormals included */
    return x;
  } else {
    k = 0;
  }

  /* x is now in the primary range */
  hfx = 0.5 * x;
  hxs = x * hfx;
  r1 = 1.0 + hxs * (Q1 + hxs * (Q2 + hxs * (Q3 + hxs * (Q4 + hxs * Q5))));
  t = 3.0 - r1 * hfx;
  e = hxs * ((r1 - t) / (6.0 - x * t));
  if (k == 0) return x - (x * e - hxs); /* c is 0 */
  e = (x * (e - c) - c);
  e -= hxs;
  if (k == -1) return 0.5 * (x - e) - 0.5;
  if (k == 1) {
    if (x < -0.25) return -2.0 * (e - (x + 0.5));
    return 1.0 + 2.0 * (x - e);
  }
  if (k <= -2 || k > 56) { /* e^x - 1 is enough */
    y = 1.0 - (e - x);
    if (k == 1024)
      y = y * 2.0 * 0x1p1023;
    else
      y = y * pow2(k);
    return y - 1.0;
  }
  if (k < 20) {
    t = double_of((uint64_t)(0x3ff00000u - (0x200000u >> k)) << 32); /* 1 - 2^-k */
    y = t - (e - x);
    y = y * pow2(k);
  } else {
    t = double_of((uint64_t)((uint32_t)(0x3ff - k) << 20) << 32); /* 2^-k */
    y = x - (e + t);
    y += 1.0;
    y = y * pow2(k);
  }
  return y;
}

/* ---- log (e_log.c) ----
 * 1. x = 2^k (1 + f), sqrt(2)/2 < 1 + f < sqrt(2);
 * 2. log(1 + f) = f - s (f - R) or f - (hfsq - s (hfsq + R)), s = f / (2 + f), hfsq = f^2 / 2;
 * 3. log(x) = k ln2_hi + (log(1 + f) + k ln2_lo). */
double ball__log(double x) {
  double hfsq, f, s, z, R, w, t1, t2, dk;
  int32_t k = 0, hx = sign_high(x), i, j;
  uint32_t lx = low_word(x);

  if (hx < 0x00100000) { /* x < 2^-1022: subnormal, zero, negative */
    if ((((uint32_t)hx & 0x7fffffffu) | lx) == 0) return -INFINITY; /* log(+-0) = -Inf */
    if (hx < 0) return is_nan(x) ? x + x : quiet_nan();            /* log(x < 0) = NaN */
    k -= 54;
    x *= two54; /* a subnormal, scaled up */
    hx = sign_high(x);
  }
  if (hx >= 0x7ff00000) return x + x; /* +Inf, NaN */
  k += (hx >> 20) - 1023;
  hx &= 0x000fffff;
  i = (hx + 0x95f64) & 0x100000;
  x = with_high(x, (uint32_t)(hx | (i ^ 0x3ff00000))); /* x or x / 2 normalised */
  k += (i >> 20);
  f = x - 1.0;
  if ((0x000fffff & (2 + hx)) < 3) { /* -2^-20 <= f < 2^-20 */
    if (f == 0.0) {
      if (k == 0) return 0.0; /* log(1) = +0 */
      dk = (double)k;
      return dk * ln2_hi + dk * ln2_lo;
    }
    R = f * f * (0.5 - 0.33333333333333333 * f);
    if (k == 0) return f - R;
    dk = (double)k;
    return dk * ln2_hi - ((R - dk * ln2_lo) - f);
  }
  s = f / (2.0 + f);
  dk = (double)k;
  z = s * s;
  i = hx - 0x6147a;
  w = z * z;
  j = 0x6b851 - hx;
  t1 = w * (Lg2 + w * (Lg4 + w * Lg6));
  t2 = z * (Lg1 + w * (Lg3 + w * (Lg5 + w * Lg7)));
  i |= j;
  R = t2 + t1;
  if (i > 0) { /* f not small: the more accurate form */
    hfsq = 0.5 * f * f;
    if (k == 0) return f - (hfsq - s * (hfsq + R));
    return dk * ln2_hi - ((hfsq - (s * (hfsq + R) + dk * ln2_lo)) - f);
  }
  if (k == 0) return f - s * (f - R);
  return dk * ln2_hi - ((s * (f - R) - dk * ln2_lo) - f);
}

/* ---- log1p (s_log1p.c) ----
 * 1. 1 + x = 2^k (1 + f), sqrt(2)/2 < 1 + f < sqrt(2); when k != 0, u = 1 + x
 *    rounded and the correction c = ((1 + x) - u) / u;
 * 2. log(1 + f) = f - (hfsq - s (hfsq + R)) as for log;
 * 3. log1p(x) = k ln2_hi + (log(1 + f) + (k ln2_lo + c)). */
double ball__log1p(double x) {
  double hfsq, f = 0.0, c = 0.0, s, z, R, u;
  int32_t k = 1, hx = sign_high(x), hu = 0, ax = hx & 0x7fffffff;

  if (hx < 0x3FDA827A) {      /* 1 + x < sqrt(2)+ */
    if (ax >= 0x3ff00000) {   /* x <= -1 (or a negative NaN) */
      if (x == -1.0) return -INFINITY;              /* log1p(-1) = -Inf */
      return is_nan(x) ? x + x : quiet_nan();       /* log1p(x < -1) = NaN */
    }
    if (ax < 0x3e200000) {    /* |x| < 2^-29 */
      if (ax < 0x3c900000) return x; /* |x| < 2^-54: x itself, -0 and subnormals included */
      return x - x * x * 0.5;
    }
    if (hx > 0 || hx <= -0x402d413c) { /* hx <= (int32_t)0xbfd2bec4: sqrt(2)/2- <= 1 + x < sqrt(2)+ */
      k = 0;
      f = x;
      hu = 1;
    }
  }
  if (hx >= 0x7ff00000) return x + x; /* +Inf, NaN */
  if (k != 0) {
    if (hx < 0x43400000) { /* x < 2^53 */
      u = 1.0 + x;
      hu = sign_high(u);
      k = (hu >> 20) - 1023;
      c = (k > 0) ? 1.0 - (u - x) : x - (u - 1.0); /* correction term */
      c /= u;
    } else {
      u = x;
      hu = sign_high(u);
      k = (hu >> 20) - 1023;
      c = 0.0;
    }
    hu &= 0x000fffff;
    /* the sqrt(2) of this test is stricter than those above, so that k = 0 is never reached here
     * (the correction term c is committed to) */
    if (hu < 0x6a09e) { /* u ~< sqrt(2) */
      u = with_high(u, (uint32_t)(hu | 0x3ff00000)); /* u normalised */
    } else {
      k += 1;
      u = with_high(u, (uint32_t)(hu | 0x3fe00000)); /* u / 2 normalised */
      hu = (0x00100000 - hu) >> 2;
    }
    f = u - 1.0;
  }
  hfsq = 0.5 * f * f;
  if (hu == 0) { /* |f| < 2^-20 */
    if (f == 0.0) {
      if (k == 0) return 0.0;
      c += k * ln2_lo;
      return k * ln2_hi + c;
    }
    R = hfsq * (1.0 - 0.66666666666666666 * f);
    if (k == 0) return f - R;
    return k * ln2_hi - ((R - (k * ln2_lo + c)) - f);
  }
  s = f / (2.0 + f);
  z = s * s;
  R = z * (Lg1 + z * (Lg2 + z * (Lg3 + z * (Lg4 + z * (Lg5 + z * (Lg6 + z * Lg7))))));
  if (k == 0) return f - (hfsq - s * (hfsq + R));
  return k * ln2_hi - ((hfsq - (s * (hfsq + R) + (k * ln2_lo + c))) - f);
}
