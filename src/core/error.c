#include "spall/error.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

int spall_error_set(struct spall_error *err, int code, const char *fmt, ...)
{
    if (!err)
        return code;
    err->code = code;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err->msg, sizeof err->msg, fmt, ap);
    va_end(ap);
    return code;
}

void spall_error_prefix(struct spall_error *err, const char *fmt, ...)
{
    if (!err)
        return;
    char head[SPALL_ERROR_MSG_LEN];
    char old[SPALL_ERROR_MSG_LEN];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(head, sizeof head, fmt, ap);
    va_end(ap);
    memcpy(old, err->msg, sizeof old);
    /* head then as much of the old message as fits */
    size_t h = strlen(head);
    size_t room = sizeof err->msg - 1;
    if (h > room)
        h = room;
    memcpy(err->msg, head, h);
    size_t o = strlen(old);
    if (o > room - h)
        o = room - h;
    memcpy(err->msg + h, old, o);
    err->msg[h + o] = '\0';
}

void spall_error_clear(struct spall_error *err)
{
    if (!err)
        return;
    err->code = 0;
    err->msg[0] = '\0';
}
