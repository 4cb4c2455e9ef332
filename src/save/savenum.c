/* savenum.c: numbers as text for the text formats: a float as the
 * shortest decimal that reads back to it, an index in decimal.
 *
 * A float has a 24-bit significand, so 9 significant digits always
 * bring it back (the decimal's rounding error, at most 5e-9 of the
 * value, is well inside the half gap to the next float, at least
 * 2^-25 = 2.98e-8 of it); fewer digits often do. For p = 1, 2, ... the
 * value rounded to p digits is computed in double and kept when it lies
 * inside the float's rounding interval (between the midpoints to its
 * neighbours) with a margin far above double's error (a few 1e-16 of
 * the value), so that a correctly rounding reader (the project's own,
 * strtof) turns it back into x whatever the double arithmetic rounded.
 * The value is scaled to 9 digits once; the shorter ones are that
 * integer rounded, compared with the interval in the same units.
 * Close calls go on to more digits (9 digits never are one), but for a
 * decimal exactly halfway, computed exactly, which such a reader takes
 * to the neighbour whose last bit is 0. */

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "save.h"

/* 10^k for k in [-POW_LO, POW_HI]: doubles, exact up to 10^22, within
 * half an ulp beyond (the compiler rounds the literals). */
#define POW_LO 64
#define POW_HI 64

static double pow10_of(int k)
{
    static const double pos[] = {
        1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16,
        1e17, 1e18, 1e19, 1e20, 1e21, 1e22, 1e23, 1e24, 1e25, 1e26, 1e27, 1e28, 1e29, 1e30, 1e31, 1e32, 1e33,
        1e34, 1e35, 1e36, 1e37, 1e38, 1e39, 1e40, 1e41, 1e42, 1e43, 1e44, 1e45, 1e46, 1e47, 1e48, 1e49, 1e50,
        1e51, 1e52, 1e53, 1e54, 1e55, 1e56, 1e57, 1e58, 1e59, 1e60, 1e61, 1e62, 1e63, 1e64,
    };
    static const double neg[] = {
        1e0,   1e-1,  1e-2,  1e-3,  1e-4,  1e-5,  1e-6,  1e-7,  1e-8,  1e-9,  1e-10, 1e-11, 1e-12,
        1e-13, 1e-14, 1e-15, 1e-16, 1e-17, 1e-18, 1e-19, 1e-20, 1e-21, 1e-22, 1e-23, 1e-24, 1e-25,
        1e-26, 1e-27, 1e-28, 1e-29, 1e-30, 1e-31, 1e-32, 1e-33, 1e-34, 1e-35, 1e-36, 1e-37, 1e-38,
        1e-39, 1e-40, 1e-41, 1e-42, 1e-43, 1e-44, 1e-45, 1e-46, 1e-47, 1e-48, 1e-49, 1e-50, 1e-51,
        1e-52, 1e-53, 1e-54, 1e-55, 1e-56, 1e-57, 1e-58, 1e-59, 1e-60, 1e-61, 1e-62, 1e-63, 1e-64,
    };
    return k >= 0 ? pos[k] : neg[-k];
}

/* d * 10^k with one rounding where 10^k is exact (|k| <= 22: dividing
 * by 10^-k rather than multiplying by its inexact inverse). */
static double scale10(double d, int k)
{
    if (k >= 0)
        return d * pow10_of(k);
    if (k >= -22)
        return d / pow10_of(-k);
    return d * pow10_of(k);
}

int save_u32(char *buf, uint32_t v)
{
    char tmp[10];
    int n = 0;
    do {
        tmp[n++] = (char)('0' + v % 10);
        v /= 10;
    } while (v);
    for (int i = 0; i < n; i++)
        buf[i] = tmp[n - 1 - i];
    return n;
}

/* The digits of n (p of them, n < 10^p) with decimal exponent k (the
 * first digit's place), as %g would lay them out: fixed from 1e-4 up
 * to 1e9, else d.ddde+XX. Trailing zeros go. */
static int lay_out(char *buf, uint64_t n, int p, int k)
{
    char dig[20];
    for (int i = p - 1; i >= 0; i--) {
        dig[i] = (char)('0' + n % 10);
        n /= 10;
    }
    while (p > 1 && dig[p - 1] == '0')
        p--;
    int o = 0;
    if (k >= -5 && k < 9) {
        if (k < 0) {
            buf[o++] = '0';
            buf[o++] = '.';
            for (int i = -1; i > k; i--)
                buf[o++] = '0';
            memcpy(buf + o, dig, (size_t)p);
            return o + p;
        }
        for (int i = 0; i <= k; i++)
            buf[o++] = i < p ? dig[i] : '0';
        if (p > k + 1) {
            buf[o++] = '.';
            memcpy(buf + o, dig + k + 1, (size_t)(p - k - 1));
            o += p - k - 1;
        }
        return o;
    }
    buf[o++] = dig[0];
    if (p > 1) {
        buf[o++] = '.';
        memcpy(buf + o, dig + 1, (size_t)(p - 1));
        o += p - 1;
    }
    buf[o++] = 'e';
    buf[o++] = k < 0 ? '-' : '+';
    int e = k < 0 ? -k : k;
    if (e >= 10)
        buf[o++] = (char)('0' + e / 10);
    else
        buf[o++] = '0';
    buf[o++] = (char)('0' + e % 10);
    return o;
}

/* Is n (p digits, the first at place kk) exactly halfway to a
 * neighbour of ax, lo or hi, and so read as ax? Only where n * 10^q is
 * exact in double (an integer of 53 bits at most); elsewhere it is no
 * tie a double could see, and the caller takes more digits. */
static int tie_to_ax(uint64_t n, int p, int kk, float ax, double lo, double hi)
{
    int q = kk - (p - 1);
    if (q < 0 || q > 22)
        return 0;
    double back = (double)n * pow10_of(q);
    if (back > 9007199254740992.0 || (back != lo && back != hi))
        return 0;
    uint32_t bits;
    memcpy(&bits, &ax, 4);
    return (bits & 1) == 0;     /* halfway goes to the neighbour whose last bit is 0 */
}

int save_float(char *buf, float x)
{
    int o = 0;
    if (signbit(x))
        buf[o++] = '-';
    if (isnan(x) || isinf(x)) {
        memcpy(buf, isnan(x) ? "nan" : signbit(x) ? "-inf" : "inf", isnan(x) ? 3 : signbit(x) ? 4 : 3);
        return isnan(x) ? 3 : signbit(x) ? 4 : 3;
    }
    if (x == 0) {
        buf[o++] = '0';
        return o;
    }
    float ax = fabsf(x);
    double d = ax;
    /* the rounding interval: halfway to each neighbour (exact in double);
     * a positive float's neighbours are its bits less and plus one */
    uint32_t bits;
    memcpy(&bits, &ax, 4);
    float fb, fa;
    uint32_t b1 = bits - 1, a1 = bits + 1;
    memcpy(&fb, &b1, 4);
    memcpy(&fa, &a1, 4);
    double below = fb, above = fa;
    if (isinf(fa))              /* past FLT_MAX: the gap goes on, and its midpoint rounds to infinity */
        above = d + (d - below);
    double lo = (d + below) / 2, hi = (d + above) / 2;
    /* k, the first digit's place: from the binary exponent (floor of
     * its log10, within one), made exact by the 9-digit scaling landing
     * in [1e8, 1e9) */
    int e2 = (int)(bits >> 23) - 127;
    int k = e2 > -127 ? (int)floor(e2 * 0.30102999566398120) : (int)floor(log10(d));   /* subnormal: rare */
    double s9 = scale10(d, 8 - k);
    while (s9 >= 1e9)
        s9 = scale10(d, 8 - ++k);
    while (s9 < 1e8)
        s9 = scale10(d, 8 - --k);
    /* everything in units of the 9th digit: the value, the interval */
    double lo9 = scale10(lo, 8 - k), hi9 = scale10(hi, 8 - k), margin9 = s9 * 1e-13;
    uint64_t n9 = (uint64_t)nearbyint(s9);
    /* A normal float's rounding interval is at most 6e-8 of it wide on
     * each side, and decimals of 6 digits at least 1e-6 of it apart: of
     * those, only the nearest can be inside, and a shorter decimal
     * inside is one of them (its trailing zeros then go). A subnormal's
     * interval is wider: every length is tried. */
    for (int p = ax < FLT_MIN ? 1 : 6; p <= 9; p++) {
        /* n9 rounded to p digits, and its neighbour on the value's other
         * side: rounding twice may land one off the nearest */
        uint64_t q = (uint64_t)pow10_of(9 - p), n0 = (n9 + q / 2) / q;
        uint64_t cand[2] = { n0, (double)(n0 * q) < s9 ? n0 + 1 : n0 - 1 };
        for (int c = 0; c < 2; c++) {
            uint64_t n = cand[c];
            double v = (double)(n * q);     /* exact: at most 1e9 */
            int kk = k;
            int inside = v > lo9 + margin9 && v < hi9 - margin9;
            if (n >= (uint64_t)pow10_of(p)) {   /* 9.96 to 2 digits is 10: one place up */
                n /= 10;
                kk++;
            }
            if (!inside && n && (fabs(v - lo9) <= margin9 || fabs(v - hi9) <= margin9))
                inside = tie_to_ax(n, p, kk, ax, lo, hi);
            if (inside || (p == 9 && c == 1))
                return o + lay_out(buf + o, inside ? n : n9, p, inside ? kk : k);
        }
    }
    return o;   /* not reached */
}
