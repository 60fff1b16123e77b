/**
 * @file render_select.c
 * @brief What `spall render` draws (issue 24 item 4): the field (a default
 *        the run has, the list of available ones on error), the component
 *        by name (x, y, z; xx, yy, zz, xy, yz, xz for tensors) and the slice
 *        axis of a 3D run.
 *
 * Why: the default field used to be fracture_density, which PD and SPH runs
 * do not write, and a missing field was reported without saying which ones
 * the frame holds; tensor components were taken by index only and 3D runs
 * could be sliced along z only.
 */
#include "io/render.h"

#include "spall/error.h"

#include <hdf5.h>
#include <stdio.h>
#include <string.h>

size_t render_frame_fields(const char *h5_path, char (*names)[RENDER_NAME_LEN], size_t max)
{
    size_t n = 0;
    H5E_auto2_t func;
    void *data;
    H5Eget_auto2(H5E_DEFAULT, &func, &data);
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
    hid_t f = H5Fopen(h5_path, H5F_ACC_RDONLY, H5P_DEFAULT);
    H5G_info_t gi;
    if (f >= 0 && H5Gget_info(f, &gi) >= 0) {
        /* by index and name: the same calls in every HDF5 1.8 - 1.14 API */
        for (hsize_t k = 0; k < gi.nlinks && n < max; k++) {
            char name[RENDER_NAME_LEN];
            ssize_t len = H5Lget_name_by_idx(f, ".", H5_INDEX_NAME, H5_ITER_INC, k, name,
                                             sizeof name, H5P_DEFAULT);
            if (len <= 0 || (size_t)len >= sizeof name)
                continue;
            if (strcmp(name, "time") == 0 || strcmp(name, "step") == 0 ||
                strcmp(name, "connectivity") == 0)
                continue; /* the frame's scalars and the XDMF topology, not fields */
            hid_t ds = H5Dopen2(f, name, H5P_DEFAULT);
            if (ds < 0)
                continue;
            H5Dclose(ds);
            snprintf(names[n++], RENDER_NAME_LEN, "%s", name);
        }
    }
    if (f >= 0)
        H5Fclose(f);
    H5Eset_auto2(H5E_DEFAULT, func, data);
    return n;
}

int render_pick_field(const char *h5_path, const char *wanted, char *out, size_t len,
                      struct spall_error *err)
{
    char names[64][RENDER_NAME_LEN];
    size_t n = render_frame_fields(h5_path, names, 64);
    if (n == 0)
        return spall_error_set(err, SPALL_ERR_IO, "'%s' holds no particle fields (not a spall "
                                                  "frame?)", h5_path);
    if (wanted) {
        for (size_t k = 0; k < n; k++)
            if (strcmp(names[k], wanted) == 0) {
                snprintf(out, len, "%s", wanted);
                return SPALL_OK;
            }
        char list[SPALL_ERROR_MSG_LEN / 2] = "";
        size_t used = 0;
        for (size_t k = 0; k < n && used + 1 < sizeof list; k++) {
            int m = snprintf(list + used, sizeof list - used, "%s%s", k ? ", " : "", names[k]);
            if (m < 0)
                break;
            used += (size_t)m;
        }
        return spall_error_set(err, SPALL_ERR_INPUT,
                               "'%s' has no field '%.64s'; this run wrote: %s (more with "
                               "output.fields in the deck)",
                               h5_path, wanted, list);
    }
    /* the first of these the run wrote: the damage picture of each model,
     * then the motion */
    static const char *const preferred[] = {"fracture_density", "damage", "plastic_strain",
                                            "effective_plastic_strain", "velocity",
                                            "displacement", NULL};
    for (size_t p = 0; preferred[p]; p++)
        for (size_t k = 0; k < n; k++)
            if (strcmp(names[k], preferred[p]) == 0) {
                snprintf(out, len, "%s", names[k]);
                return SPALL_OK;
            }
    for (size_t k = 0; k < n; k++)
        if (strcmp(names[k], "position") != 0) {
            snprintf(out, len, "%s", names[k]);
            return SPALL_OK;
        }
    snprintf(out, len, "%s", names[0]);
    return SPALL_OK;
}

int render_component_index(const char *name, const char *field, size_t nvc, size_t dim,
                           int *comp, struct spall_error *err)
{
    static const char *const sym2[] = {"xx", "yy", "xy", NULL};
    static const char *const sym3[] = {"xx", "yy", "zz", "xy", "yz", "xz", NULL};
    static const char *const full[] = {"xx", "xy", "xz", "yx", "yy", "yz", "zx", "zy", "zz", NULL};
    if (strcmp(name, "mag") == 0) {
        *comp = RENDER_MAGNITUDE;
        return SPALL_OK;
    }
    if (strlen(name) == 1 && name[0] >= '0' && name[0] <= '8') {
        *comp = name[0] - '0';
        return SPALL_OK;
    }
    const char *const *names = NULL;
    const char *what = "";
    if (nvc == dim || nvc == 1) {
        static const char *const vec[] = {"x", "y", "z", NULL};
        names = vec;
        what = nvc == 1 ? "a scalar: component 0" : "a vector: x, y";
    } else if (nvc == 3 && dim == 2) {
        names = sym2;
        what = "a symmetric tensor in 2D: xx, yy, xy";
    } else if (nvc == 6) {
        names = sym3;
        what = "a symmetric tensor: xx, yy, zz, xy, yz, xz";
    } else if (nvc == 9) {
        names = full;
        what = "a 3x3 tensor: xx, xy, ..., zz";
    }
    /* yx is xy, zy is yz, zx is xz in a symmetric tensor */
    const char *alias = names == sym2 || names == sym3
                            ? (strcmp(name, "yx") == 0   ? "xy"
                               : strcmp(name, "zy") == 0 ? "yz"
                               : strcmp(name, "zx") == 0 ? "xz"
                                                         : name)
                            : name;
    for (int k = 0; names && names[k] && (size_t)k < (nvc > 1 ? nvc : 1); k++)
        if (strcmp(names[k], alias) == 0) {
            *comp = k;
            return SPALL_OK;
        }
    return spall_error_set(err, SPALL_ERR_INPUT,
                           "--component '%.16s': field '%.64s' has %zu component(s), %s%s or "
                           "mag",
                           name, field, nvc, what, nvc == dim && dim == 3 ? ", z" : "");
}

void render_slice_axis(double *xyz, size_t n, int axis)
{
    if (!xyz || axis == 2)
        return;
    /* the drawing plane: the two other axes in right-handed order
     * (axis x: y right, z up; axis y: x right, z up), the slice axis last */
    for (size_t i = 0; i < n; i++) {
        double x = xyz[3 * i], y = xyz[3 * i + 1], z = xyz[3 * i + 2];
        if (axis == 0) {
            xyz[3 * i] = y;
            xyz[3 * i + 1] = z;
            xyz[3 * i + 2] = x;
        } else {
            xyz[3 * i] = x;
            xyz[3 * i + 1] = z;
            xyz[3 * i + 2] = y;
        }
    }
}
