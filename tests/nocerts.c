/* nocerts.c: the unit tests' binary answers, in place of mbedTLS, the
 * one call that reads the system's CA certificates.
 *
 * Criterion links libgit2 (for the diffs of failed string assertions),
 * and libgit2's initialisation, which Criterion runs at every start of
 * the binary, parses every certificate in /etc/ssl/certs with mbedTLS:
 * 53M of a trivial test's 65M instructions (callgrind). Criterion starts
 * the binary again for each test, so over make test's 770 tests that was
 * about 40G instructions spent on certificates no test uses: the tests
 * make no connection. Defined here and exported (the Makefile links with
 * --export-dynamic-symbol), this definition comes first in the dynamic
 * linker's search, so libgit2's call binds to it; it loads no
 * certificate and says it succeeded. */

typedef struct mbedtls_x509_crt mbedtls_x509_crt;

int mbedtls_x509_crt_parse_file(mbedtls_x509_crt *chain, const char *path);

int mbedtls_x509_crt_parse_file(mbedtls_x509_crt *chain, const char *path)
{
    (void)chain;
    (void)path;
    return 0;
}
