/**
 * @file output_hdf5.c
 * @brief HDF5 field frames plus an XDMF 3 index (see output.h).
 *
 * Frame layout (DIR/fields_NNNNNN.h5, NNNNNN = frame counter from 0):
 *   /time   scalar float64, attribute unit = "s"
 *   /step   scalar int64
 *   /connectivity  int64 0..n-1, the Polyvertex topology's explicit vertex
 *           cells (ParaView's Xdmf3ReaderS makes no cells without it)
 *   /NAME   float64, n x ncomp (rank 1 when ncomp == 1), attribute unit,
 *           one per selected field; n = owned particles only (ghosts are
 *           copies that belong to another rank's output).
 *   /position is always n x 3, padded with 0 in 1D/2D, because ParaView's
 *           XDMF readers need three coordinates for GeometryType XYZ;
 *           a 2D symmetric tensor is n x 6 (xdmf_file_ncomp: zz yz xz = 0).
 *
 * XDMF attribute types, component names and units: io/output_xdmf.c (a 2D
 * vector or tensor is a Matrix: a "Vector" promises 3 components).  Rigid
 * impactors and walls: DIR/bodies.xdmf, a temporal collection with one small
 * triangle mesh per body and frame (output_xdmf.c), at the frames' times.
 *
 * Crash safety: every file is first written under a hidden temporary name in
 * DIR and then rename()d over the final name (atomic within one file system),
 * so readers never see half a frame or half an index.
 */
#include "io/output.h"
#include "io/output_par.h"
#include "io/output_bonds.h"
#include "io/text_buf.h"
#include "io/output_xdmf.h"

#include "core/fields.h"
#include "core/parallel/comm.h"
#include "core/parallel/decomp.h"
#include "core/parallel/h5.h"
#include "core/particles.h"
#include "core/sim.h"
#include "spall/error.h"

#include <hdf5.h>

#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define OUTPUT_POSITION "position"
/* Vertex cell i of a frame is particle i: ParaView's default reader for
 * .xdmf (Xdmf3ReaderS) makes no cells from a Polyvertex topology without an
 * explicit connectivity array, and its default Surface representation then
 * shows nothing (issue 23). */
#define OUTPUT_CONNECTIVITY "connectivity"

struct out_field {
    char name[FIELD_NAME_LEN];
    int ncomp; /**< components as registered (position: the registry's, padded on write) */
    char unit[16];
    int parity; /**< enum field_parity: what the components are (output_xdmf.h) */
};

/* The XDMF <Grid> elements written so far are kept (struct text_buf), so the
 * index rewrite after each frame only formats the new frame. */
struct field_writer {
    char *dir;
    struct out_field *fields; /**< fields[0] is always position */
    size_t n_fields;
    size_t frames;
    struct text_buf grids;
    struct text_buf bodies; /**< bodies.xdmf's frames (rigid impactors, walls) */
    struct text_buf saved;  /**< field_writer_grids with bodies: both, for a checkpoint */
    double *buf; /**< gather buffer, n x max(ncomp, 6) */
    struct bond_writer *bonds; /**< output.fields lists `bonds` (output_bonds.h) */
    size_t buf_cap;
};

/* ---------------------------------------------------------------- helpers */

/* path_join, text_append: io/text_buf.h */

/** Field names become HDF5 paths and XML attribute values unescaped, and must
 *  not shadow /time or /step. */
static int name_is_safe(const char *name)
{
    if (!name[0] || strcmp(name, "time") == 0 || strcmp(name, "step") == 0 ||
        strcmp(name, OUTPUT_CONNECTIVITY) == 0)
        return 0;
    for (const char *c = name; *c; c++) {
        int ok = (*c >= 'a' && *c <= 'z') || (*c >= 'A' && *c <= 'Z') ||
                 (*c >= '0' && *c <= '9') || *c == '_' || *c == '-' || *c == '.';
        if (!ok)
            return 0;
    }
    return 1;
}

/* HDF5 prints its error stack to stderr by default; the library must report
 * through spall_error instead.  The previous handler is restored afterwards so
 * that an application using HDF5 itself keeps its own setting. */
struct h5_quiet {
    H5E_auto2_t func;
    void *data;
};

static void h5_quiet_begin(struct h5_quiet *q)
{
    H5Eget_auto2(H5E_DEFAULT, &q->func, &q->data);
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
}

static void h5_quiet_end(const struct h5_quiet *q)
{
    H5Eset_auto2(H5E_DEFAULT, q->func, q->data);
}

struct h5_detail {
    char text[256];
};

static herr_t h5_walk_cb(unsigned n, const H5E_error2_t *e, void *data)
{
    struct h5_detail *d = data;
    if (n != 0 || !e->desc)
        return 0;
    /* the file drivers report "..., errno = 2, error message = 'No such file
     * or directory', ..."; the quoted part is all a user needs */
    const char *key = "error message = '";
    const char *m = strstr(e->desc, key);
    if (m) {
        m += strlen(key);
        const char *end = strchr(m, '\'');
        int len = end ? (int)(end - m) : (int)strlen(m);
        snprintf(d->text, sizeof d->text, "%.*s", len, m);
    } else {
        snprintf(d->text, sizeof d->text, "%s", e->desc);
    }
    return 0;
}

/** Record an HDF5 failure: "WHAT 'PATH': <innermost HDF5 message>".  Must be
 *  called before any other HDF5 call, which would clear the error stack. */
static int h5_fail(struct spall_error *err, const char *what, const char *path)
{
    struct h5_detail d;
    snprintf(d.text, sizeof d.text, "HDF5 call failed");
    H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, h5_walk_cb, &d);
    return spall_error_set(err, SPALL_ERR_IO, "%s '%s': %s", what, path, d.text);
}

static int h5_write_unit(hid_t obj, const char *unit)
{
    const char *u = unit[0] ? unit : "1";
    hid_t type = H5Tcopy(H5T_C_S1);
    if (type < 0)
        return -1;
    /* size counts the terminator, as NULLTERM promises one to C readers */
    int bad = H5Tset_size(type, strlen(u) + 1) < 0 || H5Tset_strpad(type, H5T_STR_NULLTERM) < 0;
    hid_t space = H5Screate(H5S_SCALAR);
    hid_t attr = -1;
    if (!bad && space >= 0)
        attr = H5Acreate2(obj, "unit", type, space, H5P_DEFAULT, H5P_DEFAULT);
    bad = bad || attr < 0 || H5Awrite(attr, type, u) < 0;
    if (attr >= 0)
        H5Aclose(attr);
    if (space >= 0)
        H5Sclose(space);
    H5Tclose(type);
    return bad ? -1 : 0;
}

/** rank 0: scalar; rank 1: dims[0]; rank 2: dims[0] x dims[1]. */
static int h5_write_f64(hid_t file, const char *name, int rank, const hsize_t *dims,
                        const double *data, const char *unit)
{
    hid_t space = rank == 0 ? H5Screate(H5S_SCALAR) : H5Screate_simple(rank, dims, NULL);
    if (space < 0)
        return -1;
    hid_t ds = H5Dcreate2(file, name, H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT,
                          H5P_DEFAULT);
    int bad = ds < 0 || H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0;
    if (!bad && unit)
        bad = h5_write_unit(ds, unit) < 0;
    if (ds >= 0)
        H5Dclose(ds);
    H5Sclose(space);
    return bad ? -1 : 0;
}

static int h5_write_i64(hid_t file, const char *name, int64_t value)
{
    hid_t space = H5Screate(H5S_SCALAR);
    if (space < 0)
        return -1;
    hid_t ds = H5Dcreate2(file, name, H5T_STD_I64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    int bad = ds < 0 || H5Dwrite(ds, H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, &value) < 0;
    if (ds >= 0)
        H5Dclose(ds);
    H5Sclose(space);
    return bad ? -1 : 0;
}

/** /connectivity: int64 0, 1, ..., n - 1 (one vertex cell per particle). */
static int write_connectivity(hid_t file, size_t n)
{
    int64_t *ids = malloc((n ? n : 1) * sizeof *ids);
    if (!ids)
        return -1;
    for (size_t i = 0; i < n; i++)
        ids[i] = (int64_t)i;
    hsize_t dims[1] = {(hsize_t)n};
    hid_t space = H5Screate_simple(1, dims, NULL);
    hid_t ds = space < 0 ? -1
                         : H5Dcreate2(file, OUTPUT_CONNECTIVITY, H5T_STD_I64LE, space, H5P_DEFAULT,
                                      H5P_DEFAULT, H5P_DEFAULT);
    int bad = ds < 0 || (n && H5Dwrite(ds, H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, ids) < 0);
    if (ds >= 0)
        H5Dclose(ds);
    if (space >= 0)
        H5Sclose(space);
    free(ids);
    return bad ? -1 : 0;
}

/** Distributed run: this rank's owned rows at their global ids (output_par.c). */
static int write_rows_par(hid_t file, const char *name, int ncomp, const struct sim *s,
                          const double *data, const char *unit)
{
    hid_t ds = output_par_write_rows(file, name, ncomp, s, data);
    int bad = ds < 0 || (unit && h5_write_unit(ds, unit) < 0);
    if (ds >= 0)
        H5Dclose(ds);
    return bad ? -1 : 0;
}

/* ---------------------------------------------------------------- create */

static int writer_add(struct field_writer *w, const struct field_desc *f, struct spall_error *err)
{
    for (size_t k = 0; k < w->n_fields; k++)
        if (strcmp(w->fields[k].name, f->name) == 0)
            return SPALL_OK; /* listed twice: write once */
    if (!name_is_safe(f->name))
        return spall_error_set(err, SPALL_ERR_INTERNAL,
                               "field name '%s' cannot be an HDF5 dataset / XDMF name", f->name);
    struct out_field *o = &w->fields[w->n_fields++];
    memcpy(o->name, f->name, sizeof o->name);
    o->ncomp = f->ncomp;
    memcpy(o->unit, f->unit, sizeof o->unit);
    o->parity = (int)f->parity;
    return SPALL_OK;
}

static int unknown_field(struct spall_error *err, const struct field_registry *reg,
                         const char *name, const char *why)
{
    char list[SPALL_ERROR_MSG_LEN / 2];
    size_t len = 0;
    list[0] = '\0';
    for (size_t k = 0; k < reg->n && len + 1 < sizeof list; k++) {
        if (!(reg->fields[k].flags & FIELD_OUTPUT))
            continue;
        int m = snprintf(list + len, sizeof list - len, "%s%s", len ? ", " : "",
                         reg->fields[k].name);
        if (m < 0)
            break;
        len += (size_t)m;
    }
    size_t cut = strlen(name) > 64 ? 64 : strlen(name); /* a long typo stays one short line */
    return spall_error_set(err, SPALL_ERR_INPUT,
                           "%s output field '%.*s%s'; expected one of the registered fields: %s",
                           why, (int)cut, name, name[cut] ? "..." : "", len ? list : "(none)");
}

int field_writer_check_names(const struct sim *s, const char *const *names, size_t n_names,
                             size_t *bad, struct spall_error *err)
{
    const struct field_registry *reg = s->fields;
    if (!reg)
        return spall_error_set(err, SPALL_ERR_INTERNAL, "field writer: no field registry");
    for (size_t k = 0; k < n_names && names; k++) {
        const struct field_desc *f = field_registry_find(reg, names[k]);
        *bad = k;
        if (!f && strcmp(names[k], OUTPUT_BONDS) == 0) { /* bonds as lines */
            int rc = bond_writer_check(s, err);
            if (rc)
                return rc;
            continue;
        }
        if (!f)
            return unknown_field(err, reg, names[k], "unknown");
        if (!(f->flags & FIELD_OUTPUT) && strcmp(f->name, OUTPUT_POSITION) != 0)
            return unknown_field(err, reg, names[k], "not an");
    }
    return SPALL_OK;
}

int field_writer_create(struct field_writer **out, const char *dir, const struct sim *s,
                        const char *const *names, size_t n_names, struct spall_error *err)
{
    *out = NULL;
    const struct field_registry *reg = s->fields;
    size_t bad = 0;
    int rc0 = field_writer_check_names(s, names, n_names, &bad, err);
    if (rc0)
        return rc0;

    struct field_writer *w = calloc(1, sizeof *w);
    if (!w)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory creating field writer");
    const char *d = (dir && dir[0]) ? dir : ".";
    w->dir = malloc(strlen(d) + 1);
    w->fields = calloc(reg->n + 1, sizeof *w->fields);
    if (!w->dir || !w->fields) {
        field_writer_destroy(&w);
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory creating field writer");
    }
    strcpy(w->dir, d);

    /* position first: it is the XDMF geometry.  Without a registered
     * "position" field the writer falls back to s->p->x (ncomp = dim). */
    const struct field_desc *pos = field_registry_find(reg, OUTPUT_POSITION);
    struct field_desc fallback;
    if (!pos) {
        memset(&fallback, 0, sizeof fallback);
        strcpy(fallback.name, OUTPUT_POSITION);
        strcpy(fallback.unit, "m");
        fallback.ncomp = s->dim;
        fallback.parity = FIELD_VECTOR;
        pos = &fallback;
    }
    int rc = writer_add(w, pos, err);
    if (names && n_names) {
        for (size_t k = 0; k < n_names && !rc; k++) {
            const struct field_desc *f = field_registry_find(reg, names[k]);
            rc = f ? writer_add(w, f, err)
                 : w->bonds ? SPALL_OK : bond_writer_create(&w->bonds, w->dir, s, err);
        }
    } else {
        for (size_t k = 0; k < reg->n && !rc; k++)
            if (reg->fields[k].flags & FIELD_DEFAULT)
                rc = writer_add(w, &reg->fields[k], err);
    }
    if (rc) {
        field_writer_destroy(&w);
        return rc;
    }
    *out = w;
    return SPALL_OK;
}

size_t field_writer_frames(const struct field_writer *w)
{
    return w ? w->frames : 0;
}

void field_writer_destroy(struct field_writer **w)
{
    if (!w || !*w)
        return;
    free((*w)->dir);
    free((*w)->fields);
    free((*w)->grids.s);
    free((*w)->bodies.s);
    free((*w)->saved.s);
    free((*w)->buf);
    bond_writer_destroy(&(*w)->bonds);
    free(*w);
    *w = NULL;
}

/* ---------------------------------------------------------------- write */

/** Gather one field of particles [0, n) into w->buf as n x ncomp_out, padding
 *  (position) with zeros when ncomp_out > the field's components. */
static void gather_padded(struct field_writer *w, const struct sim *s, const struct field_desc *f,
                          int ncomp, size_t n, int ncomp_out)
{
    double *b = w->buf;
    if (f) {
        field_gather_f64(f, n, b);
    } else { /* unregistered position: straight from the particle arrays */
        for (int c = 0; c < ncomp; c++)
            for (size_t i = 0; i < n; i++)
                b[i * (size_t)ncomp + (size_t)c] = s->p->x[c][i];
    }
    if (ncomp_out == ncomp)
        return;
    if (ncomp == 3 && ncomp_out == 6) { /* 2D symmetric tensor (xdmf_file_ncomp) */
        xdmf_widen_symtensor(b, n);
        return;
    }
    /* widen in place, back to front, so no value is overwritten before use */
    for (size_t i = n; i-- > 0;) {
        for (int c = ncomp_out - 1; c >= 0; c--)
            b[i * (size_t)ncomp_out + (size_t)c] = c < ncomp ? b[i * (size_t)ncomp + (size_t)c] : 0.0;
    }
}

/** Write the frame into @p tmp; messages name @p final, the file the user
 *  asked for (the temporary is an implementation detail). */
static int write_frame_h5(struct field_writer *w, const struct sim *s, const char *tmp,
                          const char *final, size_t n, struct spall_error *err)
{
    const struct field_registry *reg = s->fields;
    /* distributed (s->par): one file opened by all ranks through MPI-IO */
    hid_t fapl = s->par ? parallel_h5_fapl() : H5Pcreate(H5P_FILE_ACCESS);
    /* STRONG: H5Fclose really closes (and flushes) the file before rename() */
    if (fapl >= 0 && !s->par)
        H5Pset_fclose_degree(fapl, H5F_CLOSE_STRONG);
    hid_t file = fapl >= 0 ? H5Fcreate(tmp, H5F_ACC_TRUNC, H5P_DEFAULT, fapl) : -1;
    if (file < 0) {
        int rc = h5_fail(err, "cannot create HDF5 frame", final);
        if (fapl >= 0)
            H5Pclose(fapl);
        return rc;
    }
    H5Pclose(fapl);

    double t = s->t;
    if (h5_write_f64(file, "time", 0, NULL, &t, "s") < 0 ||
        h5_write_i64(file, "step", (int64_t)s->step) < 0) {
        int rc = h5_fail(err, "cannot write /time, /step to", final);
        H5Fclose(file);
        return rc;
    }
    if ((s->par ? output_par_write_ids(file, OUTPUT_CONNECTIVITY, s)
                : write_connectivity(file, n)) < 0) {
        int rc = h5_fail(err, "cannot write /" OUTPUT_CONNECTIVITY " to", final);
        H5Fclose(file);
        return rc;
    }
    for (size_t k = 0; k < w->n_fields; k++) {
        const struct out_field *o = &w->fields[k];
        const struct field_desc *f = field_registry_find(reg, o->name);
        if ((!f && k != 0) || (f && f->ncomp != o->ncomp)) {
            H5Fclose(file);
            return spall_error_set(err, SPALL_ERR_INTERNAL,
                                   "output field '%s' vanished or changed components", o->name);
        }
        /* position padded to XYZ, 2D symmetric tensors to 6 (xdmf_file_ncomp) */
        int ncomp_out = k == 0 ? 3 : xdmf_file_ncomp(xdmf_field_kind(o->ncomp, s->dim, o->parity),
                                                     o->ncomp);
        gather_padded(w, s, f, o->ncomp, n, ncomp_out);
        hsize_t dims[2] = {(hsize_t)n, (hsize_t)ncomp_out};
        if ((s->par ? write_rows_par(file, o->name, ncomp_out, s, w->buf, f ? f->unit : "m")
                    : h5_write_f64(file, o->name, ncomp_out == 1 ? 1 : 2, dims, w->buf,
                                   f ? f->unit : "m")) < 0) {
            char what[FIELD_NAME_LEN + 48];
            snprintf(what, sizeof what, "cannot write dataset '%s' to", o->name);
            int rc = h5_fail(err, what, final);
            H5Fclose(file);
            return rc;
        }
    }
    if (H5Fclose(file) < 0)
        return h5_fail(err, "cannot close HDF5 frame", final);
    return SPALL_OK;
}

/** Shortest of %.15g..%.17g that reads back as the same double, so the index
 *  shows "1e-06" rather than "9.9999999999999995e-07" yet stays exact. */
static void format_exact(char *out, size_t size, double v)
{
    for (int prec = 15; prec <= 17; prec++) {
        snprintf(out, size, "%.*g", prec, v);
        if (strtod(out, NULL) == v)
            return;
    }
}

/* The rigid bodies go to their own index, bodies.xdmf: ParaView 5.11's
 * default reader (Xdmf3ReaderS) reads a frame holding particles and bodies as
 * a spatial collection, but then colours no particle by any array (measured,
 * docs/postprocessing.md); the legacy reader does. */
static int append_xdmf_bodies(struct field_writer *w, const struct sim *s, const char *tbuf,
                              size_t n)
{
    if (xdmf_rigid_count(s) == 0)
        return 0;
    char *rigid = xdmf_rigid_grids(s, n);
    if (!rigid)
        return -1;
    int bad = text_append(&w->bodies,
                          "      <Grid Name=\"bodies_%06zu\" GridType=\"Collection\""
                          " CollectionType=\"Spatial\">\n"
                          "        <Time Value=\"%s\"/>\n%s      </Grid>\n",
                          w->frames, tbuf, rigid);
    free(rigid);
    return bad;
}

static int append_xdmf_grid(struct field_writer *w, const struct sim *s, const char *h5name,
                            double t, long step, size_t n)
{
    struct text_buf *g = &w->grids;
    char tbuf[40];
    format_exact(tbuf, sizeof tbuf, t);
    int bad = text_append(g,
                          "      <Grid Name=\"frame_%06zu\" GridType=\"Uniform\">\n"
                          "        <Time Value=\"%s\"/>\n"
                          "        <Information Name=\"step\" Value=\"%ld\"/>\n"
                          "        <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"%zu\""
                          " NodesPerElement=\"1\">\n"
                          "          <DataItem Dimensions=\"%zu 1\" NumberType=\"Int\""
                          " Precision=\"8\" Format=\"HDF\">%s:/%s</DataItem>\n"
                          "        </Topology>\n"
                          "        <Geometry GeometryType=\"XYZ\">\n"
                          "          <DataItem Dimensions=\"%zu 3\" NumberType=\"Float\""
                          " Precision=\"8\" Format=\"HDF\">%s:/%s</DataItem>\n"
                          "        </Geometry>\n",
                          w->frames, tbuf, step, n, n, h5name, OUTPUT_CONNECTIVITY, n, h5name,
                          OUTPUT_POSITION);
    for (size_t k = 1; k < w->n_fields && !bad; k++) {
        const struct out_field *o = &w->fields[k];
        char dims[48];
        enum xdmf_kind kind = xdmf_field_kind(o->ncomp, s->dim, o->parity);
        const int nc = xdmf_file_ncomp(kind, o->ncomp);
        if (nc == 1)
            snprintf(dims, sizeof dims, "%zu", n);
        else
            snprintf(dims, sizeof dims, "%zu %d", n, nc);
        const char *comps = xdmf_component_names(kind, nc);
        bad = text_append(g,
                          "        <Attribute Name=\"%s\" AttributeType=\"%s\" Center=\"Node\">\n"
                          "          <Information Name=\"unit\" Value=\"%s\"/>\n"
                          "%s%s%s"
                          "          <DataItem Dimensions=\"%s\" NumberType=\"Float\""
                          " Precision=\"8\" Format=\"HDF\">%s:/%s</DataItem>\n"
                          "        </Attribute>\n",
                          o->name, xdmf_attribute_type(kind, nc), o->unit[0] ? o->unit : "1",
                          comps ? "          <Information Name=\"components\" Value=\"" : "",
                          comps ? comps : "", comps ? "\"/>\n" : "", dims, h5name, o->name);
    }
    if (!bad)
        bad = text_append(g, "      </Grid>\n");
    if (!bad)
        bad = append_xdmf_bodies(w, s, tbuf, n);
    return bad;
}

static int write_index(const struct field_writer *w, const char *name, const char *tmpname,
                       const struct text_buf *grids, struct spall_error *err)
{
    char *final = path_join(w->dir, name);
    char *tmp = path_join(w->dir, tmpname);
    int rc = SPALL_OK;
    if (!final || !tmp) {
        rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory writing XDMF index");
        goto done;
    }
    FILE *fp = fopen(tmp, "w");
    if (!fp) {
        rc = spall_error_set(err, SPALL_ERR_IO, "cannot create XDMF index '%s'", tmp);
        goto done;
    }
    fputs("<?xml version=\"1.0\" ?>\n"
          "<Xdmf Version=\"3.0\">\n"
          "  <Domain>\n"
          "    <Grid Name=\"spall\" GridType=\"Collection\" CollectionType=\"Temporal\">\n",
          fp);
    if (grids->len)
        fwrite(grids->s, 1, grids->len, fp);
    fputs("    </Grid>\n  </Domain>\n</Xdmf>\n", fp);
    int bad = ferror(fp);
    bad |= fclose(fp) != 0;
    if (bad) {
        remove(tmp);
        rc = spall_error_set(err, SPALL_ERR_IO, "cannot write XDMF index '%s'", tmp);
        goto done;
    }
    if (rename(tmp, final) != 0) {
        remove(tmp);
        rc = spall_error_set(err, SPALL_ERR_IO, "cannot rename '%s' to '%s'", tmp, final);
    }
done:
    free(final);
    free(tmp);
    return rc;
}

/* A checkpoint keeps both indexes' frames as one text (field_writer_grids):
 * the particles' grids, then, with rigid bodies, this marker and
 * bodies.xdmf's grids. */
#define OUTPUT_BODIES_MARK "<!-- spall: bodies.xdmf -->\n"

static int save_grids(struct field_writer *w)
{
    w->saved.len = 0;
    return w->bodies.len ? text_append(&w->saved, "%.*s%s%.*s", (int)w->grids.len, w->grids.s,
                                       OUTPUT_BODIES_MARK, (int)w->bodies.len, w->bodies.s)
                         : 0;
}

static int write_xdmf(const struct field_writer *w, struct spall_error *err)
{
    int rc = write_index(w, "fields.xdmf", ".fields.xdmf.tmp", &w->grids, err);
    if (!rc && w->bodies.len)
        rc = write_index(w, "bodies.xdmf", ".bodies.xdmf.tmp", &w->bodies, err);
    return rc;
}

/* Distributed (s->par): the frame's file is opened and its index bounds
 * reduced collectively, so a failure of one rank is agreed before each. */
static int frame_agree(const struct sim *s, int rc, struct spall_error *err)
{
    return s->par ? par_agree(rc, err) : rc;
}

int field_writer_write(struct field_writer *w, const struct sim *s, struct spall_error *err)
{
    size_t n = s->p->n_owned;
    size_t need = (n ? n : 1) * 6; /* position's 3, a 2D symmetric tensor's 6 */
    for (size_t k = 0; k < w->n_fields; k++)
        if (need < (n ? n : 1) * (size_t)w->fields[k].ncomp)
            need = (n ? n : 1) * (size_t)w->fields[k].ncomp;
    int rc = SPALL_OK;
    if (need > w->buf_cap) {
        double *b = realloc(w->buf, need * sizeof *b);
        if (!b) {
            rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for %zu output values",
                                 need);
        } else {
            w->buf = b;
            w->buf_cap = need;
        }
    }

    char h5name[48], tmpname[56];
    snprintf(h5name, sizeof h5name, "fields_%06zu.h5", w->frames);
    snprintf(tmpname, sizeof tmpname, ".%s.tmp", h5name);
    char *final = path_join(w->dir, h5name);
    char *tmp = path_join(w->dir, tmpname);
    if (!rc && (!final || !tmp))
        rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory writing frame");
    if (!rc)
        rc = par_fault("frame", err);
    if ((rc = frame_agree(s, rc, err)))
        goto done;
    struct h5_quiet q;
    h5_quiet_begin(&q);
    rc = write_frame_h5(w, s, tmp, final, n, err);
    h5_quiet_end(&q);
    const int root = par_rank() == 0; /* distributed: rank 0 renames and indexes */
    if (rc) {
        if (root)
            remove(tmp);
        goto done;
    }
    if (root && rename(tmp, final) != 0) {
        remove(tmp);
        rc = spall_error_set(err, SPALL_ERR_IO, "cannot rename '%s' to '%s'", tmp, final);
    }
    if ((rc = frame_agree(s, rc, err))) /* the index's bounds below are reduced */
        goto done;
    size_t old_len = w->grids.len, old_bodies = w->bodies.len;
    if (append_xdmf_grid(w, s, h5name, s->t, s->step, par_n_global(s)) || save_grids(w)) {
        w->grids.len = old_len;
        w->bodies.len = old_bodies;
        rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory writing XDMF index");
        goto done;
    }
    w->frames++;
    rc = root ? write_xdmf(w, err) : SPALL_OK;
    if (!rc && w->bonds) {
        char tbuf[40];
        format_exact(tbuf, sizeof tbuf, s->t);
        rc = bond_writer_write(w->bonds, s, w->frames - 1, tbuf, err);
    }
done:
    free(final);
    free(tmp);
    return rc;
}

const char *field_writer_grids(const struct field_writer *w, size_t *len)
{
    const struct text_buf *t = w->bodies.len ? &w->saved : &w->grids;
    *len = t->len;
    return t->s ? t->s : "";
}

int field_writer_resume(struct field_writer *w, size_t frames, const char *grids, size_t len,
                        struct spall_error *err)
{
    w->grids.len = 0;
    w->bodies.len = 0;
    const char *mark = NULL;
    for (size_t i = 0; len && i + strlen(OUTPUT_BODIES_MARK) <= len && !mark; i++)
        if (memcmp(grids + i, OUTPUT_BODIES_MARK, strlen(OUTPUT_BODIES_MARK)) == 0)
            mark = grids + i;
    size_t glen = mark ? (size_t)(mark - grids) : len;
    if (glen && text_append(&w->grids, "%.*s", (int)glen, grids))
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (XDMF index)");
    if (mark) {
        const char *b = mark + strlen(OUTPUT_BODIES_MARK);
        if (text_append(&w->bodies, "%.*s", (int)(len - (size_t)(b - grids)), b) ||
            save_grids(w))
            return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (XDMF index)");
    }
    w->frames = frames;
    return par_rank() == 0 ? write_xdmf(w, err) : SPALL_OK; /* distributed: rank 0 indexes */
}

/* ---------------------------------------------------------------- read */

int field_frame_read(const char *h5_path, const char *name, double **data, size_t *n,
                     size_t *ncomp, double *time, struct spall_error *err)
{
    *data = NULL;
    *n = 0;
    *ncomp = 0;
    struct h5_quiet q;
    h5_quiet_begin(&q);
    int rc = SPALL_OK;
    hid_t file = H5Fopen(h5_path, H5F_ACC_RDONLY, H5P_DEFAULT);
    hid_t ds = -1, space = -1;
    if (file < 0) {
        rc = h5_fail(err, "cannot open HDF5 frame", h5_path);
        goto done;
    }
    if (time) {
        hid_t tds = H5Dopen2(file, "time", H5P_DEFAULT);
        herr_t e = tds < 0 ? -1 : H5Dread(tds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, time);
        if (tds >= 0)
            H5Dclose(tds);
        if (e < 0) {
            rc = h5_fail(err, "cannot read /time from", h5_path);
            goto done;
        }
    }
    if (!name[0] || strchr(name, '/') || H5Lexists(file, name, H5P_DEFAULT) <= 0) {
        rc = spall_error_set(err, SPALL_ERR_INPUT, "frame '%s' has no dataset '%s'", h5_path,
                             name);
        goto done;
    }
    ds = H5Dopen2(file, name, H5P_DEFAULT);
    space = ds >= 0 ? H5Dget_space(ds) : -1;
    int rank = space >= 0 ? H5Sget_simple_extent_ndims(space) : -1;
    if (rank < 0) {
        rc = h5_fail(err, "cannot open dataset in", h5_path);
        goto done;
    }
    if (rank > 2) {
        rc = spall_error_set(err, SPALL_ERR_INPUT, "dataset '%s' in '%s' has rank %d (expected <= 2)",
                             name, h5_path, rank);
        goto done;
    }
    hsize_t dims[2] = {1, 1};
    if (rank > 0)
        H5Sget_simple_extent_dims(space, dims, NULL);
    size_t count = (size_t)dims[0] * (size_t)dims[1];
    double *buf = malloc((count ? count : 1) * sizeof *buf);
    if (!buf) {
        rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory reading '%s' from '%s'", name,
                             h5_path);
        goto done;
    }
    if (count && H5Dread(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) < 0) {
        rc = h5_fail(err, "cannot read dataset from", h5_path);
        free(buf);
        goto done;
    }
    *data = buf;
    *n = (size_t)dims[0];
    *ncomp = (size_t)dims[1];
done:
    if (space >= 0)
        H5Sclose(space);
    if (ds >= 0)
        H5Dclose(ds);
    if (file >= 0)
        H5Fclose(file);
    h5_quiet_end(&q);
    return rc;
}
