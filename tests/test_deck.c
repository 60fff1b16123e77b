/* Tests for the YAML deck reader (src/io/deck.c): tree positions, syntax and
 * structure errors, typed getters and the exact shape of their messages. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "io/deck.h"
#include "spall/error.h"

#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* Load @p text as "deck.yaml"; the load must succeed. */
static struct deck *load_ok(const char *text)
{
    struct deck *d = NULL;
    struct spall_error err = {0};
    int rc = deck_load_string(&d, "deck.yaml", text, &err);
    if (rc)
        print_error("unexpected load failure: %s\n", err.msg);
    assert_int_equal(rc, SPALL_OK);
    assert_non_null(d);
    return d;
}

/* Load @p text; the load must fail with SPALL_ERR_INPUT and a message that
 * starts with "deck.yaml:LINE:COL: " and contains @p needle. */
static void load_fails(const char *text, int line, int col, const char *needle)
{
    struct deck *d = (struct deck *)0x1;
    struct spall_error err = {0};
    int rc = deck_load_string(&d, "deck.yaml", text, &err);
    assert_int_equal(rc, SPALL_ERR_INPUT);
    assert_int_equal(err.code, SPALL_ERR_INPUT);
    assert_null(d);
    char prefix[64];
    snprintf(prefix, sizeof prefix, "deck.yaml:%d:%d: ", line, col);
    if (strncmp(err.msg, prefix, strlen(prefix)) != 0 || !strstr(err.msg, needle))
        print_error("message '%s' lacks '%s' or '%s'\n", err.msg, prefix, needle);
    assert_memory_equal(err.msg, prefix, strlen(prefix));
    assert_non_null(strstr(err.msg, needle));
}

/* A getter must have failed with a positioned message containing @p needle. */
static void check_msg(int rc, const struct spall_error *err, int line, int col,
                      const char *needle)
{
    assert_int_equal(rc, SPALL_ERR_INPUT);
    assert_int_equal(err->code, SPALL_ERR_INPUT);
    char prefix[64];
    snprintf(prefix, sizeof prefix, "deck.yaml:%d:%d: ", line, col);
    if (strncmp(err->msg, prefix, strlen(prefix)) != 0 || !strstr(err->msg, needle))
        print_error("message '%s' lacks '%s' or '%s'\n", err->msg, prefix, needle);
    assert_memory_equal(err->msg, prefix, strlen(prefix));
    assert_non_null(strstr(err->msg, needle));
}

/* ---------------------------------------------------------------- tree */

static void test_tree_positions(void **state)
{
    (void)state;
    struct deck *d = load_ok("model: lattice\n"
                             "lattice:\n"
                             "  spacing: 1.0e-3\n"
                             "  points: [1, 2]\n"
                             "list:\n"
                             "  - a\n"
                             "  - 'b'\n");
    const struct deck_node *r = d->root;
    assert_int_equal(r->kind, DECK_MAPPING);
    assert_int_equal(r->n, 3);
    assert_int_equal(r->line, 1);
    assert_int_equal(r->col, 1);
    assert_string_equal(r->keys[0], "model");
    assert_int_equal(r->key_line[0], 1);
    assert_int_equal(r->key_col[0], 1);
    assert_int_equal(r->items[0]->kind, DECK_SCALAR);
    assert_string_equal(r->items[0]->scalar, "lattice");
    assert_int_equal(r->items[0]->line, 1);
    assert_int_equal(r->items[0]->col, 8);

    const struct deck_node *lat = deck_peek(r, "lattice");
    assert_non_null(lat);
    assert_int_equal(lat->kind, DECK_MAPPING);
    assert_int_equal(lat->line, 3);
    assert_int_equal(lat->col, 3);
    assert_int_equal(lat->key_line[1], 4);
    assert_int_equal(lat->key_col[1], 3);
    const struct deck_node *pts = deck_peek(lat, "points");
    assert_int_equal(pts->kind, DECK_SEQUENCE);
    assert_int_equal(pts->line, 4);
    assert_int_equal(pts->col, 11);
    assert_int_equal(pts->n, 2);
    assert_int_equal(pts->items[1]->line, 4);
    assert_int_equal(pts->items[1]->col, 15);

    const struct deck_node *list = deck_peek(r, "list");
    assert_int_equal(list->kind, DECK_SEQUENCE);
    assert_int_equal(list->n, 2);
    assert_int_equal(list->items[0]->line, 6);
    assert_int_equal(list->items[0]->col, 5);
    assert_false(list->items[0]->quoted);
    assert_true(list->items[1]->quoted);
    assert_string_equal(list->items[1]->scalar, "b");
    assert_ptr_equal(list->items[1]->deck, d);
    assert_string_equal(d->path, "deck.yaml");
    assert_non_null(strstr(d->text, "spacing: 1.0e-3"));
    deck_destroy(&d);
    assert_null(d);
}

static void test_flow_and_quoting(void **state)
{
    (void)state;
    struct deck *d = load_ok("a: {b: \"1\", c: [x, {d: e}]}\n");
    const struct deck_node *a = deck_peek(d->root, "a");
    assert_int_equal(a->kind, DECK_MAPPING);
    assert_int_equal(a->line, 1);
    assert_int_equal(a->col, 4);
    const struct deck_node *b = deck_peek(a, "b");
    assert_true(b->quoted);
    assert_string_equal(b->scalar, "1");
    const struct deck_node *c = deck_peek(a, "c");
    assert_int_equal(c->n, 2);
    assert_int_equal(c->items[1]->kind, DECK_MAPPING);
    assert_string_equal(deck_peek(c->items[1], "d")->scalar, "e");
    /* deck_peek on a non-mapping and on a missing key */
    assert_null(deck_peek(c, "d"));
    assert_null(deck_peek(a, "zz"));
    assert_null(deck_peek(NULL, "a"));
    deck_destroy(&d);
}

static void test_empty_documents(void **state)
{
    (void)state;
    const char *empties[] = {"", "# only a comment\n", "---\n", "\n\n   \n"};
    for (size_t i = 0; i < sizeof empties / sizeof *empties; ++i) {
        struct deck *d = load_ok(empties[i]);
        assert_null(d->root);
        deck_destroy(&d);
        assert_null(d);
    }
    deck_destroy(NULL); /* harmless */
}

/* ---------------------------------------------------------------- syntax */

static void test_syntax_bad_indentation(void **state)
{
    (void)state;
    load_fails("a: 1\n b: 2\n", 2, 3, "YAML syntax error: mapping values are not allowed");
}

static void test_syntax_unclosed_bracket(void **state)
{
    (void)state;
    load_fails("a: [1, 2\nb: 3\n", 2, 2, "YAML syntax error");
    load_fails("a: [1, 2\nb: 3\n", 2, 2, "flow sequence at 1:4");
    /* unclosed at the end of the file: placed at the opening bracket / quote */
    load_fails("x:\n  y: {p: 1\n", 2, 6, "at the end of the file (while parsing a flow mapping");
    load_fails("a: [1, 2", 1, 4, "YAML syntax error");
    load_fails("a: 1\nb: 'unclosed\n\n# c\n", 2, 4, "quoted scalar at 2:4");
}

static void test_syntax_tab_and_control_chars(void **state)
{
    (void)state;
    load_fails("a: 1\n\tb: 2\n", 2, 1, "tab");
    /* a raw control character is a reader error; positioned by byte offset */
    load_fails("a: 1\nb: x\001y\n", 2, 5, "YAML syntax error: control characters");
}

static void test_duplicate_key(void **state)
{
    (void)state;
    load_fails("a: 1\nb:\n  c: 1\n  c: 2\n", 4, 3, "duplicate key 'c' (first at 3:3)");
    load_fails("{a: 1, a: 2}\n", 1, 8, "duplicate key 'a' (first at 1:2)");
}

static void test_nonscalar_key_and_alias(void **state)
{
    (void)state;
    load_fails("? [a, b]\n: 1\n", 1, 3, "mapping keys must be scalars");
    load_fails("? {a: 1}\n: 1\n", 1, 3, "mapping keys must be scalars; got a mapping");
    load_fails("a: &x 1\nb: *x\n", 2, 4, "aliases are not supported (*x)");
    load_fails("a: &x [1]\n*x : 2\n", 2, 1, "aliases are not supported");
    /* an anchor alone is fine */
    struct deck *d = load_ok("a: &x 1\n");
    assert_string_equal(deck_peek(d->root, "a")->scalar, "1");
    deck_destroy(&d);
}

static void test_multiple_documents(void **state)
{
    (void)state;
    load_fails("a: 1\n---\nb: 2\n", 2, 1, "expected a single YAML document");
    load_fails("--- 1\n--- 2\n", 2, 1, "expected a single YAML document");
}

static void test_nesting_limit(void **state)
{
    (void)state;
    char buf[512];
    /* 64 levels are fine */
    size_t k = 0;
    for (int i = 0; i < 64; ++i)
        buf[k++] = '[';
    for (int i = 0; i < 64; ++i)
        buf[k++] = ']';
    buf[k] = '\0';
    struct deck *d = load_ok(buf);
    assert_int_equal(d->root->kind, DECK_SEQUENCE);
    deck_destroy(&d);
    /* 65 are refused at the 65th bracket */
    k = 0;
    for (int i = 0; i < 65; ++i)
        buf[k++] = '[';
    for (int i = 0; i < 65; ++i)
        buf[k++] = ']';
    buf[k] = '\0';
    load_fails(buf, 1, 65, "nesting is too deep");
    /* and thousands do not crash */
    char *deep = malloc(20001);
    assert_non_null(deep);
    memset(deep, '[', 20000);
    deep[20000] = '\0';
    load_fails(deep, 1, 65, "nesting is too deep");
    free(deep);
}

/* ---------------------------------------------------------------- files */

static void test_file_not_found(void **state)
{
    (void)state;
    struct deck *d = (struct deck *)0x1;
    struct spall_error err = {0};
    int rc = deck_load_file(&d, "/nonexistent/dir/deck.yaml", &err);
    assert_int_equal(rc, SPALL_ERR_INPUT);
    assert_null(d);
    assert_non_null(strstr(err.msg, "cannot open deck '/nonexistent/dir/deck.yaml': "));
    assert_non_null(strstr(err.msg, "No such file"));
}

static void test_file_roundtrip(void **state)
{
    (void)state;
    /* mkstemp is not C11: a time + stack-address (ASLR) name is unique enough */
    char path[128];
    snprintf(path, sizeof path, "/tmp/spall_test_deck_%lu_%p.yaml", (unsigned long)time(NULL),
             (void *)path);
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    const char *text = "dt: 1.0e-9\nname: probe\n";
    fputs(text, f);
    fclose(f);
    struct deck *d = NULL;
    struct spall_error err = {0};
    int rc = deck_load_file(&d, path, &err);
    remove(path); /* before any assertion can end the test */
    assert_int_equal(rc, SPALL_OK);
    assert_string_equal(d->text, text);
    assert_string_equal(d->path, path);
    double dt = 0;
    assert_int_equal(deck_double_pos(d->root, "dt", true, &dt, &err), SPALL_OK);
    assert_true(dt == 1.0e-9);
    /* errors from a file name that file */
    long n = 0;
    assert_int_equal(deck_long(d->root, "name", true, 0, 10, &n, &err), SPALL_ERR_INPUT);
    char prefix[160];
    snprintf(prefix, sizeof prefix, "%s:2:7: ", path);
    assert_memory_equal(err.msg, prefix, strlen(prefix));
    deck_destroy(&d);
}

/* ---------------------------------------------------------------- getters */

static void test_double_ok_and_spaces(void **state)
{
    (void)state;
    struct deck *d = load_ok("a: 2.5\nb: ' 3e2 '\nc: -1\nd: \"7\"\n");
    struct spall_error err = {0};
    double a = 0, b = 0, c = 0, dd = 0, missing = 42;
    assert_int_equal(deck_double(d->root, "a", true, -INFINITY, INFINITY, &a, &err), SPALL_OK);
    assert_true(a == 2.5);
    assert_int_equal(deck_double(d->root, "b", true, 0, 1000, &b, &err), SPALL_OK);
    assert_true(b == 300.0);
    assert_int_equal(deck_double(d->root, "c", true, -1, 1, &c, &err), SPALL_OK);
    assert_true(c == -1.0); /* closed bounds include the ends */
    c = 0;
    assert_int_equal(deck_double(d->root, "c", true, -2, -1, &c, &err), SPALL_OK);
    assert_true(c == -1.0);
    assert_int_equal(deck_double(d->root, "d", true, -INFINITY, INFINITY, &dd, &err), SPALL_OK);
    assert_true(dd == 7.0); /* quoted numbers are still numbers */
    assert_int_equal(deck_double(d->root, "zz", false, 0, 1, &missing, &err), SPALL_OK);
    assert_true(missing == 42.0); /* optional + missing keeps the default */
    deck_destroy(&d);
}

static void test_double_not_a_number(void **state)
{
    (void)state;
    struct deck *d = load_ok("materials:\n"
                             "  epoxy:\n"
                             "    density:     abc\n"
                             "    e: 12abc\n"
                             "    f:\n"
                             "    g: {x: 1}\n");
    const struct deck_node *ep = deck_peek(deck_peek(d->root, "materials"), "epoxy");
    struct spall_error err = {0};
    double x = 5;
    int rc = deck_double(ep, "density", true, 0, INFINITY, &x, &err);
    check_msg(rc, &err, 3, 18, "key 'density' must be a number; got 'abc'");
    assert_true(x == 5.0); /* untouched on error */
    rc = deck_double(ep, "e", true, -INFINITY, INFINITY, &x, &err);
    check_msg(rc, &err, 4, 8, "key 'e' must be a number; got '12abc'");
    rc = deck_double(ep, "f", false, -INFINITY, INFINITY, &x, &err);
    check_msg(rc, &err, 5, 7, "key 'f' must be a number; got an empty value");
    rc = deck_double(ep, "g", true, -INFINITY, INFINITY, &x, &err);
    check_msg(rc, &err, 6, 8, "key 'g' must be a number; got a mapping");
    /* a bad value still counts as used */
    static const char *const allowed[] = {"density", "e", "f", "g", NULL};
    assert_int_equal(deck_check_unused(ep, "materials.epoxy", allowed, &err), SPALL_OK);
    deck_destroy(&d);
}

static void test_non_finite_refused(void **state)
{
    (void)state;
    struct deck *d = load_ok("a: nan\nb: inf\nc: -Infinity\nd: 1e999\ne: .inf\nf: -.NaN\n"
                             "g: .info\n");
    struct spall_error err = {0};
    double x = 0;
    int rc = deck_double(d->root, "a", true, -INFINITY, INFINITY, &x, &err);
    check_msg(rc, &err, 1, 4, "key 'a' must be a finite number; got 'nan'");
    rc = deck_double(d->root, "b", true, -INFINITY, INFINITY, &x, &err);
    check_msg(rc, &err, 2, 4, "finite number");
    rc = deck_double(d->root, "c", true, -INFINITY, INFINITY, &x, &err);
    check_msg(rc, &err, 3, 4, "finite number");
    rc = deck_double(d->root, "d", true, -INFINITY, INFINITY, &x, &err);
    check_msg(rc, &err, 4, 4, "key 'd' must be a finite number; got '1e999'");
    rc = deck_double(d->root, "e", true, -INFINITY, INFINITY, &x, &err);
    check_msg(rc, &err, 5, 4, "key 'e' must be a finite number; got '.inf'"); /* YAML spelling */
    rc = deck_double(d->root, "f", true, -INFINITY, INFINITY, &x, &err);
    check_msg(rc, &err, 6, 4, "finite number");
    rc = deck_double(d->root, "g", true, -INFINITY, INFINITY, &x, &err);
    check_msg(rc, &err, 7, 4, "key 'g' must be a number; got '.info'");
    assert_true(x == 0.0);
    deck_destroy(&d);
}

static void test_double_ranges(void **state)
{
    (void)state;
    struct deck *d = load_ok("solid:\n"
                             "  poisson_ratio: 0.7\n"
                             "  e: -2\n"
                             "  f: 3\n"
                             "  g: 0.50000000001\n");
    const struct deck_node *s = deck_peek(d->root, "solid");
    struct spall_error err = {0};
    double x = 0;
    int rc = deck_double(s, "poisson_ratio", true, -1, 0.5, &x, &err);
    check_msg(rc, &err, 2, 18,
              "key 'poisson_ratio' = 0.7 is out of range; expected a value in [-1, 0.5]");
    rc = deck_double(s, "e", true, 0, INFINITY, &x, &err);
    check_msg(rc, &err, 3, 6, "key 'e' = -2 is out of range; expected a value >= 0");
    rc = deck_double(s, "f", true, -INFINITY, 1, &x, &err);
    check_msg(rc, &err, 4, 6, "key 'f' = 3 is out of range; expected a value <= 1");
    /* a value %g would round onto the bound is printed in full */
    rc = deck_double(s, "g", true, -1, 0.5, &x, &err);
    check_msg(rc, &err, 5, 6, "= 0.50000000001");
    assert_true(x == 0.0);
    deck_destroy(&d);
}

static void test_double_pos_exclusive(void **state)
{
    (void)state;
    struct deck *d = load_ok("a: 0\nb: -0.0\nc: 1e-300\nd: -3\n");
    struct spall_error err = {0};
    double x = 9;
    int rc = deck_double_pos(d->root, "a", true, &x, &err);
    check_msg(rc, &err, 1, 4, "key 'a' = 0 is out of range; expected a value > 0");
    rc = deck_double_pos(d->root, "b", true, &x, &err);
    check_msg(rc, &err, 2, 4, "expected a value > 0");
    rc = deck_double_pos(d->root, "d", true, &x, &err);
    check_msg(rc, &err, 4, 4, "key 'd' = -3 is out of range; expected a value > 0");
    assert_true(x == 9.0);
    assert_int_equal(deck_double_pos(d->root, "c", true, &x, &err), SPALL_OK);
    assert_true(x == 1e-300);
    deck_destroy(&d);
}

static void test_missing_required(void **state)
{
    (void)state;
    struct deck *d = load_ok("model: lattice\n"
                             "lattice:\n"
                             "  shape: box\n"
                             "materials:\n"
                             "  epoxy:\n"
                             "    density: 1200\n"
                             "bodies:\n"
                             "  - {name: a}\n");
    struct spall_error err = {0};
    double x = 0;
    const struct deck_node *lat = deck_peek(d->root, "lattice");
    int rc = deck_double(lat, "spacing", true, 0, INFINITY, &x, &err);
    check_msg(rc, &err, 3, 3, "missing required key 'spacing' in 'lattice' (mapping at 3:3)");

    const struct deck_node *ep = deck_peek(deck_peek(d->root, "materials"), "epoxy");
    rc = deck_double(ep, "youngs_modulus", true, 0, INFINITY, &x, &err);
    check_msg(rc, &err, 6, 5,
              "missing required key 'youngs_modulus' in 'materials.epoxy' (mapping at 6:5)");

    rc = deck_double(d->root, "dt", true, 0, INFINITY, &x, &err);
    check_msg(rc, &err, 1, 1, "missing required key 'dt' in the top level (mapping at 1:1)");

    const struct deck_node *b0 = deck_peek(d->root, "bodies")->items[0];
    const char *s = NULL;
    rc = deck_string(b0, "material", true, &s, &err);
    check_msg(rc, &err, 8, 5, "missing required key 'material' in 'bodies[0]'");
    assert_null(s);

    /* a NULL map: required is an error without position, optional is fine */
    rc = deck_double(NULL, "q", true, 0, 1, &x, &err);
    assert_int_equal(rc, SPALL_ERR_INPUT);
    assert_non_null(strstr(err.msg, "missing required key 'q'"));
    assert_int_equal(deck_double(NULL, "q", false, 0, 1, &x, &err), SPALL_OK);
    deck_destroy(&d);
}

static void test_long(void **state)
{
    (void)state;
    struct deck *d = load_ok("n: 42\nm: 1e6\nk: 2.5\nj: 11\ni: -3\nh: 99999999999999999999999\n");
    struct spall_error err = {0};
    long v = 0;
    assert_int_equal(deck_long(d->root, "n", true, 0, 100, &v, &err), SPALL_OK);
    assert_int_equal(v, 42);
    assert_int_equal(deck_long(d->root, "m", true, LONG_MIN, LONG_MAX, &v, &err), SPALL_OK);
    assert_int_equal(v, 1000000);
    int rc = deck_long(d->root, "k", true, LONG_MIN, LONG_MAX, &v, &err);
    check_msg(rc, &err, 3, 4, "key 'k' must be an integer; got '2.5'");
    rc = deck_long(d->root, "j", true, 1, 10, &v, &err);
    check_msg(rc, &err, 4, 4, "key 'j' = 11 is out of range; expected a value in [1, 10]");
    rc = deck_long(d->root, "i", true, 0, LONG_MAX, &v, &err);
    check_msg(rc, &err, 5, 4, "key 'i' = -3 is out of range; expected a value >= 0");
    rc = deck_long(d->root, "h", true, LONG_MIN, LONG_MAX, &v, &err);
    check_msg(rc, &err, 6, 4, "must be an integer");
    assert_int_equal(v, 1000000);
    deck_destroy(&d);
}

static void test_bool(void **state)
{
    (void)state;
    struct deck *d = load_ok("a: true\nb: No\nc: ON\nd: off\ne: YES\nf: FALSE\ng: maybe\n"
                             "h: 1\n");
    struct spall_error err = {0};
    const char *keys = "abcdef";
    const bool want[] = {true, false, true, false, true, false};
    for (int i = 0; i < 6; ++i) {
        char k[2] = {keys[i], '\0'};
        bool v = !want[i];
        assert_int_equal(deck_bool(d->root, k, true, &v, &err), SPALL_OK);
        assert_int_equal(v, want[i]);
    }
    bool v = true;
    int rc = deck_bool(d->root, "g", true, &v, &err);
    check_msg(rc, &err, 7, 4, "key 'g' must be true or false");
    assert_non_null(strstr(err.msg, "got 'maybe'"));
    rc = deck_bool(d->root, "h", true, &v, &err);
    check_msg(rc, &err, 8, 4, "got '1'");
    assert_true(v);
    deck_destroy(&d);
}

static void test_string_and_enum(void **state)
{
    (void)state;
    struct deck *d = load_ok("name: probe\n"
                             "model:\n"
                             "  type:   foo\n"
                             "  kind: sph\n"
                             "  list: [a]\n"
                             "empty:\n");
    struct spall_error err = {0};
    const char *s = NULL;
    assert_int_equal(deck_string(d->root, "name", true, &s, &err), SPALL_OK);
    assert_string_equal(s, "probe");
    int rc = deck_string(d->root, "empty", true, &s, &err);
    check_msg(rc, &err, 6, 7, "key 'empty' must be a string; got an empty value");
    rc = deck_string(d->root, "model", true, &s, &err);
    check_msg(rc, &err, 3, 3, "key 'model' must be a string; got a mapping");

    static const char *const models[] = {"lattice", "sph", NULL};
    const struct deck_node *m = deck_peek(d->root, "model");
    int idx = -1;
    assert_int_equal(deck_enum(m, "kind", true, models, &idx, &err), SPALL_OK);
    assert_int_equal(idx, 1);
    idx = -1;
    rc = deck_enum(m, "type", true, models, &idx, &err);
    check_msg(rc, &err, 3, 11,
              "key 'type' = 'foo' is not valid; expected one of: lattice, sph");
    assert_int_equal(idx, -1);
    rc = deck_enum(m, "list", true, models, &idx, &err);
    check_msg(rc, &err, 5, 9, "must be one of: lattice, sph; got a sequence");
    deck_destroy(&d);
}

static void test_vector(void **state)
{
    (void)state;
    struct deck *d = load_ok("p2: [1, 2]\n"
                             "p3: [1, 2, 3]\n"
                             "p4: [1, 2, 3, 4]\n"
                             "p1: [1]\n"
                             "points: {x: 1}\n"
                             "bad: [1, x]\n"
                             "blk:\n"
                             "  - 0.5\n"
                             "  - -0.5\n");
    struct spall_error err = {0};
    double v[3] = {9, 9, 9};
    assert_int_equal(deck_vector(d->root, "p2", true, 2, 3, v, &err), SPALL_OK);
    assert_true(v[0] == 1 && v[1] == 2 && v[2] == 0); /* trailing component filled with 0 */
    assert_int_equal(deck_vector(d->root, "p3", true, 2, 3, v, &err), SPALL_OK);
    assert_true(v[0] == 1 && v[1] == 2 && v[2] == 3);
    assert_int_equal(deck_vector(d->root, "blk", true, 2, 2, v, &err), SPALL_OK);
    assert_true(v[0] == 0.5 && v[1] == -0.5);

    v[0] = v[1] = v[2] = 7;
    int rc = deck_vector(d->root, "p4", true, 2, 3, v, &err);
    check_msg(rc, &err, 3, 5, "key 'p4' must be a sequence of 2 to 3 numbers; got 4 items");
    rc = deck_vector(d->root, "p1", true, 2, 3, v, &err);
    check_msg(rc, &err, 4, 5, "got 1 item");
    rc = deck_vector(d->root, "points", true, 2, 3, v, &err);
    check_msg(rc, &err, 5, 9, "key 'points' must be a sequence of 2 to 3 numbers; got a mapping");
    rc = deck_vector(d->root, "bad", true, 2, 2, v, &err);
    check_msg(rc, &err, 6, 10, "must be a number; got 'x'");
    assert_non_null(strstr(err.msg, "'bad[1]'"));
    rc = deck_vector(d->root, "p3", true, 3, 3, v, &err); /* ok */
    assert_int_equal(rc, SPALL_OK);
    v[0] = v[1] = v[2] = 7;
    rc = deck_vector(d->root, "p2", true, 3, 3, v, &err);
    check_msg(rc, &err, 1, 5, "must be a sequence of 3 numbers; got 2 items");
    assert_true(v[0] == 7 && v[1] == 7 && v[2] == 7); /* untouched on error */
    assert_int_equal(deck_vector(d->root, "nope", false, 2, 3, v, &err), SPALL_OK);
    assert_true(v[0] == 7);
    deck_destroy(&d);
}

static void test_node_double(void **state)
{
    (void)state;
    struct deck *d = load_ok("xs: [1.5, oops, [2]]\n");
    const struct deck_node *xs = deck_peek(d->root, "xs");
    struct spall_error err = {0};
    double x = 0;
    assert_int_equal(deck_node_double(xs->items[0], &x, &err), SPALL_OK);
    assert_true(x == 1.5);
    int rc = deck_node_double(xs->items[1], &x, &err);
    check_msg(rc, &err, 1, 11, "expected a number; got 'oops'");
    rc = deck_node_double(xs->items[2], &x, &err);
    check_msg(rc, &err, 1, 17, "expected a number; got a sequence");
    assert_int_equal(deck_node_double(NULL, &x, &err), SPALL_ERR_INPUT);
    assert_true(x == 1.5);
    deck_destroy(&d);
}

static void test_expect_kind(void **state)
{
    (void)state;
    struct deck *d = load_ok("lattice: [1, 2]\nbodies: 3\nok: {a: 1}\n");
    struct spall_error err = {0};
    /* @p what is the expectation, as deck_build.c passes it */
    int rc = deck_expect_map(deck_peek(d->root, "lattice"), "the lattice mapping (type, ...)",
                             &err);
    check_msg(rc, &err, 1, 10, "expected the lattice mapping (type, ...); got a sequence");
    rc = deck_expect_seq(deck_peek(d->root, "bodies"), NULL, &err);
    check_msg(rc, &err, 2, 9, "expected a sequence; got '3'");
    rc = deck_expect_map(deck_peek(d->root, "bodies"), NULL, &err);
    check_msg(rc, &err, 2, 9, "expected a mapping; got '3'");
    assert_int_equal(deck_expect_map(deck_peek(d->root, "ok"), "ok", &err), SPALL_OK);
    assert_int_equal(deck_expect_seq(deck_peek(d->root, "lattice"), "l", &err), SPALL_OK);
    rc = deck_expect_map(NULL, "a solver mapping", &err);
    assert_int_equal(rc, SPALL_ERR_INPUT);
    assert_string_equal(err.msg, "missing value; expected a solver mapping");
    deck_destroy(&d);
}

static void test_get_marks_peek_does_not(void **state)
{
    (void)state;
    struct deck *d = load_ok("a: 1\nb: 2\n");
    const struct deck_node *r = d->root;
    assert_false(r->used[0]);
    assert_non_null(deck_peek(r, "a"));
    assert_false(r->used[0]);
    assert_non_null(deck_get(r, "a"));
    assert_true(r->used[0]);
    assert_false(r->used[1]);
    assert_null(deck_get(r, "c"));
    assert_null(deck_get(NULL, "a"));
    deck_destroy(&d);
}

static void test_unknown_key(void **state)
{
    (void)state;
    struct deck *d = load_ok("materials:\n"
                             "  epoxy:\n"
                             "    density: 1200\n"
                             "    youngs_modulus: 3e9\n"
                             "    densty: 1100\n"
                             "    nested: {zz: 1}\n");
    struct spall_error err = {0};
    const struct deck_node *mats = deck_get(d->root, "materials");
    const struct deck_node *ep = deck_get(mats, "epoxy");
    double x;
    assert_int_equal(deck_double_pos(ep, "density", true, &x, &err), SPALL_OK);
    assert_int_equal(deck_double_pos(ep, "youngs_modulus", true, &x, &err), SPALL_OK);
    static const char *const allowed[] = {"density", "youngs_modulus", NULL};
    int rc = deck_check_unused(ep, "materials.epoxy", allowed, &err);
    check_msg(rc, &err, 5, 5,
              "unknown key 'densty' in 'materials.epoxy'; expected one of: density, "
              "youngs_modulus");
    /* once it is read, the next unused key is reported */
    (void)deck_get(ep, "densty");
    rc = deck_check_unused(ep, "materials.epoxy", allowed, &err);
    check_msg(rc, &err, 6, 5, "unknown key 'nested'");
    (void)deck_get(ep, "nested");
    assert_int_equal(deck_check_unused(ep, "materials.epoxy", allowed, &err), SPALL_OK);
    /* not recursive: 'zz' inside nested is not reported by the parent's check */
    assert_int_equal(deck_check_unused(d->root, "deck", NULL, &err), SPALL_OK);
    /* an allowed key that was not read is not "unknown" */
    struct deck *d2 = load_ok("a: 1\nb: 2\n");
    static const char *const ab[] = {"a", "b", NULL};
    assert_int_equal(deck_check_unused(d2->root, "top", ab, &err), SPALL_OK);
    static const char *const only_a[] = {"a", NULL};
    rc = deck_check_unused(d2->root, "top", only_a, &err);
    check_msg(rc, &err, 2, 1, "unknown key 'b' in 'top'; expected one of: a");
    static const char *const none[] = {NULL};
    rc = deck_check_unused(d2->root, "top", none, &err);
    check_msg(rc, &err, 1, 1, "unknown key 'a' in 'top'; expected no keys here");
    rc = deck_check_unused(d2->root, NULL, NULL, &err);
    check_msg(rc, &err, 1, 1, "unknown key 'a'");
    assert_null(strstr(err.msg, "expected"));
    deck_destroy(&d2);
    /* a key holding a newline still gives a one-line message */
    d2 = load_ok("\"bad\\nkey\": 1\n");
    rc = deck_check_unused(d2->root, "top", only_a, &err);
    check_msg(rc, &err, 1, 1, "unknown key 'bad key'");
    assert_null(strchr(err.msg, '\n'));
    deck_destroy(&d2);
    deck_destroy(&d);
}

static void test_getter_on_non_mapping(void **state)
{
    (void)state;
    struct deck *d = load_ok("seq: [1, 2]\nn: ' 12 '\n");
    struct spall_error err = {0};
    double x = 3;
    int rc = deck_double(deck_peek(d->root, "seq"), "a", false, 0, 1, &x, &err);
    check_msg(rc, &err, 1, 6, "expected a mapping holding key 'a'; got a sequence");
    assert_true(x == 3.0);
    long n = 0;
    assert_int_equal(deck_long(d->root, "n", true, 0, 100, &n, &err), SPALL_OK);
    assert_int_equal(n, 12);
    deck_destroy(&d);
}

static void test_error_helpers(void **state)
{
    (void)state;
    struct deck *d = load_ok("solver:\n  cfl:   0.9\n");
    const struct deck_node *s = deck_peek(d->root, "solver");
    struct spall_error err = {0};
    int rc = deck_error(&err, deck_peek(s, "cfl"), "cfl %g is too large; expected <= %g", 0.9,
                        0.5);
    check_msg(rc, &err, 2, 10, "cfl 0.9 is too large; expected <= 0.5");
    rc = deck_error_key(&err, s, "cfl", "bad %s", "thing");
    check_msg(rc, &err, 2, 3, "bad thing");
    rc = deck_error_key(&err, s, "absent", "falls back");
    check_msg(rc, &err, 2, 3, "falls back"); /* the mapping itself starts at 2:3 */
    rc = deck_error(&err, NULL, "no position %d", 1);
    assert_int_equal(rc, SPALL_ERR_INPUT);
    assert_string_equal(err.msg, "no position 1");
    assert_int_equal(deck_error(NULL, s, "dropped"), SPALL_ERR_INPUT);
    /* callers re-position an existing message by passing err->msg itself */
    spall_error_set(&err, SPALL_ERR_INPUT, "inner problem");
    rc = deck_error_key(&err, s, "cfl", "%s", err.msg);
    check_msg(rc, &err, 2, 3, "inner problem");
    rc = deck_error(&err, s, "outer: %s", err.msg);
    check_msg(rc, &err, 2, 3, "outer: deck.yaml:2:3: inner problem");
    deck_destroy(&d);
}

static void test_long_scalar_excerpt(void **state)
{
    (void)state;
    char text[400];
    char big[301];
    memset(big, 'z', 300);
    big[300] = '\0';
    snprintf(text, sizeof text, "k: %s\n", big);
    struct deck *d = load_ok(text);
    struct spall_error err = {0};
    double x;
    int rc = deck_double(d->root, "k", true, 0, 1, &x, &err);
    check_msg(rc, &err, 1, 4, "...'");
    assert_true(strlen(err.msg) < 120); /* the value is cut, not echoed whole */
    deck_destroy(&d);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_tree_positions),
        cmocka_unit_test(test_flow_and_quoting),
        cmocka_unit_test(test_empty_documents),
        cmocka_unit_test(test_syntax_bad_indentation),
        cmocka_unit_test(test_syntax_unclosed_bracket),
        cmocka_unit_test(test_syntax_tab_and_control_chars),
        cmocka_unit_test(test_duplicate_key),
        cmocka_unit_test(test_nonscalar_key_and_alias),
        cmocka_unit_test(test_multiple_documents),
        cmocka_unit_test(test_nesting_limit),
        cmocka_unit_test(test_file_not_found),
        cmocka_unit_test(test_file_roundtrip),
        cmocka_unit_test(test_double_ok_and_spaces),
        cmocka_unit_test(test_double_not_a_number),
        cmocka_unit_test(test_non_finite_refused),
        cmocka_unit_test(test_double_ranges),
        cmocka_unit_test(test_double_pos_exclusive),
        cmocka_unit_test(test_missing_required),
        cmocka_unit_test(test_long),
        cmocka_unit_test(test_bool),
        cmocka_unit_test(test_string_and_enum),
        cmocka_unit_test(test_vector),
        cmocka_unit_test(test_node_double),
        cmocka_unit_test(test_expect_kind),
        cmocka_unit_test(test_get_marks_peek_does_not),
        cmocka_unit_test(test_unknown_key),
        cmocka_unit_test(test_getter_on_non_mapping),
        cmocka_unit_test(test_error_helpers),
        cmocka_unit_test(test_long_scalar_excerpt),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
