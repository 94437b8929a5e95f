/* C interface of the Cam-Clay IX UMAT library (libcamclay9).
 * The material is called through the standard Abaqus UMAT argument list (Fortran, by reference);
 * gfortran names it umat_. CMNAME is a character*80 whose hidden length comes last. */
#ifndef CAMCLAY9_H
#define CAMCLAY9_H
#ifdef __cplusplus
extern "C" {
#endif

void umat_(double *stress, double *statev, double *ddsdde, double *sse, double *spd, double *scd,
           double *rpl, double *ddsddt, double *drplde, double *drpldt, const double *stran,
           const double *dstran, const double *time, const double *dtime, const double *temp,
           const double *dtemp, const double *predef, const double *dpred, const char *cmname,
           const int *ndi, const int *nshr, const int *ntens, const int *nstatv, const double *props,
           const int *nprops, const double *coords, const double *drot, double *pnewdt,
           const double *celent, const double *dfgrd0, const double *dfgrd1, const int *noel,
           const int *npt, const int *layer, const int *kspt, const int *jstep, const int *kinc,
           unsigned long cmname_len);

/* Check PROPS and the sizes without integrating anything. Sets *code = 0 when valid; otherwise
 * *code is the offending PROPS slot (1-based), or -1 NPROPS, -2 NSTATV, -3 NTENS, -4 NDI, and message
 * (NUL-terminated, at most message_capacity bytes) names the slot, its value and the allowed range. */
void camclay9_check_props(const double *props, int nprops, int nstatv, int ntens, int ndi, int *code,
                          char *message, int message_capacity);

/* The name of PROPS slot (0-based) into name (NUL-terminated, at most capacity bytes): the model's one spelling
 * (docs/umat.md, PROPS). Returns its length, or 0 when slot is not a PROPS slot of the model. */
int camclay9_prop_name(int slot, char *name, int capacity);

/* One PROPS slot of the model's contract (ccix_props' prop_table; docs/umat.md, PROPS), MFront-style: its name
 * (the one spelling of material.set and calibrate), the symbol the UMAT's messages write, its unit with
 * stresses in MPa and time in s ("-": none; the routine takes any consistent units), its meaning in one line,
 * and its own bounds as camclay9_check_props applies them: lo and hi (-DBL_MAX, DBL_MAX where there is none),
 * and in bounds the CAMCLAY9_BOUND_* bits that apply. A slot with CAMCLAY9_BOUND_COUPLED also enters
 * conditions with other slots (a positive-definite stiffness or projection tensor, a non-zero normal) that
 * only camclay9_check_props of the whole vector decides. */
typedef struct {
  char   name[16], symbol[16], unit[16], meaning[80];
  double lo, hi;
  int    bounds;
} camclay9_prop_info_t;

enum {
  CAMCLAY9_BOUND_LO        = 1,  /* value > lo ... */
  CAMCLAY9_BOUND_LO_CLOSED = 2,  /* ... or value >= lo (set together with CAMCLAY9_BOUND_LO) */
  CAMCLAY9_BOUND_HI        = 4,  /* value < hi ... */
  CAMCLAY9_BOUND_HI_CLOSED = 8,  /* ... or value <= hi (set together with CAMCLAY9_BOUND_HI) */
  CAMCLAY9_BOUND_COUPLED   = 16  /* and conditions with other slots */
};

/* PROPS slot (0-based) into *info. Returns 1, or 0 when slot is not a PROPS slot of the model (*info empty). */
int camclay9_prop_info(int slot, camclay9_prop_info_t *info);

/* STATEV block k (0-based: sig_hard, evp_hard, pc_hard, sig_soft, evp_soft, pc_soft, evp, iterations, flags,
 * f_hard, f_soft; docs/umat.md, STATEV): its name into name (NUL-terminated, at most capacity bytes), its first
 * slot (0-based) and its number of slots. Returns 1, or 0 when there is no block k. The enum below holds the same
 * first slots as constants. */
int camclay9_statev_block(int k, char *name, int capacity, int *first, int *size);

/* Sizes (docs/umat.md). */
enum {
  CAMCLAY9_NSTATV_MIN = 32,
  CAMCLAY9_NSTATV_DIAGNOSTICS = 36,
  CAMCLAY9_NPROPS_MIN = 19,
  CAMCLAY9_NPROPS_WITH_NORMAL = 23
};

/* STATEV layout as 0-based C offsets (docs/umat.md numbers the slots from 1): the first of six
 * components for the tensors (Voigt 11 22 33 12 13 23, engineering shear for strains). */
enum {
  CAMCLAY9_SV_SIG_HARD = 0,
  CAMCLAY9_SV_EVP_HARD = 6,
  CAMCLAY9_SV_PC_HARD = 12,
  CAMCLAY9_SV_SIG_SOFT = 13,
  CAMCLAY9_SV_EVP_SOFT = 19,
  CAMCLAY9_SV_PC_SOFT = 25,
  CAMCLAY9_SV_EVP = 26,
  CAMCLAY9_SV_ITERATIONS = 32,
  CAMCLAY9_SV_FLAGS = 33
};

#ifdef __cplusplus
}
#endif
#endif
