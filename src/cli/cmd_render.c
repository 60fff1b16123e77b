/**
 * @file cmd_render.c
 * @brief `spall render`: PNG pictures of particle fields from the HDF5 frames
 *        of a run directory (see io/render.h for what is drawn).
 */
#define _POSIX_C_SOURCE 200809L
#include "cli/cli.h"

#include "io/render.h"
#include "spall/error.h"

#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

static void render_usage(FILE *out)
{
    fprintf(out,
            "usage: spall render RUN_DIR|FRAME.h5 [--field NAME] [--component C]\n"
            "                    [--frame K | --all] [-o PATH] [--width PX]\n"
            "                    [--range MIN MAX] [--reference] [--slice AXIS[=V]]\n"
            "\n"
            "Draws one particle field of the run's HDF5 frames as PNG: one disc per\n"
            "particle coloured by the value, with a colour bar, a length scale and the\n"
            "time.  2D runs are drawn in the x-y plane; 3D runs as the slice of particles\n"
            "within 0.6 spacing of a plane normal to x, y or z (default: z at the body's\n"
            "mid-plane).\n"
            "  --field NAME     dataset to draw: any field the run wrote (an unknown name\n"
            "                   lists them), e.g. velocity, displacement, stress, damage,\n"
            "                   fragment_id; default: the first the run has of\n"
            "                   fracture_density, damage, plastic_strain, velocity\n"
            "  --component C    x, y, z (vectors); xx, yy, zz, xy, yz, xz (tensors: stress,\n"
            "                   strain); mag; or an index 0-8; default: magnitude for\n"
            "                   position/velocity/displacement/force, component 0 otherwise\n"
            "  --slice AXIS[=V] 3D: the slice normal to AXIS (x, y or z) at V [m] (default:\n"
            "                   the body's mid-plane); --slice-z Z is --slice z=Z\n"
            "  --frame K        frame number K (default: the last frame)\n"
            "  --all            every frame\n"
            "  -o PATH          output PNG (one frame) or directory (--all); default\n"
            "                   RUN_DIR/FIELD_NNNNNN.png\n"
            "  --width PX       image width (default 800)\n"
            "  --range MIN MAX  fixed colour range (default: each frame's range)\n"
            "  --reference      draw particles at their reference positions\n");
}

static int is_frame_name(const char *s, long *k)
{
    size_t len = strlen(s);
    if (len != strlen("fields_000000.h5") || strncmp(s, "fields_", 7) != 0 ||
        strcmp(s + len - 3, ".h5") != 0)
        return 0;
    char *end = NULL;
    *k = strtol(s + 7, &end, 10);
    return end == s + len - 3;
}

static int cmp_long(const void *a, const void *b)
{
    long x = *(const long *)a, y = *(const long *)b;
    return (x > y) - (x < y);
}

static int parse_double(const char *s, double *v)
{
    char *end = NULL;
    *v = strtod(s, &end);
    return end != s && *end == '\0' && isfinite(*v);
}

int cli_render(int argc, char **argv)
{
    const char *input = NULL, *out = NULL, *field = NULL, *comp = NULL;
    long frame = -1;
    int axis = 2;
    int all = 0, reference = 0, width = 800;
    double vmin = NAN, vmax = NAN, slice = NAN;
    for (int k = 1; k < argc; k++) {
        const char *a = argv[k];
        int more = k + 1 < argc;
        if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
            render_usage(stdout);
            return 0;
        } else if (strcmp(a, "--field") == 0 && more) {
            field = argv[++k];
        } else if (strcmp(a, "--component") == 0 && more) {
            comp = argv[++k];
        } else if (strcmp(a, "--frame") == 0 && more) {
            char *end = NULL;
            frame = strtol(argv[++k], &end, 10);
            if (*end || frame < 0) {
                fprintf(stderr, "spall render: --frame needs a frame number >= 0\n");
                return 2;
            }
        } else if (strcmp(a, "--all") == 0) {
            all = 1;
        } else if ((strcmp(a, "-o") == 0 || strcmp(a, "--output") == 0) && more) {
            out = argv[++k];
        } else if (strcmp(a, "--width") == 0 && more) {
            width = atoi(argv[++k]);
        } else if (strcmp(a, "--range") == 0 && k + 2 < argc) {
            if (!parse_double(argv[k + 1], &vmin) || !parse_double(argv[k + 2], &vmax) ||
                !(vmax > vmin)) {
                fprintf(stderr, "spall render: --range needs two numbers MIN < MAX\n");
                return 2;
            }
            k += 2;
        } else if (strcmp(a, "--slice-z") == 0 && more) {
            if (!parse_double(argv[++k], &slice)) {
                fprintf(stderr, "spall render: --slice-z needs a number (m)\n");
                return 2;
            }
        } else if (strcmp(a, "--slice") == 0 && more) {
            const char *v = argv[++k];
            if (!(v[0] >= 'x' && v[0] <= 'z') || (v[1] && (v[1] != '=' || !parse_double(v + 2, &slice)))) {
                fprintf(stderr, "spall render: --slice needs x, y or z, optionally =V (m), "
                                "e.g. --slice y=0.01\n");
                return 2;
            }
            axis = v[0] - 'x';
        } else if (strcmp(a, "--reference") == 0) {
            reference = 1;
        } else if (a[0] == '-') {
            fprintf(stderr, "spall render: unknown option or missing value '%s' (see --help)\n", a);
            return 2;
        } else if (!input) {
            input = a;
        } else {
            fprintf(stderr, "spall render: more than one input given ('%s', '%s')\n", input, a);
            return 2;
        }
    }
    if (!input) {
        render_usage(stderr);
        return 2;
    }
    struct render_options o;
    render_options_default(&o, field);
    o.width = width;
    o.vmin = vmin;
    o.vmax = vmax;
    o.slice_z = slice;
    o.slice_axis = axis;
    o.reference = reference;
    o.component_name = comp; /* resolved against the field's components */
    struct spall_error err = {0};
    struct stat st;
    if (stat(input, &st) != 0) {
        fprintf(stderr, "spall: error: cannot open '%s'\n", input);
        return 4;
    }
    char picked[RENDER_NAME_LEN];
    if (!S_ISDIR(st.st_mode)) { /* a single frame file */
        int rc = render_pick_field(input, field, picked, sizeof picked, &err);
        if (rc) {
            fprintf(stderr, "spall: error: %s\n", err.msg);
            return cli_exit_status(rc);
        }
        field = picked;
        char png[4096];
        if (out)
            snprintf(png, sizeof png, "%s", out);
        else
            snprintf(png, sizeof png, "%.*s_%s.png", (int)(strlen(input) - 3), input, field);
        rc = render_frame_png(input, png, &o, &err);
        if (rc) {
            fprintf(stderr, "spall: error: %s\n", err.msg);
            return cli_exit_status(rc);
        }
        printf("%s\n", png);
        return 0;
    }
    /* a run directory: list its frames */
    DIR *dir = opendir(input);
    if (!dir) {
        fprintf(stderr, "spall: error: cannot read directory '%s'\n", input);
        return 4;
    }
    long *frames = NULL;
    size_t nf = 0, cap = 0;
    struct dirent *de;
    while ((de = readdir(dir)) != NULL) {
        long k;
        if (!is_frame_name(de->d_name, &k))
            continue;
        if (nf == cap) {
            cap = cap * 2 + 64;
            long *t = realloc(frames, cap * sizeof *t);
            if (!t) {
                free(frames);
                closedir(dir);
                fprintf(stderr, "spall: error: out of memory\n");
                return 1;
            }
            frames = t;
        }
        frames[nf++] = k;
    }
    closedir(dir);
    if (nf == 0) {
        free(frames);
        fprintf(stderr, "spall: error: '%s' holds no fields_NNNNNN.h5 frames\n", input);
        return 2;
    }
    qsort(frames, nf, sizeof *frames, cmp_long);
    { /* the field, from the last frame: its name goes into the PNG names */
        char h5[4096];
        snprintf(h5, sizeof h5, "%s/fields_%06ld.h5", input, frames[nf - 1]);
        int rc = render_pick_field(h5, field, picked, sizeof picked, &err);
        if (rc) {
            free(frames);
            fprintf(stderr, "spall: error: %s\n", err.msg);
            return cli_exit_status(rc);
        }
        field = picked; /* o.field stays: NULL picks the same default per frame */
    }
    size_t first = nf - 1, last = nf - 1;
    if (all) {
        first = 0;
    } else if (frame >= 0) {
        size_t j = 0;
        while (j < nf && frames[j] != frame)
            j++;
        if (j == nf) {
            fprintf(stderr, "spall: error: '%s' has no frame %ld (frames %ld..%ld)\n", input, frame,
                    frames[0], frames[nf - 1]);
            free(frames);
            return 2;
        }
        first = last = j;
    }
    if (all && out)
        mkdir(out, 0777);
    int status = 0;
    for (size_t j = first; j <= last; j++) {
        char h5[4096], png[4096];
        snprintf(h5, sizeof h5, "%s/fields_%06ld.h5", input, frames[j]);
        if (out && !all)
            snprintf(png, sizeof png, "%s", out);
        else
            snprintf(png, sizeof png, "%s/%s_%06ld.png", out ? out : input, field, frames[j]);
        int rc = render_frame_png(h5, png, &o, &err);
        if (rc) {
            fprintf(stderr, "spall: error: %s\n", err.msg);
            status = cli_exit_status(rc);
            break;
        }
        printf("%s\n", png);
    }
    free(frames);
    return status;
}
