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
    p->sp.threads = p->threads;     /* --threads 1: no helper thread anywhere */
    p->shade = SHADE_LAMBERT;
    return pipeline_set_algo(p, algo);
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
    fbuf_free(&p->fb);
    image_free(&p->img);
    shade_cache_free(&p->shade_cache);
    cells_free(&p->cells);
    memset(p, 0, sizeof *p);
}

int pipeline_render(Pipeline *p, int w, int h, float pixel_aspect, int cull, int shade_too)
{
    p->vp.w = w;
    p->vp.h = h;
    p->vp.pixel_aspect = pixel_aspect;
    p->vp.cull = cull;
    double t0 = now_ms();
    if (screen_project(&p->sp, p->scene, &p->vp))
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
        if (shade_frame(p->scene, &p->fb, p->shade, &p->shade_cache, &p->img))
            return -1;
        p->shade_ms = now_ms() - t2;
    }
    return 0;
}
