/* A host that leaves a callback of the FMU without returning: a C++ exception
 * (compiled as C++), pthread_exit, pthread_cancel while the thread waits in the
 * callback, or longjmp. Compiled as C and as C++ by crates/test/hostile/tests/leave.rs, which
 * runs it on every packaged FMU, both standards, and judges the outcome
 * (docs/reliability.md, "Leaving a callback"); compiled for aarch64 Linux and, as C++
 * with MinGW-w64's g++ (Windows: LoadLibrary, SEH exceptions), for Windows under Wine by
 * tests/python/test_platforms.py.
 *
 * Usage: leave <library> <2|3> <instantiation token> <throw|exit|cancel|longjmp>
 *        [logger|update]
 *
 * A worker thread instantiates a Co-Simulation instance with logging on and calls
 * SetupExperiment (FMI 2.0) or EnterInitializationMode (FMI 3.0), whose logCalls line
 * reaches the logger, which leaves. With "update" (FMI 3.0) the instance has an
 * intermediateUpdate callback instead, which leaves at the first intermediate point of
 * a DoStep ("returned" if the model has none). The lines printed on stdout say how far
 * it got: "left", then, after a longjmp, the status of every later call on the
 * instance. */
#ifdef _WIN32
#include <windows.h>
#define RTLD_NOW 0
#define RTLD_LOCAL 0
#define dlopen(path, flags) ((void *)LoadLibraryA(path))
#define dlsym(library, name) ((void *)GetProcAddress((HMODULE)(library), (name)))
#define dlclose(library) FreeLibrary((HMODULE)(library))
#define dlerror() "LoadLibrary failed"
#else
#include <dlfcn.h>
#endif
#include <pthread.h>
#include <semaphore.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#ifdef __cplusplus
#include <stdexcept>
#endif

typedef void *(*instantiate2_t)(const char *, int, const char *, const char *, const void *,
                                int, int);
typedef void *(*instantiate3_t)(const char *, const char *, const char *, int, int, int, int,
                                const unsigned *, size_t, void *, void *, void *);
typedef int (*call_t)(void *);
typedef int (*setup2_t)(void *, int, double, double, int, double);
typedef int (*init3_t)(void *, int, double, double, int, double);
typedef int (*step2_t)(void *, double, double, int);
typedef int (*step3_t)(void *, double, double, int, char *, char *, char *, double *);
typedef void (*free_t)(void *);

struct callbacks2 {
    void *logger, *allocate, *free, *step_finished, *environment;
};

static void *library;
static int standard;
static const char *token;
static const char *way;
static int update; /* leave the intermediateUpdate callback, not the logger */
static volatile int armed;
static sem_t in_logger;
static jmp_buf back;
static struct callbacks2 callbacks;

static void *symbol(const char *name) {
    void *f = dlsym(library, name);
    if (!f) {
        fprintf(stderr, "leave: %s is missing\n", name);
        exit(2);
    }
    return f;
}

/* What the logger does once armed. */
static void leave_now(void) {
    armed = 0;
    printf("left\n");
    fflush(stdout);
#ifdef __cplusplus
    if (!strcmp(way, "throw"))
        throw std::runtime_error("the host reports an error");
#endif
    if (!strcmp(way, "exit"))
        pthread_exit(NULL);
    if (!strcmp(way, "cancel")) {
        sem_post(&in_logger);
        for (;;)
            sleep(1); /* a cancellation point */
    }
    if (!strcmp(way, "longjmp"))
        longjmp(back, 1);
}

static void logger2(void *env, const char *name, int status, const char *category,
                    const char *message, ...) {
    (void)env, (void)name, (void)status, (void)category, (void)message;
    if (armed)
        leave_now();
}

static void logger3(void *env, int status, const char *category, const char *message) {
    (void)env, (void)status, (void)category, (void)message;
    if (armed && !update)
        leave_now();
}

static void update3(void *env, double time, char set_requested, char get_allowed,
                    char finished, char can_return_early, char *requested, double *at) {
    (void)env, (void)time, (void)set_requested, (void)get_allowed, (void)finished;
    (void)can_return_early, (void)requested, (void)at;
    if (armed)
        leave_now();
}

static void *instantiate(void) {
    if (standard == 2) {
        callbacks.logger = (void *)logger2;
        callbacks.allocate = (void *)calloc;
        callbacks.free = (void *)free;
        instantiate2_t f = (instantiate2_t)symbol("fmi2Instantiate");
        return f("leave", 1, token, NULL, &callbacks, 0, 1);
    }
    instantiate3_t f = (instantiate3_t)symbol("fmi3InstantiateCoSimulation");
    return f("leave", token, NULL, 0, 1, 0, 0, NULL, 0, NULL, (void *)logger3,
             update ? (void *)update3 : NULL);
}

/* The call whose logCalls line reaches the logger. */
static int start(void *c) {
    if (standard == 2)
        return ((setup2_t)symbol("fmi2SetupExperiment"))(c, 0, 0.0, 0, 0, 0.0);
    return ((init3_t)symbol("fmi3EnterInitializationMode"))(c, 0, 0.0, 0.0, 0, 0.0);
}

static int call(const char *name2, const char *name3, void *c) {
    return ((call_t)symbol(standard == 2 ? name2 : name3))(c);
}

static int step(void *c) {
    if (standard == 2)
        return ((step2_t)symbol("fmi2DoStep"))(c, 0.0, 1e-3, 1);
    char event, stop, early;
    double last;
    return ((step3_t)symbol("fmi3DoStep"))(c, 0.0, 1e-3, 1, &event, &stop, &early, &last);
}

/* The call that reaches the callback that leaves. */
static int leaving_call(void *c) {
    if (!update)
        return start(c);
    start(c);
    call("", "fmi3ExitInitializationMode", c);
    return step(c);
}

/* After a longjmp: the same instance, called again from this thread. */
static void after_longjmp(void *c) {
    printf("again %d\n", start(c));
    printf("reset %d\n", call("fmi2Reset", "fmi3Reset", c));
    printf("start %d\n", start(c));
    if (standard == 2)
        printf("enter %d\n", call("fmi2EnterInitializationMode", "", c));
    printf("exit %d\n", call("fmi2ExitInitializationMode", "fmi3ExitInitializationMode", c));
    printf("step %d\n", step(c));
    ((free_t)symbol(standard == 2 ? "fmi2FreeInstance" : "fmi3FreeInstance"))(c);
    printf("freed\n");
}

static void *worker(void *unused) {
    (void)unused;
    void *volatile c = instantiate();
    if (!c) {
        fprintf(stderr, "leave: the instantiation was refused\n");
        exit(2);
    }
    if (!strcmp(way, "longjmp") && setjmp(back)) {
        after_longjmp(c);
        return NULL;
    }
    armed = 1;
#ifdef __cplusplus
    try {
        leaving_call(c);
    } catch (const std::exception &e) {
        printf("caught %s\n", e.what());
        return NULL;
    }
#else
    leaving_call(c);
#endif
    printf("returned\n");
    sem_post(&in_logger); /* nothing to cancel: the callback was never called */
    return NULL;
}

int main(int argc, char **argv) {
    int callback_named = argc == 6 && (!strcmp(argv[5], "logger") || !strcmp(argv[5], "update"));
    if (argc != 5 && !callback_named) {
        fprintf(stderr, "usage: leave <library> <2|3> <token> <throw|exit|cancel|longjmp> "
                        "[logger|update]\n");
        return 2;
    }
    library = dlopen(argv[1], RTLD_NOW | RTLD_LOCAL);
    if (!library) {
        fprintf(stderr, "leave: %s\n", dlerror());
        return 2;
    }
    standard = atoi(argv[2]);
    token = argv[3];
    way = argv[4];
    update = argc == 6 && !strcmp(argv[5], "update");
    sem_init(&in_logger, 0, 0);
    pthread_t thread;
    pthread_create(&thread, NULL, worker, NULL);
    if (!strcmp(way, "cancel")) {
        sem_wait(&in_logger);
        pthread_cancel(thread);
    }
    pthread_join(thread, NULL);
    printf("joined\n");
    dlclose(library);
    return 0;
}
