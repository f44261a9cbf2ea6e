/*---------------------------------------------------------------------------*\
  demFoam DEM core - state files: save and restore (to a file or memory);
  the checks of a restored state are in stateCheck.c.
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
        dem_tags_reset(w, 0, np); /* not saved (dem.h) */
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
    if (dem_state_check(w, err, path)) return DEM_ERR_FORMAT;
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
        DEM_FAIL(w, st, "restore: '%s': %s", name, dem_error_detail(nw));
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
