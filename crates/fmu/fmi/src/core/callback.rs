//! Calls into the host's callbacks (logger, intermediate update).
//!
//! The callback types are `extern "C-unwind"`: a host callback may leave by unwinding
//! (a C++ exception, `pthread_exit`, a thread cancelled while in the callback), and
//! calling a function that unwinds through an `extern "C"` pointer would be undefined
//! behaviour in Rust. The unwind is defined, but the FMU cannot let it pass: its
//! frames hold the instance busy and catch Rust panics at every entry point (a foreign
//! exception caught there is an abort of the Rust runtime, with a less clear message).
//! So every call into the host goes through [`host`], which ends the process with a
//! message naming the callback when the callback unwinds (docs/reliability.md,
//! "Leaving a callback").

/// Ends the process when dropped: only during an unwind out of the host's callback.
struct AbortOnUnwind(&'static str);

impl Drop for AbortOnUnwind {
    fn drop(&mut self) {
        let parts = [
            "robofmu FMU: fatal: the host's ",
            self.0,
            " callback did not return: it unwound into the FMU (a C++ exception, \
             pthread_exit or a thread cancellation). FMI callbacks must return to the FMU; \
             the process is aborted.\n",
        ];
        for part in parts {
            // SAFETY: writes bytes of a live &str to stderr (no allocation, no lock: the
            // unwinding thread may hold any lock of the host).
            unsafe { libc::write(2, part.as_ptr().cast(), part.len() as _) };
        }
        // SAFETY: ends the process; nothing runs after it.
        unsafe { libc::abort() }
    }
}

thread_local! {
    /// The stack address of the innermost host callback this thread is running (0:
    /// none). A callback left with longjmp leaves it set: [`inside_callback`] then
    /// finds the caller above that frame. (A native thread-local without destructor,
    /// as handles' MARK.)
    static CALLBACK_FRAME: std::cell::Cell<usize> = const { std::cell::Cell::new(0) };
}

/// A stack address in the caller's frame (the stack grows down on every target).
#[inline(always)]
pub fn stack_mark() -> usize {
    let mark = 0u8;
    std::hint::black_box(&mark) as *const u8 as usize
}

/// Whether `mark`, a [`stack_mark`] of the current call, lies inside a host callback
/// that this thread is running (a call from the callback: re-entrant). False when the
/// innermost recorded callback frame lies below `mark`: that callback was left
/// without returning (longjmp), and its record is cleared.
pub fn inside_callback(mark: usize) -> bool {
    CALLBACK_FRAME.with(|frame| {
        let at = frame.get();
        if at != 0 && mark >= at {
            frame.set(0);
        }
        at != 0 && mark < at
    })
}

/// Runs `call`, a call of the host's callback `what` ("logger", ...); aborts the
/// process with a message if it unwinds.
///
/// Never inlined: its frame must keep a landing pad of its own whose only action is the
/// guard's cleanup. Inlined into an `extern "C"` entry point (as whole-program LTO
/// does), a forced unwind (`pthread_exit`, a cancellation) crossed the FMU's frames
/// without the abort (the leave test's intermediateUpdate cases; a C++ exception still
/// aborted). The likely cause: the call site's first action became the entry point's
/// cannot-unwind filter, which Rust's personality lets a forced unwind pass.
#[inline(never)]
pub fn host<R>(what: &'static str, call: impl FnOnce() -> R) -> R {
    let guard = AbortOnUnwind(what);
    // In this frame, above every frame of the callback.
    let mark = stack_mark();
    let outer = CALLBACK_FRAME.with(|frame| frame.replace(mark));
    let result = call();
    CALLBACK_FRAME.with(|frame| frame.set(outer));
    std::mem::forget(guard);
    result
}
