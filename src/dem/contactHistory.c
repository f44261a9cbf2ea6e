/*---------------------------------------------------------------------------*\
  demFoam DEM core - contact history outside the neighbour list: kept by
  particle ids while the particles are away (removal by migration, ghost
  exchange), and carried into the new list at a list build.
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/
#include "neighbour.h"
#include <stdlib.h>
#include <string.h>

/* The non-zero tangential history of the current list into the pending
 * store by id: of the pairs of particle index `only` (only >= 0); with
 * gone (only < 0), of the pairs between an owned particle with gone[q] != 0
 * and one that stays (owned or ghost), in one pass; else of all owned-ghost
 * pairs.  fn names the caller in messages. */
dem_status dem_history_to_pending(dem_world *w, ptrdiff_t only, const unsigned char *gone, const char *fn)
{
    if (!w->nb_off || !w->nrows) return DEM_OK;
    int row = -1;
    if (only >= 0) {
        row = w->list_index[only];
        if (row < 0 || (size_t)row >= w->nrows) return DEM_OK;
    }
    int *inv = malloc((w->nrows + 1) * sizeof(int));
    if (!inv) return DEM_FAIL(w, DEM_ERR_NOMEM, "%s: row map of %zu rows", fn, w->nrows);
    for (size_t r = 0; r < w->nrows; ++r) inv[r] = -1;
    for (size_t q = 0; q < w->n + w->ng; ++q) {
        int r = w->list_index[q];
        if (r >= 0 && (size_t)r < w->nrows) inv[r] = (int)q;
    }
    for (size_t r = 0; r < w->nrows; ++r) {
        const int a = inv[r];
        if (a < 0) continue;
        /* the tests on the indices first, the history (3 doubles) last */
        for (int k = w->nb_off[r]; k < w->nb_off[r + 1]; ++k) {
            if (only >= 0 && (int)r != row && w->nb_j[k] != row) continue;
            const int b = inv[w->nb_j[k]];
            if (b < 0) continue;
            if (only < 0 && gone) {
                int ga = (size_t)a < w->n && gone[a], gb = (size_t)b < w->n && gone[b];
                if (ga == gb) continue;
            } else if (only < 0 && (size_t)a < w->n && (size_t)b < w->n) continue;
            const double *h = w->nb_h + 3 * (size_t)k;
            if (!dem_history_nonzero(h)) continue;
            if (w->npend == w->cappend) {
                size_t nc = w->cappend ? 2 * w->cappend : 64;
                dem_pending *q = realloc(w->pend, nc * sizeof *q);
                if (!q) { free(inv); return DEM_FAIL(w, DEM_ERR_NOMEM, "%s: %zu pending contacts", fn, nc); }
                w->pend = q; w->cappend = nc;
            }
            dem_pending *d = &w->pend[w->npend++];
            d->ia = w->id[a]; d->ib = w->id[b];
            memcpy(d->h, h, sizeof d->h);
        }
    }
    free(inv);
    return DEM_OK;
}

static uint64_t hash64(int64_t k)
{
    uint64_t z = (uint64_t)k * 0x9E3779B97F4A7C15ull;
    return z ^ (z >> 29);
}

/* id -> index table (open addressing) for resolving pending contacts. */
typedef struct { int64_t *key; int *val; size_t mask; } idmap;
static int idmap_build(idmap *m, const dem_world *w)
{
    size_t np = w->n + w->ng, sz = 16;
    while (sz < 2 * np + 2) sz *= 2;
    m->key = malloc(sz * sizeof(int64_t));
    m->val = malloc(sz * sizeof(int));
    if (!m->key || !m->val) { free(m->key); free(m->val); return 0; }
    m->mask = sz - 1;
    for (size_t i = 0; i < sz; ++i) m->val[i] = -1;
    for (size_t i = 0; i < np; ++i) {
        size_t h = hash64(w->id[i]) & m->mask;
        while (m->val[h] >= 0) h = (h + 1) & m->mask;
        m->key[h] = w->id[i];
        m->val[h] = (int)i;
    }
    return 1;
}
static int idmap_get(const idmap *m, int64_t id)
{
    size_t h = hash64(id) & m->mask;
    while (m->val[h] >= 0) {
        if (m->key[h] == id) return m->val[h];
        h = (h + 1) & m->mask;
    }
    return -1;
}

static dem_status push_carry(dem_world *w, int a, int b, const double *h)
{
    if (a < 0 || b < 0 || a == b) return DEM_OK;
    GROWTO(w->carry, w->capcarry, w->ncarry + 1, dem_carry);
    dem_carry *c = &w->carry[w->ncarry++];
    if (a < b) { c->a = a; c->b = b; for (int k = 0; k < 3; ++k) c->h[k] = h[k]; }
    else { c->a = b; c->b = a; for (int k = 0; k < 3; ++k) c->h[k] = -h[k]; }
    return DEM_OK;
}

/* room for the carry rows' offsets (a function: GROWTO returns on failure,
   and the caller has its own allocations to free then) */
static dem_status grow_carry_off(dem_world *w, size_t need)
{
    GROWTO(w->carry_off, w->capcarry_off, need, int);
    return DEM_OK;
}

static int cmp_dem_wcarry(const void *a, const void *b)
{
    const dem_wcarry *x = a, *y = b;
    if (x->p != y->p) return x->p < y->p ? -1 : 1;
    if (x->wall != y->wall) return x->wall < y->wall ? -1 : 1;
    return (x->tri > y->tri) - (x->tri < y->tri);
}

/* The touching contacts of the old list (rows mapped to the new indices by
 * list_index) and the pending ones (by id), for the new list. */
dem_status dem_carry_collect(dem_world *w, dem_carried *out)
{
    dem_status st;
    size_t np = w->n + w->ng;
    out->pairs = NULL; out->walls = NULL; out->nwalls = 0;
    /* harvest the touching contacts of the old list into new indices */
    w->ncarry = 0;
    size_t oldrows = w->nrows;
    int *old2new = NULL;
    if (oldrows) {
        old2new = malloc(oldrows * sizeof(int));
        if (!old2new) return DEM_FAIL(w, DEM_ERR_NOMEM, "old2new: %zu", oldrows);
        for (size_t r = 0; r < oldrows; ++r) old2new[r] = -1;
        for (size_t p = 0; p < np; ++p) {
            int r = w->list_index[p];
            if (r >= 0 && (size_t)r < oldrows) old2new[r] = (int)p;
        }
        for (size_t r = 0; r < oldrows; ++r) {
            for (int k = w->nb_off[r]; k < w->nb_off[r + 1]; ++k) {
                const double *h = w->nb_h + 3 * (size_t)k;
                if (!dem_history_nonzero(h)) continue;
                int b = w->nb_j[k];
                if ((st = push_carry(w, old2new[r], (size_t)b < oldrows ? old2new[b] : -1, h))) {
                    free(old2new); return st;
                }
            }
        }
    }
    idmap im = {0};
    int have_map = 0;
    if (w->npend || w->nwpend) {
        if (!idmap_build(&im, w)) { free(old2new); return DEM_FAIL(w, DEM_ERR_NOMEM, "id map"); }
        have_map = 1;
        for (size_t k = 0; k < w->npend; ++k) {
            int a = idmap_get(&im, w->pend[k].ia), b = idmap_get(&im, w->pend[k].ib);
            if ((st = push_carry(w, a, b, w->pend[k].h))) { free(old2new); free(im.key); free(im.val); return st; }
        }
        w->npend = 0;
    }
    /* carry CSR by row a: counting sort */
    if ((st = grow_carry_off(w, np + 2))) { free(old2new); free(im.key); free(im.val); return st; }
    dem_carry *cs2 = malloc((w->ncarry + 1) * sizeof(dem_carry));
    if (!cs2) { free(old2new); free(im.key); free(im.val); return DEM_FAIL(w, DEM_ERR_NOMEM, "carry"); }
    memset(w->carry_off, 0, (np + 2) * sizeof(int));
    for (size_t k = 0; k < w->ncarry; ++k) w->carry_off[w->carry[k].a + 1]++;
    for (size_t p = 0; p < np; ++p) w->carry_off[p + 1] += w->carry_off[p];
    for (size_t k = 0; k < w->ncarry; ++k) cs2[w->carry_off[w->carry[k].a]++] = w->carry[k];
    for (size_t p = np; p > 0; --p) w->carry_off[p] = w->carry_off[p - 1];
    w->carry_off[0] = 0;

    /* wall history carry */
    size_t nwc_old = w->nwc;
    dem_wcarry *wcar = NULL; size_t nwcar = 0;
    if (oldrows || w->nwpend) {
        wcar = malloc((nwc_old + w->nwpend + 1) * sizeof(dem_wcarry));
        if (!wcar) { free(cs2); free(old2new); free(im.key); free(im.val); return DEM_FAIL(w, DEM_ERR_NOMEM, "wall carry"); }
        for (size_t r = 0; r < oldrows && w->wc_off; ++r) {
            if (old2new[r] < 0) continue;
            for (int k = w->wc_off[r]; k < w->wc_off[r + 1]; ++k) {
                const double *h = w->wc_h + 3 * (size_t)k;
                if (!dem_history_nonzero(h)) continue;
                dem_wcarry *c = &wcar[nwcar++];
                c->p = old2new[r]; c->wall = w->wc_wall[k]; c->tri = w->wc_tri[k];
                memcpy(c->h, h, 3 * sizeof(double));
            }
        }
        for (size_t k = 0; k < w->nwpend; ++k) {
            int p = have_map ? idmap_get(&im, w->wpend[k].id) : -1;
            if (p < 0) continue;
            dem_wcarry *c = &wcar[nwcar++];
            c->p = p; c->wall = w->wpend[k].wall; c->tri = w->wpend[k].tri;
            memcpy(c->h, w->wpend[k].h, 3 * sizeof(double));
        }
        w->nwpend = 0;
        qsort(wcar, nwcar, sizeof *wcar, cmp_dem_wcarry);
    }
    free(old2new);
    if (have_map) { free(im.key); free(im.val); }
    out->pairs = cs2; out->walls = wcar; out->nwalls = nwcar;
    return DEM_OK;
}
