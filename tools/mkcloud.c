/* mkcloud.c: a synthetic scan for the point-cloud benchmark and the
 * README's capture. Loads a model and writes a binary little-endian PLY
 * point cloud (x y z float, red green blue uchar):
 *
 *   mkcloud MODEL OUT.ply N [sorted]
 *                               N points spread over the surface by area
 *                               (a seeded generator: the same file each
 *                               time), coloured by their face's normal;
 *                               in random order (the worst case for the
 *                               one-per-box pass: no two neighbours in
 *                               the file land near each other), or
 *                               sorted along the model's triangles, as
 *                               a scanner sweeps a surface
 *   mkcloud MODEL OUT.ply 0     the model's vertices, no colour
 *
 * Built and run by make bench-points (tools/bench-points.sh). */

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mesh.h"

static uint64_t rng_state = 0x9E3779B97F4A7C15ull;

static double urand(void)
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 7;
    rng_state ^= rng_state << 17;
    return (double)(rng_state >> 11) / 9007199254740992.0;
}

typedef struct {
    uint32_t a, b, c;       /* the triangle's vertices (a fan of its face) */
} Tri;

static void put_point(FILE *f, const float p[3], const unsigned char rgb[3])
{
    unsigned char rec[15];
    memcpy(rec, p, 12);         /* little-endian hosts only: the benchmark's */
    memcpy(rec + 12, rgb, 3);
    fwrite(rec, 1, sizeof rec, f);
}

int main(int argc, char **argv)
{
    if (argc != 4 && !(argc == 5 && !strcmp(argv[4], "sorted"))) {
        fprintf(stderr, "usage: mkcloud MODEL OUT.ply N [sorted]\n");
        return 2;
    }
    int sorted = argc == 5;
    Mesh m;
    char err[512];
    if (mesh_load(&m, argv[1], err, sizeof err)) {
        fprintf(stderr, "mkcloud: %s\n", err);
        return 1;
    }
    unsigned long long n = strtoull(argv[3], NULL, 10);
    uint64_t count = n ? n : m.nverts;
    FILE *f = fopen(argv[2], "wb");
    if (!f) {
        perror(argv[2]);
        return 1;
    }
    fprintf(f, "ply\nformat binary_little_endian 1.0\ncomment mkcloud %s\nelement vertex %llu\n"
               "property float x\nproperty float y\nproperty float z\n%send_header\n",
            argv[1], (unsigned long long)count,
            n ? "property uchar red\nproperty uchar green\nproperty uchar blue\n" : "");
    if (!n) {
        /* positions only: zview shades an uncoloured cloud by depth */
        for (uint32_t v = 0; v < m.nverts; v++)
            fwrite(&m.pos[3 * (size_t)v], 4, 3, f);
    } else {
        /* triangles and their cumulative areas */
        size_t ntri = 0;
        for (uint32_t k = 0; k < m.nfaces; k++)
            ntri += m.face_start[k + 1] - m.face_start[k] - 2;
        Tri *tri = malloc((ntri ? ntri : 1) * sizeof *tri);
        double *cum = malloc((ntri ? ntri : 1) * sizeof *cum);
        if (!tri || !cum || !ntri) {
            fprintf(stderr, "mkcloud: no triangles, or out of memory\n");
            return 1;
        }
        size_t t = 0;
        double total = 0;
        for (uint32_t k = 0; k < m.nfaces; k++)
            for (uint32_t c = m.face_start[k] + 1; c + 1 < m.face_start[k + 1]; c++) {
                Tri r = { m.corner[m.face_start[k]], m.corner[c], m.corner[c + 1] };
                const float *a = &m.pos[3 * (size_t)r.a], *b = &m.pos[3 * (size_t)r.b], *d = &m.pos[3 * (size_t)r.c];
                double u[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] }, w[3] = { d[0] - a[0], d[1] - a[1], d[2] - a[2] };
                double x = u[1] * w[2] - u[2] * w[1], y = u[2] * w[0] - u[0] * w[2], z = u[0] * w[1] - u[1] * w[0];
                total += 0.5 * sqrt(x * x + y * y + z * z);
                tri[t] = r;
                cum[t++] = total;
            }
        /* sorted: the order statistics of N uniform variates, as the
         * running sums of N + 1 exponential ones over their total (one
         * pass for the total, the same seed again for the points) */
        double esum = 0, acc = 0;
        uint64_t seed = rng_state;
        if (sorted) {
            for (uint64_t i = 0; i <= count; i++)
                esum += -log(1 - urand());
            rng_state = seed;
        }
        size_t walk = 0;
        for (uint64_t i = 0; i < count; i++) {
            double at;
            if (sorted) {
                acc += -log(1 - urand());
                at = acc / esum * total;
            } else {
                at = urand() * total;
            }
            size_t lo = sorted ? walk : 0, hi = ntri - 1;
            while (lo < hi) {
                size_t mid = (lo + hi) / 2;
                if (cum[mid] < at)
                    lo = mid + 1;
                else
                    hi = mid;
            }
            walk = lo;
            const Tri *r = &tri[lo];
            const float *a = &m.pos[3 * (size_t)r->a], *b = &m.pos[3 * (size_t)r->b], *d = &m.pos[3 * (size_t)r->c];
            double s = urand(), q = urand();
            if (s + q > 1) {
                s = 1 - s;
                q = 1 - q;
            }
            float p[3];
            double nrm[3] = { (b[1] - a[1]) * (d[2] - a[2]) - (b[2] - a[2]) * (d[1] - a[1]),
                              (b[2] - a[2]) * (d[0] - a[0]) - (b[0] - a[0]) * (d[2] - a[2]),
                              (b[0] - a[0]) * (d[1] - a[1]) - (b[1] - a[1]) * (d[0] - a[0]) };
            double len = sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
            unsigned char rgb[3];
            for (int k = 0; k < 3; k++) {
                p[k] = (float)(a[k] + s * (b[k] - a[k]) + q * (d[k] - a[k]));
                double c = len > 0 ? nrm[k] / len : 0;
                rgb[k] = (unsigned char)lround(150 + 100 * c);
            }
            put_point(f, p, rgb);
        }
        free(tri);
        free(cum);
    }
    if (fclose(f) != 0) {
        perror(argv[2]);
        return 1;
    }
    mesh_free(&m);
    return 0;
}
