/* The link-time stand-in for libgcc_s.so.1 of every Linux FMU binary
 * (scripts/build-fmus.sh): the unwinder functions the Rust standard library calls,
 * with libgcc_s's names and symbol versions (libgcc_s.map). The FMU is linked against
 * this stub instead of the LLVM libunwind that zig would otherwise copy into it, so it
 * needs libgcc_s.so.1 and at run time calls the unwinder of the process: the one the
 * host's C++ exceptions, pthread_exit and pthread_cancel unwind with. With a copy of its
 * own, the FMU's personality routine was handed the other unwinder's context and the
 * process jumped into data (issue 42). The bodies are never run. */
void _Unwind_Backtrace(void) {}
void _Unwind_DeleteException(void) {}
void _Unwind_FindEnclosingFunction(void) {}
void _Unwind_Find_FDE(void) {}
void _Unwind_ForcedUnwind(void) {}
void _Unwind_GetCFA(void) {}
void _Unwind_GetDataRelBase(void) {}
void _Unwind_GetGR(void) {}
void _Unwind_GetIP(void) {}
void _Unwind_GetIPInfo(void) {}
void _Unwind_GetLanguageSpecificData(void) {}
void _Unwind_GetRegionStart(void) {}
void _Unwind_GetTextRelBase(void) {}
void _Unwind_RaiseException(void) {}
void _Unwind_Resume(void) {}
void _Unwind_Resume_or_Rethrow(void) {}
void _Unwind_SetGR(void) {}
void _Unwind_SetIP(void) {}
