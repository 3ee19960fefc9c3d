/* The firmware's cosine as docs/models/README.md#firmware-cosine describes it, written from that text: only +, -, *, /
 * in double, in this order, no fused multiply-add (-ffp-contract=off). The outside controller's (C11); also
 * compiled by outside_cos_test.cpp, which compares it with the firmware's own over many arguments. The arguments
 * here are precession angles (|x| < pi/2); the documented reduction covers |x| < 823549. */
#ifndef GYROSTAB_INTEROP_OUTSIDE_COS_H
#define GYROSTAB_INTEROP_OUTSIDE_COS_H

#include <math.h>


static double outside_horner(double x, const double* c, int n) {
  double r = c[n - 1];
  for (int i = n - 2; i >= 0; --i) r = c[i] + x * r;
  return r;
}

static double outside_sin_kernel(double hi, double lo) {
  static const double k[] = {-0x1.5555555555555p-3,  0x1.1111111111111p-7,  -0x1.a01a01a01a01ap-13,
                             0x1.71de3a556c734p-19,  -0x1.ae64567f544e4p-26, 0x1.6124613a86d09p-33,
                             -0x1.ae7f3e733b81fp-41, 0x1.952c77030ad4ap-49};
  const double z = hi * hi;
  const double s = outside_horner(z, k, 8);
  return hi + ((hi * z) * s + lo * (1.0 - 0.5 * z));
}

static double outside_cos_kernel(double hi, double lo) {
  static const double k[] = {0x1.5555555555555p-5,  -0x1.6c16c16c16c17p-10, 0x1.a01a01a01a01ap-16,
                             -0x1.27e4fb7789f5cp-22, 0x1.1eed8eff8d898p-29, -0x1.93974a8c07c9dp-37,
                             0x1.ae7f3e733b81fp-45,  -0x1.6827863b97d97p-53};
  const double z = hi * hi;
  const double c = outside_horner(z, k, 8);
  const double hz = 0.5 * z;
  const double w = 1.0 - hz;
  return w + (((1.0 - w) - hz) + ((z * z) * c - hi * lo));
}

static void outside_two_sum(double a, double b, double* s, double* err) {
  *s = a + b;
  const double bb = *s - a;
  *err = (a - (*s - bb)) + (b - bb);
}

static double outside_cos(double x) {
  if (x != x) return x;
  const double ax = fabs(x);
  if (ax == INFINITY || ax >= 823549.0) return NAN; /* beyond the documented reduction: never a case angle */
  if (ax < 0x1p-27) return 1.0;
  int quadrant = 0;
  double hi = ax, lo = 0.0;
  if (ax > 0x1.921fb54442d18p-1) { /* pi/4 */
    const double kd = (ax * 0x1.45f306dc9c883p-1 + 0x1.8p52) - 0x1.8p52;
    const double t = ax - kd * 0x1.921fb544p+0;
    double ahi, alo, bhi, blo;
    outside_two_sum(t, -(kd * 0x1.0b4611a6p-34), &ahi, &alo);
    outside_two_sum(ahi, -(kd * 0x1.3198a2e037073p-69), &bhi, &blo);
    const double b = blo + alo;
    hi = bhi + b;
    lo = b - (hi - bhi);
    quadrant = (int)kd & 3;
  }
  switch (quadrant) {
    case 0: return outside_cos_kernel(hi, lo);
    case 1: return -outside_sin_kernel(hi, lo);
    case 2: return -outside_cos_kernel(hi, lo);
    default: return outside_sin_kernel(hi, lo);
  }
}

#endif
