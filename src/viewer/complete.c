/* complete.c: Tab completion of file paths for the viewer's open prompt,
 * as a shell does it: the names in the path's directory that start with
 * what was typed of its last component, completed as far as they agree. */

#define _DEFAULT_SOURCE         /* d_type, strdup */

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "prompt.h"

#define MATCH_MAX 4096          /* names looked at past this are not listed (still counted) */

int path_expand_home(const char *in, char *out, size_t outlen)
{
    const char *home = getenv("HOME");
    int n;
    if (in[0] == '~' && (in[1] == '/' || in[1] == 0) && home && *home)
        n = snprintf(out, outlen, "%s%s", home, in + 1);
    else
        n = snprintf(out, outlen, "%s", in);
    return n < 0 || (size_t)n >= outlen ? -1 : 0;
}

static int cmp_str(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

/* Is dir/name a directory (following a symbolic link)? */
static int is_dir(const char *dir, const char *name, const struct dirent *d)
{
    if (d->d_type == DT_DIR)
        return 1;
    if (d->d_type != DT_LNK && d->d_type != DT_UNKNOWN)
        return 0;
    char full[4096];
    struct stat st;
    if (snprintf(full, sizeof full, "%s%s", dir, name) >= (int)sizeof full)
        return 0;
    return stat(full, &st) == 0 && S_ISDIR(st.st_mode);
}

int path_complete(const char *in, char *out, size_t outlen, char *list, size_t listlen)
{
    char path[4096];
    if (list && listlen)
        list[0] = 0;
    if (path_expand_home(in, path, sizeof path) || strlen(path) >= outlen)
        return -1;
    strcpy(out, path);
    const char *slash = strrchr(path, '/');
    size_t dlen = slash ? (size_t)(slash - path) + 1 : 0;
    char dir[4096];
    memcpy(dir, path, dlen);
    dir[dlen] = 0;
    const char *base = path + dlen;
    size_t blen = strlen(base);
    DIR *d = opendir(dlen ? dir : ".");
    if (!d)
        return 0;
    char **names = NULL;
    int n = 0, kept = 0, cap = 0;
    size_t common = 0;          /* bytes all names share (valid when n > 0) */
    char first[256] = "";
    int first_dir = 0;
    struct dirent *e;
    while ((e = readdir(d))) {
        const char *nm = e->d_name;
        if (!strcmp(nm, ".") || !strcmp(nm, "..") || strncmp(nm, base, blen) != 0)
            continue;
        if (nm[0] == '.' && base[0] != '.')
            continue;
        int isd = is_dir(dir, nm, e);
        if (n == 0) {
            snprintf(first, sizeof first, "%s", nm);
            common = strlen(first);
            first_dir = isd;
        } else {
            size_t k = 0;
            while (k < common && nm[k] == first[k])
                k++;
            common = k;
        }
        n++;
        if (list && kept < MATCH_MAX) {
            if (kept == cap) {
                int nc = cap ? 2 * cap : 64;
                char **g = realloc(names, (size_t)nc * sizeof *g);
                if (!g)
                    continue;
                names = g;
                cap = nc;
            }
            size_t l = strlen(nm);
            char *c = malloc(l + 2);
            if (!c)
                continue;
            memcpy(c, nm, l);
            c[l] = isd ? '/' : 0;
            c[l + 1] = 0;
            names[kept++] = c;
        }
    }
    closedir(d);
    int rc = n;
    if (n > 0) {
        /* do not end inside a UTF-8 character */
        while (common > blen && (first[common] & 0xc0) == 0x80)
            common--;
        int slash_too = n == 1 && first_dir;
        if (dlen + common + (size_t)slash_too + 1 > outlen) {
            rc = -1;
        } else {
            memcpy(out + dlen, first, common);
            out[dlen + common] = 0;
            if (slash_too)
                strcat(out, "/");
        }
    }
    if (list && listlen && kept) {
        qsort(names, (size_t)kept, sizeof *names, cmp_str);
        size_t at = 0;
        for (int i = 0; i < kept; i++) {
            size_t l = strlen(names[i]);
            if (at + l + 2 > listlen)
                break;
            if (at)
                list[at++] = '\n';
            memcpy(list + at, names[i], l);
            at += l;
            list[at] = 0;
        }
    }
    for (int i = 0; i < kept; i++)
        free(names[i]);
    free(names);
    return rc;
}
