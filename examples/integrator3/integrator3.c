/* A third-party FMI 3.0 co-simulation FMU in C: two integrators y' = sign gain u (arrays
 * u[2] and y[2] of Float64, y(0) = y0[2]), stepped exactly for u held over the step;
 * sign is an Int32 and frozen a Boolean parameter (y holds while frozen). It is not part
 * of robofmu: examples/integrator3/build_fmu.py compiles it against FMPy's FMI 3.0
 * headers, and docs/python-api.md couples it with our PID through robofmu.System.
 * Every FMI 3.0 function is exported (importers load them all); what this FMU does not
 * do returns fmi3Error. */
#include <stdlib.h>
#include <string.h>
#include "fmi3Functions.h"

enum { TIME, U, Y, GAIN, Y0, SIGN, FROZEN };  /* value references */
typedef struct {
    double time, u[2], y[2], gain, y0[2];
    fmi3Int32 sign;
    fmi3Boolean frozen, initialized;
} Model;

static void defaults(Model *m) {
    memset(m, 0, sizeof *m);
    m->gain = 1.0;
    m->sign = 1;
}

/* The Float64 values of vr: their address and count; NULL for another vr. */
static double *float64(Model *m, fmi3ValueReference vr, size_t *n) {
    switch (vr) {
    case TIME: *n = 1; return &m->time;
    case U: *n = 2; return m->u;
    case Y: *n = 2; return m->y;
    case GAIN: *n = 1; return &m->gain;
    case Y0: *n = 2; return m->y0;
    default: return NULL;
    }
}

const char *fmi3GetVersion(void) { return fmi3Version; }
fmi3Status fmi3SetDebugLogging(fmi3Instance c, fmi3Boolean on, size_t n, const fmi3String k[]) { return fmi3OK; }
fmi3Instance fmi3InstantiateCoSimulation(fmi3String name, fmi3String token, fmi3String resources,
        fmi3Boolean visible, fmi3Boolean logging, fmi3Boolean eventModeUsed,
        fmi3Boolean earlyReturnAllowed, const fmi3ValueReference required[], size_t nRequired,
        fmi3InstanceEnvironment env, fmi3LogMessageCallback log,
        fmi3IntermediateUpdateCallback update) {
    Model *m = malloc(sizeof(Model));
    if (m) defaults(m);
    return m;
}
void fmi3FreeInstance(fmi3Instance c) { free(c); }
fmi3Status fmi3EnterInitializationMode(fmi3Instance c, fmi3Boolean toleranceDefined,
        fmi3Float64 tolerance, fmi3Float64 startTime, fmi3Boolean stopTimeDefined,
        fmi3Float64 stopTime) {
    ((Model *)c)->time = startTime;
    return fmi3OK;
}
fmi3Status fmi3ExitInitializationMode(fmi3Instance c) {
    Model *m = c;
    memcpy(m->y, m->y0, sizeof m->y);
    m->initialized = fmi3True;
    return fmi3OK;
}
fmi3Status fmi3Terminate(fmi3Instance c) { return fmi3OK; }
fmi3Status fmi3Reset(fmi3Instance c) { defaults(c); return fmi3OK; }

fmi3Status fmi3GetFloat64(fmi3Instance c, const fmi3ValueReference vr[], size_t nvr,
                          fmi3Float64 values[], size_t nValues) {
    size_t at = 0, n;
    for (size_t i = 0; i < nvr; i++) {
        double *v = float64(c, vr[i], &n);
        if (!v || at + n > nValues) return fmi3Error;
        memcpy(values + at, v, n * sizeof *v);
        at += n;
    }
    return at == nValues ? fmi3OK : fmi3Error;
}
fmi3Status fmi3SetFloat64(fmi3Instance c, const fmi3ValueReference vr[], size_t nvr,
                          const fmi3Float64 values[], size_t nValues) {
    Model *m = c;
    size_t at = 0, n;
    for (size_t i = 0; i < nvr; i++) {
        double *v = float64(m, vr[i], &n);
        /* y and time are not set; the parameters (fixed) only before initialization ends */
        if (!v || vr[i] == Y || vr[i] == TIME || (vr[i] != U && m->initialized)
            || at + n > nValues) return fmi3Error;
        memcpy(v, values + at, n * sizeof *v);
        at += n;
    }
    return at == nValues ? fmi3OK : fmi3Error;
}
fmi3Status fmi3GetInt32(fmi3Instance c, const fmi3ValueReference vr[], size_t nvr,
                        fmi3Int32 values[], size_t nValues) {
    if (nvr != 1 || vr[0] != SIGN || nValues != 1) return fmi3Error;
    values[0] = ((Model *)c)->sign;
    return fmi3OK;
}
fmi3Status fmi3SetInt32(fmi3Instance c, const fmi3ValueReference vr[], size_t nvr,
                        const fmi3Int32 values[], size_t nValues) {
    Model *m = c;
    if (nvr != 1 || vr[0] != SIGN || nValues != 1 || m->initialized
        || values[0] < -1 || values[0] > 1) return fmi3Error;
    m->sign = values[0];
    return fmi3OK;
}
fmi3Status fmi3GetBoolean(fmi3Instance c, const fmi3ValueReference vr[], size_t nvr,
                          fmi3Boolean values[], size_t nValues) {
    if (nvr != 1 || vr[0] != FROZEN || nValues != 1) return fmi3Error;
    values[0] = ((Model *)c)->frozen;
    return fmi3OK;
}
fmi3Status fmi3SetBoolean(fmi3Instance c, const fmi3ValueReference vr[], size_t nvr,
                          const fmi3Boolean values[], size_t nValues) {
    Model *m = c;
    if (nvr != 1 || vr[0] != FROZEN || nValues != 1 || m->initialized) return fmi3Error;
    m->frozen = values[0];
    return fmi3OK;
}
fmi3Status fmi3DoStep(fmi3Instance c, fmi3Float64 t, fmi3Float64 h, fmi3Boolean noSetPrior,
                      fmi3Boolean *eventHandlingNeeded, fmi3Boolean *terminateSimulation,
                      fmi3Boolean *earlyReturn, fmi3Float64 *lastSuccessfulTime) {
    Model *m = c;
    for (int i = 0; i < 2 && !m->frozen; i++) m->y[i] += m->sign * m->gain * m->u[i] * h;
    m->time = t + h;
    *eventHandlingNeeded = *terminateSimulation = *earlyReturn = fmi3False;
    *lastSuccessfulTime = m->time;
    return fmi3OK;
}

/* What this FMU does not do. */
#define NO(name, ...) fmi3Status name(fmi3Instance c, __VA_ARGS__) { return fmi3Error; }
#define NO_GET(T) NO(fmi3Get##T, const fmi3ValueReference vr[], size_t nvr, fmi3##T v[], size_t n)
#define NO_SET(T) NO(fmi3Set##T, const fmi3ValueReference vr[], size_t nvr, const fmi3##T v[], size_t n)
NO_GET(Float32) NO_GET(Int8) NO_GET(UInt8) NO_GET(Int16) NO_GET(UInt16) NO_GET(UInt32)
NO_GET(Int64) NO_GET(UInt64) NO_GET(String)
NO_SET(Float32) NO_SET(Int8) NO_SET(UInt8) NO_SET(Int16) NO_SET(UInt16) NO_SET(UInt32)
NO_SET(Int64) NO_SET(UInt64) NO_SET(String)
NO(fmi3GetBinary, const fmi3ValueReference vr[], size_t nvr, size_t s[], fmi3Binary v[], size_t n)
NO(fmi3SetBinary, const fmi3ValueReference vr[], size_t nvr, const size_t s[], const fmi3Binary v[], size_t n)
NO(fmi3GetClock, const fmi3ValueReference vr[], size_t nvr, fmi3Clock v[])
NO(fmi3SetClock, const fmi3ValueReference vr[], size_t nvr, const fmi3Clock v[])
NO(fmi3GetNumberOfVariableDependencies, fmi3ValueReference vr, size_t *n)
NO(fmi3GetVariableDependencies, fmi3ValueReference d, size_t e[], fmi3ValueReference i[], size_t ie[], fmi3DependencyKind k[], size_t n)
NO(fmi3GetFMUState, fmi3FMUState *s)
NO(fmi3SetFMUState, fmi3FMUState s)
NO(fmi3FreeFMUState, fmi3FMUState *s)
NO(fmi3SerializedFMUStateSize, fmi3FMUState s, size_t *n)
NO(fmi3SerializeFMUState, fmi3FMUState s, fmi3Byte b[], size_t n)
NO(fmi3DeserializeFMUState, const fmi3Byte b[], size_t n, fmi3FMUState *s)
NO(fmi3GetDirectionalDerivative, const fmi3ValueReference u[], size_t nu, const fmi3ValueReference k[], size_t nk, const fmi3Float64 s[], size_t ns, fmi3Float64 r[], size_t nr)
NO(fmi3GetAdjointDerivative, const fmi3ValueReference u[], size_t nu, const fmi3ValueReference k[], size_t nk, const fmi3Float64 s[], size_t ns, fmi3Float64 r[], size_t nr)
NO(fmi3GetIntervalDecimal, const fmi3ValueReference vr[], size_t n, fmi3Float64 i[], fmi3IntervalQualifier q[])
NO(fmi3GetIntervalFraction, const fmi3ValueReference vr[], size_t n, fmi3UInt64 c_[], fmi3UInt64 r[], fmi3IntervalQualifier q[])
NO(fmi3GetShiftDecimal, const fmi3ValueReference vr[], size_t n, fmi3Float64 s[])
NO(fmi3GetShiftFraction, const fmi3ValueReference vr[], size_t n, fmi3UInt64 c_[], fmi3UInt64 r[])
NO(fmi3SetIntervalDecimal, const fmi3ValueReference vr[], size_t n, const fmi3Float64 i[])
NO(fmi3SetIntervalFraction, const fmi3ValueReference vr[], size_t n, const fmi3UInt64 c_[], const fmi3UInt64 r[])
NO(fmi3SetShiftDecimal, const fmi3ValueReference vr[], size_t n, const fmi3Float64 s[])
NO(fmi3SetShiftFraction, const fmi3ValueReference vr[], size_t n, const fmi3UInt64 c_[], const fmi3UInt64 r[])
NO(fmi3UpdateDiscreteStates, fmi3Boolean *a, fmi3Boolean *b, fmi3Boolean *d, fmi3Boolean *e, fmi3Boolean *f, fmi3Float64 *g)
NO(fmi3CompletedIntegratorStep, fmi3Boolean a, fmi3Boolean *b, fmi3Boolean *d)
NO(fmi3SetTime, fmi3Float64 t)
NO(fmi3SetContinuousStates, const fmi3Float64 x[], size_t n)
NO(fmi3GetContinuousStateDerivatives, fmi3Float64 x[], size_t n)
NO(fmi3GetEventIndicators, fmi3Float64 x[], size_t n)
NO(fmi3GetContinuousStates, fmi3Float64 x[], size_t n)
NO(fmi3GetNominalsOfContinuousStates, fmi3Float64 x[], size_t n)
NO(fmi3GetNumberOfEventIndicators, size_t *n)
NO(fmi3GetNumberOfContinuousStates, size_t *n)
NO(fmi3GetOutputDerivatives, const fmi3ValueReference vr[], size_t nvr, const fmi3Int32 o[], fmi3Float64 v[], size_t n)
NO(fmi3ActivateModelPartition, fmi3ValueReference vr, fmi3Float64 t)
fmi3Status fmi3EnterEventMode(fmi3Instance c) { return fmi3Error; }
fmi3Status fmi3EnterConfigurationMode(fmi3Instance c) { return fmi3Error; }
fmi3Status fmi3ExitConfigurationMode(fmi3Instance c) { return fmi3Error; }
fmi3Status fmi3EvaluateDiscreteStates(fmi3Instance c) { return fmi3Error; }
fmi3Status fmi3EnterContinuousTimeMode(fmi3Instance c) { return fmi3Error; }
fmi3Status fmi3EnterStepMode(fmi3Instance c) { return fmi3Error; }
fmi3Instance fmi3InstantiateModelExchange(fmi3String name, fmi3String token, fmi3String resources,
        fmi3Boolean visible, fmi3Boolean logging, fmi3InstanceEnvironment env,
        fmi3LogMessageCallback log) { return NULL; }
fmi3Instance fmi3InstantiateScheduledExecution(fmi3String name, fmi3String token,
        fmi3String resources, fmi3Boolean visible, fmi3Boolean logging,
        fmi3InstanceEnvironment env, fmi3LogMessageCallback log,
        fmi3ClockUpdateCallback clockUpdate, fmi3LockPreemptionCallback lock,
        fmi3UnlockPreemptionCallback unlock) { return NULL; }
