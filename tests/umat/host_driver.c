/* A host of the single-file UMAT, as a C program with POSIX threads (issue 21). It is linked with an
 * object compiled from the installed camclay9_umat.f90 or camclay9_umat_abaqus.for exactly as a host
 * compiles it (tests/umat/host_files.cmake). Modes:
 *
 *   threads    8 materials (PROPS differing in the bedding normal, phi, pc0, eta, NTENS 6 and 4), one per
 *              thread. Each material's path of 40 viscoplastic increments is first run alone, serially;
 *              then all 8 threads start together at a barrier and run their path over and over for
 *              0.5 s (at least 10 times each), so that they overlap on every core whatever the speed
 *              of a call. Every STRESS, STATEV, DDSDDE and PNEWDT of every increment must equal the
 *              serial run bit for bit (memcmp). A UMAT that shares anything between threads (a material
 *              cache, a static local) hands one thread another's material and fails here: the UMAT of
 *              before issue 21, compiled without OpenMP, gave 3 000 to 40 000 differing increments of
 *              ~200 000 in five runs.
 *   bad_props  one call with PROPS(17) = 0 (lambda_p of the soft frame): the UMAT must stop; returning
 *              prints "returned instead of stopping" and exits 0, which the test counts as a failure.
 *   rejected   one call with DTIME = -1: the UMAT must reject it (PNEWDT < 1, STRESS and STATEV
 *              unchanged) with a message and go on; exit 0 when it did.
 *
 * For the hook build (-DCAMCLAY9_STOP_HOOK=test_host_stop) this file provides the host's stop routine,
 * and for the mock-Abaqus build mock_abaqus.f90 provides XIT and opens the message file (unit 7). */
#include <pthread.h>
#include <sched.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "camclay9.h"

enum { NMAT = 8, NINC = 40, MIN_REPEAT = 10, NSTATV = 36 };
static const double RUN_SECONDS = 0.5;

/* The mock-Abaqus build links mock_abaqus.f90, which opens job.msg on unit 7 as Abaqus does. */
void mock_abaqus_start_(void) __attribute__((weak));

/* The host's stop routine of the hook build: shows the message its own way and ends the process. */
void test_host_stop_(const char *message, size_t length) {
  printf("test host: stopped by the UMAT: %.*s\n", (int)length, message);
  fflush(stdout);
  exit(3);
}

typedef struct {
  int    ntens, nprops;
  double props[23];
} Material;

/* What one increment returns. */
typedef struct {
  double stress[6], statev[NSTATV], ddsdde[36], pnewdt;
} Output;

static Material materials[NMAT];
static Output   serial[NMAT][NINC];
static long     mismatches[NMAT], paths[NMAT];
static pthread_barrier_t start;

static void woodford(Material *m, int ntens, double phi, const double n[3]) {
  const double w[20] = {0.5,  2900, 18000, 13000, 4100, 6900, 1.46,   0.00013, 0.73, -0.20,
                        0.40, 2.0,  1.3e13, 4600, 3100, 1.46, 0.0026, 35.0,    1.3e10, 0.0};
  memcpy(m->props, w, sizeof w);
  m->props[0] = phi;
  memcpy(m->props + 20, n, 3 * sizeof(double));
  m->ntens  = ntens;
  m->nprops = 23;
}

static void make_materials(void) {
  const double z[3] = {0, 0, 1}, x[3] = {1, 0, 0}, o[3] = {0.5, 0.3, 0.8}, p[3] = {0.6, 0.8, 0}, q[3] = {0, 1, 0};
  woodford(&materials[0], 6, 0.5, z);
  woodford(&materials[1], 6, 0.5, x);
  woodford(&materials[2], 6, 0.4, o);
  woodford(&materials[3], 6, 0.6, o);     /* differs from 2 in phi only */
  woodford(&materials[4], 6, 0.5, z);
  materials[4].props[11] = 3.0;           /* pc0 of the hard frame */
  woodford(&materials[5], 6, 0.5, x);
  materials[5].props[12] = 1.3e12;        /* eta of the hard frame */
  woodford(&materials[6], 4, 0.5, p);     /* plane strain, normal in the 1-2 plane */
  woodford(&materials[7], 4, 0.7, q);
}

/* One UMAT call with the arguments a small-strain host passes. */
static void call(const Material *m, double *stress, double *statev, double *ddsdde, const double *dstran,
                 double dtime, double *pnewdt, int noel) {
  double sse = 0, spd = 0, scd = 0, rpl, ddsddt[6], drplde[6], drpldt, stran[6] = {0}, time[2] = {0, 0},
         temp = 0, dtemp = 0, predef[1] = {0}, dpred[1] = {0}, coords[3] = {0},
         drot[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, celent = 1, dfgrd[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  int  ndi = 3, nshr = m->ntens - 3, nstatv = NSTATV, npt = 1, layer = 1, kspt = 1, jstep[4] = {1, 1, 0, 0},
      kinc = 1;
  char cmname[80];
  memset(cmname, ' ', sizeof cmname);
  memcpy(cmname, "WOODFORD", 8);
  umat_(stress, statev, ddsdde, &sse, &spd, &scd, &rpl, ddsddt, drplde, &drpldt, stran, dstran, time, &dtime,
        &temp, &dtemp, predef, dpred, cmname, &ndi, &nshr, &m->ntens, &nstatv, m->props, &m->nprops, coords,
        drot, pnewdt, &celent, dfgrd, dfgrd, &noel, &npt, &layer, &kspt, jstep, &kinc, sizeof cmname);
}

/* The path of material k: from -35 MPa in both frames (STATEV zero), 40 increments of compression with
 * shear, 100 s each; the hard frame starts far outside its surface (pc0 = 2 MPa), so both frames flow. */
static void run_path(int k, Output out[NINC]) {
  const Material *m = &materials[k];
  double stress[6] = {-35, -35, -35, 0, 0, 0}, statev[NSTATV] = {0};
  const double de[6] = {-2e-5, 1e-5, -6e-5, 1.4e-5, -4e-6, 8e-6};
  if (m->ntens == 4) stress[3] = 0;
  for (int i = 0; i < NINC; i++) {
    Output *o = &out[i];
    o->pnewdt = 1e30;   /* Abaqus sets PNEWDT large before each call */
    memset(o->ddsdde, 0, sizeof o->ddsdde);
    call(m, stress, statev, o->ddsdde, de, 100.0, &o->pnewdt, k + 1);
    memcpy(o->stress, stress, sizeof stress);
    memcpy(o->statev, statev, sizeof statev);
  }
}

static double seconds(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}

static void *worker(void *arg) {
  int    k = (int)(size_t)arg;
  Output out[NINC];
  pthread_barrier_wait(&start);
  double t0 = seconds();
  while (paths[k] < MIN_REPEAT || seconds() - t0 < RUN_SECONDS) {
    run_path(k, out);
    for (int i = 0; i < NINC; i++) mismatches[k] += memcmp(&out[i], &serial[k][i], sizeof out[i]) != 0;
    ++paths[k];
    sched_yield();
  }
  return NULL;
}

static int threads(void) {
  make_materials();
  for (int k = 0; k < NMAT; k++) run_path(k, serial[k]);
  /* The materials differ: a cache handing one thread another's material cannot go unnoticed. */
  for (int k = 1; k < NMAT; k++)
    if (memcmp(serial[k][NINC - 1].statev, serial[0][NINC - 1].statev, 32 * sizeof(double)) == 0) {
      printf("host_driver: materials 0 and %d give the same state: the test cannot see a mix-up\n", k);
      return 1;
    }
  if (serial[0][NINC - 1].statev[32] < 1) {
    printf("host_driver: no local iteration in the last increment: the path is not viscoplastic\n");
    return 1;
  }
  pthread_t t[NMAT];
  pthread_barrier_init(&start, NULL, NMAT);
  for (int k = 0; k < NMAT; k++) pthread_create(&t[k], NULL, worker, (void *)(size_t)k);
  long total = 0, calls = 0;
  for (int k = 0; k < NMAT; k++) {
    pthread_join(t[k], NULL);
    total += mismatches[k];
    calls += paths[k] * NINC;
    printf("thread %d (NTENS %d, phi %.1f): %ld of %ld increments differ from the serial run\n", k,
           materials[k].ntens, materials[k].props[0], mismatches[k], paths[k] * NINC);
  }
  printf("%d threads, %ld increments: %ld differ from the serial run bit for bit\n", NMAT, calls, total);
  return total != 0;
}

int main(int argc, char **argv) {
  const char *mode = argc > 1 ? argv[1] : "threads";
  if (mock_abaqus_start_) mock_abaqus_start_();
  if (!strcmp(mode, "threads")) return threads();
  make_materials();
  double stress[6] = {-35, -35, -35, 0, 0, 0}, statev[NSTATV] = {0}, ddsdde[36], de[6] = {0, 0, -1e-5, 0, 0, 0},
         pnewdt = 1e30;
  if (!strcmp(mode, "bad_props")) {
    materials[0].props[16] = 0;   /* PROPS(17) */
    call(&materials[0], stress, statev, ddsdde, de, 100.0, &pnewdt, 12);
    printf("host_driver: the UMAT returned instead of stopping\n");
    return 0;
  }
  if (!strcmp(mode, "rejected")) {
    double s0[6], v0[NSTATV];
    call(&materials[0], stress, statev, ddsdde, de, 100.0, &pnewdt, 12);   /* an initialised state */
    memcpy(s0, stress, sizeof s0);
    memcpy(v0, statev, sizeof v0);
    pnewdt = 1e30;
    call(&materials[0], stress, statev, ddsdde, de, -1.0, &pnewdt, 12);
    int ok = pnewdt < 1 && !memcmp(s0, stress, sizeof s0) && !memcmp(v0, statev, sizeof v0);
    printf("host_driver: DTIME = -1 %s (PNEWDT = %g)\n", ok ? "rejected, state unchanged" : "NOT rejected", pnewdt);
    return !ok;
  }
  fprintf(stderr, "host_driver: unknown mode %s (threads, bad_props, rejected)\n", mode);
  return 2;
}
