/*---------------------------------------------------------------------------*\
  demFoam DEM core - private definitions shared by the source files of
  src/dem.  Not installed; the OpenFOAM side only sees include/dem.h.

  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/
#ifndef DEM_PRIVATE_H
#define DEM_PRIVATE_H

#include "dem.h"
#include <stdint.h>
#include <stddef.h>

#define DEM_PI 3.14159265358979323846

/* Phase timers of dem_world_step (dem_world_phase_times): compiled in with
 * -DDEM_PROFILE only; otherwise no code at all.  C11 timespec_get. */
enum { DEM_PROF_INTEGRATE, DEM_PROF_NEIGHBOUR, DEM_PROF_PAIRS, DEM_PROF_WALLS };
#ifdef DEM_PROFILE
#include <time.h>
static inline double dem_prof_now(void)
{
    struct timespec t;
    timespec_get(&t, TIME_UTC);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}
#define DEM_PROF_START(v) const double v = dem_prof_now()
#define DEM_PROF_ADD(w, k, v) ((w)->prof[k] += dem_prof_now() - (v))
#else
#define DEM_PROF_START(v) ((void)0)
#define DEM_PROF_ADD(w, k, v) ((void)0)
#endif

/*--- error helpers ---------------------------------------------------------*/
dem_status dem_fail_(const dem_world *w, dem_status code, const char *file, int line,
                     const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 5, 6)))
#endif
    ;
#define DEM_FAIL(w, code, ...) dem_fail_((w), (code), __FILE__, __LINE__, __VA_ARGS__)
/* The text of w's last error message after "file:line: status: ". */
const char *dem_error_detail(const dem_world *w);
/* A required pointer argument: DEM_ERR_ARG naming the function and argument. */
#define DEM_NEED(w, ptr, fn) do { if (!(ptr)) return DEM_FAIL((w), DEM_ERR_ARG, \
    "%s: %s is NULL; a valid pointer is required", (fn), #ptr); } while (0)
/* Particle storage uses int indices (neighbour list, cells): owned + ghost
 * particles of a world are limited to this. */
#define DEM_MAX_PARTICLES 2147483647
void dem_log_(const dem_world *w, dem_log_level lvl, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/*--- materials -------------------------------------------------------------*/
/* Parameters of one material pair, computed once (dem_pairs_update) so that
 * the pair loop does one table look-up and no law dispatch.              */
typedef struct {
    /* Hertz-Mindlin [Z] Table 2 */
    double estar;        /* E* */
    double cn, ct;       /* dimensionless damping */
    double mindlin;      /* (2 - nu) / (2 (1 - nu)): delta_t,max = mu * mindlin * delta_n */
    /* derived constants of the Hertz-Mindlin kernel (no divisions in the loop) */
    double k43;          /* (4/3) E* */
    double cn8;          /* c_n sqrt(8 E*) */
    double mumind;       /* mu * mindlin */
    double imumind;      /* 1 / (mu mindlin), 0 if mu = 0 */
    double k43_mind;     /* (4/3) E* / mindlin = mu |f_cn| / (delta_t,max sqrt(R* delta)) */
    double ct8;          /* c_t sqrt(8 E* / mindlin) */
    /* spring-dashpot [S] */
    double kn, kt;
    double eta_fixed;    /* >= 0: normal damping [N s/m] used as given */
    double beta;         /* eta_fixed < 0: eta_n = beta sqrt(k_n m_eff) (restitution given) */
    /* common */
    double mu, mu_r, e;
    double nu;
    double g8;           /* hertzMindlinNoSlip: 8 G*, 1/G* = (2-nu_i)/G_i + (2-nu_j)/G_j */
    double pred;         /* 1: damping at the predicted end-of-step velocity (dem_config.damping_predicted) */
} dem_pair;

typedef struct { int a, b; dem_material m; } dem_pair_override;

typedef struct {
    double x0[3];        /* point at t = t0 */
    double n[3];         /* unit normal */
    double vel[3];
    double t0;           /* time of x0 */
    int material, wall;
} dem_plane;

typedef struct {
    size_t nv, ntri;
    double *v0;          /* vertices at time t0 */
    int *tri;            /* 3 per triangle */
    double *nrm;         /* unit normal per triangle */
    double vel[3];
    double t0;
    int material, wall;
} dem_mesh;

typedef struct {
    size_t nv;
    double *poly;        /* 3*nv */
    double n[3];         /* unit normal */
    double area;
    dem_rate_kind kind;
    double rate, t_start, t_end;
    dem_particle_template t;
    double tw_d[64], tw_rho[64]; /* copies of discrete tables (values, weights) */
    size_t nd_d, nd_rho;
    double due;          /* particles (number) or kg (mass) owed */
    double next_d, next_rho; int have_next;
    int64_t inserted;
    int warned;          /* blocked warning given */
} dem_inlet;

typedef struct {
    int kind;            /* 0 plane, 1 box, 2 none */
    double a[3], b[3];   /* plane: point, normal; box: lo, hi */
    int64_t count;
    double mass;
} dem_outlet;

/* A contact carried across a list rebuild: rows are new indices, h is
 * oriented for (row a, partner b). */
typedef struct { int a, b; double h[3]; } dem_carry;
/* Contact history waiting for its particles by id (unpack). */
typedef struct { int64_t ia, ib; double h[3]; } dem_pending;
typedef struct { int64_t id; int wall, tri; double h[3]; } dem_wpending;

struct dem_world {
    char err[640];
    dem_log_fn log; void *log_user;
    dem_config cfg;

    /* materials */
    int nmat, capmat;
    dem_material *mat;       /* as given by the user */
    double *mat_e, *mat_c;   /* derived restitution / damping per material (cache) */
    int nmat_derived;        /* materials [0, nmat_derived) have mat_e/mat_c */
    dem_pair_override *ovr;  /* dem_world_set_pair */
    int novr;
    int derived_law;
    dem_pair *pair;          /* nmat*nmat, valid when !pairs_dirty */
    int pairs_dirty;

    /* particles (SoA); capacity cap, n owned + ng ghosts */
    size_t n, ng, cap;
    int64_t *id;
    double *x, *v, *w;       /* 3 per particle */
    double *f, *t;           /* contact force and torque of the last evaluation */
    double *rad, *mass, *rho;
    int *mat_of;
    float *x0;               /* positions at the last list build */
    int *list_index;         /* row of the particle in the current list (-1: none) */
    /* coupling arrays, allocated on first dem_world_arrays() call */
    int have_ext;
    double *fext, *text, *K, *uf, *J;
    int64_t *tag[DEM_N_TAGS]; /* the caller's per-particle values (dem.h DEM_N_TAGS) */
    double *Ma;              /* added (virtual) mass [kg], see dem.h added_mass */
    int64_t next_id;

    /* neighbour grid */
    int nc[3]; double cs[3]; double cutoff, skin, amax;
    double glo[3];           /* grid origin: the particles' box on open axes, the domain on periodic ones */
    double plo[3], phi[3];   /* the box of the particle centres at the build (triangle binning) */
    size_t ncells, capcells;
    int *cell_start;         /* ncells + 1 */
    int *cell_item;          /* particle per slot */
    int *cell_of;            /* per particle */
    int *perm; int *old2new;
    double *tmp;             /* 3 * cap doubles */

    /* half Verlet list in CSR form, history beside the entries */
    int list_valid;          /* 0: rebuild before the next force evaluation */
    size_t nrows;            /* rows of the current list */
    size_t caprows;
    int *nb_off;             /* nrows + 1 */
    size_t nnb, capnb;
    int *nb_j;
    unsigned char *nb_s;     /* periodic image code 0..26 */
    double *nb_h;            /* 3 per entry: tangential history */
    double shift[27][3];
    /* wall candidate list: CSR by particle row */
    int *wc_off; size_t nwc, capwc;
    int *wc_wall;            /* wall id */
    int *wc_tri;             /* triangle (mesh) or -1 (plane) */
    double *wc_h;            /* 3 per entry */
    double t_build;
    int64_t nbuilds;
    double prof[4];          /* seconds per step phase (DEM_PROFILE builds): dem_phase_times order */

    /* carry buffers (reused) */
    dem_carry *carry; size_t ncarry, capcarry;
    int *carry_off; size_t capcarry_off;
    dem_pending *pend; size_t npend, cappend;
    dem_wpending *wpend; size_t nwpend, capwpend;

    /* walls: ids 0..nplanes+nmeshes-1 in creation order */
    int nwalls;
    int *wall_kind;          /* 0 plane, 1 mesh */
    int *wall_index;
    dem_plane *planes; int nplanes;
    dem_mesh *meshes; int nmeshes;
    /* triangle bins: global triangle list over meshes */
    size_t ntri_all;
    int *tri_mesh, *tri_local;
    int *tcell_start; int *tcell_item; size_t ntcell_item, captcell_item;

    /* time */
    double time;
    int64_t step;

    /* rng: xoshiro256** */
    uint64_t rng[4];

    /* inlets / outlets / records */
    dem_inlet *inlets; int ninlets;
    dem_outlet *outlets; int noutlets;
    dem_removed_record *rec; size_t nrec, caprec;
    int64_t inserted, removed;
    int64_t reorders;

    /* keep filter of the set-up (dem_world_set_keep_filter): placed but not
       stored particles as x, y, z, r (fill.c) */
    dem_inside_fn keep; void *keep_user;
    /* optional box outside which keep refuses everything (lattice fills skip it) */
    int keep_box_set; double keep_lo[3], keep_hi[3];
    double *shadow; size_t nshadow, capshadow;

    /* last force evaluation */
    double max_overlap;
    size_t pair_contacts, wall_contacts;
    int forces_valid;
    /* split step (dem_world_step_drift / dem_world_step_forces) */
    int drift_pending;       /* 1 between a drift and its force half */
    double drift_d2max;      /* largest squared displacement since the list build, at the drift */
    double hdt;              /* history increment of the current force evaluation */
    void *scratch;           /* contact buffers of the phased pair loops (contactKernel.h) */
    size_t capscratch;       /* entries */
    /* per-contact record (dem_world_record_contacts, dem_world_contacts) */
    int crec_on;             /* the user asked for recording */
    int crec_now;            /* the current evaluation records (buffer large enough) */
    int crec_valid;          /* the last evaluation was recorded */
    dem_contact *crec; size_t ncrec, capcrec;
};

/*--- function multiversioning ----------------------------------------------*/
/* Hot loops (Hertz-Mindlin pair loop, kick/drift) are compiled for each of
 * DEM_CLONES and the CPU picks one at load time (ifunc, GCC on x86-64 ELF);
 * every clone does the same IEEE operations (no FMA under -std=c11), so the
 * results are bit-identical.  -DDEM_NO_MULTIVERSION: generic x86-64 only;
 * -DDEM_CLONES='"avx2","default"' e.g. restricts the set. */
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__ELF__) && \
    !defined(DEM_NO_MULTIVERSION)
#ifndef DEM_CLONES
#define DEM_CLONES "avx512f", "avx2", "default"
#endif
#define DEM_MULTIVERSION __attribute__((target_clones(DEM_CLONES)))
#else
#define DEM_MULTIVERSION
#endif

/*--- internal functions ----------------------------------------------------*/
dem_status dem_reserve(dem_world *w, size_t cap);
dem_status dem_pairs_update(dem_world *w);
dem_status dem_ext_alloc(dem_world *w);
dem_status dem_list_build(dem_world *w);
dem_status dem_scratch_ensure(dem_world *w);
#define DEM_SCRATCH_ENTRY 368 /* bytes per contact of the phased loop buffer */
#define DEM_SCRATCH_EXTRA 80  /* entries beyond the longest row (block of the phased loop) */
void       dem_forces(dem_world *w, double hist_dt);
dem_status dem_append_particle(dem_world *w, const dem_particle *p);
/* A particle the keep filter refuses: its id taken, counted as inserted,
   its centre and radius in the shadow list (fill.c) */
dem_status dem_shadow_particle(dem_world *w, const dem_particle *p);
dem_status dem_particle_check(dem_world *w, const dem_particle *p, const char *what);
dem_status dem_room_for(dem_world *w, size_t n, const char *what);
int        dem_mass_ok(double radius, double density);
int        dem_inertia_ok(double mass, double radius);
dem_status dem_inlet_check(dem_world *w, const dem_inlet *in, const char *what);
dem_status dem_template_check(dem_world *w, const dem_particle_template *t, double *dmax, const char *fn);
dem_status dem_config_check(dem_world *w, const dem_config *c);
/* Whether m is rigid (DEM_RIGID) under the law */
int dem_material_rigid(const dem_material *m, int law);
dem_status dem_material_check(dem_world *w, const dem_material *m, const char *what, int law_check);
void       dem_remove_index(dem_world *w, size_t i);
dem_status dem_inlets_run(dem_world *w);
dem_status dem_outlets_run(dem_world *w);
void       dem_wall_position(const dem_world *w, int wall, double time, double off[3]);
int        dem_closest_on_triangle(const double *p, const double *a, const double *b,
                                   const double *c, double q[3]);
dem_status dem_contact_time_internal(const dem_world *w, double v_imp, int rayleigh, int damped, double *tc);
double     dem_hertz_time(double meff, double rstar, double estar, double v);
dem_status dem_remove_booked(dem_world *w, size_t i, int outlet);
/* Checks of a cylinder's base, axis, radius and length (fn names the
   caller) and its unit axis ax with two unit vectors e1, e2 across it (fill.c) */
dem_status dem_cylinder_frame(dem_world *w, const char *fn, const double base[3], const double axis[3],
                              double radius, double length, double ax[3], double e1[3], double e2[3]);
dem_status dem_history_to_pending(dem_world *w, ptrdiff_t only, const unsigned char *gone, const char *fn);
/* Checks of a restored state (stateCheck.c): 1 (message in err) if unusable */
int        dem_state_check(dem_world *w, dem_world *err, const char *path);

/* restitution <-> damping mappings (restitution.c) */
double dem_hm_restitution(double cn);          /* e(c_n), Hertz-Mindlin of [Z] */
double dem_hm_damping(double e);               /* inverse */
double dem_hm_time_ratio(double cn);           /* damped / elastic contact duration, Hertz-Mindlin */
double dem_lsd_beta(double e);                 /* eta = beta sqrt(k m) */

/* rng */
uint64_t dem_rng_next(dem_world *w);
double   dem_rng_uniform(dem_world *w);        /* [0,1) */
void     dem_rng_seed(dem_world *w, uint64_t seed);
double   dem_dist_draw(dem_world *w, const dem_distribution *d);

static inline double dem_dot(const double *a, const double *b)
{ return a[0]*b[0] + a[1]*b[1] + a[2]*b[2]; }
static inline void dem_cross(const double *a, const double *b, double *c)
{ c[0] = a[1]*b[2] - a[2]*b[1]; c[1] = a[2]*b[0] - a[0]*b[2]; c[2] = a[0]*b[1] - a[1]*b[0]; }

/* The caller's tags of particles [first, first + n) to -1 (a new particle,
 * an unpacked or a restored one: dem.h DEM_N_TAGS); coupling arrays only. */
static inline void dem_tags_reset(dem_world *w, size_t first, size_t n)
{
    for (int k = 0; k < DEM_N_TAGS; ++k)
        for (size_t i = first; i < first + n; ++i) w->tag[k][i] = -1;
}

/* Whether a stored tangential history (3 doubles) holds a contact: zero
 * means none (contact.c clears it when a pair separates). */
static inline int dem_history_nonzero(const double *h) { return h[0] != 0 || h[1] != 0 || h[2] != 0; }

#endif
