/**
 * @file test_examples_build.c
 * @brief Every shipped deck (examples/<case>/<case>.yaml and any other
 *        .yaml in an example folder) loads and builds into a simulation:
 *        an example that no longer parses after a key was renamed or an
 *        option refused is caught here, without running it.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "core/particles.h"
#include "core/sim.h"
#include "io/deck.h"
#include "io/deck_build.h"
#include "spall/error.h"

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

static int has_suffix(const char *s, const char *suffix)
{
    size_t n = strlen(s), k = strlen(suffix);
    return n >= k && strcmp(s + n - k, suffix) == 0;
}

/* Load and build one deck; 0 on success, the message printed otherwise. */
static int build_one(const char *path, size_t *particles)
{
    struct spall_error e = {0};
    struct deck *d = NULL;
    struct sim *s = NULL;
    struct run_output ro;
    int rc = deck_load_file(&d, path, &e);
    if (!rc)
        rc = deck_build_sim(d, &s, &ro, &e);
    deck_destroy(&d);
    if (rc) {
        fprintf(stderr, "%s: %s\n", path, e.msg);
        return rc;
    }
    *particles = s->p->n;
    sim_destroy(&s);
    return 0;
}

static void test_every_example_builds(void **state)
{
    (void)state;
    const char *src = getenv("SPALL_SOURCE_DIR");
    char root[1024];
    snprintf(root, sizeof root, "%s/examples", src ? src : "..");
    DIR *top = opendir(root);
    assert_non_null(top);
    int decks = 0, failed = 0;
    struct dirent *ent;
    while ((ent = readdir(top)) != NULL) {
        if (ent->d_name[0] == '.')
            continue;
        char dir[2048];
        snprintf(dir, sizeof dir, "%s/%s", root, ent->d_name);
        struct stat st;
        if (stat(dir, &st) != 0 || !S_ISDIR(st.st_mode))
            continue;
        DIR *sub = opendir(dir);
        if (!sub)
            continue;
        struct dirent *f;
        while ((f = readdir(sub)) != NULL) {
            if (!has_suffix(f->d_name, ".yaml"))
                continue;
            char path[3072];
            snprintf(path, sizeof path, "%s/%s", dir, f->d_name);
            size_t n = 0;
            decks++;
            if (build_one(path, &n))
                failed++;
            else
                printf("  %-60s %zu particles\n", f->d_name, n);
        }
        closedir(sub);
    }
    closedir(top);
    printf("%d example decks, %d failed to build\n", decks, failed);
    assert_true(decks >= 30);
    assert_int_equal(failed, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_every_example_builds),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
