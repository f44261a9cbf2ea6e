/*---------------------------------------------------------------------------*\
  demFoam DEM core - state files (save/restore), particle packing for
  domain decomposition (pack/unpack), ghosts.
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)

  State file (binary, native byte order, checked on read):
      "DEMSTATE" | uint32 version | uint32 0x01020304 | uint32 sizeof(double)
      | sections in the fixed order of save_world()
  Everything that influences later steps is stored: configuration,
  materials, all particle arrays in storage order, the neighbour list with
  its tangential history and wall-contact history (so that force summation
  order - and therefore every bit - is the same after a restore), walls,
  inlets (with owed amounts and pre-drawn sizes), outlet totals, removal
  records, RNG state, time and step.
\*---------------------------------------------------------------------------*/
#define _POSIX_C_SOURCE 200809L /* open_memstream, fmemopen */
#include "dem_private.h"
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define DEM_STATE_VERSION 3u /* 2: pair overrides, config.impact_speed, inlet warning flag;
                                3: added_mass (version 2 files are read with added_mass 0) */
static const char state_magic[8] = {'D', 'E', 'M', 'S', 'T', 'A', 'T', 'E'};

typedef struct { FILE *f; int bad; uint64_t left; /* restore: bytes not read yet */ } wio;

static void put(wio *o, const void *p, size_t bytes)
{
    if (o->bad || bytes == 0) return;
    if (fwrite(p, 1, bytes, o->f) != bytes) o->bad = 1;
}
static void get(wio *o, void *p, size_t bytes)
{
    if (o->bad || bytes == 0) return;
    if (bytes > o->left || fread(p, 1, bytes, o->f) != bytes) { o->bad = 1; return; }
    o->left -= bytes;
}
/* 1 if count items of elem bytes can still be in the file (bounds every
 * allocation of a restore by the file size). */
static int fits(const wio *o, uint64_t count, uint64_t elem)
{
    return !o->bad && (elem == 0 || count <= o->left / elem);
}
#define PUT(o, x) put((o), &(x), sizeof(x))
#define GET(o, x) get((o), &(x), sizeof(x))

static void save_world(wio *o, const dem_world *w)
{
    uint32_t ver = DEM_STATE_VERSION, endian = 0x01020304u, sd = (uint32_t)sizeof(double);
    put(o, state_magic, sizeof state_magic);
    PUT(o, ver); PUT(o, endian); PUT(o, sd);
    PUT(o, w->cfg);
    PUT(o, w->nmat);
    put(o, w->mat, (size_t)w->nmat * sizeof *w->mat);
    PUT(o, w->novr);
    put(o, w->ovr, (size_t)w->novr * sizeof *w->ovr);
    uint64_t n = w->n, ng = w->ng;
    size_t np = w->n + w->ng;
    PUT(o, n); PUT(o, ng); PUT(o, w->next_id); PUT(o, w->have_ext);
    put(o, w->id, np * sizeof(int64_t));
    put(o, w->x, 3 * np * sizeof(double)); put(o, w->v, 3 * np * sizeof(double));
    put(o, w->w, 3 * np * sizeof(double)); put(o, w->f, 3 * np * sizeof(double));
    put(o, w->t, 3 * np * sizeof(double));
    put(o, w->rad, np * sizeof(double)); put(o, w->mass, np * sizeof(double));
    put(o, w->rho, np * sizeof(double)); put(o, w->mat_of, np * sizeof(int));
    put(o, w->x0, 3 * np * sizeof(float)); put(o, w->list_index, np * sizeof(int));
    if (w->have_ext) {
        put(o, w->fext, 3 * np * sizeof(double)); put(o, w->text, 3 * np * sizeof(double));
        put(o, w->K, np * sizeof(double)); put(o, w->uf, 3 * np * sizeof(double));
        put(o, w->J, 3 * np * sizeof(double));
        put(o, w->Ma, np * sizeof(double));
    }
    /* neighbour list */
    uint64_t nrows = w->nb_off ? w->nrows : 0, nnb = w->nnb, nwc = w->nwc;
    PUT(o, w->list_valid); PUT(o, nrows); PUT(o, nnb); PUT(o, nwc);
    PUT(o, w->skin); PUT(o, w->amax); PUT(o, w->cutoff); PUT(o, w->shift);
    PUT(o, w->t_build); PUT(o, w->nbuilds);
    if (nrows) {
        put(o, w->nb_off, (nrows + 1) * sizeof(int));
        put(o, w->nb_j, nnb * sizeof(int)); put(o, w->nb_s, nnb);
        put(o, w->nb_h, 3 * nnb * sizeof(double));
        int has_wc = w->wc_off != NULL;
        PUT(o, has_wc);
        if (has_wc) {
            put(o, w->wc_off, (nrows + 1) * sizeof(int));
            put(o, w->wc_wall, nwc * sizeof(int)); put(o, w->wc_tri, nwc * sizeof(int));
            put(o, w->wc_h, 3 * nwc * sizeof(double));
        }
    }
    uint64_t npend = w->npend, nwpend = w->nwpend;
    PUT(o, npend); put(o, w->pend, npend * sizeof *w->pend);
    PUT(o, nwpend); put(o, w->wpend, nwpend * sizeof *w->wpend);
    /* walls */
    PUT(o, w->nwalls); PUT(o, w->nplanes); PUT(o, w->nmeshes);
    put(o, w->wall_kind, (size_t)w->nwalls * sizeof(int));
    put(o, w->wall_index, (size_t)w->nwalls * sizeof(int));
    put(o, w->planes, (size_t)w->nplanes * sizeof *w->planes);
    for (int k = 0; k < w->nmeshes; ++k) {
        const dem_mesh *m = &w->meshes[k];
        uint64_t nv = m->nv, nt = m->ntri;
        PUT(o, nv); PUT(o, nt);
        put(o, m->v0, 3 * nv * sizeof(double)); put(o, m->tri, 3 * nt * sizeof(int));
        put(o, m->nrm, 3 * nt * sizeof(double));
        PUT(o, m->vel); PUT(o, m->t0); PUT(o, m->material); PUT(o, m->wall);
    }
    /* time, rng, inlets, outlets, records, counters */
    PUT(o, w->time); PUT(o, w->step); PUT(o, w->rng);
    PUT(o, w->ninlets);
    for (int k = 0; k < w->ninlets; ++k) {
        dem_inlet in = w->inlets[k];
        in.poly = NULL;
        PUT(o, in);
        put(o, w->inlets[k].poly, 3 * in.nv * sizeof(double));
    }
    PUT(o, w->noutlets);
    put(o, w->outlets, (size_t)w->noutlets * sizeof *w->outlets);
    uint64_t nrec = w->nrec;
    PUT(o, nrec); put(o, w->rec, nrec * sizeof *w->rec);
    PUT(o, w->inserted); PUT(o, w->removed); PUT(o, w->reorders);
    PUT(o, w->max_overlap);
    uint64_t pc = w->pair_contacts, wc = w->wall_contacts;
    PUT(o, pc); PUT(o, wc); PUT(o, w->forces_valid);
}

dem_status dem_world_save(const dem_world *w, const char *path)
{
    if (!w) return DEM_ERR_ARG;
    if (w->drift_pending)
        return DEM_FAIL(w, DEM_ERR_STATE, "save: step %lld is half done (dem_world_step_drift was called); "
                        "a state is saved between steps: call dem_world_step_forces first", (long long)w->step);
    DEM_NEED(w, path, "save");
    FILE *f = fopen(path, "wb");
    if (!f) return DEM_FAIL(w, DEM_ERR_IO, "save: cannot open '%s' for writing", path);
    wio o = {f, 0, 0};
    save_world(&o, w);
    if (fclose(f) != 0) o.bad = 1;
    if (o.bad) return DEM_FAIL(w, DEM_ERR_IO, "save: write error on '%s'", path);
    return DEM_OK;
}

dem_status dem_world_save_memory(const dem_world *w, void **buf, size_t *capacity, size_t *size)
{
    if (!w) return DEM_ERR_ARG;
    if (w->drift_pending)
        return DEM_FAIL(w, DEM_ERR_STATE, "save_memory: step %lld is half done (dem_world_step_drift was called); "
                        "a state is saved between steps: call dem_world_step_forces first", (long long)w->step);
    if (!buf || !capacity || !size)
        return DEM_FAIL(w, DEM_ERR_ARG, "save_memory: buf, capacity and size must not be NULL");
    /* into the caller's buffer when it is large enough (no allocation,
       no fresh pages: the per-step checkpoint of demFoam) */
    if (*buf && *capacity > 0) {
        FILE *f = fmemopen(*buf, *capacity, "wb");
        if (f) {
            setvbuf(f, NULL, _IONBF, 0);
            wio o = {f, 0, 0};
            save_world(&o, w);
            long used = ftell(f);
            if (fclose(f) != 0) o.bad = 1;
            if (!o.bad && used >= 0 && (size_t)used < *capacity) {
                *size = (size_t)used;
                return DEM_OK;
            }
        }
    }
    /* first call or grown state: a new buffer with 1/8 slack */
    char *p = NULL;
    size_t n = 0;
    FILE *f = open_memstream(&p, &n);
    if (!f) return DEM_FAIL(w, DEM_ERR_NOMEM, "save_memory: cannot open a memory stream");
    wio o = {f, 0, 0};
    save_world(&o, w);
    if (fclose(f) != 0) o.bad = 1;
    if (o.bad) { free(p); return DEM_FAIL(w, DEM_ERR_NOMEM, "save_memory: out of memory"); }
    size_t cap = n + n / 8 + 64;
    char *q = realloc(p, cap);
    if (!q) { free(p); return DEM_FAIL(w, DEM_ERR_NOMEM, "save_memory: out of memory (%zu bytes)", cap); }
    free(*buf);
    *buf = q;
    *capacity = cap;
    *size = n;
    return DEM_OK;
}

/* The text of an error message after "file:line: status: ". */
static const char *detail(const dem_world *w)
{
    const char *p = strstr(w->err, ": ");
    if (p) p = strstr(p + 2, ": ");
    return p ? p + 2 : w->err;
}

static int finite_all(const double *a, size_t n)
{
    for (size_t i = 0; i < n; ++i) if (!isfinite(a[i])) return 0;
    return 1;
}

static int csr_ok(const int *off, size_t rows, size_t total)
{
    if (off[0] != 0 || (size_t)off[rows] != total) return 0;
    for (size_t r = 0; r < rows; ++r) if (off[r + 1] < off[r]) return 0;
    return 1;
}

/* Checks of everything a restored world relies on: indices in range, sizes
 * consistent, the checks of configure/add_material, particle sizes and
 * masses, walls and inlets.  Positions, velocities, forces, coupling inputs
 * and contact histories are the state as saved (a non-finite one is
 * reported by the next dem_world_step, as before the save).  The message
 * goes to err; returns 1 if the state is unusable. */
static int corrupt(dem_world *err, const char *path, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
static int corrupt(dem_world *err, const char *path, const char *fmt, ...)
{
    char buf[400];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    DEM_FAIL(err, DEM_ERR_FORMAT, "restore: '%s' is corrupt: %s", path, buf);
    return 1;
}
#define CORRUPT(...) return corrupt(err, path, __VA_ARGS__)
static int check_loaded(dem_world *w, dem_world *err, const char *path)
{
    size_t np = w->n + w->ng;
    if (dem_config_check(w, &w->cfg)) CORRUPT("configuration: %s", detail(w));
    for (int i = 0; i < w->nmat; ++i) {
        char what[32];
        snprintf(what, sizeof what, "material %d", i);
        if (dem_material_check(w, &w->mat[i], what, 0)) CORRUPT("%s", detail(w));
    }
    for (int k = 0; k < w->novr; ++k) {
        const dem_pair_override *o = &w->ovr[k];
        if (o->a < 0 || o->a >= w->nmat || o->b < 0 || o->b >= w->nmat)
            CORRUPT("pair override %d: materials %d, %d of %d", k, o->a, o->b, w->nmat);
        if (dem_material_check(w, &o->m, "pair override", 0)) CORRUPT("%s", detail(w));
    }
    if (w->next_id < 0) CORRUPT("next id %lld", (long long)w->next_id);
    for (size_t i = 0; i < np; ++i) {
        if (w->id[i] < 0 || w->id[i] == INT64_MAX) CORRUPT("particle %zu: id %lld", i, (long long)w->id[i]);
        if (!(w->rad[i] > 0) || !(w->rho[i] > 0) || !isfinite(w->rho[i]) || !dem_inertia_ok(w->mass[i], w->rad[i]))
            CORRUPT("particle %zu (id %lld): radius %g, mass %g, density %g", i, (long long)w->id[i], w->rad[i],
                    w->mass[i], w->rho[i]);
        if (w->mat_of[i] < 0 || w->mat_of[i] >= w->nmat)
            CORRUPT("particle %zu (id %lld): material %d of %d", i, (long long)w->id[i], w->mat_of[i], w->nmat);
        if (w->list_index[i] < -1 || (w->list_index[i] >= 0 && (size_t)w->list_index[i] >= w->nrows))
            CORRUPT("particle %zu: list row %d of %zu", i, w->list_index[i], w->nrows);
    }
    /* neighbour list */
    if (w->list_valid && w->nrows != np) CORRUPT("valid neighbour list of %zu rows for %zu particles", w->nrows, np);
    if (!isfinite(w->skin) || !(w->skin >= 0) || !isfinite(w->amax) || !isfinite(w->cutoff) ||
        !finite_all(&w->shift[0][0], 81) || !isfinite(w->t_build) || w->nbuilds < 0)
        CORRUPT("neighbour list parameters (skin %g, shifts, build time %g, builds %lld)", w->skin, w->t_build,
                (long long)w->nbuilds);
    if (w->nrows) {
        if (!csr_ok(w->nb_off, w->nrows, w->nnb)) CORRUPT("neighbour list offsets");
        for (size_t k = 0; k < w->nnb; ++k)
            if (w->nb_j[k] < 0 || (size_t)w->nb_j[k] >= w->nrows || w->nb_s[k] >= 27)
                CORRUPT("neighbour list entry %zu: partner %d of %zu rows, image %d", k, w->nb_j[k], w->nrows,
                        (int)w->nb_s[k]);
        if (!w->wc_off) CORRUPT("neighbour list without its wall list");
        if (!csr_ok(w->wc_off, w->nrows, w->nwc)) CORRUPT("wall list offsets");
    } else if (w->nnb || w->nwc) CORRUPT("%zu list entries and %zu wall entries without rows", w->nnb, w->nwc);
    /* walls: ids, kinds and indices consistent both ways */
    for (int k = 0; k < w->nwalls; ++k) {
        int kind = w->wall_kind[k], idx = w->wall_index[k];
        if (!((kind == 0 && idx >= 0 && idx < w->nplanes && w->planes[idx].wall == k) ||
              (kind == 1 && idx >= 0 && idx < w->nmeshes && w->meshes[idx].wall == k)))
            CORRUPT("wall %d: kind %d, index %d", k, kind, idx);
    }
    for (int k = 0; k < w->nplanes; ++k) {
        const dem_plane *P = &w->planes[k];
        if (P->wall < 0 || P->wall >= w->nwalls || w->wall_kind[P->wall] != 0 || w->wall_index[P->wall] != k ||
            P->material < 0 || P->material >= w->nmat || !finite_all(P->x0, 3) || !finite_all(P->n, 3) ||
            !finite_all(P->vel, 3) || !isfinite(P->t0) || !(dem_dot(P->n, P->n) > 0))
            CORRUPT("plane %d (wall %d, material %d)", k, P->wall, P->material);
    }
    size_t ntri = 0;
    for (int k = 0; k < w->nmeshes; ++k) {
        const dem_mesh *m = &w->meshes[k];
        if (m->wall < 0 || m->wall >= w->nwalls || w->wall_kind[m->wall] != 1 || w->wall_index[m->wall] != k ||
            m->material < 0 || m->material >= w->nmat || m->ntri == 0 || !finite_all(m->v0, 3 * m->nv) ||
            !finite_all(m->nrm, 3 * m->ntri) || !finite_all(m->vel, 3) || !isfinite(m->t0))
            CORRUPT("mesh %d (wall %d, material %d, %zu triangles)", k, m->wall, m->material, m->ntri);
        for (size_t i = 0; i < 3 * m->ntri; ++i)
            if (m->tri[i] < 0 || (size_t)m->tri[i] >= m->nv)
                CORRUPT("mesh %d: vertex index %d of %zu", k, m->tri[i], m->nv);
        ntri += m->ntri;
    }
    if (ntri != w->ntri_all) CORRUPT("triangle count");
    for (size_t k = 0; k < w->nwc; ++k) {
        int wall = w->wc_wall[k], t = w->wc_tri[k];
        if (wall < 0 || wall >= w->nwalls ||
            (w->wall_kind[wall] == 0 && t != -1) ||
            (w->wall_kind[wall] == 1 && (t < 0 || (size_t)t >= w->meshes[w->wall_index[wall]].ntri)))
            CORRUPT("wall list entry %zu: wall %d, triangle %d", k, wall, t);
    }
    /* time, counters, random numbers */
    if (!isfinite(w->time) || w->step < 0 || w->inserted < 0 || w->inserted > INT64_MAX / 2 || w->removed < 0 ||
        w->removed > INT64_MAX / 2 || w->reorders < 0 || w->reorders > INT64_MAX / 2 || w->nbuilds > INT64_MAX / 2)
        CORRUPT("time %g, step %lld or counters", w->time, (long long)w->step);
    if (!(w->rng[0] | w->rng[1] | w->rng[2] | w->rng[3])) CORRUPT("random number state is zero");
    for (int k = 0; k < w->ninlets; ++k) {
        char what[32];
        snprintf(what, sizeof what, "inlet %d", k);
        if (dem_inlet_check(w, &w->inlets[k], what)) CORRUPT("%s", detail(w));
    }
    for (int k = 0; k < w->noutlets; ++k) {
        const dem_outlet *o = &w->outlets[k];
        if (o->kind < 0 || o->kind > 2 || o->count < 0 || o->count > INT64_MAX / 2 ||
            (o->kind == 0 && (!finite_all(o->a, 3) || !finite_all(o->b, 3))) ||
            (o->kind == 1 && (isnan(o->a[0] + o->a[1] + o->a[2]) || isnan(o->b[0] + o->b[1] + o->b[2]))))
            CORRUPT("outlet %d (kind %d)", k, o->kind);
    }
    return 0;
}
#undef CORRUPT

#define CHECK_ALLOC(p) do { if (!(p)) { st = DEM_ERR_NOMEM; goto fail; } } while (0)

static dem_status load_world(wio *o, dem_world *w, const char *path, dem_world *err)
{
    dem_status st = DEM_OK;
    char magic[8];
    uint32_t ver = 0, endian = 0, sd = 0;
    get(o, magic, sizeof magic);
    GET(o, ver); GET(o, endian); GET(o, sd);
    if (o->bad || memcmp(magic, state_magic, sizeof magic) != 0)
        return DEM_FAIL(err, DEM_ERR_FORMAT, "restore: '%s' is not a demFoam DEM state file", path);
    if ((ver != DEM_STATE_VERSION && ver != 2u) || endian != 0x01020304u || sd != sizeof(double))
        return DEM_FAIL(err, DEM_ERR_FORMAT, "restore: '%s' has version %u (byte-order mark 0x%08x, "
                        "double %u bytes); this library reads version %u, native byte order",
                        path, ver, endian, sd, DEM_STATE_VERSION);
    GET(o, w->cfg);
    GET(o, w->nmat);
    if (o->bad || w->nmat < 0 || w->nmat > 1000000 || !fits(o, (uint64_t)w->nmat, sizeof *w->mat)) goto bad;
    w->capmat = w->nmat;
    if (w->nmat) { w->mat = malloc((size_t)w->nmat * sizeof *w->mat); CHECK_ALLOC(w->mat); }
    get(o, w->mat, (size_t)w->nmat * sizeof *w->mat);
    GET(o, w->novr);
    if (o->bad || w->novr < 0 || w->novr > 1000000 || !fits(o, (uint64_t)w->novr, sizeof *w->ovr)) goto bad;
    if (w->novr) { w->ovr = malloc((size_t)w->novr * sizeof *w->ovr); CHECK_ALLOC(w->ovr); }
    get(o, w->ovr, (size_t)w->novr * sizeof *w->ovr);
    w->pairs_dirty = 1;
    uint64_t n = 0, ng = 0;
    GET(o, n); GET(o, ng); GET(o, w->next_id); GET(o, w->have_ext);
    /* >= 172 bytes per particle follow */
    if (o->bad || n > DEM_MAX_PARTICLES || ng > DEM_MAX_PARTICLES - n || !fits(o, n + ng, 172)) goto bad;
    size_t np = (size_t)(n + ng);
    int have_ext = w->have_ext;
    w->have_ext = 0;
    if ((st = dem_reserve(w, np > 64 ? np : 64))) goto fail;
    if (have_ext && (st = dem_ext_alloc(w))) goto fail;
    w->n = (size_t)n; w->ng = (size_t)ng;
    get(o, w->id, np * sizeof(int64_t));
    get(o, w->x, 3 * np * sizeof(double)); get(o, w->v, 3 * np * sizeof(double));
    get(o, w->w, 3 * np * sizeof(double)); get(o, w->f, 3 * np * sizeof(double));
    get(o, w->t, 3 * np * sizeof(double));
    get(o, w->rad, np * sizeof(double)); get(o, w->mass, np * sizeof(double));
    get(o, w->rho, np * sizeof(double)); get(o, w->mat_of, np * sizeof(int));
    get(o, w->x0, 3 * np * sizeof(float)); get(o, w->list_index, np * sizeof(int));
    if (have_ext) {
        get(o, w->fext, 3 * np * sizeof(double)); get(o, w->text, 3 * np * sizeof(double));
        get(o, w->K, np * sizeof(double)); get(o, w->uf, 3 * np * sizeof(double));
        get(o, w->J, 3 * np * sizeof(double));
        if (ver >= 3u) get(o, w->Ma, np * sizeof(double));
    }
    uint64_t nrows = 0, nnb = 0, nwc = 0;
    GET(o, w->list_valid); GET(o, nrows); GET(o, nnb); GET(o, nwc);
    GET(o, w->skin); GET(o, w->amax); GET(o, w->cutoff); GET(o, w->shift);
    GET(o, w->t_build); GET(o, w->nbuilds);
    if (o->bad || nrows > DEM_MAX_PARTICLES || nnb > INT_MAX || nwc > INT_MAX || !fits(o, nrows, sizeof(int)) ||
        !fits(o, nnb, sizeof(int) + 1 + 3 * sizeof(double)))
        goto bad;
    w->nrows = (size_t)nrows; w->nnb = (size_t)nnb; w->nwc = (size_t)nwc;
    if (nrows) {
        w->caprows = (size_t)nrows + 1;
        w->nb_off = malloc(w->caprows * sizeof(int)); CHECK_ALLOC(w->nb_off);
        w->capnb = (size_t)nnb + 1;
        w->nb_j = malloc(w->capnb * sizeof(int)); CHECK_ALLOC(w->nb_j);
        w->nb_s = malloc(w->capnb); CHECK_ALLOC(w->nb_s);
        w->nb_h = malloc(3 * w->capnb * sizeof(double)); CHECK_ALLOC(w->nb_h);
        get(o, w->nb_off, (nrows + 1) * sizeof(int));
        get(o, w->nb_j, nnb * sizeof(int)); get(o, w->nb_s, nnb);
        get(o, w->nb_h, 3 * nnb * sizeof(double));
        int has_wc = 0;
        GET(o, has_wc);
        if (has_wc && !fits(o, nwc, 2 * sizeof(int) + 3 * sizeof(double))) goto bad;
        if (has_wc) {
            w->capwc = (size_t)nwc + 1;
            w->wc_off = malloc(((size_t)nrows + 1) * sizeof(int)); CHECK_ALLOC(w->wc_off);
            w->wc_wall = malloc(w->capwc * sizeof(int)); CHECK_ALLOC(w->wc_wall);
            w->wc_tri = malloc(w->capwc * sizeof(int)); CHECK_ALLOC(w->wc_tri);
            w->wc_h = malloc(3 * w->capwc * sizeof(double)); CHECK_ALLOC(w->wc_h);
            get(o, w->wc_off, (nrows + 1) * sizeof(int));
            get(o, w->wc_wall, nwc * sizeof(int)); get(o, w->wc_tri, nwc * sizeof(int));
            get(o, w->wc_h, 3 * nwc * sizeof(double));
        }
    }
    uint64_t npend = 0, nwpend = 0;
    GET(o, npend);
    if (o->bad || !fits(o, npend, sizeof *w->pend)) goto bad;
    w->cappend = (size_t)npend; w->npend = (size_t)npend;
    if (npend) { w->pend = malloc((size_t)npend * sizeof *w->pend); CHECK_ALLOC(w->pend); }
    get(o, w->pend, (size_t)npend * sizeof *w->pend);
    GET(o, nwpend);
    if (o->bad || !fits(o, nwpend, sizeof *w->wpend)) goto bad;
    w->capwpend = (size_t)nwpend; w->nwpend = (size_t)nwpend;
    if (nwpend) { w->wpend = malloc((size_t)nwpend * sizeof *w->wpend); CHECK_ALLOC(w->wpend); }
    get(o, w->wpend, (size_t)nwpend * sizeof *w->wpend);
    GET(o, w->nwalls); GET(o, w->nplanes); GET(o, w->nmeshes);
    if (o->bad || w->nwalls < 0 || w->nplanes < 0 || w->nmeshes < 0 || w->nplanes > INT_MAX - w->nmeshes ||
        w->nwalls != w->nplanes + w->nmeshes || !fits(o, (uint64_t)w->nwalls, 2 * sizeof(int)) ||
        !fits(o, (uint64_t)w->nplanes + (uint64_t)w->nmeshes, sizeof(dem_plane) / 4))
        goto bad;
    if (w->nwalls) {
        w->wall_kind = malloc((size_t)w->nwalls * sizeof(int)); CHECK_ALLOC(w->wall_kind);
        w->wall_index = malloc((size_t)w->nwalls * sizeof(int)); CHECK_ALLOC(w->wall_index);
    }
    get(o, w->wall_kind, (size_t)w->nwalls * sizeof(int));
    get(o, w->wall_index, (size_t)w->nwalls * sizeof(int));
    if (w->nplanes) { w->planes = malloc((size_t)w->nplanes * sizeof *w->planes); CHECK_ALLOC(w->planes); }
    get(o, w->planes, (size_t)w->nplanes * sizeof *w->planes);
    if (w->nmeshes) { w->meshes = calloc((size_t)w->nmeshes, sizeof *w->meshes); CHECK_ALLOC(w->meshes); }
    for (int k = 0; k < w->nmeshes; ++k) {
        dem_mesh *m = &w->meshes[k];
        uint64_t nv = 0, nt = 0;
        GET(o, nv); GET(o, nt);
        if (o->bad || nv > INT_MAX || nt > (uint64_t)INT_MAX - w->ntri_all || !fits(o, nv, 3 * sizeof(double)) ||
            !fits(o, nt, 3 * sizeof(int) + 3 * sizeof(double)))
            goto bad;
        m->nv = (size_t)nv; m->ntri = (size_t)nt;
        m->v0 = malloc(3 * m->nv * sizeof(double) + 1); CHECK_ALLOC(m->v0);
        m->tri = malloc(3 * m->ntri * sizeof(int) + 1); CHECK_ALLOC(m->tri);
        m->nrm = malloc(3 * m->ntri * sizeof(double) + 1); CHECK_ALLOC(m->nrm);
        get(o, m->v0, 3 * m->nv * sizeof(double)); get(o, m->tri, 3 * m->ntri * sizeof(int));
        get(o, m->nrm, 3 * m->ntri * sizeof(double));
        GET(o, m->vel); GET(o, m->t0); GET(o, m->material); GET(o, m->wall);
        size_t base = w->ntri_all;
        int *tm = realloc(w->tri_mesh, (base + m->ntri + 1) * sizeof(int)); CHECK_ALLOC(tm); w->tri_mesh = tm;
        int *tl = realloc(w->tri_local, (base + m->ntri + 1) * sizeof(int)); CHECK_ALLOC(tl); w->tri_local = tl;
        for (size_t t = 0; t < m->ntri; ++t) { w->tri_mesh[base + t] = k; w->tri_local[base + t] = (int)t; }
        w->ntri_all += m->ntri;
    }
    GET(o, w->time); GET(o, w->step); GET(o, w->rng);
    GET(o, w->ninlets);
    if (o->bad || w->ninlets < 0 || w->ninlets > 1000000 || !fits(o, (uint64_t)w->ninlets, sizeof(dem_inlet))) goto bad;
    if (w->ninlets) { w->inlets = calloc((size_t)w->ninlets, sizeof *w->inlets); CHECK_ALLOC(w->inlets); }
    for (int k = 0; k < w->ninlets; ++k) {
        dem_inlet *in = &w->inlets[k];
        GET(o, *in);
        in->poly = NULL;
        if (o->bad || in->nv > 1000000 || !fits(o, in->nv, 3 * sizeof(double))) goto bad;
        in->poly = malloc(3 * in->nv * sizeof(double) + 1); CHECK_ALLOC(in->poly);
        get(o, in->poly, 3 * in->nv * sizeof(double));
    }
    GET(o, w->noutlets);
    if (o->bad || w->noutlets < 0 || w->noutlets > 1000000 || !fits(o, (uint64_t)w->noutlets, sizeof *w->outlets)) goto bad;
    if (w->noutlets) { w->outlets = malloc((size_t)w->noutlets * sizeof *w->outlets); CHECK_ALLOC(w->outlets); }
    get(o, w->outlets, (size_t)w->noutlets * sizeof *w->outlets);
    uint64_t nrec = 0;
    GET(o, nrec);
    if (o->bad || !fits(o, nrec, sizeof *w->rec)) goto bad;
    w->nrec = w->caprec = (size_t)nrec;
    if (nrec) { w->rec = malloc((size_t)nrec * sizeof *w->rec); CHECK_ALLOC(w->rec); }
    get(o, w->rec, (size_t)nrec * sizeof *w->rec);
    GET(o, w->inserted); GET(o, w->removed); GET(o, w->reorders);
    GET(o, w->max_overlap);
    uint64_t pc = 0, wc = 0;
    GET(o, pc); GET(o, wc); GET(o, w->forces_valid);
    w->pair_contacts = (size_t)pc; w->wall_contacts = (size_t)wc;
    if (o->bad) goto bad;
    {
        char extra;
        if (fread(&extra, 1, 1, o->f) == 1) goto bad; /* trailing data */
    }
    if (check_loaded(w, err, path)) return DEM_ERR_FORMAT;
    if (w->nrows && (st = dem_scratch_ensure(w))) goto fail;
    return DEM_OK;
bad:
    /* counts read before their arrays were allocated: nothing for destroy to free */
    if (!w->meshes) w->nmeshes = 0;
    if (!w->inlets) w->ninlets = 0;
    return DEM_FAIL(err, DEM_ERR_FORMAT, "restore: '%s' is truncated or corrupt (a size or count does not match "
                    "the data)", path);
fail:
    if (!w->meshes) w->nmeshes = 0;
    if (!w->inlets) w->ninlets = 0;
    return DEM_FAIL(err, st, "restore: '%s': out of memory", path);
}

/* Load a state of size bytes from an open stream into w (name for the
 * messages); w is replaced only if the whole state reads back and checks. */
static dem_status restore_stream(dem_world *w, FILE *f, uint64_t size, const char *name)
{
    dem_world *nw = NULL;
    dem_status st = dem_world_create(&nw);
    if (st) { fclose(f); return DEM_FAIL(w, st, "restore: out of memory"); }
    wio o = {f, 0, size};
    st = load_world(&o, nw, name, w);
    fclose(f);
    /* the pair table too before anything changes: a failed restore leaves w as it was */
    if (!st && (st = dem_pairs_update(nw)))
        DEM_FAIL(w, st, "restore: '%s': %s", name, detail(nw));
    if (st) { dem_world_destroy(&nw); return st; }
    /* swap contents, keep the logger and the contact-recording setting */
    dem_log_fn lf = w->log; void *lu = w->log_user;
    int crec_on = w->crec_on;
    dem_world tmp = *w;
    *w = *nw;
    *nw = tmp;
    w->log = lf; w->log_user = lu;
    w->crec_on = crec_on;
    w->err[0] = '\0';
    dem_world_destroy(&nw);
    dem_log_(w, DEM_LOG_INFO, "restored '%s': %zu particles, step %lld, t = %g", name, w->n,
             (long long)w->step, w->time);
    return DEM_OK;
}

dem_status dem_world_restore(dem_world *w, const char *path)
{
    if (!w) return DEM_ERR_ARG;
    DEM_NEED(w, path, "restore");
    FILE *f = fopen(path, "rb");
    if (!f) return DEM_FAIL(w, DEM_ERR_IO, "restore: cannot open '%s' for reading", path);
    long size = -1;
    if (fseek(f, 0, SEEK_END) == 0) size = ftell(f);
    if (size < 0 || fseek(f, 0, SEEK_SET) != 0) {
        fclose(f);
        return DEM_FAIL(w, DEM_ERR_IO, "restore: cannot determine the size of '%s' (not a regular file?)", path);
    }
    return restore_stream(w, f, (uint64_t)size, path);
}

dem_status dem_world_restore_memory(dem_world *w, const void *buf, size_t size)
{
    if (!w) return DEM_ERR_ARG;
    if (!buf || size == 0) return DEM_FAIL(w, DEM_ERR_ARG, "restore_memory: empty buffer (%zu bytes)", size);
    FILE *f = fmemopen((void *)buf, size, "rb");
    if (!f) return DEM_FAIL(w, DEM_ERR_NOMEM, "restore_memory: cannot open a memory stream");
    return restore_stream(w, f, (uint64_t)size, "(memory)");
}

/*--- pack / unpack ------------------------------------------------------------------*/
/* Layout: uint32 magic | uint32 npair | uint32 nwall | uint32 flags |
 *         int64 id | double x,v,w,f,t (15) | radius, mass, density |
 *         int material | int pad | double fext,text (6), K, u (3), J (3), added mass |
 *         npair x (int64 partner id, double h[3])  (h oriented as seen from this particle)
 *         nwall x (int wall, int tri, double h[3])                                      */
#define PACK_MAGIC 0x444d5032u /* "DMP2" (2: added mass) */
typedef struct {
    uint32_t magic, npair, nwall, flags;
    int64_t id;
    double xvwft[15], rad, mass, rho;
    int32_t mat, pad;
    double ext[14];
} pack_head;
typedef struct { int64_t partner; double h[3]; } pack_pair;
typedef struct { int32_t wall, tri; double h[3]; } pack_wall;

/* row -> particle index (inverse of list_index); NULL if identity */
static int *row_owner(const dem_world *w)
{
    if (w->list_valid) return NULL;
    int *inv = malloc((w->nrows + 1) * sizeof(int));
    if (!inv) return NULL;
    for (size_t r = 0; r < w->nrows; ++r) inv[r] = -1;
    for (size_t p = 0; p < w->n + w->ng; ++p) {
        int r = w->list_index[p];
        if (r >= 0 && (size_t)r < w->nrows) inv[r] = (int)p;
    }
    return inv;
}

/* pack_particle (hist = 1) and pack_ghost (hist = 0: no contact history) */
static dem_status pack(const dem_world *w, size_t index, void *buf, size_t *size, int hist, const char *fn)
{
    DEM_NEED(w, size, fn);
    if (index >= w->n + w->ng)
        return DEM_FAIL(w, DEM_ERR_RANGE, "%s: index %zu; allowed below %zu (owned + ghost particles)",
                        fn, index, w->n + w->ng);
    int *inv = hist ? row_owner(w) : NULL;
    if (hist && !w->list_valid && !inv && w->nrows)
        return DEM_FAIL(w, DEM_ERR_NOMEM, "%s: row map", fn);
#define OWNER(r) (inv ? inv[(r)] : (int)(r))
    int row = hist && w->nb_off ? w->list_index[index] : -1;
    if ((size_t)row >= w->nrows) row = -1;
    uint32_t npair = 0, nwall = 0;
    pack_head hd;
    memset(&hd, 0, sizeof hd);
    /* count */
    for (int pass = 0; pass < 2; ++pass) {
        char *out = buf ? (char *)buf + sizeof hd : NULL;
        npair = nwall = 0;
        if (row >= 0) {
            for (size_t r = 0; r < w->nrows; ++r) {
                for (int k = w->nb_off[r]; k < w->nb_off[r + 1]; ++k) {
                    const double *h = w->nb_h + 3 * (size_t)k;
                    if (h[0] == 0 && h[1] == 0 && h[2] == 0) continue;
                    int other, sign;
                    if ((int)r == row) { other = w->nb_j[k]; sign = 1; }
                    else if (w->nb_j[k] == row) { other = (int)r; sign = -1; }
                    else continue;
                    int po = OWNER(other);
                    if (po < 0) continue;
                    if (pass == 1 && out) {
                        pack_pair pp;
                        pp.partner = w->id[po];
                        for (int c = 0; c < 3; ++c) pp.h[c] = sign * h[c];
                        memcpy(out + (size_t)npair * sizeof pp, &pp, sizeof pp);
                    }
                    npair++;
                }
            }
            if (w->wc_off) {
                char *wout = out ? out + (size_t)npair * sizeof(pack_pair) : NULL;
                for (int k = w->wc_off[row]; k < w->wc_off[row + 1]; ++k) {
                    const double *h = w->wc_h + 3 * (size_t)k;
                    if (h[0] == 0 && h[1] == 0 && h[2] == 0) continue;
                    if (pass == 1 && wout) {
                        pack_wall pw;
                        pw.wall = w->wc_wall[k]; pw.tri = w->wc_tri[k];
                        memcpy(pw.h, h, sizeof pw.h);
                        memcpy(wout + (size_t)nwall * sizeof pw, &pw, sizeof pw);
                    }
                    nwall++;
                }
            }
        }
        if (pass == 0) {
            size_t need = sizeof hd + npair * sizeof(pack_pair) + nwall * sizeof(pack_wall);
            if (!buf) { *size = need; free(inv); return DEM_OK; }
            if (*size < need) {
                free(inv);
                return DEM_FAIL(w, DEM_ERR_RANGE, "%s: *size = %zu bytes; need %zu", fn, *size, need);
            }
            *size = need;
        }
    }
#undef OWNER
    free(inv);
    hd.magic = PACK_MAGIC; hd.npair = npair; hd.nwall = nwall;
    hd.id = w->id[index];
    for (int c = 0; c < 3; ++c) {
        hd.xvwft[c] = w->x[3 * index + c]; hd.xvwft[3 + c] = w->v[3 * index + c];
        hd.xvwft[6 + c] = w->w[3 * index + c]; hd.xvwft[9 + c] = w->f[3 * index + c];
        hd.xvwft[12 + c] = w->t[3 * index + c];
    }
    hd.rad = w->rad[index]; hd.mass = w->mass[index]; hd.rho = w->rho[index]; hd.mat = w->mat_of[index];
    if (w->have_ext) {
        hd.flags = 1;
        for (int c = 0; c < 3; ++c) {
            hd.ext[c] = w->fext[3 * index + c]; hd.ext[3 + c] = w->text[3 * index + c];
            hd.ext[7 + c] = w->uf[3 * index + c]; hd.ext[10 + c] = w->J[3 * index + c];
        }
        hd.ext[6] = w->K[index];
        hd.ext[13] = w->Ma[index];
    }
    memcpy(buf, &hd, sizeof hd);
    return DEM_OK;
}

dem_status dem_world_pack_particle(const dem_world *w, size_t index, void *buf, size_t *size)
{
    if (!w) return DEM_ERR_ARG;
    return pack(w, index, buf, size, 1, "pack_particle");
}

dem_status dem_world_pack_ghost(const dem_world *w, size_t index, void *buf, size_t *size)
{
    if (!w) return DEM_ERR_ARG;
    return pack(w, index, buf, size, 0, "pack_ghost");
}

dem_status dem_world_unpack_particle(dem_world *w, const void *buf, size_t size, int ghost)
{
    if (!w) return DEM_ERR_ARG;
    DEM_NEED(w, buf, "unpack_particle");
    pack_head hd;
    if (size < sizeof hd)
        return DEM_FAIL(w, DEM_ERR_FORMAT, "unpack_particle: size = %zu bytes; the header alone needs %zu", size, sizeof hd);
    memcpy(&hd, buf, sizeof hd);
    size_t need = sizeof hd + hd.npair * sizeof(pack_pair) + hd.nwall * sizeof(pack_wall);
    if (hd.magic != PACK_MAGIC)
        return DEM_FAIL(w, DEM_ERR_FORMAT, "unpack_particle: magic 0x%08x; need 0x%08x (not a packed particle)",
                        hd.magic, PACK_MAGIC);
    if (size < need)
        return DEM_FAIL(w, DEM_ERR_FORMAT, "unpack_particle: size = %zu bytes; %u contacts and %u wall contacts "
                        "need %zu", size, hd.npair, hd.nwall, need);
    if (hd.mat < 0 || hd.mat >= w->nmat)
        return DEM_FAIL(w, DEM_ERR_NOTFOUND, "unpack_particle: particle id %lld has material %d; allowed 0..%d "
                        "(%d materials defined)", (long long)hd.id, hd.mat, w->nmat - 1, w->nmat);
    /* everything is checked before anything is stored */
    if (hd.id < 0 || hd.id == INT64_MAX)
        return DEM_FAIL(w, DEM_ERR_FORMAT, "unpack_particle: id %lld; allowed 0..%lld", (long long)hd.id,
                        (long long)(INT64_MAX - 1));
    for (int c = 0; c < 15; ++c)
        if (!isfinite(hd.xvwft[c]))
            return DEM_FAIL(w, DEM_ERR_NAN, "unpack_particle: id %lld: %s[%d] = %g; must be finite", (long long)hd.id,
                            (const char *[]){"x", "v", "omega", "force", "torque"}[c / 3], c % 3, hd.xvwft[c]);
    if (!(hd.rad > 0) || !(hd.rho > 0) || !isfinite(hd.rho) || !dem_inertia_ok(hd.mass, hd.rad))
        return DEM_FAIL(w, DEM_ERR_RANGE, "unpack_particle: id %lld: radius = %g, mass = %g, density = %g; need "
                        "positive finite values (mass and moment of inertia normal doubles)", (long long)hd.id,
                        hd.rad, hd.mass, hd.rho);
    for (int c = 0; c < 14; ++c)
        if (!isfinite(hd.ext[c]) || ((c == 6 || c == 13) && hd.ext[c] < 0))
            return DEM_FAIL(w, DEM_ERR_RANGE, "unpack_particle: id %lld: coupling value %d = %g; need finite "
                            "(drag_coeff and added_mass >= 0)", (long long)hd.id, c, hd.ext[c]);
    const char *body = (const char *)buf + sizeof hd;
    for (uint32_t k = 0; k < hd.npair; ++k) {
        pack_pair pp;
        memcpy(&pp, body + (size_t)k * sizeof pp, sizeof pp);
        if (!isfinite(pp.h[0]) || !isfinite(pp.h[1]) || !isfinite(pp.h[2]))
            return DEM_FAIL(w, DEM_ERR_NAN, "unpack_particle: id %lld: contact %u with id %lld has a non-finite "
                            "history", (long long)hd.id, k, (long long)pp.partner);
    }
    for (uint32_t k = 0; k < hd.nwall && !ghost; ++k) {
        pack_wall pw;
        memcpy(&pw, body + (size_t)hd.npair * sizeof(pack_pair) + (size_t)k * sizeof pw, sizeof pw);
        if (!isfinite(pw.h[0]) || !isfinite(pw.h[1]) || !isfinite(pw.h[2]))
            return DEM_FAIL(w, DEM_ERR_NAN, "unpack_particle: id %lld: wall contact %u has a non-finite history",
                            (long long)hd.id, k);
    }
    dem_status s = dem_room_for(w, 1, "unpack_particle");
    if (s) return s;
    /* room for the pending contacts first: no failure after the particle is stored */
    if (hd.npair && w->npend + hd.npair > w->cappend) {
        size_t nc = w->cappend ? 2 * w->cappend : 64;
        while (nc < w->npend + hd.npair) nc *= 2;
        dem_pending *q = realloc(w->pend, nc * sizeof *q);
        if (!q) return DEM_FAIL(w, DEM_ERR_NOMEM, "unpack_particle: %zu pending contacts", nc);
        w->pend = q; w->cappend = nc;
    }
    if (!ghost && hd.nwall && w->nwpend + hd.nwall > w->capwpend) {
        size_t nc = w->capwpend ? 2 * w->capwpend : 64;
        while (nc < w->nwpend + hd.nwall) nc *= 2;
        dem_wpending *q = realloc(w->wpend, nc * sizeof *q);
        if (!q) return DEM_FAIL(w, DEM_ERR_NOMEM, "unpack_particle: %zu pending wall contacts", nc);
        w->wpend = q; w->capwpend = nc;
    }
    size_t i;
    if (!ghost) {
        dem_particle p;
        memset(&p, 0, sizeof p);
        p.id = hd.id;
        for (int c = 0; c < 3; ++c) { p.x[c] = hd.xvwft[c]; p.v[c] = hd.xvwft[3 + c]; p.omega[c] = hd.xvwft[6 + c]; }
        p.radius = hd.rad; p.density = hd.rho; p.material = hd.mat;
        if ((s = dem_append_particle(w, &p))) return s;
        i = w->n - 1;
    } else {
        if ((s = dem_reserve(w, w->n + w->ng + 1))) return s;
        i = w->n + w->ng;
        w->id[i] = hd.id;
        for (int c = 0; c < 3; ++c) {
            w->x[3 * i + c] = hd.xvwft[c]; w->v[3 * i + c] = hd.xvwft[3 + c]; w->w[3 * i + c] = hd.xvwft[6 + c];
            w->x0[3 * i + c] = (float)hd.xvwft[c];
        }
        w->rad[i] = hd.rad; w->rho[i] = hd.rho; w->mat_of[i] = hd.mat;
        w->list_index[i] = -1;
        w->ng++;
        w->list_valid = 0;
        w->reorders++;
        if (hd.id >= w->next_id) w->next_id = hd.id + 1;
    }
    w->mass[i] = hd.mass;
    for (int c = 0; c < 3; ++c) { w->f[3 * i + c] = hd.xvwft[9 + c]; w->t[3 * i + c] = hd.xvwft[12 + c]; }
    if (w->have_ext) {
        for (int c = 0; c < 3; ++c) {
            w->fext[3 * i + c] = hd.ext[c]; w->text[3 * i + c] = hd.ext[3 + c];
            w->uf[3 * i + c] = hd.ext[7 + c]; w->J[3 * i + c] = hd.ext[10 + c];
        }
        w->K[i] = hd.ext[6];
        w->Ma[i] = hd.ext[13];
    }
    const char *p = (const char *)buf + sizeof hd;
    for (uint32_t k = 0; k < hd.npair; ++k) {
        pack_pair pp;
        memcpy(&pp, p + (size_t)k * sizeof pp, sizeof pp);
        dem_pending *d = &w->pend[w->npend++];
        d->ia = hd.id; d->ib = pp.partner;
        memcpy(d->h, pp.h, sizeof d->h);
    }
    p += (size_t)hd.npair * sizeof(pack_pair);
    for (uint32_t k = 0; k < hd.nwall && !ghost; ++k) {
        pack_wall pw;
        memcpy(&pw, p + (size_t)k * sizeof pw, sizeof pw);
        dem_wpending *d = &w->wpend[w->nwpend++];
        d->id = hd.id; d->wall = pw.wall; d->tri = pw.tri;
        memcpy(d->h, pw.h, sizeof d->h);
    }
    return DEM_OK;
}

dem_status dem_world_clear_ghosts(dem_world *w)
{
    if (!w) return DEM_ERR_ARG;
    if (w->ng == 0) return DEM_OK;
    /* keep the history of owned-ghost contacts by id (a ghost unpacked
       again with the same id gets it back at the next list build) */
    dem_status st = dem_history_to_pending(w, -1, "clear_ghosts");
    if (st) return st;
    for (size_t i = w->n; i < w->n + w->ng; ++i) w->list_index[i] = -1;
    w->ng = 0;
    w->list_valid = 0;
    w->reorders++;
    return DEM_OK;
}

dem_status dem_world_set_ghost_states(dem_world *w, size_t first, size_t count, const double *xvw)
{
    if (!w) return DEM_ERR_ARG;
    if (count == 0) {
        if (first > w->ng)
            return DEM_FAIL(w, DEM_ERR_RANGE, "set_ghost_states: first = %zu; allowed 0..%zu (%zu ghosts)",
                            first, w->ng, w->ng);
        return DEM_OK;
    }
    DEM_NEED(w, xvw, "set_ghost_states");
    if (first >= w->ng || count > w->ng - first)
        return DEM_FAIL(w, DEM_ERR_RANGE, "set_ghost_states: ghosts [%zu, %zu) (first = %zu, count = %zu); "
                        "allowed within [0, %zu) (%zu ghosts present)", first, first + count, first, count,
                        w->ng, w->ng);
    /* all or nothing: check every value first */
    static const char *const what[3] = {"x", "v", "omega"};
    for (size_t k = 0; k < 9 * count; ++k)
        if (!isfinite(xvw[k]))
            return DEM_FAIL(w, DEM_ERR_NAN, "set_ghost_states: ghost position %zu (id %lld): %s[%d] = %g "
                            "(xvw[%zu]); must be finite", first + k / 9, (long long)w->id[w->n + first + k / 9],
                            what[(k % 9) / 3], (int)(k % 3), xvw[k], k);
    for (size_t g = 0; g < count; ++g) {
        size_t i = w->n + first + g;
        const double *s = xvw + 9 * g;
        memcpy(w->x + 3 * i, s, 3 * sizeof(double));
        memcpy(w->v + 3 * i, s + 3, 3 * sizeof(double));
        memcpy(w->w + 3 * i, s + 6, 3 * sizeof(double));
    }
    /* list, history, x0 and the storage order are untouched (no reorder) */
    return DEM_OK;
}
