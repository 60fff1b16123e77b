/* Tests for io/output.h: HDF5 frames + XDMF index, frame read-back, history.csv. */
#define _POSIX_C_SOURCE 200809L

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <hdf5.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "core/fields.h"
#include "core/particles.h"
#include "core/sim.h"
#include "io/output.h"
#include "spall/error.h"

#define NP 5

struct fixture {
    char dir[64];
    struct sim *s;
    double *damage;
    double *traction[3];
};

/* ------------------------------------------------------------ state set-up */

/* Deterministic state of frame k, chosen so values are not round numbers. */
static double pos_val(int k, size_t i, int c) { return 1e-3 * (double)i + 0.37 * c + k / 3.0; }
static double vel_val(int k, size_t i, int c) { return (double)(k + 1) * (i + 0.5) - c / 7.0; }
static double dmg_val(int k, size_t i) { return (double)(k * (int)i) / 11.0; }
static double tr_val(int k, size_t i, int c) { return 1e6 * (k + 2) + 1e3 * (double)i + c; }

static void displacement_compute(const void *ctx, size_t n, double *out)
{
    const struct sim *s = ctx;
    for (size_t i = 0; i < n; i++)
        for (int d = 0; d < s->dim; d++)
            out[i * (size_t)s->dim + (size_t)d] = s->p->x[d][i] - s->p->x0[d][i];
}

static void set_frame_state(struct fixture *fx, int k)
{
    struct sim *s = fx->s;
    for (size_t i = 0; i < NP; i++) {
        for (int c = 0; c < 2; c++) {
            s->p->x[c][i] = pos_val(k, i, c);
            s->p->v[c][i] = vel_val(k, i, c);
        }
        fx->damage[i] = dmg_val(k, i);
        for (int c = 0; c < 3; c++)
            fx->traction[c][i] = tr_val(k, i, c);
    }
    s->t = 0.25e-6 * k;
    s->step = 100 * k + 7;
}

static int setup(void **state)
{
    struct fixture *fx = calloc(1, sizeof *fx);
    struct spall_error err = {0};
    strcpy(fx->dir, "/tmp/spall_test_output_XXXXXX");
    assert_non_null(mkdtemp(fx->dir));
    struct sim *s = calloc(1, sizeof *s);
    s->dim = 2;
    assert_int_equal(particles_create(&s->p, 2, 2, &err), SPALL_OK);
    for (size_t i = 0; i < NP; i++) {
        double pos[3] = {pos_val(0, i, 0), pos_val(0, i, 1), 0.0};
        assert_int_equal(particles_append(s->p, pos, 0, NULL, &err), SPALL_OK);
    }
    fx->damage = calloc(NP, sizeof(double));
    for (int c = 0; c < 3; c++)
        fx->traction[c] = calloc(NP, sizeof(double));
    assert_int_equal(field_registry_create(&s->fields, &err), SPALL_OK);
    struct field_registry *r = s->fields;
    unsigned od = FIELD_OUTPUT | FIELD_DEFAULT;
    double **xs[2] = {&s->p->x[0], &s->p->x[1]};
    double **vs[2] = {&s->p->v[0], &s->p->v[1]};
    double **ds[1] = {&fx->damage};
    double **ts[3] = {&fx->traction[0], &fx->traction[1], &fx->traction[2]};
    assert_int_equal(field_registry_add_f64(r, "position", "m", 2, xs, od, &err), SPALL_OK);
    assert_int_equal(field_registry_add_f64(r, "velocity", "m/s", 2, vs, od, &err), SPALL_OK);
    assert_int_equal(field_registry_add_f64(r, "damage", "1", 1, ds, od, &err), SPALL_OK);
    /* a 3-component vector in 2D must say so: 3 components of unknown kind are a
     * 2D symmetric tensor (xx yy xy) to the XDMF writer (output_xdmf.h) */
    assert_int_equal(field_registry_add_f64_parity(r, "traction", "Pa", 3, ts, od, FIELD_VECTOR, &err),
                     SPALL_OK);
    assert_int_equal(field_registry_add_f64(r, "internal", "1", 1, ds, FIELD_RESTART, &err),
                     SPALL_OK);
    assert_int_equal(field_registry_add_f64(r, "force", "N", 2, vs, FIELD_OUTPUT, &err), SPALL_OK);
    struct field_desc d;
    memset(&d, 0, sizeof d);
    strcpy(d.name, "displacement");
    strcpy(d.unit, "m");
    d.ncomp = 2;
    d.type = FIELD_F64;
    d.flags = od;
    d.compute = displacement_compute;
    d.ctx = s;
    assert_int_equal(field_registry_add(r, &d, &err), SPALL_OK);
    memset(&d, 0, sizeof d);
    strcpy(d.name, "id");
    strcpy(d.unit, "1");
    d.ncomp = 1;
    d.type = FIELD_I64;
    d.flags = od;
    d.comp[0] = (void **)&s->p->gid;
    assert_int_equal(field_registry_add(r, &d, &err), SPALL_OK);
    fx->s = s;
    *state = fx;
    return 0;
}

static void remove_in(const char *dir, const char *name)
{
    char path[256];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    remove(path);
}

static int teardown(void **state)
{
    struct fixture *fx = *state;
    char name[64];
    for (int k = 0; k < 8; k++) {
        snprintf(name, sizeof name, "fields_%06d.h5", k);
        remove_in(fx->dir, name);
    }
    remove_in(fx->dir, "fields.xdmf");
    remove_in(fx->dir, "history.csv");
    rmdir(fx->dir);
    field_registry_destroy(&fx->s->fields);
    particles_destroy(&fx->s->p);
    free(fx->s);
    free(fx->damage);
    for (int c = 0; c < 3; c++)
        free(fx->traction[c]);
    free(fx);
    return 0;
}

struct path_buf {
    char s[128];
};

static struct path_buf frame_path(const struct fixture *fx, int k)
{
    struct path_buf p;
    snprintf(p.s, sizeof p.s, "%s/fields_%06d.h5", fx->dir, k);
    return p;
}

static int file_exists(const char *path)
{
    FILE *fp = fopen(path, "rb");
    if (fp)
        fclose(fp);
    return fp != NULL;
}

static char *slurp(const char *path)
{
    FILE *fp = fopen(path, "rb");
    if (!fp)
        return NULL;
    fseek(fp, 0, SEEK_END);
    long len = ftell(fp);
    fseek(fp, 0, SEEK_SET);
    char *s = malloc((size_t)len + 1);
    size_t got = fread(s, 1, (size_t)len, fp);
    s[got] = '\0';
    fclose(fp);
    return s;
}

static size_t count_substr(const char *hay, const char *needle)
{
    size_t k = 0;
    for (const char *p = strstr(hay, needle); p; p = strstr(p + 1, needle))
        k++;
    return k;
}

/* Writes three frames with the default field set. */
static void write_three(struct fixture *fx)
{
    struct spall_error err = {0};
    struct field_writer *w = NULL;
    assert_int_equal(field_writer_create(&w, fx->dir, fx->s, NULL, 0, &err), SPALL_OK);
    for (int k = 0; k < 3; k++) {
        set_frame_state(fx, k);
        assert_int_equal(field_writer_write(w, fx->s, &err), SPALL_OK);
        assert_int_equal(field_writer_frames(w), (size_t)(k + 1));
    }
    field_writer_destroy(&w);
    assert_null(w);
}

static void read_expect(const char *path, const char *name, size_t n, size_t ncomp, double *data_out,
                        double *time)
{
    struct spall_error err = {0};
    double *data = NULL;
    size_t rn = 0, rc = 0;
    int st = field_frame_read(path, name, &data, &rn, &rc, time, &err);
    if (st)
        fail_msg("%s", err.msg);
    assert_int_equal(rn, n);
    assert_int_equal(rc, ncomp);
    memcpy(data_out, data, n * ncomp * sizeof *data);
    free(data);
}

/* ------------------------------------------------------------ tests */

static void test_frames_round_trip(void **state)
{
    struct fixture *fx = *state;
    write_three(fx);
    double buf[NP * 3];
    for (int k = 0; k < 3; k++) {
        struct path_buf fp = frame_path(fx, k);
        const char *path = fp.s;
        double t = -1.0;
        read_expect(path, "position", NP, 3, buf, &t);
        assert_true(t == 0.25e-6 * k);
        for (size_t i = 0; i < NP; i++) {
            assert_true(buf[i * 3 + 0] == pos_val(k, i, 0));
            assert_true(buf[i * 3 + 1] == pos_val(k, i, 1));
            assert_true(buf[i * 3 + 2] == 0.0); /* 2D padded to XYZ */
        }
        read_expect(path, "velocity", NP, 2, buf, NULL);
        for (size_t i = 0; i < NP; i++)
            for (int c = 0; c < 2; c++)
                assert_true(buf[i * 2 + (size_t)c] == vel_val(k, i, c));
        read_expect(path, "damage", NP, 1, buf, NULL);
        for (size_t i = 0; i < NP; i++)
            assert_true(buf[i] == dmg_val(k, i));
        read_expect(path, "traction", NP, 3, buf, NULL);
        for (size_t i = 0; i < NP; i++)
            for (int c = 0; c < 3; c++)
                assert_true(buf[i * 3 + (size_t)c] == tr_val(k, i, c));
        read_expect(path, "displacement", NP, 2, buf, NULL); /* computed field */
        for (size_t i = 0; i < NP; i++)
            for (int c = 0; c < 2; c++)
                assert_true(buf[i * 2 + (size_t)c] == pos_val(k, i, c) - pos_val(0, i, c));
        read_expect(path, "id", NP, 1, buf, NULL); /* int64 field written as float64 */
        for (size_t i = 0; i < NP; i++)
            assert_true(buf[i] == (double)i);
        read_expect(path, "step", 1, 1, buf, NULL);
        assert_true(buf[0] == 100.0 * k + 7);

        /* not FIELD_DEFAULT: absent */
        struct spall_error err = {0};
        double *data = NULL;
        size_t n, nc;
        assert_int_equal(field_frame_read(path, "force", &data, &n, &nc, NULL, &err),
                         SPALL_ERR_INPUT);
        assert_null(data);
        assert_non_null(strstr(err.msg, "force"));
    }
    /* no temporaries left behind */
    char tmp[128];
    snprintf(tmp, sizeof tmp, "%s/.fields_000002.h5.tmp", fx->dir);
    assert_false(file_exists(tmp));
    snprintf(tmp, sizeof tmp, "%s/.fields.xdmf.tmp", fx->dir);
    assert_false(file_exists(tmp));
    assert_false(file_exists(frame_path(fx, 3).s));
}

static void test_units_and_types_in_h5(void **state)
{
    struct fixture *fx = *state;
    write_three(fx);
    hid_t f = H5Fopen(frame_path(fx, 1).s, H5F_ACC_RDONLY, H5P_DEFAULT);
    assert_true(f >= 0);
    const char *names[] = {"velocity", "traction", "damage", "position", "time"};
    const char *units[] = {"m/s", "Pa", "1", "m", "s"};
    for (int k = 0; k < 5; k++) {
        hid_t ds = H5Dopen2(f, names[k], H5P_DEFAULT);
        assert_true(ds >= 0);
        hid_t dt = H5Dget_type(ds);
        assert_int_equal(H5Tget_class(dt), H5T_FLOAT);
        assert_int_equal(H5Tget_size(dt), 8);
        H5Tclose(dt);
        hid_t a = H5Aopen(ds, "unit", H5P_DEFAULT);
        assert_true(a >= 0);
        hid_t at = H5Aget_type(a);
        char u[32] = {0};
        assert_true(H5Tget_size(at) < sizeof u);
        assert_true(H5Aread(a, at, u) >= 0);
        assert_string_equal(u, units[k]);
        H5Tclose(at);
        H5Aclose(a);
        H5Dclose(ds);
    }
    hid_t ds = H5Dopen2(f, "step", H5P_DEFAULT);
    hid_t dt = H5Dget_type(ds);
    assert_int_equal(H5Tget_class(dt), H5T_INTEGER);
    assert_int_equal(H5Tget_size(dt), 8);
    H5Tclose(dt);
    H5Dclose(ds);
    H5Fclose(f);
}

/* Small XML well-formedness check (elements nest and close, attributes are
 * quoted, one root).  libxml2 is not a project dependency, so this stands in
 * for a parser; it is enough to catch a missing or mis-ordered close tag. */
static int xml_well_formed(const char *s)
{
    char stack[16][32];
    int depth = 0, roots = 0;
    const char *p = s;
    while (*p) {
        if (*p != '<') {
            if (*p == '&' || *p == '>')
                return 0;
            p++;
            continue;
        }
        if (p[1] == '?') {
            p = strstr(p, "?>");
            if (!p)
                return 0;
            p += 2;
            continue;
        }
        int closing = p[1] == '/';
        const char *q = p + 1 + closing;
        size_t len = strcspn(q, " \t\n/>");
        if (len == 0 || len >= 32)
            return 0;
        char name[32];
        memcpy(name, q, len);
        name[len] = '\0';
        q += len;
        /* attributes: name="value" */
        while (*q == ' ' || *q == '\n' || *q == '\t') {
            while (*q == ' ' || *q == '\n' || *q == '\t')
                q++;
            if (*q == '/' || *q == '>')
                break;
            size_t an = strcspn(q, "=> \n");
            if (an == 0 || q[an] != '=' || q[an + 1] != '"' || closing)
                return 0;
            const char *end = strchr(q + an + 2, '"');
            if (!end || memchr(q + an + 2, '<', (size_t)(end - q - an - 2)))
                return 0;
            q = end + 1;
        }
        int self_close = 0;
        if (*q == '/') {
            self_close = 1;
            q++;
        }
        if (*q != '>')
            return 0;
        p = q + 1;
        if (closing) {
            if (depth == 0 || strcmp(stack[depth - 1], name) != 0)
                return 0;
            depth--;
        } else if (!self_close) {
            if (depth == 0)
                roots++;
            if (depth == 16)
                return 0;
            strcpy(stack[depth++], name);
        } else if (depth == 0) {
            roots++;
        }
    }
    return depth == 0 && roots == 1;
}

static void test_xdmf_index(void **state)
{
    struct fixture *fx = *state;
    write_three(fx);
    char path[128];
    snprintf(path, sizeof path, "%s/fields.xdmf", fx->dir);
    char *x = slurp(path);
    assert_non_null(x);
    assert_true(xml_well_formed(x));
    assert_false(xml_well_formed("<a><b></a></b>")); /* the checker itself rejects bad XML */
    assert_false(xml_well_formed("<a x=1></a>"));
    assert_non_null(strstr(x, "<Xdmf Version=\"3.0\">"));
    assert_non_null(strstr(x, "GridType=\"Collection\" CollectionType=\"Temporal\""));
    assert_int_equal(count_substr(x, "<Grid "), 4);
    assert_int_equal(count_substr(x, "GridType=\"Uniform\""), 3);
    assert_int_equal(count_substr(x, "TopologyType=\"Polyvertex\" NumberOfElements=\"5\""), 3);
    assert_int_equal(count_substr(x, "GeometryType=\"XYZ\""), 3);
    /* explicit vertex cells (issue 23: Xdmf3ReaderS shows no cells without) */
    assert_int_equal(count_substr(x, "Dimensions=\"5 1\" NumberType=\"Int\" Precision=\"8\" "
                                     "Format=\"HDF\">fields_000001.h5:/connectivity<"),
                     1);
    assert_int_equal(count_substr(x, "Dimensions=\"5 3\" NumberType=\"Float\" Precision=\"8\" "
                                     "Format=\"HDF\">fields_000000.h5:/position<"),
                     1);
    const char *tv = x;
    for (int k = 0; k < 3; k++) {
        char needle[64];
        snprintf(needle, sizeof needle, "fields_%06d.h5:/", k);
        assert_int_equal(count_substr(x, needle), 7); /* connectivity, position, 5 default attributes */
        /* frame times in order, exact after parsing, written short */
        tv = strstr(tv, "<Time Value=\"");
        assert_non_null(tv);
        tv += strlen("<Time Value=\"");
        char *end;
        assert_true(strtod(tv, &end) == 0.25e-6 * k);
        assert_true(*end == '"');
    }
    assert_non_null(strstr(x, "<Time Value=\"2.5e-07\"/>"));
    assert_null(strstr(tv, "<Time "));
    /* attribute kinds ParaView understands (see output_hdf5.c) */
    assert_int_equal(count_substr(x, "Name=\"velocity\" AttributeType=\"Matrix\""), 3);
    assert_int_equal(count_substr(x, "Name=\"displacement\" AttributeType=\"Matrix\""), 3);
    assert_int_equal(count_substr(x, "Name=\"traction\" AttributeType=\"Vector\""), 3);
    assert_int_equal(count_substr(x, "Name=\"damage\" AttributeType=\"Scalar\""), 3);
    assert_int_equal(count_substr(x, "Dimensions=\"5\" NumberType"), 6); /* damage, id */
    assert_null(strstr(x, "force"));
    assert_null(strstr(x, "internal"));
    free(x);
}

static void test_selected_fields(void **state)
{
    struct fixture *fx = *state;
    struct spall_error err = {0};
    struct field_writer *w = NULL;
    const char *names[] = {"force", "damage", "force"};
    assert_int_equal(field_writer_create(&w, fx->dir, fx->s, names, 3, &err), SPALL_OK);
    set_frame_state(fx, 2);
    assert_int_equal(field_writer_write(w, fx->s, &err), SPALL_OK);
    field_writer_destroy(&w);
    double buf[NP * 3];
    read_expect(frame_path(fx, 0).s, "force", NP, 2, buf, NULL);
    assert_true(buf[3] == vel_val(2, 1, 1));
    read_expect(frame_path(fx, 0).s, "position", NP, 3, buf, NULL); /* always written */
    double *data = NULL;
    size_t n, nc;
    assert_int_equal(field_frame_read(frame_path(fx, 0).s, "velocity", &data, &n, &nc, NULL, &err),
                     SPALL_ERR_INPUT);
    char path[128];
    snprintf(path, sizeof path, "%s/fields.xdmf", fx->dir);
    char *x = slurp(path);
    assert_int_equal(count_substr(x, "Name=\"force\""), 1); /* listed twice, written once */
    assert_int_equal(count_substr(x, "<Attribute "), 2);
    free(x);
}

static void test_unknown_field(void **state)
{
    struct fixture *fx = *state;
    struct spall_error err = {0};
    struct field_writer *w = (struct field_writer *)&err; /* must be reset to NULL */
    const char *names[] = {"velocity", "bogus"};
    assert_int_equal(field_writer_create(&w, fx->dir, fx->s, names, 2, &err), SPALL_ERR_INPUT);
    assert_null(w);
    assert_non_null(strstr(err.msg, "unknown output field 'bogus'"));
    assert_non_null(strstr(err.msg, "registered fields: position, velocity, damage"));
    assert_non_null(strstr(err.msg, "displacement"));
    assert_null(strstr(err.msg, "internal")); /* not an output field: not offered */

    const char *restart_only[] = {"internal"};
    assert_int_equal(field_writer_create(&w, fx->dir, fx->s, restart_only, 1, &err),
                     SPALL_ERR_INPUT);
    assert_null(w);
    assert_non_null(strstr(err.msg, "'internal'"));

    /* a field called "time" would overwrite the frame's /time dataset */
    double **ds[1] = {&fx->damage};
    assert_int_equal(field_registry_add_f64(fx->s->fields, "time", "s", 1, ds, FIELD_OUTPUT, &err),
                     SPALL_OK);
    const char *clash[] = {"time"};
    assert_int_equal(field_writer_create(&w, fx->dir, fx->s, clash, 1, &err), SPALL_ERR_INTERNAL);
    assert_null(w);
    assert_non_null(strstr(err.msg, "'time'"));
}

static void test_missing_directory(void **state)
{
    struct fixture *fx = *state;
    struct spall_error err = {0};
    struct field_writer *w = NULL;
    char dir[128];
    snprintf(dir, sizeof dir, "%s/no/such/dir", fx->dir);
    assert_int_equal(field_writer_create(&w, dir, fx->s, NULL, 0, &err), SPALL_OK);
    assert_int_equal(field_writer_write(w, fx->s, &err), SPALL_ERR_IO);
    assert_non_null(strstr(err.msg, dir));
    assert_non_null(strstr(err.msg, "No such file or directory"));
    assert_int_equal(field_writer_frames(w), 0);
    field_writer_destroy(&w);

    double *data = NULL;
    size_t n = 7, nc = 7;
    char path[160];
    snprintf(path, sizeof path, "%s/fields_000000.h5", dir);
    assert_int_equal(field_frame_read(path, "position", &data, &n, &nc, NULL, &err), SPALL_ERR_IO);
    assert_non_null(strstr(err.msg, path));
    assert_null(data);
    assert_int_equal(n, 0);

    /* a file that is not HDF5 */
    snprintf(path, sizeof path, "%s/history.csv", fx->dir);
    FILE *fp = fopen(path, "w");
    fputs("not hdf5\n", fp);
    fclose(fp);
    assert_int_equal(field_frame_read(path, "position", &data, &n, &nc, NULL, &err), SPALL_ERR_IO);
    assert_non_null(strstr(err.msg, path));
}

/* 1D, no "position" in the registry, no particles: geometry comes from p->x,
 * padded to 3 components, and an empty frame is still valid. */
static void test_1d_fallback_and_empty(void **state)
{
    struct fixture *fx = *state;
    struct spall_error err = {0};
    struct sim s1;
    memset(&s1, 0, sizeof s1);
    s1.dim = 1;
    assert_int_equal(particles_create(&s1.p, 1, 4, &err), SPALL_OK);
    assert_int_equal(field_registry_create(&s1.fields, &err), SPALL_OK);
    struct field_writer *w = NULL;
    assert_int_equal(field_writer_create(&w, fx->dir, &s1, NULL, 0, &err), SPALL_OK);
    assert_int_equal(field_writer_write(w, &s1, &err), SPALL_OK); /* n = 0 */
    for (int i = 0; i < 3; i++) {
        double pos[3] = {0.5 * i, 0, 0};
        assert_int_equal(particles_append(s1.p, pos, 0, NULL, &err), SPALL_OK);
    }
    s1.t = 1.5;
    assert_int_equal(field_writer_write(w, &s1, &err), SPALL_OK);
    field_writer_destroy(&w);

    double *data = NULL;
    size_t n = 9, nc = 9;
    assert_int_equal(field_frame_read(frame_path(fx, 0).s, "position", &data, &n, &nc, NULL, &err),
                     SPALL_OK);
    assert_int_equal(n, 0);
    assert_int_equal(nc, 3);
    free(data);
    double buf[9], t = 0;
    read_expect(frame_path(fx, 1).s, "position", 3, 3, buf, &t);
    assert_true(t == 1.5);
    for (int i = 0; i < 3; i++) {
        assert_true(buf[i * 3] == 0.5 * i);
        assert_true(buf[i * 3 + 1] == 0.0 && buf[i * 3 + 2] == 0.0);
    }
    field_registry_destroy(&s1.fields);
    particles_destroy(&s1.p);
}

static void test_history_round_trip(void **state)
{
    struct fixture *fx = *state;
    struct spall_error err = {0};
    char path[128];
    snprintf(path, sizeof path, "%s/history.csv", fx->dir);
    const char *cols[] = {"time [s]", "kinetic [J]", "probe \"A\", vx [m/s]"};
    struct history_writer *h = NULL;
    assert_int_equal(history_writer_create(&h, path, cols, 3, &err), SPALL_OK);
    const double rows[3][3] = {{0.0, 1.0 / 3.0, -2.5}, {1e-7, 12345678901.0, 1e-300},
                               {2e-7, -0.0, 6.02214076e23}};
    for (int r = 0; r < 3; r++) {
        assert_int_equal(history_writer_append(h, rows[r], &err), SPALL_OK);
        /* flushed: a reader sees the row before the writer is closed */
        char *text = slurp(path);
        assert_int_equal(count_substr(text, "\n"), (size_t)r + 2);
        free(text);
    }
    history_writer_destroy(&h);
    assert_null(h);

    char expect[1024];
    int len = snprintf(expect, sizeof expect, "time [s],kinetic [J],\"probe \"\"A\"\", vx [m/s]\"\n");
    for (int r = 0; r < 3; r++)
        len += snprintf(expect + len, sizeof expect - (size_t)len, "%.10g,%.10g,%.10g\n",
                        rows[r][0], rows[r][1], rows[r][2]);
    char *text = slurp(path);
    assert_string_equal(text, expect);
    /* values parse back to within the 10 significant digits written */
    const char *line = strchr(text, '\n') + 1;
    for (int r = 0; r < 3; r++) {
        char *end;
        for (int c = 0; c < 3; c++) {
            double v = strtod(line, &end);
            double tol = 1e-9 * (rows[r][c] < 0 ? -rows[r][c] : rows[r][c]);
            assert_true(v - rows[r][c] <= tol && rows[r][c] - v <= tol);
            line = end + 1;
        }
    }
    assert_string_equal(text + strlen(text) - 1, "\n");
    free(text);
}

static void test_history_errors(void **state)
{
    struct fixture *fx = *state;
    struct spall_error err = {0};
    char path[128];
    snprintf(path, sizeof path, "%s/missing/history.csv", fx->dir);
    const char *cols[] = {"time [s]"};
    struct history_writer *h = NULL;
    assert_int_equal(history_writer_create(&h, path, cols, 1, &err), SPALL_ERR_IO);
    assert_null(h);
    assert_non_null(strstr(err.msg, path));
    assert_non_null(strstr(err.msg, "No such file"));

    snprintf(path, sizeof path, "%s/history.csv", fx->dir);
    const char *bad[] = {"time [s]", "two\nlines"};
    assert_int_equal(history_writer_create(&h, path, bad, 2, &err), SPALL_ERR_INPUT);
    assert_null(h);
    assert_non_null(strstr(err.msg, "column 2"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_frames_round_trip, setup, teardown),
        cmocka_unit_test_setup_teardown(test_units_and_types_in_h5, setup, teardown),
        cmocka_unit_test_setup_teardown(test_xdmf_index, setup, teardown),
        cmocka_unit_test_setup_teardown(test_selected_fields, setup, teardown),
        cmocka_unit_test_setup_teardown(test_unknown_field, setup, teardown),
        cmocka_unit_test_setup_teardown(test_missing_directory, setup, teardown),
        cmocka_unit_test_setup_teardown(test_1d_fallback_and_empty, setup, teardown),
        cmocka_unit_test_setup_teardown(test_history_round_trip, setup, teardown),
        cmocka_unit_test_setup_teardown(test_history_errors, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
