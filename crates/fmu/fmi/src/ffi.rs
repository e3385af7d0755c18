//! Helpers of the C boundary shared by the front-ends: slices and references from the
//! host's pointers (null accepted only where nothing is read or written), finiteness
//! checks, C strings in and out, and the text of a caught panic.

use std::ffi::{CStr, CString, c_char};

/// Text of a caught panic payload.
pub fn panic_message(payload: &(dyn std::any::Any + Send)) -> String {
    if let Some(s) = payload.downcast_ref::<&str>() {
        s.to_string()
    } else if let Some(s) = payload.downcast_ref::<String>() {
        s.clone()
    } else {
        "unknown panic payload".to_string()
    }
}

/// Refuses a C array of `n` > 0 elements that is null or longer than memory can
/// hold, without forming a slice (so a caller can check this before other arguments).
pub fn check_array<T>(ptr: *const T, n: usize, what: &str) -> Result<(), String> {
    if n > 0 && ptr.is_null() {
        Err(format!("{what} is a null pointer (length {n})"))
    } else if !fits_in_memory::<T>(n) {
        Err(format!(
            "{what}: a length of {n} elements exceeds the address space"
        ))
    } else {
        Ok(())
    }
}

/// A slice from a C array; null is accepted only for an empty array.
///
/// # Safety
/// A non-null `ptr` must be valid for `n` elements for the returned lifetime.
pub unsafe fn input_slice<'a, T>(ptr: *const T, n: usize, what: &str) -> Result<&'a [T], String> {
    if n == 0 {
        Ok(&[])
    } else {
        check_array(ptr, n, what)?;
        // SAFETY: non-null and, by the caller's contract, valid for n elements.
        Ok(unsafe { std::slice::from_raw_parts(ptr, n) })
    }
}

/// A mutable slice over a C output array; null is accepted only for an empty array.
///
/// # Safety
/// A non-null `ptr` must be valid and unaliased for `n` elements for the returned
/// lifetime.
pub unsafe fn output_slice<'a, T>(
    ptr: *mut T,
    n: usize,
    what: &str,
) -> Result<&'a mut [T], String> {
    if n == 0 {
        Ok(&mut [])
    } else {
        check_array(ptr, n, what)?;
        // SAFETY: non-null and, by the caller's contract, valid for n elements.
        Ok(unsafe { std::slice::from_raw_parts_mut(ptr, n) })
    }
}

/// A single output value behind a pointer.
///
/// # Safety
/// A non-null `ptr` must be valid and unaliased for the returned lifetime.
pub unsafe fn output_ref<'a, T>(ptr: *mut T, what: &str) -> Result<&'a mut T, String> {
    if ptr.is_null() {
        Err(format!("{what} is a null pointer"))
    } else {
        // SAFETY: non-null and, by the caller's contract, valid.
        Ok(unsafe { &mut *ptr })
    }
}

pub fn check_finite(value: f64, what: &str) -> Result<f64, String> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(format!("{what} = {value} is not finite"))
    }
}

/// A C string argument as UTF-8 text.
///
/// # Safety
/// A non-null `ptr` must point to a NUL-terminated string that lives for `'a`.
pub unsafe fn text<'a>(ptr: *const c_char, what: &str) -> Result<&'a str, String> {
    if ptr.is_null() {
        return Err(format!("{what} is a null pointer"));
    }
    // SAFETY: non-null, and NUL-terminated by the caller's contract.
    let s = unsafe { CStr::from_ptr(ptr) };
    s.to_str().map_err(|_| format!("{what} is not UTF-8"))
}

/// `message` as a C string, NUL bytes (which would cut it short) replaced by spaces.
pub fn c_string(message: &str) -> CString {
    CString::new(message.replace('\0', " ")).unwrap_or_default()
}

/// Calls `f` with `text` as a NUL-terminated C string, NUL bytes replaced by spaces
/// and, with `double_percent`, every '%' doubled; built in a buffer on the stack when
/// it fits (a log message: no allocation, and nothing to leak when a callback is left
/// with longjmp), on the heap otherwise.
pub fn with_c_text<R>(text: &str, double_percent: bool, f: impl FnOnce(*const c_char) -> R) -> R {
    let mut buffer = [0u8; 512];
    let mut n = 0;
    for &b in text.as_bytes() {
        let out: &[u8] = match b {
            0 => b" ",
            b'%' if double_percent => b"%%",
            _ => std::slice::from_ref(&b),
        };
        if n + out.len() >= buffer.len() {
            let escaped = if double_percent {
                text.replace('%', "%%")
            } else {
                text.to_string()
            };
            return f(c_string(&escaped).as_ptr());
        }
        buffer[n..n + out.len()].copy_from_slice(out);
        n += out.len();
    }
    f(buffer.as_ptr().cast())
}

/// Whether `n` elements of `T` can exist at all (a slice may span at most isize::MAX
/// bytes): a larger count from the host is refused before any slice is formed.
fn fits_in_memory<T>(n: usize) -> bool {
    n.checked_mul(std::mem::size_of::<T>())
        .is_some_and(|bytes| bytes <= isize::MAX as usize)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_length_beyond_the_address_space_is_refused_before_a_slice_is_formed() {
        // Expected: from_raw_parts requires n * size_of::<T>() <= isize::MAX (std docs);
        // 2^60 f64 are 2^63 bytes, one byte more than isize::MAX allows.
        let x = [1.0_f64; 3];
        let huge = 1_usize << 60;
        let err = unsafe { input_slice(x.as_ptr(), huge, "values[]") }.unwrap_err();
        assert!(err.contains("exceeds the address space"), "{err}");
        let mut y = [0.0_f64; 3];
        let err = unsafe { output_slice(y.as_mut_ptr(), huge, "values[]") }.unwrap_err();
        assert!(err.contains("exceeds the address space"), "{err}");
        assert_eq!(
            unsafe { input_slice(x.as_ptr(), 3, "values[]") }.unwrap(),
            &x
        );
        assert!(fits_in_memory::<f64>((isize::MAX as usize) / 8));
        assert!(!fits_in_memory::<f64>((isize::MAX as usize) / 8 + 1));
    }

    #[test]
    fn c_text_is_the_c_string_with_percent_signs_doubled_on_the_stack_or_the_heap() {
        // Expected: the same bytes as c_string (and, doubled, as replace('%', "%%"))
        // for a short text (stack buffer) and one longer than the buffer (heap).
        let read = |p: *const c_char| unsafe { CStr::from_ptr(p) }.to_str().unwrap().to_string();
        assert_eq!(with_c_text("50% of\0x", true, read), "50%% of x");
        assert_eq!(with_c_text("50% of\0x", false, read), "50% of x");
        let long = "%".repeat(300) + "\0" + &"y".repeat(300);
        let expected = "%".repeat(600) + " " + &"y".repeat(300);
        assert_eq!(with_c_text(&long, true, read), expected);
        assert_eq!(
            with_c_text(&long, false, read),
            c_string(&long).to_str().unwrap()
        );
        assert_eq!(with_c_text("", true, read), "");
    }
}
