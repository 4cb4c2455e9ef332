/* perturb: write an edited copy of an OBJ model, for the --diff
 * benchmark (make bench-diff writes into /tmp; the output is never
 * committed). Every line is copied as it is but the vertices: each is
 * moved out from the model's centre by a bump, the vertices within
 * RADIUS (a fraction of the bounding box's diagonal) of the vertex in the
 * middle of the file (or vertex AT, counted from 1) raised by up to
 * AMOUNT of the diagonal, smoothly to nothing at the bump's edge; and
 * every vertex by a pseudo-random wobble of up to NOISE of the
 * diagonal, so that no distance is 0.
 *
 *   perturb IN.obj OUT.obj [AMOUNT [RADIUS [NOISE [AT]]]]
 *
 * Defaults: 0.01, 0.1, 0.0001. Only `v x y z` lines are changed. */

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int is_vertex(const char *line)
{
    return line[0] == 'v' && (line[1] == ' ' || line[1] == '\t');
}

int main(int argc, char **argv)
{
    if (argc < 3) {
        fprintf(stderr, "usage: perturb IN.obj OUT.obj [AMOUNT [RADIUS [NOISE [AT]]]]\n");
        return 2;
    }
    double amount = argc > 3 ? atof(argv[3]) : 0.01, radius = argc > 4 ? atof(argv[4]) : 0.1,
           noise = argc > 5 ? atof(argv[5]) : 0.0001;
    FILE *in = fopen(argv[1], "r");
    if (!in) {
        perror(argv[1]);
        return 1;
    }
    /* first pass: the box, the vertex count */
    static char line[1 << 16];
    double lo[3] = { INFINITY, INFINITY, INFINITY }, hi[3] = { -INFINITY, -INFINITY, -INFINITY };
    uint64_t nv = 0;
    while (fgets(line, sizeof line, in))
        if (is_vertex(line)) {
            double p[3];
            if (sscanf(line + 2, "%lf %lf %lf", &p[0], &p[1], &p[2]) != 3)
                continue;
            for (int k = 0; k < 3; k++) {
                lo[k] = fmin(lo[k], p[k]);
                hi[k] = fmax(hi[k], p[k]);
            }
            nv++;
        }
    double diag = sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                       (hi[2] - lo[2]) * (hi[2] - lo[2]));
    double c[3] = { (lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2 }, bump[3] = { 0, 0, 0 };
    /* the bump's centre: the middle vertex of the file, or AT */
    uint64_t at = argc > 6 && atoll(argv[6]) > 0 ? (uint64_t)atoll(argv[6]) - 1 : nv / 2;
    rewind(in);
    uint64_t k = 0;
    while (fgets(line, sizeof line, in))
        if (is_vertex(line) && k++ == at) {
            sscanf(line + 2, "%lf %lf %lf", &bump[0], &bump[1], &bump[2]);
            break;
        }
    FILE *out = fopen(argv[2], "w");
    if (!out) {
        perror(argv[2]);
        return 1;
    }
    rewind(in);
    uint64_t seed = 0x9E3779B97F4A7C15ull;
    double r = radius * diag;
    while (fgets(line, sizeof line, in)) {
        double p[3];
        if (!is_vertex(line) || sscanf(line + 2, "%lf %lf %lf", &p[0], &p[1], &p[2]) != 3) {
            fputs(line, out);
            continue;
        }
        double d2 = 0, out_dir[3], len = 0;
        for (int i = 0; i < 3; i++) {
            d2 += (p[i] - bump[i]) * (p[i] - bump[i]);
            out_dir[i] = p[i] - c[i];
            len += out_dir[i] * out_dir[i];
        }
        len = sqrt(len);
        double t = d2 < r * r ? 1 - d2 / (r * r) : 0, lift = amount * diag * t * t;
        for (int i = 0; i < 3; i++) {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            double wobble = ((double)(seed >> 11) / 9007199254740992.0 * 2 - 1) * noise * diag;
            p[i] += (len > 0 ? out_dir[i] / len * lift : 0) + wobble;
        }
        fprintf(out, "v %.7g %.7g %.7g\n", p[0], p[1], p[2]);
    }
    if (ferror(in) || fclose(out)) {
        fprintf(stderr, "perturb: %s: write failed\n", argv[2]);
        return 1;
    }
    fclose(in);
    return 0;
}
