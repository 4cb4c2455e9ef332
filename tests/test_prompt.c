/* test_prompt.c: the viewer's open prompt: line editing, and Tab
 * completion of paths on a temporary directory. */

#define _DEFAULT_SOURCE         /* mkdtemp, setenv */

#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "../src/viewer/prompt.h"
#include "tty.h"

static void type(Prompt *p, const char *s)
{
    for (; *s; s++)
        cr_assert_eq(prompt_key(p, (unsigned char)*s), PR_EDIT);
}

Test(prompt, editing_keys)
{
    Prompt p;
    prompt_start(&p, "open: ");
    type(&p, "abc");
    cr_expect_str_eq(p.buf, "abc");
    prompt_key(&p, 127);
    cr_expect_str_eq(p.buf, "ab");
    prompt_key(&p, TK_LEFT);
    prompt_key(&p, 'x');
    cr_expect_str_eq(p.buf, "axb");
    cr_expect_eq(p.cur, 2);
    prompt_key(&p, TK_HOME);
    prompt_key(&p, TK_DEL);
    cr_expect_str_eq(p.buf, "xb");
    prompt_key(&p, TK_END);
    prompt_key(&p, 0xe9);          /* é: two bytes, one character */
    cr_expect_str_eq(p.buf, "xb\xc3\xa9");
    prompt_key(&p, TK_BACKSPACE);
    cr_expect_str_eq(p.buf, "xb", "a whole character goes");
    prompt_key(&p, 'U' & 0x1f);
    cr_expect_str_eq(p.buf, "");
    cr_expect_eq(p.cur, 0);
    prompt_key(&p, 127);
    cr_expect_str_eq(p.buf, "", "backspace on an empty line does nothing");
    type(&p, "m.obj");
    cr_expect_eq(prompt_key(&p, '\r'), PR_DONE);
    cr_expect_eq(prompt_key(&p, TK_ESC), PR_CANCEL);
}

static char dir[64];

static void touch(const char *name)
{
    char path[256];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "w");
    cr_assert(f, "%s", path);
    fclose(f);
}

static void setup(void)
{
    snprintf(dir, sizeof dir, "/tmp/zv-prompt-XXXXXX");
    cr_assert(mkdtemp(dir));
    touch("dragon.obj");
    touch("dragon.ply");
    touch("bunny.obj");
    touch(".hidden.obj");
    char sub[128];
    snprintf(sub, sizeof sub, "%s/models", dir);
    cr_assert_eq(mkdir(sub, 0755), 0);
}

static void teardown(void)
{
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    cr_expect_eq(system(cmd), 0);
}

Test(prompt, completion_on_a_directory, .init = setup, .fini = teardown)
{
    char in[256], out[256], list[512];
    snprintf(in, sizeof in, "%s/b", dir);
    cr_expect_eq(path_complete(in, out, sizeof out, list, sizeof list), 1);
    cr_expect(strstr(out, "/bunny.obj") && !strcmp(strstr(out, "/bunny.obj"), "/bunny.obj"), "%s", out);
    /* ambiguous: the common prefix, and both listed */
    snprintf(in, sizeof in, "%s/dr", dir);
    cr_expect_eq(path_complete(in, out, sizeof out, list, sizeof list), 2);
    cr_expect(!strcmp(out + strlen(dir), "/dragon."), "%s", out);
    cr_expect_str_eq(list, "dragon.obj\ndragon.ply");
    /* a lone directory gets its slash */
    snprintf(in, sizeof in, "%s/mo", dir);
    cr_expect_eq(path_complete(in, out, sizeof out, list, sizeof list), 1);
    cr_expect(!strcmp(out + strlen(dir), "/models/"), "%s", out);
    /* hidden names only when asked for */
    snprintf(in, sizeof in, "%s/", dir);
    cr_expect_eq(path_complete(in, out, sizeof out, list, sizeof list), 4);
    cr_expect_str_eq(list, "bunny.obj\ndragon.obj\ndragon.ply\nmodels/");
    snprintf(in, sizeof in, "%s/.h", dir);
    cr_expect_eq(path_complete(in, out, sizeof out, NULL, 0), 1);
    /* nothing matches: unchanged */
    snprintf(in, sizeof in, "%s/zz", dir);
    cr_expect_eq(path_complete(in, out, sizeof out, list, sizeof list), 0);
    cr_expect_str_eq(out, in);
    /* ~ is the home directory */
    setenv("HOME", dir, 1);
    cr_expect_eq(path_complete("~/bu", out, sizeof out, NULL, 0), 1);
    snprintf(in, sizeof in, "%s/bunny.obj", dir);
    cr_expect_str_eq(out, in);
    cr_expect_eq(path_expand_home("~", out, sizeof out), 0);
    cr_expect_str_eq(out, dir);
    cr_expect_eq(path_expand_home("a~", out, sizeof out), 0);
    cr_expect_str_eq(out, "a~");
}

Test(prompt, tab_completes_then_a_second_tab_lists, .init = setup, .fini = teardown)
{
    Prompt p;
    prompt_start(&p, "open: ");
    type(&p, dir);
    type(&p, "/d");
    prompt_key(&p, TK_TAB);
    cr_expect(!strcmp(p.buf + strlen(dir), "/dragon."), "%s", p.buf);
    cr_expect_str_eq(p.list, "", "the first Tab only completes");
    prompt_key(&p, TK_TAB);
    cr_expect_str_eq(p.list, "dragon.obj\ndragon.ply", "the second lists");
    cr_expect_eq(p.nlist, 2);
    type(&p, "p");
    cr_expect_str_eq(p.list, "", "typing hides the list");
    prompt_key(&p, TK_TAB);
    cr_expect(!strcmp(p.buf + strlen(dir), "/dragon.ply"), "%s", p.buf);
    cr_expect_eq(p.cur, p.len);
}
