/* Linked into every Linux FMU binary by scripts/build-fmus.sh. The C runtime objects
 * that gcc links into a shared library run __cxa_finalize(&__dso_handle) when the
 * library is unloaded, which runs (and forgets) the exit handlers the library
 * registered with __cxa_atexit; zig links none of them, so after dlclose such a handler
 * stayed registered and the process crashed in exit() jumping into the unloaded code
 * (robofmu-hostile-lifecycle, issue 29). This destructor does what those objects do. */
extern void *__dso_handle;
extern void __cxa_finalize(void *) __attribute__((weak));

__attribute__((destructor)) static void robofmu_finalize(void)
{
    if (__cxa_finalize)
        __cxa_finalize(&__dso_handle);
}
