/**
 * @file text_buf.h
 * @brief Small helpers of the output writers (output_hdf5.c, output_bonds.c):
 *        a growable text buffer (XDMF index entries) and DIR/NAME paths.
 */
#ifndef SPALL_IO_TEXT_BUF_H
#define SPALL_IO_TEXT_BUF_H

#include <stddef.h>

/** Growable text; zero-initialise, free(t.s) when done. */
struct text_buf {
    char *s;
    size_t len, cap;
};

/** Append printf-formatted text; 0, or -1 (out of memory, @p t unchanged). */
int text_append(struct text_buf *t, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/** "DIR/NAME", malloc'd (NULL when out of memory). */
char *path_join(const char *dir, const char *name);

#endif
