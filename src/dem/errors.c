/*---------------------------------------------------------------------------*\
  demFoam DEM core - status strings, error messages and the logger.
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/
#include "dem_private.h"
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

/*--- status strings ----------------------------------------------------------*/
static const char *const status_text[] = {
#define DEM_X_TEXT(name, text) text,
    DEM_STATUS_LIST(DEM_X_TEXT)
#undef DEM_X_TEXT
};

const char *dem_status_string(dem_status s)
{
    if ((int)s < 0 || (int)s >= DEM_STATUS_COUNT) return "unknown status";
    return status_text[s];
}

dem_status dem_fail_(const dem_world *wc, dem_status code, const char *file, int line,
                     const char *fmt, ...)
{
    dem_world *w = (dem_world *)wc; /* the error text is mutable state of a const handle */
    if (!w) return code;
    const char *base = strrchr(file, '/');
    base = base ? base + 1 : file;
    int k = snprintf(w->err, sizeof w->err, "%s:%d: %s: ", base, line, dem_status_string(code));
    if (k < 0) k = 0;
    if ((size_t)k < sizeof w->err) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(w->err + k, sizeof w->err - (size_t)k, fmt, ap);
        va_end(ap);
    }
    return code;
}

void dem_log_(const dem_world *w, dem_log_level lvl, const char *fmt, ...)
{
    if (!w || !w->log) return;
    char buf[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    w->log(lvl, buf, w->log_user);
}

const char *dem_world_last_error(const dem_world *w) { return w ? w->err : ""; }

void dem_world_set_logger(dem_world *w, dem_log_fn fn, void *user)
{
    if (!w) return;
    w->log = fn;
    w->log_user = user;
}

/* The text of an error message after "file:line: status: ". */
const char *dem_error_detail(const dem_world *w)
{
    const char *p = strstr(w->err, ": ");
    if (p) p = strstr(p + 2, ": ");
    return p ? p + 2 : w->err;
}
