/* pipeline.c: one frame through the stages, timed stage by stage. */

#include <string.h>
#include <unistd.h>

#include "app.h"

int default_threads(void)
{
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n < 1 ? 1 : n > 64 ? 64 : (int)n;
}

int pipeline_init(Pipeline *p, Scene *s, const HsrAlgo *algo, int threads)
{
    memset(p, 0, sizeof *p);
    p->scene = s;
    p->threads = threads > 0 ? threads : default_threads();
    p->shade = SHADE_LAMBERT;
    p->samples = 1;
    p->crease = SHADE_CREASE_DEFAULT;
    p->highlight = -1;
    return pipeline_set_algo(p, algo);
}

void pipeline_apply_options(Pipeline *p, const Options *o)
{
    p->shade = (ShadeMode)o->shade;
    p->crease = o->crease;
    p->edges = o->edges;
    p->order = (PolyOrder)o->order;
    if (o->samples > 0)
        p->samples = o->samples;
}

int pipeline_set_algo(Pipeline *p, const HsrAlgo *algo)
{
    if (p->algo)
        hsr_runner_free(&p->run);
    p->algo = algo;
    return hsr_runner_init(&p->run, algo, p->threads);
}

void pipeline_free(Pipeline *p)
{
    if (p->algo)
        hsr_runner_free(&p->run);
    screen_free(&p->sp);
    reorder_free(&p->reorder);
    fbuf_free(&p->fb);
    image_free(&p->img);
    image_free(&p->img_ss);
    shade_cache_free(&p->shade_cache);
    cells_free(&p->cells);
    memset(p, 0, sizeof *p);
}

int pipeline_samples_side(int samples)
{
    int k = 1;
    while ((k + 1) * (k + 1) <= samples)
        k++;
    return k;
}

int pipeline_render(Pipeline *p, int w, int h, float pixel_aspect, int cull, int shade_too)
{
    int k = pipeline_samples_side(p->samples);
    if ((long)w * k > SCREEN_MAX || (long)h * k > SCREEN_MAX)
        k = 1;          /* a huge image needs no supersampling */
    p->vp.w = w * k;
    p->vp.h = h * k;
    p->vp.pixel_aspect = pixel_aspect;
    p->vp.cull = cull;
    double t0 = now_ms();
    if (screen_project(&p->sp, p->scene, &p->vp))
        return -1;
    if (p->order != ORDER_FILE && screen_reorder(&p->sp, p->order, 1, &p->reorder))
        return -1;
    double t1 = now_ms();
    HsrInput in = { .sp = &p->sp, .scene = p->scene, .vp = &p->vp };
    if (hsr_run(&p->run, &in, &p->fb, &p->st))
        return -1;
    double t2 = now_ms();
    p->project_ms = t1 - t0;
    p->hsr_ms = t2 - t1;
    p->shade_ms = 0;
    if (shade_too) {
        ShadeSettings set = { p->shade, p->crease, p->highlight, p->edges };
        if (k == 1 ? shade_frame(p->scene, &p->sp, &p->fb, &set, &p->shade_cache, &p->img)
                   : shade_frame(p->scene, &p->sp, &p->fb, &set, &p->shade_cache, &p->img_ss) ||
                         image_downsample(&p->img_ss, k, &p->img))
            return -1;
        p->shade_ms = now_ms() - t2;
    }
    return 0;
}
