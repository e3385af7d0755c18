/* The C host of benches/bench_api.py: runs a co-simulation of FMI 2.0 co-simulation FMUs
 * (unzipped) with direct calls, sampled coupling with inputs held over each step: the
 * same FMI calls as robofmu's master with input_extrapolation = "hold". The plan (FMUs,
 * start values, connections grouped per target and source FMU, the experiment) is a text
 * file that bench_api.py writes; prints the wall time of each whole run (load,
 * instantiate, initialise, step, free) and the last recorded row.
 *   c_host PLAN RUNS */
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "fmi2Functions.h"

#define MAX_FMUS 8
#define MAX_VARS 64

typedef struct {
    char dir[4096], id[256], guid[256];
    void *lib;
    fmi2Component c;
    fmi2InstantiateTYPE *instantiate;
    fmi2FreeInstanceTYPE *free_instance;
    fmi2SetupExperimentTYPE *setup;
    fmi2EnterInitializationModeTYPE *enter;
    fmi2ExitInitializationModeTYPE *exit_init;
    fmi2TerminateTYPE *terminate;
    fmi2GetRealTYPE *get_real;
    fmi2SetRealTYPE *set_real;
    fmi2SetIntegerTYPE *set_integer;
    fmi2SetBooleanTYPE *set_boolean;
    fmi2DoStepTYPE *do_step;
} Fmu;

typedef struct { int fmu; char type; fmi2ValueReference vr; double value; } Start;
typedef struct { int dst, src, n; fmi2ValueReference src_vr[MAX_VARS], dst_vr[MAX_VARS]; } Group;

static Fmu fmus[MAX_FMUS];
static Start starts[256];
static Group groups[64];
static int n_fmus, n_starts, n_groups;
static double t0, t1, h;

static void logger(fmi2ComponentEnvironment e, fmi2String n, fmi2Status s, fmi2String c,
                   fmi2String m, ...) {}

static void die(const char *what, const char *more) {
    fprintf(stderr, "c_host: %s %s\n", what, more ? more : "");
    exit(1);
}

static void *sym(Fmu *f, const char *name) {
    void *p = dlsym(f->lib, name);
    if (!p) die("missing symbol", name);
    return p;
}

static void load(Fmu *f) {
    char path[8192];
    snprintf(path, sizeof path, "%s/binaries/linux64/%s.so", f->dir, f->id);
    f->lib = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    if (!f->lib) die("cannot load", dlerror());
    f->instantiate = sym(f, "fmi2Instantiate");
    f->free_instance = sym(f, "fmi2FreeInstance");
    f->setup = sym(f, "fmi2SetupExperiment");
    f->enter = sym(f, "fmi2EnterInitializationMode");
    f->exit_init = sym(f, "fmi2ExitInitializationMode");
    f->terminate = sym(f, "fmi2Terminate");
    f->get_real = sym(f, "fmi2GetReal");
    f->set_real = sym(f, "fmi2SetReal");
    f->set_integer = sym(f, "fmi2SetInteger");
    f->set_boolean = sym(f, "fmi2SetBoolean");
    f->do_step = sym(f, "fmi2DoStep");
}

static void check(fmi2Status s, const char *what) {
    if (s > fmi2Warning) die("call failed:", what);
}

static void propagate(void) {
    double v[MAX_VARS];
    for (int g = 0; g < n_groups; g++) {
        Group *p = &groups[g];
        check(fmus[p->src].get_real(fmus[p->src].c, p->src_vr, p->n, v), "fmi2GetReal");
        check(fmus[p->dst].set_real(fmus[p->dst].c, p->dst_vr, p->n, v), "fmi2SetReal");
    }
}

static double run(double *last) {
    struct timespec a, b;
    clock_gettime(CLOCK_MONOTONIC, &a);
    fmi2CallbackFunctions cb = {logger, calloc, free, NULL, NULL};
    for (int i = 0; i < n_fmus; i++) {
        Fmu *f = &fmus[i];
        char uri[8192];
        load(f);
        snprintf(uri, sizeof uri, "file://%s/resources", f->dir);
        f->c = f->instantiate(f->id, fmi2CoSimulation, f->guid, uri, &cb, fmi2False, fmi2False);
        if (!f->c) die("fmi2Instantiate failed:", f->id);
        check(f->setup(f->c, fmi2False, 0.0, t0, fmi2True, t1), "fmi2SetupExperiment");
    }
    for (int k = 0; k < n_starts; k++) {
        Start *s = &starts[k];
        Fmu *f = &fmus[s->fmu];
        if (s->type == 'r') check(f->set_real(f->c, &s->vr, 1, &s->value), "fmi2SetReal");
        else if (s->type == 'i') {
            fmi2Integer x = (fmi2Integer)s->value;
            check(f->set_integer(f->c, &s->vr, 1, &x), "fmi2SetInteger");
        } else {
            fmi2Boolean x = s->value != 0.0;
            check(f->set_boolean(f->c, &s->vr, 1, &x), "fmi2SetBoolean");
        }
    }
    for (int i = 0; i < n_fmus; i++) check(fmus[i].enter(fmus[i].c), "fmi2EnterInitializationMode");
    propagate();
    for (int i = 0; i < n_fmus; i++) check(fmus[i].exit_init(fmus[i].c), "fmi2ExitInitializationMode");
    propagate();
    long steps = (long)((t1 - t0) / h + 0.5);
    for (long k = 0; k < steps; k++) {
        double t = t0 + k * h;
        for (int i = 0; i < n_fmus; i++) check(fmus[i].do_step(fmus[i].c, t, h, fmi2True), "fmi2DoStep");
        propagate();
    }
    Group *p = &groups[n_groups - 1];
    check(fmus[p->src].get_real(fmus[p->src].c, p->src_vr, p->n, last), "fmi2GetReal");
    for (int i = 0; i < n_fmus; i++) {
        fmus[i].terminate(fmus[i].c);
        fmus[i].free_instance(fmus[i].c);
        dlclose(fmus[i].lib);
    }
    clock_gettime(CLOCK_MONOTONIC, &b);
    return (b.tv_sec - a.tv_sec) + 1e-9 * (b.tv_nsec - a.tv_nsec);
}

int main(int argc, char **argv) {
    if (argc != 3) die("usage: c_host PLAN RUNS", NULL);
    FILE *in = fopen(argv[1], "r");
    if (!in) die("cannot read", argv[1]);
    if (fscanf(in, "%d", &n_fmus) != 1 || n_fmus > MAX_FMUS) die("bad plan", "fmus");
    for (int i = 0; i < n_fmus; i++)
        if (fscanf(in, "%4095s %255s %255s", fmus[i].dir, fmus[i].id, fmus[i].guid) != 3) die("bad plan", "fmu");
    if (fscanf(in, "%d", &n_starts) != 1 || n_starts > 256) die("bad plan", "starts");
    for (int k = 0; k < n_starts; k++)
        if (fscanf(in, "%d %c %u %lf", &starts[k].fmu, &starts[k].type, &starts[k].vr, &starts[k].value) != 4) die("bad plan", "start");
    if (fscanf(in, "%d", &n_groups) != 1 || n_groups > 64 || n_groups < 1) die("bad plan", "groups");
    for (int g = 0; g < n_groups; g++) {
        Group *p = &groups[g];
        if (fscanf(in, "%d %d %d", &p->dst, &p->src, &p->n) != 3 || p->n > MAX_VARS) die("bad plan", "group");
        for (int j = 0; j < p->n; j++) if (fscanf(in, "%u %u", &p->src_vr[j], &p->dst_vr[j]) != 2) die("bad plan", "pair");
    }
    if (fscanf(in, "%lf %lf %lf", &t0, &t1, &h) != 3) die("bad plan", "experiment");
    fclose(in);
    int runs = atoi(argv[2]);
    double last[MAX_VARS];
    for (int r = 0; r < runs; r++) printf("%.9f\n", run(last));
    printf("last");
    for (int j = 0; j < groups[n_groups - 1].n; j++) printf(" %.17g", last[j]);
    printf("\n");
    return 0;
}
