/* checkwhere.c: where --check found each problem (CheckLocations), in
 * its two reports: the text report's lines under each count (the first
 * few of each kind, in file units), and the "locations" member of each
 * object in --json (of each kind its full count and the first
 * --max-locations). Faces are named by their index in the file (from 0,
 * in file order across objects), points by their coordinates. */

#include <stdio.h>
#include <string.h>

#include "meshcheck.h"
#include "oneshot.h"

/* ==== Text ==== */

/* " (x y z)" of p into buf at *len. */
static void put_point(char *buf, size_t n, size_t *len, const float *p)
{
    if (*len + 1 >= n)
        return;
    int w = snprintf(buf + *len, n - *len, " (%g %g %g)", p[0], p[1], p[2]);
    *len = w > 0 && *len + (size_t)w < n ? *len + (size_t)w : n - 1;
}

static void put_text(char *buf, size_t n, size_t *len, const char *fmt, unsigned long long v)
{
    if (*len + 1 >= n)
        return;
    int w = snprintf(buf + *len, n - *len, fmt, v);
    *len = w > 0 && *len + (size_t)w < n ? *len + (size_t)w : n - 1;
}

/* Item i of kind k in words: "hole 1: 4 edges, perimeter 4 mm, through
 * (0 1 0) (1 1 0) (1 1 1) ...". */
static void item_text(const CheckLocations *l, CheckLocKind k, uint32_t i, const char *unit, char *buf, size_t n)
{
    size_t len = 0;
    buf[0] = 0;
    switch (k) {
    case CHECK_LOC_HOLES: {
        uint32_t s = l->loop_start[i], e = l->loop_start[i + 1];
        int w = snprintf(buf, n, "hole %u: %u edges, perimeter %g%s%s, through", i + 1, e - s, l->loop_length[i],
                         unit[0] ? " " : "", unit);
        len = w > 0 && (size_t)w < n ? (size_t)w : n - 1;
        for (uint32_t p = s; p < e && p < s + 3; p++)
            put_point(buf, n, &len, l->loop_pt + 3 * (size_t)p);
        if (e - s > 3)
            put_text(buf, n, &len, " ...", 0);
        break;
    }
    case CHECK_LOC_NM_EDGES: {
        put_text(buf, n, &len, "non-manifold edge %llu:", i + 1ull);
        put_point(buf, n, &len, l->edge_pt + 6 * (size_t)i);
        put_text(buf, n, &len, " to", 0);
        put_point(buf, n, &len, l->edge_pt + 6 * (size_t)i + 3);
        put_text(buf, n, &len, ", faces", 0);
        for (uint32_t f = l->edge_start[i]; f < l->edge_start[i + 1]; f++)
            put_text(buf, n, &len, " %llu", l->edge_face[f]);
        break;
    }
    case CHECK_LOC_NM_VERTICES:
        put_text(buf, n, &len, "non-manifold vertex %llu:", i + 1ull);
        put_point(buf, n, &len, l->vert_pt + 3 * (size_t)i);
        break;
    case CHECK_LOC_CROSSING: {
        const double *p = l->pair_pt + 3 * (size_t)i;
        snprintf(buf, n, "crossing %u: faces %u and %u, through (%g %g %g)", i + 1, l->pair_face[2 * i],
                 l->pair_face[2 * i + 1], p[0], p[1], p[2]);
        break;
    }
    default:
        break;
    }
}

void check_text_locations(Out *out, const CheckLocations *l, const CheckCounts *c, int line, const char *unit,
                          const char *ind)
{
    static const char *const face_words[3] = { "flipped faces:", "degenerate faces:", "duplicate faces:" };
    for (int k = 0; k < CHECK_LOC_KINDS; k++) {
        const CheckRow *r = meshcheck_loc_row((CheckLocKind)k);
        uint64_t total = meshcheck_loc_total(c, (CheckLocKind)k);
        uint32_t n = meshcheck_loc_located(l, (CheckLocKind)k);
        if (!r || r->line != line || !n)
            continue;
        char text[512];
        if (k >= CHECK_LOC_FLIPPED && k <= CHECK_LOC_DUPLICATE) {
            /* faces: their indices on one line */
            const uint32_t *f = l->face[k - CHECK_LOC_FLIPPED];
            snprintf(text, sizeof text, "%s", face_words[k - CHECK_LOC_FLIPPED]);
            size_t len = strlen(text);
            for (uint32_t i = 0; i < n; i++)
                put_text(text, sizeof text, &len, " %llu", f[i]);
            if (total > n)
                put_text(text, sizeof text, &len, " and %llu more", (unsigned long long)(total - n));
            out_printf(out, "%s%-14s%s\n", ind, "", text);
            continue;
        }
        for (uint32_t i = 0; i < n; i++) {
            item_text(l, (CheckLocKind)k, i, unit, text, sizeof text);
            out_printf(out, "%s%-14s%s\n", ind, "", text);
        }
        static const char *const more[CHECK_LOC_KINDS][2] = {
            [CHECK_LOC_HOLES] = { "hole", "holes" },
            [CHECK_LOC_NM_EDGES] = { "non-manifold edge", "non-manifold edges" },
            [CHECK_LOC_NM_VERTICES] = { "non-manifold vertex", "non-manifold vertices" },
            [CHECK_LOC_CROSSING] = { "pair", "pairs" },
        };
        if (total > n)
            out_printf(out, "%s%-14s(and %llu more %s)\n", ind, "", (unsigned long long)(total - n),
                       more[k][total - n != 1]);
    }
}

/* ==== JSON ==== */

static void json_point(Out *out, const float *p)
{
    out_printf(out, "[%.9g, %.9g, %.9g]", p[0], p[1], p[2]);
}

/* Item i of kind k as a JSON value. */
static void json_item(Out *out, const CheckLocations *l, CheckLocKind k, uint32_t i)
{
    switch (k) {
    case CHECK_LOC_HOLES: {
        uint32_t s = l->loop_start[i], e = l->loop_start[i + 1];
        out_printf(out, "{\"edges\": %u, \"perimeter\": %.9g, \"loop\": [", e - s, l->loop_length[i]);
        for (uint32_t p = s; p < e; p++) {
            out_printf(out, "%s", p > s ? ", " : "");
            json_point(out, l->loop_pt + 3 * (size_t)p);
        }
        out_printf(out, "]}");
        break;
    }
    case CHECK_LOC_NM_EDGES:
        out_printf(out, "{\"ends\": [");
        json_point(out, l->edge_pt + 6 * (size_t)i);
        out_printf(out, ", ");
        json_point(out, l->edge_pt + 6 * (size_t)i + 3);
        out_printf(out, "], \"faces\": [");
        for (uint32_t f = l->edge_start[i]; f < l->edge_start[i + 1]; f++)
            out_printf(out, "%s%u", f > l->edge_start[i] ? ", " : "", l->edge_face[f]);
        out_printf(out, "]}");
        break;
    case CHECK_LOC_NM_VERTICES:
        out_printf(out, "{\"point\": ");
        json_point(out, l->vert_pt + 3 * (size_t)i);
        out_printf(out, "}");
        break;
    case CHECK_LOC_FLIPPED:
    case CHECK_LOC_DEGENERATE:
    case CHECK_LOC_DUPLICATE:
        out_printf(out, "%u", l->face[k - CHECK_LOC_FLIPPED][i]);
        break;
    case CHECK_LOC_CROSSING: {
        const double *p = l->pair_pt + 3 * (size_t)i;
        out_printf(out, "{\"faces\": [%u, %u], \"point\": [%.17g, %.17g, %.17g]}", l->pair_face[2 * i],
                   l->pair_face[2 * i + 1], p[0], p[1], p[2]);
        break;
    }
    case CHECK_LOC_KINDS:
        break;
    }
}

void check_json_locations(Out *out, const CheckLocations *l, const CheckCounts *c, const char *ind)
{
    out_printf(out, ",\n%s\"locations\": {", ind);
    for (int k = 0; k < CHECK_LOC_KINDS; k++) {
        const CheckRow *r = meshcheck_loc_row((CheckLocKind)k);
        uint32_t n = meshcheck_loc_located(l, (CheckLocKind)k);
        /* a face's items are numbers: several a line */
        int inline_items = k >= CHECK_LOC_FLIPPED && k <= CHECK_LOC_DUPLICATE;
        out_printf(out, "%s\n%s  \"%s\": {\"count\": %llu, \"items\": [", k ? "," : "", ind, r ? r->json : "?",
                   (unsigned long long)meshcheck_loc_total(c, (CheckLocKind)k));
        for (uint32_t i = 0; i < n; i++) {
            if (inline_items)
                out_printf(out, "%s", i ? ", " : "");
            else
                out_printf(out, "%s\n%s    ", i ? "," : "", ind);
            json_item(out, l, (CheckLocKind)k, i);
        }
        if (n && !inline_items)
            out_printf(out, "\n%s  ", ind);
        out_printf(out, "]}");
    }
    out_printf(out, "\n%s}", ind);
}
