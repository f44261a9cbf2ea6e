/*---------------------------------------------------------------------------*\
  demFoam - the C11 discrete-element core.  Public API (the only header the
  OpenFOAM side includes).
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)

  Conventions
  - Opaque handle dem_world; create/destroy: dem_world_create(&w),
    dem_world_destroy(&w) (destroy NULLs the pointer).
  - Every call returns a dem_status.  On error the handle keeps a message
    with the offending value and the source file/line
    (dem_world_last_error).  The library never prints, exits or aborts;
    diagnostics go through a logger callback the caller installs.
  - SI units throughout.  Vectors are stored xyzxyz... (3 doubles per
    particle) in structure-of-arrays form.
  - Pointers returned by dem_world_arrays() stay valid until the next
    resizing call: add/remove particles, insertion, dem_world_step() when
    inlets or outlets are active, dem_world_restore(), unpack.
  - Particles have a stable 64-bit global id separate from their storage
    index; removal swaps with the last owned particle.  Owned particles
    occupy indices [0, n_owned), ghost copies [n_owned, n_owned + n_ghost)
    in the order they were unpacked (decomposition support below).
\*---------------------------------------------------------------------------*/
#ifndef DEM_H
#define DEM_H

#include <math.h>   /* INFINITY (DEM_RIGID) */
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/*--- status codes (one X-macro list gives the enum and the messages) -------*/
#define DEM_STATUS_LIST(X)                                                   \
    X(DEM_OK,            "success")                                          \
    X(DEM_ERR_NOMEM,     "out of memory")                                    \
    X(DEM_ERR_ARG,       "invalid argument")                                 \
    X(DEM_ERR_RANGE,     "value out of the allowed range")                   \
    X(DEM_ERR_TIMESTEP,  "time step above the safe fraction of the contact time") \
    X(DEM_ERR_NAN,       "non-finite value in the particle state")           \
    X(DEM_ERR_OVERLAP,   "runaway overlap between particles or with a wall") \
    X(DEM_ERR_FULL,      "could not place the requested particles")          \
    X(DEM_ERR_IO,        "input/output error")                               \
    X(DEM_ERR_FORMAT,    "unrecognised or incompatible state data")          \
    X(DEM_ERR_STATE,     "call not allowed in the current state")            \
    X(DEM_ERR_NOTFOUND,  "no such item")

typedef enum {
#define DEM_X_ENUM(name, text) name,
    DEM_STATUS_LIST(DEM_X_ENUM)
#undef DEM_X_ENUM
    DEM_STATUS_COUNT
} dem_status;

/** Static text for a status code (never NULL). */
const char *dem_status_string(dem_status s);

typedef struct dem_world dem_world;

/*--- logging ----------------------------------------------------------------*/
typedef enum { DEM_LOG_DEBUG, DEM_LOG_INFO, DEM_LOG_WARNING } dem_log_level;
typedef void (*dem_log_fn)(dem_log_level level, const char *message, void *user);

/*--- world ------------------------------------------------------------------*/
dem_status  dem_world_create(dem_world **w);
void        dem_world_destroy(dem_world **w);
/** Text of the last error on this handle, with file:line; "" if none. */
const char *dem_world_last_error(const dem_world *w);
void        dem_world_set_logger(dem_world *w, dem_log_fn fn, void *user);

typedef enum {
    DEM_CONTACT_HERTZ_MINDLIN = 0, /* [Z] Table 2: Hertz + Mindlin-Deresiewicz (delta_t,max), rolling friction */
    DEM_CONTACT_LINEAR_SPRING_DASHPOT, /* [S] 17-26, f = 1 */
    DEM_CONTACT_HERTZ_SPRING_DASHPOT,  /* [S] 17-26, f = sqrt(delta/d) */
    DEM_CONTACT_HERTZ_MINDLIN_NO_SLIP, /* Hertz normal as hertzMindlin; incremental Mindlin no-slip
                                          tangential spring k_t = 8 G* sqrt(R* delta), Coulomb limit */
    DEM_CONTACT_LAW_COUNT
} dem_contact_law;

/** Name of a contact law ("hertzMindlin", "linearSpringDashpot",
 *  "hertzSpringDashpot"); NULL for an invalid value. */
const char *dem_contact_law_name(dem_contact_law law);
/** Look a law up by the name above; DEM_ERR_NOTFOUND if none matches. */
dem_status  dem_contact_law_from_name(const char *name, dem_contact_law *law);

typedef struct {
    dem_contact_law contact_law;
    double dt;               /* time step [s], > 0 */
    double gravity[3];       /* [m/s2] */
    double domain_lo[3];     /* bounding box of the neighbour grid [m]; along */
    double domain_hi[3];     /* a periodic axis it is the period */
    int    periodic[3];      /* 1: periodic along that axis */
    double skin;             /* Verlet skin [m]; <= 0: 0.2 x largest diameter */
    double max_dt_fraction;  /* dt must be <= this x the smallest contact time; default 0.2 */
    double max_overlap_ratio;/* stop with DEM_ERR_OVERLAP above this overlap/diameter; default 0.1 */
    uint64_t seed;           /* random seed for insertion */
    int    spatial_sort;     /* added: 1 (default) re-sorts owned particles by cell at each
                                neighbour-list build (storage order changes; use id) */
    int    damping_predicted;/* added: 1: the normal damping force of every law uses the relative
                                normal velocity at the end of the step, predicted from the pair's
                                own force (restitution within 0.5 % of the requested e at
                                dt = t_c/50; docs/theory.md, "Damping in the time step");
                                0 (default): the half-step velocity of velocity Verlet (first
                                order in dt; e a few % low at t_c/50 for e < 0.3) */
    double impact_speed;     /* added: Hertz laws' time-step check.  0 (default): dt is checked
                                against min(Rayleigh time, Hertz time at 2 max|v| + max wall speed);
                                > 0: against the Hertz time at max(impact_speed, 2 max|v| + wall
                                speed) only (no Rayleigh time) */
} dem_config;

/** Fill c with defaults: Hertz-Mindlin, dt 1e-6, gravity (0,0,-9.81), unit box, non-periodic. */
void       dem_config_default(dem_config *c);
/** Apply a configuration (checked; may be called again before particles exist). */
dem_status dem_world_configure(dem_world *w, const dem_config *c);
/** Apply only the settings of c that may change while particles exist
    (dt, gravity, max_dt_fraction, max_overlap_ratio, spatial_sort,
    impact_speed; checked as by dem_world_configure); the rest of the
    world's configuration stays (e.g. after dem_world_restore). */
dem_status dem_world_configure_run(dem_world *w, const dem_config *c);
/** The world's configuration as in use (e.g. the periodic box of a restored
    state), copied into *c. */
dem_status dem_world_get_config(const dem_world *w, dem_config *c);

/*--- materials ------------------------------------------------------------*/
/* Pairwise combination: 1/E* = (1-nu_i^2)/E_i + (1-nu_j^2)/E_j; friction,
 * rolling friction and restitution: the smaller of the two (documented in
 * docs/); linear stiffness: series combination (k_i k_j / (k_i + k_j)) for
 * unlike materials, the value itself for like ones.
 * Damping: give restitution in (0,1] and damping < 0, or damping >= 0 and
 * restitution < 0; the other is derived (dem_world_material_get). */
/* A rigid material (walls only): youngs_modulus = DEM_RIGID (Hertz-Mindlin)
 * or stiffness_n = DEM_RIGID (spring-dashpot laws).  A pair of a particle
 * material p with it takes E* = E_p/(1 - nu_p^2), nu_p, and k_n, k_t of p
 * (the rigid body does not deform); friction, rolling friction and
 * restitution combine as for any pair (the smaller).  Particles of a rigid
 * material are refused. */
#define DEM_RIGID INFINITY

typedef struct {
    double youngs_modulus;   /* E [Pa] (Hertz laws); DEM_RIGID: rigid */
    double poisson_ratio;    /* nu in [0, 0.5) */
    double stiffness_n;      /* k_n [N/m] (linear law); DEM_RIGID: rigid */
    double stiffness_t;      /* k_t [N/m] (linear law); <= 0: 2/7 k_n */
    double friction;         /* mu_s >= 0 */
    double rolling_friction; /* mu_r >= 0, a length [m] */
    double restitution;      /* e_n in (0,1]; < 0: derive from damping */
    double damping;          /* Hertz-Mindlin: dimensionless c_n (= c_t);
                                spring-dashpot: normal damping [N s/m];
                                < 0: derive from restitution */
} dem_material;

dem_status dem_world_add_material(dem_world *w, const dem_material *m, int *material_id);
/** Added: override the combined parameters of one material pair (either
 *  order; e.g. a particle material with a wall material): that pair behaves
 *  as two bodies of material m (like-material rules: k_n, k_t, friction,
 *  rolling friction, restitution/damping as given, E* = E/(2(1 - nu^2))). */
dem_status dem_world_set_pair(dem_world *w, int material_a, int material_b, const dem_material *m);
/** The material as used, with the derived restitution or damping filled in. */
dem_status dem_world_material_get(const dem_world *w, int material_id, dem_material *m);

/*--- particles --------------------------------------------------------------*/
typedef struct {
    int64_t id;              /* < 0: assigned by the world (next free id) */
    double  x[3], v[3], omega[3];
    double  radius;          /* > 0 */
    double  density;         /* > 0 */
    int     material;
} dem_particle;

dem_status dem_world_add_particles(dem_world *w, size_t n, const dem_particle *p);
/** Remove owned particle at storage index i (swap with last).  outlet >= 0
 *  books it on that outlet (count, mass, record) and in dem_stats.removed;
 *  -1 books nothing anywhere (e.g. migration to another rank, or a particle
 *  the caller counts itself) and keeps the particle's pair contact history
 *  by id until the next neighbour-list build, so that owned partners get it
 *  back if the particle returns as a ghost (decomposition support below). */
dem_status dem_world_remove_particle(dem_world *w, size_t index, int outlet);
/** Added: remove every owned particle i with keep[i] == 0 (keep: one entry
 *  per owned particle), without an outlet, as dem_world_remove_particle(w,
 *  i, -1) for each from the highest index down: the particles that stay end
 *  in the same order, and the pair history between one that goes and one
 *  that stays goes to the pending store (pairs of two that go are dropped).
 *  One pass over the neighbour list: O(n + list), where the repeated calls
 *  cost O(n + list) each (decomposed set-up from a whole state). keep may
 *  be NULL only when the world holds no particles (a processor with none). */
dem_status dem_world_remove_unkept(dem_world *w, const unsigned char *keep);
/** Added: remove the m owned particles index[0..m-1] (each once, any order),
 *  particle index[q] booked on outlet[q] (-1: none, as in
 *  dem_world_remove_particle), from the highest index down: the particles
 *  that stay end in the same order as after the repeated calls, and the
 *  pair history between one removed without an outlet and one that stays
 *  goes to the pending store.  One pass over the neighbour list for all m
 *  (the repeated calls cost one each): the migration and outlets of a
 *  fluid step.  outlet may be NULL (none for all). */
dem_status dem_world_remove_particles(dem_world *w, const size_t *index, const int *outlet, size_t m);

/** Added: the caller's per-particle values (dem_arrays.tag): the core never
 *  reads them; a particle keeps its tags through re-sorts, removals' swaps
 *  and ghost shifts; insertion, unpack and restore set them to -1 (they are
 *  neither packed nor saved).  E.g. the host cell of the fluid mesh, looked
 *  up by storage index instead of by a table over all ids. */
#define DEM_N_TAGS 3

typedef struct {
    size_t n_owned, n_ghost;
    const int64_t *id;
    double *x, *v, *omega;          /* 3 per particle; writable */
    const double *radius, *mass, *density;
    const int *material;
    double *force_ext, *torque_ext; /* 3 per particle: added every step until changed (fluid forces) */
    double *drag_coeff;             /* K_i [kg/s]: drag K_i (u_fluid,i - v_i), integrated implicitly */
    double *fluid_velocity;         /* u_fluid,i, 3 per particle */
    double *drag_impulse;           /* 3 per particle: sum over steps of K_i (u_fluid,i - v_i) dt
                                       with the implicit end-of-step velocity; reset by the caller */
    double *added_mass;             /* added: m_a,i [kg] >= 0 (default 0), e.g. virtual mass
                                       C_vm rho_f V_p: translational inertia m + m_a, gravity m g
                                       (the particle feels -m_a dv/dt, implicitly); kept until changed */
    int64_t *tag[DEM_N_TAGS];       /* added: 1 per particle each, the caller's (see DEM_N_TAGS) */
} dem_arrays;

/** Direct access to the particle arrays (see validity rule at the top). */
dem_status dem_world_arrays(dem_world *w, dem_arrays *a);
size_t     dem_world_count(const dem_world *w);     /* owned particles */
double     dem_world_time(const dem_world *w);
/** Added: set the clock (e.g. to the fluid solver's time); walls keep their
 *  current positions, inlets' start/end times are read on this clock. */
dem_status dem_world_set_time(dem_world *w, double t);
int64_t    dem_world_step_count(const dem_world *w);
/** Added: incremented whenever the storage order of particles changes (spatial
 *  sort during dem_world_step, insertion, removal); cache index-keyed data
 *  only while it is unchanged. */
int64_t    dem_world_reorder_count(const dem_world *w);

/** Advance nsteps time steps (velocity Verlet; drag semi-implicit).
 *  The contact kernel is built with -fno-trapping-math and written so that
 *  it raises no division-by-zero/invalid/overflow flags (tested with traps
 *  on, tests/dem/test_fpe.c); a caller running with traps may still prefer
 *  to hold them around the call (feholdexcept) as defence in depth. */
dem_status dem_world_step(dem_world *w, int64_t nsteps);
/** Added: one step in two halves, for a decomposed world whose ghosts must
 *  be refreshed between the drift and the force evaluation.
 *  dem_world_step_drift: the start checks of dem_world_step (DEM_ERR_NAN,
 *  DEM_ERR_TIMESTEP, ...; list build and first force evaluation if needed),
 *  the start half kick and the drift of the owned particles, step and time
 *  advanced, outlets and inlets run (on an outlet/inlet error the end kick
 *  is done and the step is complete, as dem_world_step(w, 1) does).  Then
 *  the caller may migrate (dem_world_pack_particles, dem_world_remove_particle
 *  (w, i, -1), dem_world_unpack_particle(w, ..., 0)) and refresh the ghosts
 *  (dem_world_clear_ghosts, dem_world_pack_ghost, dem_world_unpack_particle
 *  (w, ..., 1)), read and write the arrays, before
 *  dem_world_step_forces: list rebuild if invalid or if the displacement
 *  since the build may exceed the skin, force evaluation, the overlap check
 *  (DEM_ERR_OVERLAP), the end half kick of the owned particles.
 *  n drift/forces pairs give bit-identical results to dem_world_step(w, n)
 *  when nothing is changed between the calls (tests/dem/test_decomp.c).
 *  Order is enforced (DEM_ERR_STATE): step_forces needs a pending drift;
 *  dem_world_step, step_drift, dem_world_configure and the save calls are
 *  refused while a drift is pending. */
dem_status dem_world_step_drift(dem_world *w);
dem_status dem_world_step_forces(dem_world *w);
/** Added: dem_world_step_drift for the second and later steps of a run of
 *  split steps (the DEM sub-steps of one fluid step): without the start
 *  checks (state, time step, contact time; an O(n) pass), which the run's
 *  first dem_world_step_drift did, as dem_world_step(w, n) does them once
 *  for its n steps.  Bit-identical to dem_world_step_drift.  When the list
 *  or the forces are not valid, or a drift is pending, it is
 *  dem_world_step_drift (full checks, or its DEM_ERR_STATE). */
dem_status dem_world_step_drift_next(dem_world *w);
/** Added: 1 if the next dem_world_step_forces would rebuild the neighbour
 *  list, else 0.  Meant between dem_world_step_drift and step_forces: the
 *  list is invalid (insertion, removal, unpack, clear_ghosts,
 *  dem_world_invalidate_list, ... since the build) or the largest
 *  displacement of the owned particles since the build, d, may exceed the
 *  skin (2 d > skin, or d + moving-wall speed x time since the build > skin).
 *  Without a pending drift: 1 if the list is invalid, else 0.  0 for NULL.
 *  Decomposed runs: see the Verlet scheme under decomposition support. */
int        dem_world_list_stale(const dem_world *w);
/** Added: 1 if the neighbour list is invalid whatever the displacements
 *  (insertion, removal, unpack, clear_ghosts, dem_world_invalidate_list,
 *  ... since the build: the owned set or the ghosts changed), else 0; 0 for
 *  NULL.  A decomposed run renews its ghost sets then (processorGhosts). */
int        dem_world_list_invalid(const dem_world *w);
/** Added: the largest displacement of the ghosts since the last neighbour-
 *  list build [m] (their positions as set by dem_world_set_ghost_states
 *  against those at the build); 0 when the list is invalid, without ghosts
 *  or for NULL.  A decomposed run rebuilds its list when it may exceed half
 *  the skin, as the core does for the owned particles (processorGhosts). */
double     dem_world_ghost_displacement(const dem_world *w);
/** Added: the largest displacement of the owned particles since the last
 *  neighbour-list build [m], as measured by the pending drift (the d of
 *  dem_world_list_stale; particles inserted by that drift's inlets are not
 *  in it).  0 without a pending drift or for NULL.  Decomposed runs bound
 *  the displacement since a partner's ghost set was chosen with it
 *  (docs/parallel.md, "Neighbour-only communication"). */
double     dem_world_drift_displacement(const dem_world *w);
/** Added: the next force evaluation (step_forces, or the start of a step)
 *  rebuilds the neighbour list (e.g. another rank needs a rebuild).  The
 *  contact history is carried over exactly as by any rebuild; the stored
 *  forces and the particles are unchanged. */
dem_status dem_world_invalidate_list(dem_world *w);
/** Added: the Verlet skin in use [m]: dem_config.skin if > 0; else (auto,
 *  0.2 x the largest diameter of the owned and ghost particles present at
 *  a build) the skin chosen at the last list build, or before any build the
 *  one a build now would choose (0 without particles).  An auto skin can
 *  change at a build and differ between ranks: give decomposed runs
 *  dem_config.skin > 0, the same on every rank. */
double     dem_world_skin(const dem_world *w);
/** The largest time step the next dem_world_step accepts now: max_dt_fraction
 *  x the contact time of its check (HUGE_VAL without particles); the state
 *  is checked first (DEM_ERR_NAN as dem_world_step). */
dem_status dem_world_max_dt(dem_world *w, double *dt_max);

/** Smallest contact time estimate over the material pairs and particle
 *  sizes present (Hertz: at the given impact speed; linear: t_c of [S]). */
dem_status dem_world_contact_time(const dem_world *w, double impact_speed, double *t_contact);
/** The same with the pairs' damping (longer): hertzMindlin scales the Hertz
 *  time by the damped/elastic duration of its scaled impact (depends on c_n
 *  only), linearSpringDashpot gives its damped half period (as
 *  dem_world_contact_time does), hertzSpringDashpot the elastic Hertz time. */
dem_status dem_world_contact_time_damped(const dem_world *w, double impact_speed, double *t_contact);

/*--- walls --------------------------------------------------------------------*/
/** Infinite plane through point with the given normal, which must point INTO
 *  the domain (towards the particles): a particle interacts when its signed
 *  distance d = (x - point).normal lies in (-a, a); the overlap is a - d.
 *  (Triangle-mesh walls are two-sided; their orientation does not matter.) */
dem_status dem_world_add_plane(dem_world *w, const double point[3], const double normal[3],
                               int material, const double velocity[3], int *wall_id);
/** Triangle mesh wall: vertices 3*nv doubles, triangles 3*ntri vertex indices.
 *  Contacts with faces, edges and vertices, counted once where triangles
 *  share an edge or vertex. */
dem_status dem_world_add_trimesh(dem_world *w, size_t nv, const double *vertices,
                                 size_t ntri, const int *triangles, int material,
                                 const double velocity[3], int *wall_id);
dem_status dem_world_set_wall_velocity(dem_world *w, int wall_id, const double velocity[3]);

/*--- insertion ----------------------------------------------------------------*/
typedef enum { DEM_DIST_FIXED, DEM_DIST_UNIFORM, DEM_DIST_NORMAL, DEM_DIST_DISCRETE } dem_dist_kind;
typedef struct {
    dem_dist_kind kind;
    double a, b;             /* fixed: a; uniform: [a, b]; normal: mean a, std dev b (truncated at +-3 b) */
    size_t n;                /* discrete: n values with weights (need not sum to 1) */
    const double *values, *weights;
} dem_distribution;

typedef struct {
    dem_distribution diameter, density;
    int    material;
    double velocity[3];
} dem_particle_template;

typedef int (*dem_inside_fn)(const double x[3], void *user);

/** Place n non-overlapping particles in the box (also inside the optional
 *  test).  DEM_ERR_FULL with *inserted < n if they do not fit. */
dem_status dem_world_fill_box(dem_world *w, const double lo[3], const double hi[3],
                              dem_inside_fn inside, void *user, size_t n,
                              const dem_particle_template *t, size_t *inserted);
dem_status dem_world_fill_cylinder(dem_world *w, const double base[3], const double axis[3],
                                   double radius, double length, size_t n,
                                   const dem_particle_template *t, size_t *inserted);

/** Keep filter for the set-up of a decomposed run (docs/parallel.md, "Initial
 *  particles and settling"): while set, a particle that add_particles or a
 *  fill places with keep(x, user) == 0 is not stored.  It still takes its
 *  id and counts as inserted, and its centre and radius are kept in a
 *  shadow list that later fills avoid, so that every draw and every id is
 *  the unfiltered one (*inserted of a fill counts it too).  NULL clears the
 *  filter and the shadow list.  Not part of the saved state. */
dem_status dem_world_set_keep_filter(dem_world *w, dem_inside_fn keep, void *user);
/** Added: a box outside which the keep filter refuses every position (NULL,
 *  NULL: none; cleared with the filter), so that a lattice fill computes
 *  only the cells near it. */
dem_status dem_world_set_keep_box(dem_world *w, const double lo[3], const double hi[3]);

/** Added: place n particles on a jittered cubic lattice filling the box
 *  (layers along z) or the cylinder (layers along its axis): cells of edge
 *  s, the largest with at least n cells inside the region; the full layers
 *  from the bottom up and, in the last, cells chosen by a hash; each
 *  particle's size, density and jitter (at most (s - d)/2 per direction: no
 *  overlaps) drawn from a stream of its own index.  Every particle is a
 *  function of (seed, first id, index): with a keep filter nothing is drawn
 *  or kept for the cells outside (no shadow list; O(N/P) per processor).
 *  The region must hold no particle placed before (DEM_ERR_RANGE naming
 *  one); DEM_ERR_FULL if n cells of the largest diameter do not fit.  The
 *  world's own random stream is left as it was. */
dem_status dem_world_fill_lattice_box(dem_world *w, const double lo[3], const double hi[3], size_t n,
                                      const dem_particle_template *t, size_t *inserted);
dem_status dem_world_fill_lattice_cylinder(dem_world *w, const double base[3], const double axis[3],
                                           double radius, double length, size_t n,
                                           const dem_particle_template *t, size_t *inserted);

/** Added: place n particles at random in the box or cylinder, block by
 *  block: the centres' region (the region less the largest radius) cut
 *  into blocks of about 64 particles and edge at least the largest
 *  diameter; each block gets the floor or ceiling of its share of n
 *  (stratified rounding) and places them by random sequential addition
 *  (up to 10 000 random positions each) from a stream
 *  of (seed, first id, block); blocks in eight colours by index parity, so
 *  a block depends on blocks at most seven away.  Every particle is a
 *  function of (seed, first id, n, region): with a keep filter and keep
 *  box a processor places only the blocks near its box (no shadow list;
 *  O(N/P) per processor) and gets the serial particles there.  The region
 *  must hold no particle placed before (DEM_ERR_RANGE naming one);
 *  DEM_ERR_FULL naming the block that could not place its share (the
 *  particles placed before it stay, as with dem_world_fill_box).  The
 *  world's own random stream is left as it was. */
dem_status dem_world_fill_blocks_box(dem_world *w, const double lo[3], const double hi[3], size_t n,
                                     const dem_particle_template *t, size_t *inserted);
dem_status dem_world_fill_blocks_cylinder(dem_world *w, const double base[3], const double axis[3],
                                          double radius, double length, size_t n,
                                          const dem_particle_template *t, size_t *inserted);

typedef enum { DEM_RATE_NUMBER, DEM_RATE_MASS } dem_rate_kind;
/** Stream insertion through a planar polygon (nv vertices, 3*nv doubles) at a
 *  rate [1/s or kg/s] between t_start and t_end, with the template velocity. */
dem_status dem_world_add_inlet(dem_world *w, size_t nv, const double *polygon,
                               dem_rate_kind kind, double rate, double t_start, double t_end,
                               const dem_particle_template *t, int *inlet_id);
/** Remove all inlets (their ids become invalid); e.g. on the processors
 *  that must not insert after a decomposed restart of a serial state. */
dem_status dem_world_clear_inlets(dem_world *w);

/*--- outlets and deletion -----------------------------------------------------*/
/** Outlet that deletes particles whose centre is beyond a plane (on the side the normal points to). */
dem_status dem_world_add_outlet_plane(dem_world *w, const double point[3], const double normal[3], int *outlet_id);
/** Outlet that deletes particles whose centre is inside a box. */
dem_status dem_world_add_outlet_box(dem_world *w, const double lo[3], const double hi[3], int *outlet_id);
/** Outlet with no geometry: particles are booked on it by dem_world_remove_particle. */
dem_status dem_world_add_outlet(dem_world *w, int *outlet_id);

typedef struct { int64_t id; double time, diameter, density; int outlet; } dem_removed_record;
dem_status dem_world_outlet_totals(const dem_world *w, int outlet_id, int64_t *count, double *mass);
/** Records of removed particles since the last clear (pointer valid until the next step or clear). */
dem_status dem_world_removed_records(const dem_world *w, const dem_removed_record **records, size_t *n);
void       dem_world_clear_removed_records(dem_world *w);

/*--- diagnostics ----------------------------------------------------------------*/
typedef struct {
    double kinetic_energy, rotational_energy;  /* [J] */
    double momentum[3];
    double max_overlap_ratio;                  /* max overlap / diameter (pairs and walls) */
    size_t pair_contacts, wall_contacts;
    int64_t inserted, removed;                 /* inserted: add_particles, fill, inlets; removed:
                                                  booked on an outlet.  Not counted: unpack (migration
                                                  in) and dem_world_remove_particle(w, i, -1) */
    int64_t list_builds;                       /* added: neighbour-list builds so far */
} dem_stats;
dem_status dem_world_stats(const dem_world *w, dem_stats *s);
/** Added: heap memory held by the world [bytes]: particle arrays (per-particle
 *  storage incl. capacity slack and the coupling arrays once allocated) and
 *  the neighbour/wall lists with their contact history.  Either may be NULL. */
dem_status dem_world_memory(const dem_world *w, size_t *particle_bytes, size_t *list_bytes);
/** Added: wall-clock seconds spent in the phases of stepping since the world
 *  was created: integration (half kicks, drift, outlets/inlets), neighbour-list
 *  builds, pair forces (incl. zeroing the force arrays) and wall contacts.
 *  Measured only by a core built with -DDEM_PROFILE
 *  (make -C src/dem EXTRA_CFLAGS=-DDEM_PROFILE; bench/dem/profile); any
 *  other build writes zeros and returns DEM_ERR_STATE. */
typedef struct { double integrate, neighbour, pairs, walls; } dem_phase_times;
dem_status dem_world_phase_times(const dem_world *w, dem_phase_times *t);
/** Per owned particle: coordination number (particle contacts) and the sum
 *  of contact forces (3 per particle), as of the last force evaluation.
 *  Either pointer may be NULL.  DEM_ERR_STATE (nothing written) when the
 *  particles changed since that evaluation (insert, remove, restore, a wall
 *  change, ghosts cleared): the answer is then not known until the next
 *  step. */
dem_status dem_world_particle_contacts(const dem_world *w, int *coordination, double *contact_force);

/** Added: one contact of the last force evaluation (dem_world_contacts).
 *  Forces act on particle a (b, a particle, gets the opposite); they are the
 *  terms the step used: force_n + force_t is, bit for bit, the contact's
 *  share of a's contact force (rolling-friction torques are not reported). */
typedef struct {
    int64_t id_a;            /* particle a (id) */
    int64_t id_b;            /* wall = 0: particle b (id); wall = 1: the wall id */
    int     wall;            /* 1: particle-wall contact */
    int     ghost;           /* 1: a or b is a ghost copy (decomposed run; the pair is also
                                reported by the rank owning the other particle) */
    double  overlap;         /* a_a + a_b - |x_a - x_b| (wall: a_a - distance) [m] */
    double  normal[3];       /* unit normal from b (wall: the closest wall point) to a */
    double  force_n[3];      /* normal force on a (elastic + damping) = f_n normal [N] */
    double  force_t[3];      /* tangential force on a [N] */
} dem_contact;
/** Added: record the contacts of every force evaluation from now on (on = 1;
 *  0 stops and frees the record; the setting survives dem_world_restore).
 *  Off by default: recording writes one
 *  dem_contact (104 bytes) per contact and evaluation.  The recorded pair
 *  loop does the same arithmetic as the plain one: trajectories are
 *  bit-identical with recording on or off. */
dem_status dem_world_record_contacts(dem_world *w, int on);
/** Added: the contacts of the last force evaluation: every touching pair of
 *  the neighbour list once (a periodic pair once, with its image; owned-ghost
 *  pairs are reported on both ranks, flagged ghost), then the wall contacts.
 *  *count gets the number of contacts; out NULL: only the count; else
 *  capacity (entries of out) must be >= *count (DEM_ERR_RANGE, nothing
 *  written, *count set).  The record belongs to the world; out to the caller.
 *  DEM_ERR_STATE when recording was off at the last evaluation or the
 *  particles or walls changed since (the conditions of
 *  dem_world_particle_contacts): take a step first. */
dem_status dem_world_contacts(const dem_world *w, dem_contact *out, size_t capacity, size_t *count);

/*--- state ----------------------------------------------------------------------*/
/** Full state incl. contact history, inlets, outlet accounting and RNG; a
 *  restored world continues bit-identically. */
dem_status dem_world_save(const dem_world *w, const char *path);
dem_status dem_world_restore(dem_world *w, const char *path);
/** The same state in memory (e.g. a last-good-state checkpoint).  *buf
 *  (NULL or malloc'ed, *capacity bytes) is reused when the state fits,
 *  else replaced by a larger malloc'ed buffer; *size gets the state's
 *  bytes.  Release the buffer with free().  restore leaves w unchanged on
 *  error. */
dem_status dem_world_save_memory(const dem_world *w, void **buf, size_t *capacity, size_t *size);
dem_status dem_world_restore_memory(dem_world *w, const void *buf, size_t size);
/** Added: 0 if a and b have the same contact law, damping option, periodic
 *  box, materials, material pairs, walls (kind, material, triangles), inlets
 *  and outlets (their number); else 1 and the first difference in what
 *  (n bytes), a's value first ("material 0: friction 0.5, the state's 0.4").
 *  For a continued run: the input's world against the restored state. */
int dem_world_setup_diff(const dem_world *a, const dem_world *b, char *what, size_t n);

/*--- decomposition support --------------------------------------------------------*/
/* Ghosts take part in the force evaluation only: the half neighbour list holds
 * owned-owned and owned-ghost pairs (never ghost-ghost), the pair force acts on
 * the owned particle as in a world owning both, ghosts have no wall contacts
 * and are neither integrated nor checked nor removed by outlets.  Owned-ghost
 * pairs are evaluated (and counted in dem_stats.pair_contacts) on both ranks.
 * Every ghost refresh (clear_ghosts, unpack) invalidates the neighbour list
 * (rebuilt, and owned particles re-sorted, at the next force evaluation: index
 * by id); dem_world_set_ghost_states does not.
 * Ghost order: ghosts occupy [n_owned, n_owned + n_ghost) in the order of their
 * dem_world_unpack_particle(..., 1) calls (ghost position k = storage index
 * n_owned + k) until dem_world_clear_ghosts.  No list build (the spatial sort
 * permutes owned particles only), insertion (inlets, fill, add_particles),
 * owned unpack (ghost = 0), removal (outlets, remove_particle) or restore
 * changes their relative order: the ghost block is shifted as a whole when
 * the owned count changes, so the positions k stay valid.
 * Verlet scheme for a decomposed run (tests/dem/test_decomp.c): per step
 * step_drift on every rank; stale = OR over ranks of dem_world_list_stale;
 * if stale: migrate, clear_ghosts, send as ghosts the owned particles within
 * r_i + r_max + skin (dem_world_skin, r_max the global largest radius) of the
 * neighbour's region and remember their ids in order, then
 * dem_world_invalidate_list; else send only the states (x, v, omega) of the
 * same particles in the same order with dem_world_set_ghost_states (look them
 * up by id: owned particles are re-sorted at list builds); then step_forces.
 * (The simplest sound scheme, with a global OR per step.  demFoam instead lets
 * each pair of neighbouring ranks renew its ghost sets when either side's
 * particles moved more than skin/2 since the pair's last renewal, and each
 * rank rebuild its list when its own or a partner's particles may have moved
 * more than skin/2 since its build, bounded with
 * dem_world_drift_displacement: no collective per step; src/demCoupling/
 * processorGhosts/processorGhosts.C, docs/parallel.md.)
 * Ranks must use the same dt and skin; an owned particle may stray outside
 * its region between rebuilds (migration happens at rebuilds only).  A
 * periodic wrap of positions happens at list builds only.
 * Contact history waits in a pending store keyed by ids until the next list
 * build; if it holds the same pair twice, the entry stored first wins (e.g.
 * a particle migrating in before dem_world_clear_ghosts: the history packed
 * with it wins over the one this side kept while it was a ghost here). */
/** Bytes needed to pack particle i with its contact history (buf NULL) or pack it. */
dem_status dem_world_pack_particle(const dem_world *w, size_t index, void *buf, size_t *size);
/** Added: pack the m particles index[0..m-1] with their contact history, one
 *  after the other in that order, each record byte-identical to
 *  dem_world_pack_particle's; one pass over the neighbour list for all m (a
 *  migration costs O(list + m), not O(m x list)).  buf NULL: *bytes = the
 *  bytes needed; else *bytes is buf's size in and the bytes written out.
 *  sizes (may be NULL) gets each record's bytes.  DEM_ERR_RANGE for an index
 *  out of range or a too small buffer, DEM_ERR_ARG for an index given twice. */
dem_status dem_world_pack_particles(const dem_world *w, const size_t *index, size_t m, void *buf, size_t *bytes,
                                    size_t *sizes);
/** Added: as dem_world_pack_particle but without any contact history, for a
 *  ghost copy (the receiving side keeps its own owned-ghost history across
 *  dem_world_clear_ghosts; packed history would add duplicate pending entries). */
dem_status dem_world_pack_ghost(const dem_world *w, size_t index, void *buf, size_t *size);
/** Unpack a particle as owned (ghost = 0, with its forces, coupling values and
 *  contact history; not counted in dem_stats.inserted) or as a ghost copy
 *  (ghost = 1: pair history kept, wall history ignored).  Neither resets the
 *  stored forces of the other particles (no new first force evaluation). */
dem_status dem_world_unpack_particle(dem_world *w, const void *buf, size_t size, int ghost);
dem_status dem_world_clear_ghosts(dem_world *w);
/** Added: set x, v and omega of the ghosts at ghost positions [first,
 *  first + count) from xvw (9 doubles per ghost: x0 x1 x2 v0 v1 v2 w0 w1 w2)
 *  WITHOUT invalidating the neighbour list or touching the contact history,
 *  the forces, the displacement references or the storage order: the cheap
 *  ghost refresh between list builds (the ghost set stays that of the last
 *  build; the caller's rebuild decision, dem_world_list_stale, must cover
 *  the ghosts' displacement).  All or nothing: DEM_ERR_RANGE if the range
 *  exceeds the n_ghost ghosts present, DEM_ERR_NAN for a non-finite value,
 *  DEM_ERR_ARG for xvw NULL with count > 0.  count = 0 is a no-op. */
dem_status dem_world_set_ghost_states(dem_world *w, size_t first, size_t count, const double *xvw);

#ifdef __cplusplus
}
#endif
#endif /* DEM_H */
