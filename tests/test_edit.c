/* test_edit.c: objects added to and removed from a built scene (edit.c)
 * give the scene a load of the remaining files gives, ids and colours
 * included; what is cached from a scene (hzb-octree's trees) follows. */

#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app.h"
#include "testlib.h"

/* a file of two objects (one with a colour of its own), points and a line */
static const char *file_a =
    "o left\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\nf 1 3 2\n"
    "o right\nv 2 0 0\nv 3 0 0\nv 3 1 1\nv 2 1 0.5\nf 5 6 7 8\np 5 6\nl 5 7 8\n";
static const char *file_b = "v 0 0 -1\nv 1 0 -1\nv 0 1 -1\nf 1 2 3\nf 1 3 2\nl 1 2\n";
static const char *file_c = "v 0 0 2\nv 2 0 2\nv 0 2 2\nv 1 1 3\nf 1 2 3\nf 1 2 4\nf 2 3 4\n";

/* Scene of the given OBJ texts, one file each (named fK.obj, fK+1.obj
 * ... from K = first). */
static void build(Scene *s, const char *const *texts, int n, int first)
{
    Mesh *m = calloc((size_t)n, sizeof *m);
    cr_assert(m);
    char err[256], name[32];
    for (int i = 0; i < n; i++) {
        snprintf(name, sizeof name, "f%d.obj", first + i);
        cr_assert_eq(mesh_parse(&m[i], name, texts[i], strlen(texts[i]), err, sizeof err), 0, "%s", err);
    }
    cr_assert_eq(scene_build(s, m, n, err, sizeof err), 0, "%s", err);
}

/* The two scenes hold the same objects, polygons, ids and colours. */
static void expect_same(const Scene *a, const Scene *b)
{
    cr_assert_eq(a->nobjs, b->nobjs);
    cr_assert_eq(a->nmeshes, b->nmeshes);
    cr_assert_eq(a->nfaces, b->nfaces);
    cr_assert_eq(a->npolys, b->npolys);
    cr_assert_eq(a->npoints, b->npoints);
    cr_assert_eq(a->nsegs, b->nsegs);
    cr_assert_eq(a->nprims, b->nprims);
    for (int i = 0; i < a->nobjs; i++) {
        const Object *p = &a->objs[i], *q = &b->objs[i];
        cr_expect_str_eq(p->name, q->name);
        cr_expect_eq(p->face_base, q->face_base, "object %d", i);
        cr_expect_eq(p->poly_first, q->poly_first, "object %d", i);
        cr_expect_eq(p->poly_count, q->poly_count, "object %d", i);
        cr_expect_eq(p->seg_first, q->seg_first, "object %d", i);
        cr_expect_eq(p->point_id0, q->point_id0, "object %d", i);
        cr_expect_eq(p->seg_id0, q->seg_id0, "object %d", i);
        cr_expect_eq(scene_object_file(a, i), scene_object_file(b, i), "object %d", i);
        cr_expect_str_eq(p->mesh->path, q->mesh->path);
    }
    /* either may be in the compact form (scene.h): compared through the
     * accessors */
    char msg[256];
    cr_expect_eq(tl_scene_faces_differ(a, b, msg, sizeof msg), 0, "%s", msg);
    cr_expect_eq(memcmp(a->seg_corner, b->seg_corner, a->nsegs * sizeof(uint32_t)), 0);
}

Test(edit, adding_files_gives_the_scene_loading_them_together_gives)
{
    const char *one[] = { file_a }, *two[] = { file_b }, *all[] = { file_a, file_b };
    Scene s, part, ref;
    build(&s, one, 1, 0);
    build(&part, two, 1, 1);
    build(&ref, all, 2, 0);
    uint32_t gen = s.gen;
    char err[128];
    cr_assert_eq(scene_add(&s, &part, err, sizeof err), 0, "%s", err);
    cr_expect_eq(part.nobjs, 0, "the part is left empty");
    cr_expect_neq(s.gen, gen, "the generation moves on");
    expect_same(&s, &ref);
    scene_free(&part);
    scene_free(&s);
    scene_free(&ref);
}

Test(edit, a_single_object_scene_gets_distinct_colours_when_another_comes)
{
    const char *one[] = { file_b }, *two[] = { file_c }, *all[] = { file_b, file_c };
    Scene s, part, ref;
    build(&s, one, 1, 0);
    build(&part, two, 1, 1);
    build(&ref, all, 2, 0);
    char err[128];
    cr_assert_eq(scene_add(&s, &part, err, sizeof err), 0, "%s", err);
    expect_same(&s, &ref);
    cr_expect(memcmp(&s.face_rgb[0], &s.face_rgb[3 * s.objs[1].face_base], 3) != 0, "two colours");
    scene_free(&part);
    scene_free(&s);
    scene_free(&ref);
}

/* The viewer's first file is a part added to an empty scene: the part
 * is taken whole, so a file of triangles stays in the compact form
 * (scene.h, issue 21), the same scene a load of it alone makes. */
Test(edit, a_file_added_to_an_empty_scene_stays_compact)
{
    const char *one[] = { file_c };
    Scene s, part, ref;
    build(&part, one, 1, 0);
    build(&ref, one, 1, 0);
    char err[128];
    cr_assert_eq(scene_build(&s, NULL, 0, err, sizeof err), 0, "%s", err);
    cr_assert(!part.poly_start && !part.poly_lface && !part.face_normal && !part.face_rgb, "a compact part");
    cr_assert_eq(scene_wire_build(&part, err, sizeof err), 0, "%s", err);
    uint32_t gen = s.gen;
    cr_assert_eq(scene_add(&s, &part, err, sizeof err), 0, "%s", err);
    cr_expect_eq(part.nobjs, 0, "the part is left empty");
    cr_expect_neq(s.gen, gen, "the generation moves on");
    cr_expect(!s.poly_start && !s.poly_lface && !s.face_normal && !s.face_rgb, "still compact");
    cr_expect(!s.wire_built && !s.wire && s.nwire == 0, "the wireframe to be built again, as after any edit");
    expect_same(&s, &ref);
    scene_free(&part);
    scene_free(&s);
    scene_free(&ref);
}

Test(edit, removing_objects_renumbers_ids_and_drops_an_empty_file)
{
    const char *all[] = { file_a, file_b, file_c }, *a[] = { file_a }, *c[] = { file_c };
    Scene s, ref, part;
    build(&s, all, 3, 0);
    /* the reference: f0 and f2 (scene_add is checked against scene_build above) */
    build(&ref, a, 1, 0);
    build(&part, c, 1, 2);
    char err[128];
    cr_assert_eq(scene_add(&ref, &part, err, sizeof err), 0, "%s", err);
    scene_free(&part);
    /* f1.obj is object 2 (the third): its file goes with it */
    cr_assert_eq(scene_remove(&s, 2, err, sizeof err), 0, "%s", err);
    cr_assert_eq(s.nmeshes, 2);
    cr_assert_str_eq(s.meshes[1].path, "f2.obj");
    expect_same(&s, &ref);
    /* one object of a file of two: the file stays */
    cr_assert_eq(scene_remove(&s, 0, err, sizeof err), 0, "%s", err);
    cr_expect_eq(s.nobjs, 2);
    cr_expect_eq(s.nmeshes, 2);
    cr_expect_str_eq(s.objs[0].name, "right");
    cr_expect_eq(s.objs[0].face_base, 0);
    cr_expect_eq(s.objs[1].face_base, 1);
    cr_expect_eq(s.objs[0].point_id0, (int32_t)s.nfaces, "points come right after the faces");
    cr_expect_eq(scene_remove(&s, 5, err, sizeof err), -1, "no such object");
    scene_free(&s);
    scene_free(&ref);
}

Test(edit, clearing_leaves_an_empty_scene_every_algorithm_draws)
{
    const char *all[] = { file_a, file_b };
    Scene s;
    build(&s, all, 2, 0);
    scene_clear(&s);
    cr_assert_eq(s.nobjs, 0);
    cr_assert_eq(s.nfaces, 0);
    cr_assert_eq(s.nprims, 0);
    for (int k = 0; k < hsr_nalgos; k++) {
        Pipeline p;
        cr_assert_eq(pipeline_init(&p, &s, hsr_algos[k], 2), 0);
        p.wireframe = 1;
        p.shade = SHADE_SMOOTH;
        p.edges = 1;
        cr_assert_eq(pipeline_render(&p, 40, 30, 1.0f, 0, 1), 0, "%s", hsr_algos[k]->name);
        cr_expect_str_eq(frame_empty_reason(&p), "the scene has nothing to draw");
        pipeline_free(&p);
    }
    /* and takes a file again */
    const char *one[] = { file_c };
    Scene part;
    build(&part, one, 1, 0);
    char err[128];
    cr_assert_eq(scene_add(&s, &part, err, sizeof err), 0, "%s", err);
    cr_expect_eq(s.nobjs, 1);
    cr_expect_eq(s.nfaces, 3);
    scene_free(&part);
    scene_free(&s);
}

/* hzb-octree keeps its trees across frames: after the scene changes in
 * place (same Scene pointer, and here the same polygon count and object
 * count too), its picture must still be the z-buffer's. */
static void expect_octree_agrees(Pipeline *oct, Pipeline *ref, const char *what)
{
    scene_fit(oct->scene);
    cr_assert_eq(pipeline_render(oct, 120, 90, 1.0f, 0, 0), 0);
    cr_assert_eq(pipeline_render(ref, 120, 90, 1.0f, 0, 0), 0);
    int x = -1, y = -1;
    long d = tl_diff(&ref->fb, &oct->fb, &x, &y);
    cr_expect_eq(d, 0, "%s: %ld pixels differ from the z-buffer, first at %d,%d", what, d, x, y);
}

Test(edit, hzb_octree_trees_follow_the_scene_through_edits)
{
    /* two files of equal counts: removing one and adding the other keeps
     * npolys and nobjs, so only the generation tells the scenes apart */
    const char *ab[] = { file_b, file_c }, *one[] = { file_c };
    const char *c2 = "v 0 0 -3\nv 2 0 -3\nv 0 2 -3\nv 1 1 -1\nf 1 2 3\nf 1 2 4\nf 2 3 4\n";
    Scene s;
    build(&s, ab, 2, 0);
    Pipeline oct, ref;
    cr_assert_eq(pipeline_init(&oct, &s, hsr_find("hzb-octree"), 1), 0);
    cr_assert_eq(pipeline_init(&ref, &s, hsr_find("zbuffer"), 1), 0);
    expect_octree_agrees(&oct, &ref, "first frame");
    char err[128];
    /* without pipeline_scene_changing: the generation alone must do */
    cr_assert_eq(scene_remove(&s, 1, err, sizeof err), 0, "%s", err);
    Scene part;
    const char *other[] = { c2 };
    build(&part, other, 1, 2);
    cr_assert_eq(scene_add(&s, &part, err, sizeof err), 0, "%s", err);
    scene_free(&part);
    expect_octree_agrees(&oct, &ref, "after remove and add");
    /* the viewer's way: told first */
    cr_assert_eq(pipeline_scene_changing(&oct), 0);
    build(&part, one, 1, 3);
    cr_assert_eq(scene_add(&s, &part, err, sizeof err), 0, "%s", err);
    scene_free(&part);
    expect_octree_agrees(&oct, &ref, "after add");
    pipeline_free(&oct);
    pipeline_free(&ref);
    scene_free(&s);
}

/* The case the generation exists for: an edit whose new polygon list
 * lands where the old one was (the allocator hands a freed block back),
 * with the same polygon and object counts but objects of other sizes.
 * Made deterministic here by writing the new scene into the old arrays.
 * Keyed by pointer and counts alone, the trees of the old scene (object
 * 0 with 400 polygons, object 1 with 600) would be walked for the new
 * one (600 and 400), each object's tree reading the other's polygons.
 * The octree's last pass draws what no tree reached, so the picture
 * stays right even then; the walk shows it: its node counts are those of
 * a fresh runner's trees only when the scene got trees of its own. */
/* OBJ text of a strip of `tris` triangles across x0..x1 (y 0..1) at z. */
static char *strip(int tris, float x0, float x1, float z)
{
    size_t cap = 64 * (size_t)tris + 256, at = 0;
    char *t = malloc(cap);
    cr_assert(t);
    int cols = tris / 2;
    for (int i = 0; i <= cols; i++) {
        float x = x0 + (x1 - x0) * (float)i / (float)cols;
        at += (size_t)snprintf(t + at, cap - at, "v %g 0 %g\nv %g 1 %g\n", x, z, x, z);
    }
    for (int i = 0; i < cols; i++) {
        int a = 2 * i + 1;
        at += (size_t)snprintf(t + at, cap - at, "f %d %d %d\nf %d %d %d\n", a, a + 2, a + 1, a + 1, a + 2, a + 3);
    }
    return t;
}

Test(edit, hzb_octree_trees_are_not_taken_for_a_scene_in_reused_memory)
{
    char *x0 = strip(400, -1, 0, 0), *x1 = strip(600, 0, 1, 0);
    char *y0 = strip(600, -1, 0, 0), *y1 = strip(400, 0, 1, 0);
    const char *x[] = { x0, x1 }, *y[] = { y0, y1 };
    Scene s, n;
    build(&s, x, 2, 0);
    build(&n, y, 2, 0);
    cr_assert_eq(s.npolys, n.npolys);
    cr_assert_eq(s.poly_start[s.npolys], n.poly_start[n.npolys]);
    Pipeline oct, ref;
    cr_assert_eq(pipeline_init(&oct, &s, hsr_find("hzb-octree"), 1), 0);
    cr_assert_eq(pipeline_init(&ref, &s, hsr_find("zbuffer"), 1), 0);
    expect_octree_agrees(&oct, &ref, "first scene");
    /* n's contents in s's arrays, s's pointer: an in-place edit */
    uint32_t *pc = s.poly_corner, *ps = s.poly_start, *pl = s.poly_lface;
    memcpy(pc, n.poly_corner, n.poly_start[n.npolys] * sizeof *pc);
    memcpy(ps, n.poly_start, (n.npolys + 1) * sizeof *ps);
    memcpy(pl, n.poly_lface, n.npolys * sizeof *pl);
    Scene old = s;
    s = n;
    s.poly_corner = pc;
    s.poly_start = ps;
    s.poly_lface = pl;
    s.gen = old.gen + 1;
    expect_octree_agrees(&oct, &ref, "the scene in the same memory");
    /* the walk is the one of trees made for this scene: a fresh runner's */
    Pipeline fresh;
    cr_assert_eq(pipeline_init(&fresh, &s, hsr_find("hzb-octree"), 1), 0);
    cr_assert_eq(pipeline_render(&fresh, 120, 90, 1.0f, 0, 0), 0);
    cr_expect_eq(oct.st.nodes_visited, fresh.st.nodes_visited, "octree nodes visited: %llu, fresh trees %llu",
                 (unsigned long long)oct.st.nodes_visited, (unsigned long long)fresh.st.nodes_visited);
    cr_expect_eq(oct.st.polys_culled, fresh.st.polys_culled);
    pipeline_free(&fresh);
    pipeline_free(&oct);
    pipeline_free(&ref);
    /* give each scene back what it owns */
    n.poly_corner = NULL;
    n.poly_start = NULL;
    n.poly_lface = NULL;
    s.poly_corner = s.poly_start = s.poly_lface = NULL;
    scene_free(&s);         /* n's other arrays */
    n.poly_corner = pc;
    n.poly_start = ps;
    n.poly_lface = pl;
    old.poly_corner = old.poly_start = old.poly_lface = NULL;
    scene_free(&old);
    n.meshes = NULL;
    n.nmeshes = 0;
    n.objs = NULL;
    n.face_normal = NULL;
    n.face_rgb = NULL;
    n.face_own = NULL;
    n.face_obj = NULL;
    n.seg_corner = NULL;
    scene_free(&n);         /* the polygon arrays */
    free(x0);
    free(x1);
    free(y0);
    free(y1);
}

/* The trees of a big scene are built on a thread of their own, reading
 * the scene. An edit frees the scene's arrays: the builder must be
 * stopped first (pipeline_scene_changing), else it may read freed memory
 * or finish trees of a scene gone. The builder reads the scene only in
 * its first milliseconds, so make asan catches a missing stop only when
 * the edit falls in them; the picture must be the z-buffer's anyway. */
Test(edit, hzb_octree_builder_is_stopped_before_an_edit)
{
    char *big = strip(140000, -1, 1, 0), *small = strip(40, -1, 1, -0.5f);
    const char *one[] = { big }, *two[] = { small };
    Scene s, part;
    build(&s, one, 1, 0);
    build(&part, two, 1, 1);
    Pipeline oct, ref;
    cr_assert_eq(pipeline_init(&oct, &s, hsr_find("hzb-octree"), 2), 0);
    cr_assert_eq(pipeline_init(&ref, &s, hsr_find("zbuffer"), 1), 0);
    cr_assert_eq(pipeline_render(&oct, 160, 120, 1.0f, 0, 0), 0);
    int building = oct.st.building;
    char err[128];
    cr_assert_eq(pipeline_scene_changing(&oct), 0);
    cr_assert_eq(scene_add(&s, &part, err, sizeof err), 0, "%s", err);
    /* the next trees are built for the new scene: until they are ready,
     * frames draw without them; the picture is the z-buffer's throughout */
    for (int k = 0; k < 200; k++) {
        expect_octree_agrees(&oct, &ref, "after the edit");
        if (!oct.st.building)
            break;
    }
    cr_log_info("the builder was %s when the scene changed", building ? "running" : "done");
    pipeline_free(&oct);
    pipeline_free(&ref);
    scene_free(&part);
    scene_free(&s);
    free(big);
    free(small);
}
