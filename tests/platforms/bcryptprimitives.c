/* Test-only stand-in for Windows' bcryptprimitives.dll, which Wine 8 lacks: Rust's
 * standard library (1.78 and newer) imports ProcessPrng from it to seed its hash
 * maps. Windows 10 and newer ship the real DLL; this one is built by
 * tests/python/test_platforms.py beside the test host under Wine and never goes into
 * an FMU. ProcessPrng fills the buffer from advapi32's RtlGenRandom
 * (SystemFunction036), which Wine has; it takes at most 4 GiB - 1 a call, so a longer
 * buffer is filled in pieces. */
#include <windows.h>

BOOLEAN WINAPI SystemFunction036(PVOID buffer, ULONG length);

__declspec(dllexport) BOOL WINAPI ProcessPrng(PBYTE data, SIZE_T length)
{
    while (length > 0) {
        ULONG piece = length > 0xffffffffu ? 0xffffffffu : (ULONG)length;
        if (!SystemFunction036(data, piece))
            return FALSE;
        data += piece;
        length -= piece;
    }
    return TRUE;
}
