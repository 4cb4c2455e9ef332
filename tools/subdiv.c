/* subdiv: write a denser copy of an OBJ model, for the benchmark's
 * many-triangle case (make bench builds it and writes into /tmp; the
 * output is never committed). Each triangle (polygons are fanned) becomes
 * six around its centroid, through the midpoints of its edges; a midpoint
 * is shared by the two triangles of its edge, so the result is one
 * connected mesh like a scan, not copies. The dragon's 871,414 triangles
 * become 5,228,484.
 *
 *   subdiv IN.obj OUT.obj
 *
 * Only v and f lines are read (v/vt/vn corners and negative indices
 * allowed); faces keep their order and winding, so the output's face
 * order is as local as the input's. */

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    float   *v;                 /* 3 per vertex */
    uint32_t nv, cap;
} Verts;

typedef struct {
    uint64_t *key;              /* edge (lo << 32 | hi) + 1, 0 = empty */
    uint32_t *mid;              /* its midpoint's vertex index */
    uint64_t  mask;
} EdgeMap;

static void *xrealloc(void *p, size_t n)
{
    void *q = realloc(p, n);
    if (!q) {
        fprintf(stderr, "subdiv: out of memory\n");
        exit(1);
    }
    return q;
}

static uint32_t vert_add(Verts *vs, float x, float y, float z)
{
    if (vs->nv == vs->cap) {
        vs->cap = vs->cap ? vs->cap * 2 : 1024;
        vs->v = xrealloc(vs->v, (size_t)vs->cap * 3 * sizeof *vs->v);
    }
    float *d = vs->v + 3 * (size_t)vs->nv;
    d[0] = x;
    d[1] = y;
    d[2] = z;
    return vs->nv++;
}

/* The midpoint of edge a-b, made on first use. */
static uint32_t midpoint(EdgeMap *em, Verts *vs, uint32_t a, uint32_t b)
{
    uint32_t lo = a < b ? a : b, hi = a < b ? b : a;
    uint64_t key = ((uint64_t)lo << 32 | hi) + 1;
    uint64_t h = (key * 0x9e3779b97f4a7c15ULL) >> 20;
    for (;; h++) {
        uint64_t i = h & em->mask;
        if (em->key[i] == key)
            return em->mid[i];
        if (!em->key[i]) {
            const float *p = vs->v + 3 * (size_t)a, *q = vs->v + 3 * (size_t)b;
            em->key[i] = key;
            em->mid[i] = vert_add(vs, 0.5f * (p[0] + q[0]), 0.5f * (p[1] + q[1]), 0.5f * (p[2] + q[2]));
            return em->mid[i];
        }
    }
}

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: subdiv IN.obj OUT.obj\n");
        return 2;
    }
    FILE *in = fopen(argv[1], "r");
    if (!in) {
        perror(argv[1]);
        return 1;
    }
    Verts vs = { 0 };
    uint32_t *tri = NULL;       /* 3 per input triangle, 0-based */
    size_t ntri = 0, cap_tri = 0;
    char line[4096];
    while (fgets(line, sizeof line, in)) {
        if (line[0] == 'v' && line[1] == ' ') {
            float x, y, z;
            if (sscanf(line + 2, "%f %f %f", &x, &y, &z) == 3)
                vert_add(&vs, x, y, z);
        } else if (line[0] == 'f' && line[1] == ' ') {
            uint32_t c[64];
            int n = 0;
            char *p = line + 2;
            while (n < 64) {
                char *end;
                long k = strtol(p, &end, 10);
                if (end == p)
                    break;
                c[n++] = (uint32_t)(k < 0 ? (long)vs.nv + k : k - 1);
                p = end;
                while (*p && *p != ' ' && *p != '\t' && *p != '\n')
                    p++;        /* skip /vt/vn */
            }
            for (int k = 1; k + 1 < n; k++) {
                if (ntri == cap_tri) {
                    cap_tri = cap_tri ? cap_tri * 2 : 1024;
                    tri = xrealloc(tri, cap_tri * 3 * sizeof *tri);
                }
                tri[3 * ntri] = c[0];
                tri[3 * ntri + 1] = c[k];
                tri[3 * ntri + 2] = c[k + 1];
                ntri++;
            }
        }
    }
    fclose(in);
    uint32_t nv0 = vs.nv;
    for (size_t i = 0; i < 3 * ntri; i++)
        if (tri[i] >= nv0) {
            fprintf(stderr, "subdiv: %s: a face refers to a missing vertex\n", argv[1]);
            return 1;
        }
    EdgeMap em;
    uint64_t slots = 1;
    while (slots < 3 * (uint64_t)ntri)
        slots *= 2;
    em.mask = slots - 1;
    em.key = calloc(slots, sizeof *em.key);
    em.mid = malloc(slots * sizeof *em.mid);
    uint32_t *out = malloc(ntri * 18 * sizeof *out);
    if (!em.key || !em.mid || !out) {
        fprintf(stderr, "subdiv: out of memory\n");
        return 1;
    }
    for (size_t t = 0; t < ntri; t++) {
        uint32_t a = tri[3 * t], b = tri[3 * t + 1], c = tri[3 * t + 2];
        uint32_t ab = midpoint(&em, &vs, a, b), bc = midpoint(&em, &vs, b, c), ca = midpoint(&em, &vs, c, a);
        const float *p = vs.v + 3 * (size_t)a, *q = vs.v + 3 * (size_t)b, *r = vs.v + 3 * (size_t)c;
        uint32_t g = vert_add(&vs, (p[0] + q[0] + r[0]) / 3, (p[1] + q[1] + r[1]) / 3, (p[2] + q[2] + r[2]) / 3);
        uint32_t six[18] = { a, ab, g, ab, b, g, b, bc, g, bc, c, g, c, ca, g, ca, a, g };
        memcpy(out + 18 * t, six, sizeof six);
    }
    FILE *f = fopen(argv[2], "w");
    if (!f) {
        perror(argv[2]);
        return 1;
    }
    fprintf(f, "# %s subdivided: each triangle into six (zview tools/subdiv.c)\n", argv[1]);
    for (uint32_t i = 0; i < vs.nv; i++)
        fprintf(f, "v %.7g %.7g %.7g\n", vs.v[3 * (size_t)i], vs.v[3 * (size_t)i + 1], vs.v[3 * (size_t)i + 2]);
    for (size_t i = 0; i < 6 * ntri; i++)
        fprintf(f, "f %u %u %u\n", out[3 * i] + 1, out[3 * i + 1] + 1, out[3 * i + 2] + 1);
    if (fflush(f) != 0 || ferror(f) || fclose(f) != 0) {
        perror(argv[2]);
        return 1;
    }
    fprintf(stderr, "subdiv: %u vertices, %zu triangles -> %s\n", vs.nv, 6 * ntri, argv[2]);
    return 0;
}
