/*---------------------------------------------------------------------------*\
  demFoam DEM core - particle packing for domain decomposition: one particle
  (with its contact history) or a ghost into a buffer and back.
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/
#include "dem_private.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

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

/* the header of particle index with npair pair and nwall wall contacts */
static void fill_head(const dem_world *w, size_t index, uint32_t npair, uint32_t nwall, pack_head *hd)
{
    memset(hd, 0, sizeof *hd);
    hd->magic = PACK_MAGIC; hd->npair = npair; hd->nwall = nwall;
    hd->id = w->id[index];
    for (int c = 0; c < 3; ++c) {
        hd->xvwft[c] = w->x[3 * index + c]; hd->xvwft[3 + c] = w->v[3 * index + c];
        hd->xvwft[6 + c] = w->w[3 * index + c]; hd->xvwft[9 + c] = w->f[3 * index + c];
        hd->xvwft[12 + c] = w->t[3 * index + c];
    }
    hd->rad = w->rad[index]; hd->mass = w->mass[index]; hd->rho = w->rho[index]; hd->mat = w->mat_of[index];
    if (w->have_ext) {
        hd->flags = 1;
        for (int c = 0; c < 3; ++c) {
            hd->ext[c] = w->fext[3 * index + c]; hd->ext[3 + c] = w->text[3 * index + c];
            hd->ext[7 + c] = w->uf[3 * index + c]; hd->ext[10 + c] = w->J[3 * index + c];
        }
        hd->ext[6] = w->K[index];
        hd->ext[13] = w->Ma[index];
    }
}


/* The m particles idx[] one after the other, each as a single pack would
 * write it; with hist their contacts come from one pass over the neighbour
 * list for all m (O(list + m), not O(m x list)): a pair (row r, partner j)
 * goes to r's record as seen from r and to j's with the sign flipped, in
 * list order, as the one-particle pack orders it.  buf NULL: *bytes and
 * sizes[] only (sizes may be NULL). */
static dem_status pack_many(const dem_world *w, const size_t *idx, size_t m, void *buf, size_t *bytes,
                            size_t *sizes, int hist, const char *fn)
{
    DEM_NEED(w, bytes, fn);
    if (m) DEM_NEED(w, idx, fn);
    const size_t ntot = w->n + w->ng;
    for (size_t q = 0; q < m; ++q)
        if (idx[q] >= ntot)
            return DEM_FAIL(w, DEM_ERR_RANGE, "%s: index %zu (entry %zu of %zu); allowed below %zu (owned + ghost "
                            "particles)", fn, idx[q], q, m, ntot);
    const int lists = hist && w->nb_off && w->nrows;
    dem_status st = DEM_OK;
    int *inv = NULL, *slot = NULL;
    /* one particle (pack_particle, and pack_ghost once per ghost sent):
       counts and offsets on the stack, no allocation */
    uint32_t cnt1[2] = {0, 0};
    size_t off1[2];
    const int heap = m > 1;
    uint32_t *npair = heap ? calloc(2 * m, sizeof *npair) : cnt1, *nwall = npair ? npair + m : NULL;
    size_t *off = heap ? malloc((m + 1) * sizeof *off) : off1;
    char *seen = heap ? calloc(ntot, 1) : NULL;
    if (!npair || !off || (heap && !seen)) { st = DEM_FAIL(w, DEM_ERR_NOMEM, "%s: %zu particles", fn, m); goto out; }
    for (size_t q = 0; q < m && seen; ++q) {
        if (seen[idx[q]]) {
            st = DEM_FAIL(w, DEM_ERR_ARG, "%s: index %zu given twice (index[%zu]); each particle once", fn, idx[q], q);
            goto out;
        }
        seen[idx[q]] = 1;
    }
    if (lists) {
        inv = row_owner(w);
        slot = malloc(w->nrows * sizeof *slot);
        if ((!w->list_valid && !inv) || !slot) { st = DEM_FAIL(w, DEM_ERR_NOMEM, "%s: row map", fn); goto out; }
        for (size_t r = 0; r < w->nrows; ++r) slot[r] = -1;
        for (size_t q = 0; q < m; ++q) {
            int row = w->list_index[idx[q]];
            if (row >= 0 && (size_t)row < w->nrows) slot[row] = (int)q;
        }
    }
#define OWNER(r) (inv ? inv[(r)] : (int)(r))
    /* pass 0 counts, pass 1 writes */
    for (int pass = 0; pass < 2; ++pass) {
        if (pass == 1) {
            off[0] = 0;
            for (size_t q = 0; q < m; ++q)
                off[q + 1] = off[q] + sizeof(pack_head) + npair[q] * sizeof(pack_pair) + nwall[q] * sizeof(pack_wall);
            if (sizes) for (size_t q = 0; q < m; ++q) sizes[q] = off[q + 1] - off[q];
            if (!buf) { *bytes = off[m]; goto out; }
            if (*bytes < off[m]) {
                st = DEM_FAIL(w, DEM_ERR_RANGE, "%s: *size = %zu bytes; need %zu", fn, *bytes, off[m]);
                goto out;
            }
            *bytes = off[m];
            for (size_t q = 0; q < m; ++q) {
                pack_head hd;
                fill_head(w, idx[q], npair[q], nwall[q], &hd);
                memcpy((char *)buf + off[q], &hd, sizeof hd);
                npair[q] = nwall[q] = 0; /* cursors from here */
            }
        }
        if (!lists) continue;
        for (size_t r = 0; r < w->nrows; ++r) {
            const int rowPacked = slot[r] >= 0;
            for (int k = w->nb_off[r]; k < w->nb_off[r + 1]; ++k) {
                /* the partner's slot before the history: most pairs have
                   neither side packed, and nb_j is a sixth of nb_h's bytes */
                const int j = w->nb_j[k];
                if (!rowPacked && slot[j] < 0) continue;
                const double *h = w->nb_h + 3 * (size_t)k;
                if (!dem_history_nonzero(h)) continue;
                /* as seen from r (partner j), then as seen from j (partner r) */
                for (int side = 0; side < 2; ++side) {
                    const int q = side ? slot[j] : slot[r], po = OWNER(side ? (int)r : j);
                    if (q < 0 || po < 0) continue;
                    if (pass == 1) {
                        pack_pair pp;
                        pp.partner = w->id[po];
                        for (int c = 0; c < 3; ++c) pp.h[c] = side ? -h[c] : h[c];
                        memcpy((char *)buf + off[q] + sizeof(pack_head) + npair[q] * sizeof pp, &pp, sizeof pp);
                    }
                    npair[q]++;
                }
            }
        }
        for (size_t q = 0; q < m && w->wc_off; ++q) {
            const int row = w->list_index[idx[q]];
            if (row < 0 || (size_t)row >= w->nrows) continue;
            char *wout = pass ? (char *)buf + off[q] + sizeof(pack_head) + npair[q] * sizeof(pack_pair) : NULL;
            for (int k = w->wc_off[row]; k < w->wc_off[row + 1]; ++k) {
                const double *h = w->wc_h + 3 * (size_t)k;
                if (!dem_history_nonzero(h)) continue;
                if (wout) {
                    pack_wall pw;
                    pw.wall = w->wc_wall[k]; pw.tri = w->wc_tri[k];
                    memcpy(pw.h, h, sizeof pw.h);
                    memcpy(wout + nwall[q] * sizeof pw, &pw, sizeof pw);
                }
                nwall[q]++;
            }
        }
    }
#undef OWNER
out:
    free(seen);
    if (heap) { free(off); free(npair); }
    free(slot);
    free(inv);
    return st;
}

dem_status dem_world_pack_particles(const dem_world *w, const size_t *index, size_t m, void *buf, size_t *bytes,
                                    size_t *sizes)
{
    if (!w) return DEM_ERR_ARG;
    return pack_many(w, index, m, buf, bytes, sizes, 1, "pack_particles");
}

dem_status dem_world_pack_particle(const dem_world *w, size_t index, void *buf, size_t *size)
{
    if (!w) return DEM_ERR_ARG;
    return pack_many(w, &index, 1, buf, size, NULL, 1, "pack_particle");
}

dem_status dem_world_pack_ghost(const dem_world *w, size_t index, void *buf, size_t *size)
{
    if (!w) return DEM_ERR_ARG;
    return pack_many(w, &index, 1, buf, size, NULL, 0, "pack_ghost");
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
        dem_tags_reset(w, i, 1); /* not packed (dem.h) */
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
