/* fakeassimp.c: a stand-in for libassimp, built by the tests and found
 * through LD_LIBRARY_PATH. Its import does what an exploited parser
 * would, as ZV_STANDIN says: "create" a file, "exec" a shell, "socket"
 * (connect to a local port), "alloc" without bound, "spin" for ever,
 * "chatter" (write escapes to stderr and fail with a message of several
 * lines quoting them, as assimp's importers do),
 * "read" the file ZV_STANDIN_READ (its error says what it read), "raise"
 * its memory limit to the ceiling. Each that succeeds
 * leaves a marker file in ZV_STANDIN_DIR, so that a test run without the
 * sandbox proves the attempt is real and one with it that nothing
 * happened. Without ZV_STANDIN the file's name says what to do. Exports every function zview looks up (src/mesh/assimp.c). */
#define _GNU_SOURCE

#include <arpa/inet.h>
#include <errno.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <unistd.h>

#include <assimp/cimport.h>
#include <assimp/material.h>
#include <assimp/scene.h>
#include <assimp/version.h>

static char error_text[200] = "stand-in: nothing was asked";

static void mark(const char *what)
{
    const char *dir = getenv("ZV_STANDIN_DIR");
    char p[512];
    snprintf(p, sizeof p, "%s/%s", dir ? dir : "/tmp", what);
    int fd = open(p, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0)
        close(fd);
}

/* What to do: ZV_STANDIN, else the file's name ("spin.fbx"), so that
 * one viewer can open several stand-ins. */
static void attack(const char *file)
{
    const char *what = getenv("ZV_STANDIN");
    if (!what || !*what)
        what = file ? file : "";
    if (strstr(what, "create"))
        mark("created");
    if (strstr(what, "exec")) {
        char cmd[600];
        const char *dir = getenv("ZV_STANDIN_DIR");
        snprintf(cmd, sizeof cmd, "touch '%s/exec-ran'", dir ? dir : "/tmp");
        execl("/bin/sh", "sh", "-c", cmd, (char *)NULL);
    }
    if (strstr(what, "socket")) {
        int s = socket(AF_INET, SOCK_STREAM, 0);
        if (s >= 0) {
            struct sockaddr_in a = { .sin_family = AF_INET, .sin_port = htons(9) };
            a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
            (void)connect(s, (struct sockaddr *)&a, sizeof a);
            close(s);
            mark("socket-opened");
        }
    }
    if (strstr(what, "read")) {
        /* a file the model may not name, opened read-only as a parser
         * taken over would: the filter allows it, only Landlock stops it */
        const char *p = getenv("ZV_STANDIN_READ");
        int fd = p ? open(p, O_RDONLY) : -1;
        char buf[64];
        ssize_t n = fd >= 0 ? read(fd, buf, sizeof buf) : -1;
        if (fd >= 0)
            close(fd);
        if (n >= 0)
            snprintf(error_text, sizeof error_text, "stand-in: read %zd bytes of %s", n, p);
        else
            snprintf(error_text, sizeof error_text, "stand-in: cannot read %s: %s", p ? p : "(unset)",
                     strerror(errno));
        return;
    }
    if (strstr(what, "raise")) {
        /* lift the memory limit to its ceiling, as a parser taken over
         * would before it allocates: the filter refuses it */
        struct rlimit rl;
        int r = getrlimit(RLIMIT_DATA, &rl) == 0 ? (rl.rlim_cur = rl.rlim_max, setrlimit(RLIMIT_DATA, &rl)) : -1;
        if (r == 0)
            snprintf(error_text, sizeof error_text, "stand-in: raised the memory limit");
        else
            snprintf(error_text, sizeof error_text, "stand-in: cannot raise the memory limit: %s", strerror(errno));
        return;
    }
    if (strstr(what, "spin")) {
        volatile unsigned long n = 0;
        for (;;)
            n++;                /* a parser in an endless loop: Esc must end it */
    }
    if (strstr(what, "chatter")) {
        /* a library's own words on stderr, quoting its file: OSC 52 (the
         * clipboard), CSI 2J (clear), a C1 CSI, a line of zview's forged,
         * and a long last line without its newline */
        fputs("library chatter \x1b]52;c;aGk=\x07 and \x1b[2J\n", stderr);
        fputs("zview: a forged line \x1b[2J\xc2\x9b\n", stderr);
        char longline[3000];
        memset(longline, 'x', sizeof longline);
        fwrite(longline, 1, sizeof longline, stderr);
        snprintf(error_text, sizeof error_text, "stand-in: line one\nline two \x1b]52;c;aGk=\x07\r\n\n  end\n");
        return;
    }
    if (strstr(what, "alloc")) {
        size_t total = 0;
        for (;;) {
            char *p = malloc((size_t)64 << 20);
            if (!p)
                break;
            memset(p, 1, (size_t)64 << 20);
            total += 64;
        }
        snprintf(error_text, sizeof error_text, "stand-in: no more memory after %zu MB", total);
        return;
    }
    snprintf(error_text, sizeof error_text, "stand-in: the import did what it was told (%s)", what);
}

const struct aiScene *aiImportFile(const char *f, unsigned int fl)
{
    (void)fl;
    attack(f);
    return NULL;
}

const struct aiScene *aiImportFileEx(const char *f, unsigned int fl, struct aiFileIO *io)
{
    (void)fl, (void)io;
    attack(f);
    return NULL;
}

const struct aiScene *aiImportFileFromMemory(const char *b, unsigned int n, unsigned int fl, const char *h)
{
    (void)b, (void)n, (void)fl, (void)h;
    attack(NULL);
    return NULL;
}

void aiReleaseImport(const struct aiScene *s) { (void)s; }
const char *aiGetErrorString(void) { return error_text; }
aiBool aiIsExtensionSupported(const char *e)
{
    return e && (!strcmp(e, ".fbx") || !strcmp(e, ".glb") || !strcmp(e, ".gltf")) ? AI_TRUE : AI_FALSE;
}
size_t aiGetImportFormatCount(void) { return 0; }
const struct aiImporterDesc *aiGetImportFormatDescription(size_t i) { (void)i; return NULL; }
unsigned int aiGetVersionMajor(void) { return 5; }
unsigned int aiGetVersionMinor(void) { return 0; }
unsigned int aiGetVersionPatch(void) { return 0; }
enum aiReturn aiGetMaterialColor(const struct aiMaterial *m, const char *k, unsigned int t, unsigned int i,
                                 struct aiColor4D *c)
{
    (void)m, (void)k, (void)t, (void)i, (void)c;
    return aiReturn_FAILURE;
}
enum aiReturn aiGetMaterialFloatArray(const struct aiMaterial *m, const char *k, unsigned int t, unsigned int i,
                                      ai_real *o, unsigned int *n)
{
    (void)m, (void)k, (void)t, (void)i, (void)o, (void)n;
    return aiReturn_FAILURE;
}
enum aiReturn aiGetMaterialString(const struct aiMaterial *m, const char *k, unsigned int t, unsigned int i,
                                  struct aiString *s)
{
    (void)m, (void)k, (void)t, (void)i, (void)s;
    return aiReturn_FAILURE;
}
void aiIdentityMatrix4(struct aiMatrix4x4 *m) { (void)m; }
enum aiReturn aiGetMaterialTexture(const struct aiMaterial *m, enum aiTextureType t, unsigned int i,
                                   struct aiString *p, enum aiTextureMapping *mp, unsigned int *uv, ai_real *b,
                                   enum aiTextureOp *op, enum aiTextureMapMode *mm, unsigned int *fl)
{
    (void)m, (void)t, (void)i, (void)p, (void)mp, (void)uv, (void)b, (void)op, (void)mm, (void)fl;
    return aiReturn_FAILURE;
}
