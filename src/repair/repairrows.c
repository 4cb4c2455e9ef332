/* repairrows.c: the repair's figures as data (repair_rows), in the order a
 * report says them: what each step did, then what is left. The CLI's
 * text report and its JSON read the rows. */

#include <stdio.h>

#include "repair.h"

#define FIELD(f) .field = #f, .offset = offsetof(RepairReport, f), .size = sizeof(((RepairReport *)0)->f)

const RepairRow repair_rows[] = {
    { FIELD(welded), .step = REPAIR_WELD, .json = "welded", .one = "vertex welded", .many = "vertices welded" },
    { FIELD(degenerate), .step = REPAIR_CLEAN, .json = "degenerate_dropped",
      .one = "degenerate face dropped", .many = "degenerate faces dropped" },
    { FIELD(duplicate), .step = REPAIR_CLEAN, .json = "duplicate_dropped",
      .one = "duplicate face dropped", .many = "duplicate faces dropped" },
    { FIELD(flaps), .step = REPAIR_CLEAN, .json = "flaps_dropped",
      .one = "face dropped with its copy (a two-sided flap)", .many = "faces dropped with their copies (two-sided flaps)" },
    { FIELD(dup_kept), .step = REPAIR_CLEAN, .json = "duplicate_kept",
      .one = "duplicate face kept (dropping it would open an edge)",
      .many = "duplicate faces kept (dropping them would open edges)" },
    { FIELD(repeated), .step = REPAIR_CLEAN, .json = "repeated_corners_dropped",
      .one = "repeated corner dropped", .many = "repeated corners dropped" },
    { FIELD(unused), .step = REPAIR_CLEAN, .json = "unused_dropped",
      .one = "unused vertex dropped", .many = "unused vertices dropped" },
    { FIELD(nm_edges), .step = REPAIR_MANIFOLD, .json = "nonmanifold_edges_split",
      .one = "non-manifold edge split", .many = "non-manifold edges split" },
    { FIELD(nm_vertices), .step = REPAIR_MANIFOLD, .json = "nonmanifold_vertices_split",
      .one = "non-manifold vertex split", .many = "non-manifold vertices split" },
    { FIELD(split_vertices), .step = REPAIR_MANIFOLD, .json = "split_vertices_added",
      .one = "vertex added by the splits", .many = "vertices added by the splits" },
    { FIELD(cuts_undone), .step = REPAIR_MANIFOLD, .json = "fin_cuts_undone",
      .one = "face of a fin of three or five faces left on it (cut loose, no fill could close the cut)",
      .many = "faces of fins of three or five faces left on them (cut loose, no fill could close the cut)" },
    { FIELD(fins), .step = REPAIR_MANIFOLD, .json = "stray_fin_faces_dropped",
      .one = "stray fin face dropped (an open part cut loose from a non-manifold edge)",
      .many = "stray fin faces dropped (open parts cut loose from non-manifold edges)" },
    { FIELD(flipped), .step = REPAIR_WINDING, .json = "faces_flipped", .one = "face flipped", .many = "faces flipped" },
    { FIELD(outward), .step = REPAIR_WINDING, .json = "parts_turned_outward",
      .one = "inside-out part turned outward", .many = "inside-out parts turned outward" },
    { FIELD(filled), .step = REPAIR_HOLES, .json = "holes_filled", .one = "hole filled", .many = "holes filled" },
    { FIELD(fill_faces), .step = REPAIR_HOLES, .json = "fill_faces",
      .one = "triangle added to fill them", .many = "triangles added to fill them" },
    { FIELD(fill_vertices), .step = REPAIR_HOLES, .json = "fill_vertices",
      .one = "vertex added to fill them", .many = "vertices added to fill them" },
    { FIELD(fans), .step = REPAIR_HOLES, .json = "fan_fills",
      .one = "hole filled by a fan from a new centre", .many = "holes filled by a fan from a new centre" },
    { FIELD(open), .step = REPAIR_HOLES, .json = "holes_open", .one = "hole left open", .many = "holes left open" },
    { FIELD(open_largest), .step = REPAIR_HOLES, .json = "largest_open_edges",
      .one = "edge in the largest hole left open", .many = "edges in the largest hole left open" },
    { FIELD(open_too_big), .step = REPAIR_HOLES, .json = "holes_over_max",
      .one = "hole open for having more edges than the limit",
      .many = "holes open for having more edges than the limit" },
    { FIELD(held_back), .json = "objects_held_back",
      .one = "object repaired less (the full repair made a figure of the check worse)",
      .many = "objects repaired less (the full repair made a figure of the check worse)" },
    { FIELD(left_holes), .json = "left_holes", .one = "hole left", .many = "holes left", .problem = 1 },
    { FIELD(left_nm_edges), .json = "left_nonmanifold_edges",
      .one = "non-manifold edge left", .many = "non-manifold edges left", .problem = 1 },
    { FIELD(left_nm_vertices), .json = "left_nonmanifold_vertices",
      .one = "non-manifold vertex left", .many = "non-manifold vertices left", .problem = 1 },
    { FIELD(left_flipped), .json = "left_flipped", .one = "flipped face left", .many = "flipped faces left",
      .problem = 1 },
    { FIELD(left_nonorientable), .json = "left_non_orientable",
      .one = "non-orientable part left (no flip makes it agree)",
      .many = "non-orientable parts left (no flip makes them agree)", .problem = 1 },
    { FIELD(left_inside_out), .json = "left_inside_out",
      .one = "object left inside out", .many = "objects left inside out", .problem = 1 },
    { FIELD(left_degenerate), .json = "left_degenerate",
      .one = "degenerate face left", .many = "degenerate faces left", .problem = 1 },
    { FIELD(left_duplicate), .json = "left_duplicate",
      .one = "duplicate face left", .many = "duplicate faces left", .problem = 1 },
    { FIELD(left_crossings), .json = "left_crossings",
      .one = "pair of crossing faces left (reported, not changed)",
      .many = "pairs of crossing faces left (reported, not changed)", .problem = 1 },
};
const int repair_nrows = (int)(sizeof repair_rows / sizeof *repair_rows);

uint64_t repair_value(const RepairRow *r, const RepairReport *rep)
{
    const char *p = (const char *)rep + r->offset;
    return r->size == sizeof(uint64_t) ? *(const uint64_t *)p : *(const uint32_t *)p;
}

void repair_say(const RepairRow *r, const RepairReport *rep, char *buf, size_t n)
{
    uint64_t v = repair_value(r, rep);
    if (!v) {
        if (n)
            buf[0] = 0;
        return;
    }
    snprintf(buf, n, "%llu %s", (unsigned long long)v, v == 1 ? r->one : r->many);
}

const char *repair_open_why(RepairOpenWhy why)
{
    switch (why) {
    case REPAIR_OPEN_TOO_BIG:
        return "more edges than the limit on holes";
    case REPAIR_OPEN_CROSSING:
        return "every fill tried would cross the model or put three faces on an edge";
    case REPAIR_OPEN_UNORIENTED:
        return "its edges do not run one way round (the rim of a non-orientable part)";
    case REPAIR_OPEN_LONE_FACE:
        return "the rim of one face alone (its fill would be the face again, the other way round)";
    }
    return "open";
}
