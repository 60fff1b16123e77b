/**
 * @file pen_csv.c
 * @brief Small numeric CSV reader for the penetration data files
 *        (the files under data/penetration, fit inputs): header of names, numeric rows,
 *        '#' comments; every error names the file and the line.
 */
#include "spall/penetration.h"

#include "spall/error.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static char *trim(char *s)
{
    while (*s && isspace((unsigned char)*s))
        s++;
    size_t n = strlen(s);
    while (n > 0 && isspace((unsigned char)s[n - 1]))
        s[--n] = '\0';
    return s;
}

void pen_csv_free(struct pen_csv *csv)
{
    if (!csv)
        return;
    for (size_t k = 0; csv->names && k < csv->n_cols; k++)
        free(csv->names[k]);
    free(csv->names);
    free(csv->data);
    memset(csv, 0, sizeof *csv);
}

int pen_csv_column(const struct pen_csv *csv, const char *name)
{
    for (size_t k = 0; k < csv->n_cols; k++)
        if (strcmp(csv->names[k], name) == 0)
            return (int)k;
    return -1;
}

static int parse_header(char *line, struct pen_csv *csv, const char *path, long ln,
                        struct spall_error *err)
{
    size_t n = 1;
    for (const char *c = line; *c; c++)
        n += *c == ',';
    csv->names = calloc(n, sizeof *csv->names);
    if (!csv->names)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory reading %s", path);
    char *save = line;
    for (size_t k = 0; k < n; k++) {
        char *comma = strchr(save, ',');
        if (comma)
            *comma = '\0';
        char *name = trim(save);
        if (!*name)
            return spall_error_set(err, SPALL_ERR_INPUT, "%s:%ld: column %zu has no name", path,
                                   ln, k + 1);
        csv->names[k] = malloc(strlen(name) + 1);
        if (!csv->names[k])
            return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory reading %s", path);
        strcpy(csv->names[k], name);
        csv->n_cols = k + 1;
        save = comma ? comma + 1 : save + strlen(save);
    }
    return SPALL_OK;
}

static int parse_row(char *line, struct pen_csv *csv, size_t *cap, const char *path, long ln,
                     struct spall_error *err)
{
    if ((csv->n_rows + 1) * csv->n_cols > *cap) {
        size_t nc = *cap ? 2 * *cap : 64 * csv->n_cols;
        double *d = realloc(csv->data, nc * sizeof *d);
        if (!d)
            return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory reading %s", path);
        csv->data = d;
        *cap = nc;
    }
    double *row = csv->data + csv->n_rows * csv->n_cols;
    char *s = line;
    for (size_t k = 0; k < csv->n_cols; k++) {
        char *end = NULL;
        row[k] = strtod(s, &end);
        if (end == s || !isfinite(row[k]))
            return spall_error_set(err, SPALL_ERR_INPUT,
                                   "%s:%ld: column '%s' is not a number; expected %zu numbers",
                                   path, ln, csv->names[k], csv->n_cols);
        while (*end && isspace((unsigned char)*end))
            end++;
        if (k + 1 < csv->n_cols) {
            if (*end != ',')
                return spall_error_set(err, SPALL_ERR_INPUT,
                                       "%s:%ld: %zu value(s) on the line; expected %zu", path, ln,
                                       k + 1, csv->n_cols);
            s = end + 1;
        } else if (*end) {
            return spall_error_set(err, SPALL_ERR_INPUT,
                                   "%s:%ld: more than %zu values on the line", path, ln,
                                   csv->n_cols);
        }
    }
    csv->n_rows++;
    return SPALL_OK;
}

int pen_csv_read(const char *path, struct pen_csv *csv, struct spall_error *err)
{
    memset(csv, 0, sizeof *csv);
    FILE *f = fopen(path, "r");
    if (!f)
        return spall_error_set(err, SPALL_ERR_INPUT, "cannot open CSV file '%s'", path);
    char buf[4096];
    long ln = 0;
    size_t cap = 0;
    int rc = SPALL_OK, header = 0;
    while (fgets(buf, sizeof buf, f)) {
        ln++;
        if (!strchr(buf, '\n') && !feof(f)) {
            rc = spall_error_set(err, SPALL_ERR_INPUT, "%s:%ld: line longer than %zu characters",
                                 path, ln, sizeof buf - 2);
            break;
        }
        char *line = trim(buf);
        if (!*line || *line == '#')
            continue;
        rc = header ? parse_row(line, csv, &cap, path, ln, err)
                    : parse_header(line, csv, path, ln, err);
        if (rc)
            break;
        header = 1;
    }
    fclose(f);
    if (!rc && !header)
        rc = spall_error_set(err, SPALL_ERR_INPUT, "%s: no header line (column names)", path);
    if (!rc && csv->n_rows == 0)
        rc = spall_error_set(err, SPALL_ERR_INPUT, "%s: no data rows", path);
    if (rc)
        pen_csv_free(csv);
    return rc;
}
