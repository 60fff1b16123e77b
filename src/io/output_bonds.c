/**
 * @file output_bonds.c
 * @brief Bonds as line cells (output_bonds.h): DIR/bonds_NNNNNN.h5 beside
 *        each field frame, and the index DIR/bonds.xdmf that ParaView opens
 *        to show every bond of a lattice or peridynamics run as a line
 *        coloured by its state.
 *
 * Frame layout (NNNNNN = the field frame's number):
 *   /time           scalar float64 [s]
 *   /connectivity   int64, m x 2: particle indices (rows of the frame's
 *                   /position) of each bond, i < j, each bond once
 *   /broken         float64, m: 1 for a broken bond (BOND_BROKEN, pre-cut
 *                   ones included), 0 for an intact one
 * bonds.xdmf: a temporal collection of Uniform grids, TopologyType Polyline
 * with NodesPerElement 2, the geometry taken from the field frame's
 * /position, `broken` a cell attribute.  Measured with ParaView 5.11
 * (tests/client: client_pv_bonds_*): both XDMF readers give one 2-point
 * polyline cell per bond and the default Surface representation draws them.
 */
#include "io/output_bonds.h"

#include "io/text_buf.h"

#include "core/bond_list.h"
#include "core/model.h"
#include "core/particles.h"
#include "core/sim.h"
#include "spall/error.h"

#include <hdf5.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct bond_writer {
    char *dir;
    struct text_buf grids; /**< the index's grid entries so far */
};

/** The model's fixed bond list, or NULL (unbonded model). */
static const struct bond_list *bonds_of(const struct sim *s)
{
    if (!s->ops || !s->model)
        return NULL;
    if (s->ops->bonds)
        return s->ops->bonds(s->model);
    return s->ops->halo_bonds ? s->ops->halo_bonds(s->model) : NULL;
}

int bond_writer_check(const struct sim *s, struct spall_error *err)
{
    if (!bonds_of(s))
        return spall_error_set(err, SPALL_ERR_INPUT,
                               "output field 'bonds': the %s model has no bonds (lattice and "
                               "peridynamics runs have)",
                               s->ops ? s->ops->name : "(no)");
    if (s->par)
        return spall_error_set(err, SPALL_ERR_INPUT,
                               "output field 'bonds' is written by serial runs only");
    return SPALL_OK;
}

int bond_writer_create(struct bond_writer **out, const char *dir, const struct sim *s,
                       struct spall_error *err)
{
    *out = NULL;
    int rc = bond_writer_check(s, err);
    if (rc)
        return rc;
    struct bond_writer *w = calloc(1, sizeof *w);
    if (w)
        w->dir = malloc(strlen(dir) + 1);
    if (!w || !w->dir) {
        bond_writer_destroy(&w);
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory creating the bond writer");
    }
    strcpy(w->dir, dir);
    *out = w;
    return SPALL_OK;
}

void bond_writer_destroy(struct bond_writer **w)
{
    if (!w || !*w)
        return;
    free((*w)->dir);
    free((*w)->grids.s);
    free(*w);
    *w = NULL;
}

static int write_ds(hid_t file, const char *name, hid_t ftype, hid_t mtype, int rank,
                    const hsize_t *dims, const void *data)
{
    hid_t space = rank == 0 ? H5Screate(H5S_SCALAR) : H5Screate_simple(rank, dims, NULL);
    if (space < 0)
        return -1;
    hid_t ds = H5Dcreate2(file, name, ftype, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    int empty = rank > 0 && dims[0] == 0;
    int bad = ds < 0 || (!empty && H5Dwrite(ds, mtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0);
    if (ds >= 0)
        H5Dclose(ds);
    H5Sclose(space);
    return bad ? -1 : 0;
}

/* Each bond once (i < j, partners among the owned particles): the pairs
 * into ij (2 per bond), the states into broken; returns the count. */
static size_t collect(const struct bond_list *bl, size_t n, int64_t *ij, double *broken)
{
    size_t m = 0;
    for (size_t i = 0; i < n && i < bl->n; i++)
        for (size_t k = bl->offset[i]; k < bl->offset[i + 1]; k++) {
            int32_t j = bl->partner[k];
            if (j < 0 || (size_t)j <= i || (size_t)j >= n)
                continue;
            if (ij) {
                ij[2 * m] = (int64_t)i;
                ij[2 * m + 1] = (int64_t)j;
                broken[m] = (bl->state[k] & BOND_BROKEN) ? 1.0 : 0.0;
            }
            m++;
        }
    return m;
}

/* Write @p text to DIR/NAME through a temporary and rename (as the frames). */
static int write_file(const char *dir, const char *name, const char *text,
                      struct spall_error *err)
{
    char tmpname[64];
    snprintf(tmpname, sizeof tmpname, ".%s.tmp", name);
    char *final = path_join(dir, name), *tmp = path_join(dir, tmpname);
    int rc = SPALL_OK;
    FILE *fp = final && tmp ? fopen(tmp, "w") : NULL;
    if (!fp) {
        rc = spall_error_set(err, SPALL_ERR_IO, "cannot create '%s'", tmp ? tmp : name);
    } else {
        int bad = fputs(text, fp) < 0;
        bad |= fclose(fp) != 0;
        if (bad || rename(tmp, final) != 0) {
            remove(tmp);
            rc = spall_error_set(err, SPALL_ERR_IO, "cannot write '%s'", final);
        }
    }
    free(final);
    free(tmp);
    return rc;
}

int bond_writer_write(struct bond_writer *w, const struct sim *s, size_t frame,
                      const char *time_text, struct spall_error *err)
{
    const struct bond_list *bl = bonds_of(s);
    if (!bl)
        return spall_error_set(err, SPALL_ERR_INTERNAL, "bond writer: the model lost its bonds");
    const size_t n = s->p->n_owned;
    const size_t m = collect(bl, n, NULL, NULL);
    int64_t *ij = malloc((m ? m : 1) * 2 * sizeof *ij);
    double *broken = malloc((m ? m : 1) * sizeof *broken);
    char h5name[48], tmpname[56], fields[48];
    snprintf(h5name, sizeof h5name, "bonds_%06zu.h5", frame);
    snprintf(tmpname, sizeof tmpname, ".%s.tmp", h5name);
    snprintf(fields, sizeof fields, "fields_%06zu.h5", frame);
    char *final = path_join(w->dir, h5name), *tmp = path_join(w->dir, tmpname);
    int rc = SPALL_OK;
    if (!ij || !broken || !final || !tmp) {
        rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory writing %zu bonds", m);
        goto done;
    }
    collect(bl, n, ij, broken);
    hid_t file = H5Fcreate(tmp, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    hsize_t d2[2] = {(hsize_t)m, 2}, d1[1] = {(hsize_t)m};
    double t = s->t;
    int bad = file < 0 ||
              write_ds(file, "time", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, 0, NULL, &t) < 0 ||
              write_ds(file, "connectivity", H5T_STD_I64LE, H5T_NATIVE_INT64, 2, d2, ij) < 0 ||
              write_ds(file, "broken", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, 1, d1, broken) < 0;
    if (file >= 0)
        bad |= H5Fclose(file) < 0;
    if (bad || rename(tmp, final) != 0) {
        remove(tmp);
        rc = spall_error_set(err, SPALL_ERR_IO, "cannot write the bonds frame '%s'", final);
        goto done;
    }
    size_t old = w->grids.len;
    if (text_append(&w->grids,
                    "      <Grid Name=\"bonds_%06zu\" GridType=\"Uniform\">\n"
                    "        <Time Value=\"%s\"/>\n"
                    "        <Topology TopologyType=\"Polyline\" NumberOfElements=\"%zu\""
                    " NodesPerElement=\"2\">\n"
                    "          <DataItem Dimensions=\"%zu 2\" NumberType=\"Int\" Precision=\"8\""
                    " Format=\"HDF\">%s:/connectivity</DataItem>\n"
                    "        </Topology>\n"
                    "        <Geometry GeometryType=\"XYZ\">\n"
                    "          <DataItem Dimensions=\"%zu 3\" NumberType=\"Float\" Precision=\"8\""
                    " Format=\"HDF\">%s:/position</DataItem>\n"
                    "        </Geometry>\n"
                    "        <Attribute Name=\"broken\" AttributeType=\"Scalar\" Center=\"Cell\">\n"
                    "          <Information Name=\"unit\" Value=\"1\"/>\n"
                    "          <DataItem Dimensions=\"%zu\" NumberType=\"Float\" Precision=\"8\""
                    " Format=\"HDF\">%s:/broken</DataItem>\n"
                    "        </Attribute>\n"
                    "      </Grid>\n",
                    frame, time_text, m, m, h5name, n, fields, m, h5name)) {
        w->grids.len = old;
        rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (bonds.xdmf)");
        goto done;
    }
    const char *head = "<?xml version=\"1.0\" ?>\n"
                       "<Xdmf Version=\"3.0\">\n"
                       "  <Domain>\n"
                       "    <Grid Name=\"bonds\" GridType=\"Collection\""
                       " CollectionType=\"Temporal\">\n";
    const char *tail = "    </Grid>\n  </Domain>\n</Xdmf>\n";
    size_t len = strlen(head) + w->grids.len + strlen(tail) + 1;
    char *text = malloc(len);
    if (!text) {
        rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (bonds.xdmf)");
        goto done;
    }
    snprintf(text, len, "%s%s%s", head, w->grids.s, tail);
    rc = write_file(w->dir, "bonds.xdmf", text, err);
    free(text);
done:
    free(ij);
    free(broken);
    free(final);
    free(tmp);
    return rc;
}
