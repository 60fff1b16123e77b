#include "spall/error.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

int spall_error_set(struct spall_error *err, int code, const char *fmt, ...)
{
    if (!err)
        return code;
    err->code = code;
    err->key[0] = '\0';
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err->msg, sizeof err->msg, fmt, ap);
    va_end(ap);
    return code;
}

/* A key path cut short would name another key: keep none instead. */
static void write_key(struct spall_error *err, const char *fmt, va_list ap)
{
    int len = vsnprintf(err->key, sizeof err->key, fmt, ap);
    if (len < 0 || (size_t)len >= sizeof err->key)
        err->key[0] = '\0';
}

int spall_error_set_key(struct spall_error *err, int code, const char *key, const char *fmt, ...)
{
    if (!err)
        return code;
    err->code = code;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err->msg, sizeof err->msg, fmt, ap);
    va_end(ap);
    size_t len = key ? strlen(key) : 0;
    if (len >= sizeof err->key) /* cut short it would name another key */
        len = 0;
    memcpy(err->key, key ? key : "", len);
    err->key[len] = '\0';
    return code;
}

void spall_error_default_key(struct spall_error *err, const char *fmt, ...)
{
    if (!err || err->key[0])
        return;
    va_list ap;
    va_start(ap, fmt);
    write_key(err, fmt, ap);
    va_end(ap);
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
    err->key[0] = '\0';
    err->agreed = 0;
}
