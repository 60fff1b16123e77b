#define _POSIX_C_SOURCE 200809L
/**
 * @file history.c
 * @brief history.csv writer (see output.h).
 *
 * One header line with the column names as given (the caller puts units in
 * brackets, e.g. "time [s]"), then one row per call with every value printed
 * as %.10g.  Each row is flushed so that a run killed mid-way still leaves a
 * complete record of the rows it reported, and a plotting script can follow a
 * running simulation.  Names holding a comma or a double quote are quoted as
 * RFC 4180 asks; a line break in a name is refused (it would break the row
 * structure).
 */
#include "io/output.h"

#include "spall/error.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <unistd.h>

struct history_writer {
    FILE *fp;
    char *path;
    size_t n_columns;
};

static int write_name(FILE *fp, const char *name)
{
    if (!strpbrk(name, ",\""))
        return fputs(name, fp) < 0 ? -1 : 0;
    if (fputc('"', fp) == EOF)
        return -1;
    for (const char *c = name; *c; c++) {
        if (*c == '"' && fputc('"', fp) == EOF)
            return -1;
        if (fputc(*c, fp) == EOF)
            return -1;
    }
    return fputc('"', fp) == EOF ? -1 : 0;
}

int history_writer_create(struct history_writer **out, const char *path,
                          const char *const *columns, size_t n_columns, struct spall_error *err)
{
    *out = NULL;
    if (n_columns == 0 || !columns)
        return spall_error_set(err, SPALL_ERR_INTERNAL, "history '%s': no columns", path);
    for (size_t k = 0; k < n_columns; k++)
        if (!columns[k] || strpbrk(columns[k], "\r\n"))
            return spall_error_set(err, SPALL_ERR_INPUT,
                                   "history '%s': column %zu name is missing or holds a line break",
                                   path, k + 1);
    struct history_writer *h = calloc(1, sizeof *h);
    if (!h)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory creating history writer");
    h->path = malloc(strlen(path) + 1);
    if (!h->path) {
        free(h);
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory creating history writer");
    }
    strcpy(h->path, path);
    h->n_columns = n_columns;
    errno = 0;
    h->fp = fopen(path, "w");
    if (!h->fp) {
        int e = errno;
        history_writer_destroy(&h);
        return spall_error_set(err, SPALL_ERR_IO, "cannot create history file '%s': %s", path,
                               e ? strerror(e) : "fopen failed");
    }
    int bad = 0;
    for (size_t k = 0; k < n_columns && !bad; k++) {
        if (k && fputc(',', h->fp) == EOF)
            bad = 1;
        if (!bad && write_name(h->fp, columns[k]) < 0)
            bad = 1;
    }
    if (bad || fputc('\n', h->fp) == EOF || fflush(h->fp) != 0) {
        history_writer_destroy(&h);
        return spall_error_set(err, SPALL_ERR_IO, "cannot write header of history file '%s'",
                               path);
    }
    *out = h;
    return SPALL_OK;
}

int history_writer_append(struct history_writer *h, const double *values, struct spall_error *err)
{
    int bad = 0;
    for (size_t k = 0; k < h->n_columns && !bad; k++)
        bad = fprintf(h->fp, k ? ",%.10g" : "%.10g", values[k]) < 0;
    if (bad || fputc('\n', h->fp) == EOF || fflush(h->fp) != 0)
        return spall_error_set(err, SPALL_ERR_IO, "cannot write to history file '%s'", h->path);
    return SPALL_OK;
}

long history_writer_bytes(const struct history_writer *h)
{
    return ftell(h->fp);
}

int history_writer_resume(struct history_writer **out, const char *path, long bytes,
                          size_t n_columns, struct spall_error *err)
{
    *out = NULL;
    struct history_writer *h = calloc(1, sizeof *h);
    if (!h || !(h->path = malloc(strlen(path) + 1))) {
        free(h);
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory creating history writer");
    }
    strcpy(h->path, path);
    h->n_columns = n_columns;
    errno = 0;
    h->fp = fopen(path, "r+");
    /* rows after the checkpoint were written by the run that is being
     * continued: they are replaced, not repeated */
    if (!h->fp || fseek(h->fp, 0, SEEK_END) != 0 || ftell(h->fp) < bytes ||
        ftruncate(fileno(h->fp), (off_t)bytes) != 0 || fseek(h->fp, bytes, SEEK_SET) != 0) {
        int e = errno;
        history_writer_destroy(&h);
        return spall_error_set(err, SPALL_ERR_INPUT,
                               "cannot continue history file '%s' at byte %ld: %s", path, bytes,
                               e ? strerror(e) : "it is shorter than at the checkpoint");
    }
    *out = h;
    return SPALL_OK;
}

void history_writer_destroy(struct history_writer **h)
{
    if (!h || !*h)
        return;
    if ((*h)->fp)
        fclose((*h)->fp);
    free((*h)->path);
    free(*h);
    *h = NULL;
}
