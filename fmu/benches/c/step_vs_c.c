/* One co-simulation step of the packaged contact FMU through its C ABI (7 fmi2SetReal values +
 * fmi2DoStep + 3 fmi2GetReal values, model polach, the ellipse unchanged) timed beside a plain C
 * evaluation of Polach's formulas (Kalker's coefficients given, no validation) in the same
 * process, twice:
 *   - "run-time inputs": the C function reads its inputs from memory the compiler cannot see
 *     through (volatile), as an FMU reads what a master sets: every formula is evaluated;
 *   - "literal inputs": called with literals except the longitudinal creepage, as
 *     ../shared/bench/step-vs-c does: the compiler folds or hoists out of the loop everything
 *     that does not depend on that creepage (the spin force's exp, pow and K_M, K_S), so about
 *     half of the formula is left to time.
 * The formulas are the shared bench's (Polach 2000, eqs. 7, 14, 20-25 as ERRATA.md corrects
 * them). Best of 7 runs of 400 000 steps each; prints both ratios.
 * usage: step_vs_c SO_PATH GUID VR_IN(7, comma) VR_OUT(3, comma) RESOURCE_URI */
#include <dlfcn.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
typedef void *Component;
typedef struct { void *logger, *allocate, *free_memory, *step_finished, *environment; } Callbacks;
typedef Component (*InstantiateFn)(const char *, int, const char *, const char *, const Callbacks *, int, int);
typedef int (*SetupFn)(Component, int, double, double, int, double);
typedef int (*ModeFn)(Component);
typedef int (*RealFn)(Component, const unsigned *, size_t, double *);
typedef int (*StepFn)(Component, double, double, int);

static void logger(void *e, const char *n, int s, const char *c, const char *m, ...) { (void)e; (void)n; (void)s; (void)c; (void)m; }
static double now(void) { struct timespec t; clock_gettime(CLOCK_MONOTONIC, &t); return t.tv_sec + 1e-9 * t.tv_nsec; }

/* Polach's forces for load Q, friction mu, semi-axes a, b, shear modulus G, creepages sx, sy,
 * spin psi and Kalker's c11, c22, c23. */
static inline __attribute__((always_inline)) void polach(double Q, double mu, double a, double b, double G, double sx, double sy, double psi,
                          double c11, double c22, double c23, double *Fx, double *Fy) {
  double syc = sy; if (fabs(sy + psi * a) > fabs(sy)) syc = sy + psi * a;
  double sc = hypot(sx, syc); if (sc == 0) { *Fx = *Fy = 0; return; }
  double s = hypot(sx, sy); double cjj = s > 0 ? hypot(c11 * sx / s, c22 * sy / s) : 0;
  double eps = M_PI * G * a * b * cjj * sc / (4 * Q * mu);
  double F = 2 * Q * mu / M_PI * (eps / (1 + eps * eps) + atan(eps));
  double KS = 1 + 6.3 * (1 - exp(-a / b));
  double eM = 8.0 / 3.0 * G * b * sqrt(a * b) / (Q * mu) * c23 * fabs(syc) / KS;
  double h = 2 / (eM * eM + 1);
  double KM = fabs(eM) * h * h * (0.5 - h / 3) - pow(h * (2 - h), 1.5) / 3;
  double FyS = -9.0 / 16.0 * a * Q * mu * KM * KS * psi / sc;
  *Fx = -F * sx / sc; *Fy = -(F * sy / sc + FyS);
}

/* The inputs the master would set, where the compiler cannot see their values. */
static volatile double Q_ = 8e4, mu_ = 0.3, a_ = 6e-3, b_ = 6e-3, G_ = 8.2e10, sy_ = 2e-4, psi_ = 0.01,
                       c11_ = 4.12, c22_ = 3.67, c23_ = 1.47;

__attribute__((noinline)) static void polach_run_time(double sx, double *Fx, double *Fy) {
  polach(Q_, mu_, a_, b_, G_, sx, sy_, psi_, c11_, c22_, c23_, Fx, Fy);
}

static void parse(const char *s, unsigned *v, int n) { for (int i = 0; i < n; i++) { v[i] = strtoul(s, (char **)&s, 10); if (*s == ',') s++; } }

int main(int argc, char **argv) {
  if (argc < 6) { fprintf(stderr, "usage: step_vs_c SO_PATH GUID VR_IN VR_OUT RESOURCE_URI\n"); return 2; }
  void *so = dlopen(argv[1], RTLD_NOW | RTLD_LOCAL); if (!so) { printf("dlopen: %s\n", dlerror()); return 1; }
  InstantiateFn instantiate = (InstantiateFn)dlsym(so, "fmi2Instantiate");
  SetupFn setup = (SetupFn)dlsym(so, "fmi2SetupExperiment");
  ModeFn enter = (ModeFn)dlsym(so, "fmi2EnterInitializationMode"), exit_mode = (ModeFn)dlsym(so, "fmi2ExitInitializationMode");
  RealFn set_real = (RealFn)dlsym(so, "fmi2SetReal"), get_real = (RealFn)dlsym(so, "fmi2GetReal");
  StepFn step = (StepFn)dlsym(so, "fmi2DoStep");
  if (!instantiate || !setup || !enter || !exit_mode || !set_real || !get_real || !step) { printf("missing symbols\n"); return 1; }
  unsigned inputs[7], outputs[3]; parse(argv[3], inputs, 7); parse(argv[4], outputs, 3);
  Callbacks callbacks = {(void *)logger, (void *)calloc, (void *)free, NULL, NULL};
  Component c = instantiate("step_vs_c", 1, argv[2], argv[5], &callbacks, 0, 0);
  if (!c || setup(c, 0, 0, 0.0, 0, 0.0) || enter(c) || exit_mode(c)) { printf("instantiation failed\n"); return 1; }
  const int n = 400000; double out[3], in[7], t = 0, h = 1e-4, sink = 0, Fx, Fy;
  double best_step = 1e9, best_run_time = 1e9, best_literal = 1e9;
  for (int run = 0; run < 7; run++) {
    double t0 = now();
    for (int i = 0; i < n; i++) {
      in[0] = 1e-4 + 1e-10 * i; in[1] = 2e-4; in[2] = 0.01; in[3] = 8e4; in[4] = 6e-3; in[5] = 6e-3; in[6] = 0.3;
      if (set_real(c, inputs, 7, in) || step(c, t, h, 1) || get_real(c, outputs, 3, out)) { printf("call failed at %d\n", i); return 1; }
      t += h; sink += out[0];
    }
    double t1 = now();
    for (int i = 0; i < n; i++) { polach_run_time(1e-4 + 1e-10 * i, &Fx, &Fy); sink += Fx; }
    double t2 = now();
    for (int i = 0; i < n; i++) {
      polach(8e4, 0.3, 6e-3, 6e-3, 8.2e10, 1e-4 + 1e-10 * i, 2e-4, 0.01, 4.12, 3.67, 1.47, &Fx, &Fy); sink += Fx;
    }
    double t3 = now();
    if (t1 - t0 < best_step) best_step = t1 - t0;
    if (t2 - t1 < best_run_time) best_run_time = t2 - t1;
    if (t3 - t2 < best_literal) best_literal = t3 - t2;
  }
  printf("step %.1f ns; C Polach with run-time inputs %.1f ns: ratio %.2f; with literal inputs (as ../shared/bench/step-vs-c) "
         "%.1f ns: ratio %.2f (sink %g)\n", best_step / n * 1e9, best_run_time / n * 1e9, best_step / best_run_time,
         best_literal / n * 1e9, best_step / best_literal, sink);
  return 0;
}
