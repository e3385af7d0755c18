//! The one loader of a shared library in robofmu, [`Library`]: the packager
//! (`crates/build/packager`) reads each FMU cdylib's description of itself through it,
//! and the test host (`crates/test/fmi-host`) looks up the FMI functions of a binary
//! with it.
//!
//! Linux and macOS: `dlopen(path, RTLD_NOW | RTLD_LOCAL)`, `dlsym`, `dlclose`, as a C
//! importer does (every symbol resolved at load time, none made visible to later
//! libraries). Windows: `LoadLibraryW`, `GetProcAddress`, `FreeLibrary`.

use std::ffi::{CStr, c_void};
use std::path::Path;

/// A loaded library, closed when dropped (after every instance made from it was freed).
pub struct Library(*mut c_void);

// A module handle is a plain address; the loader's calls may come from any thread.
unsafe impl Send for Library {}
unsafe impl Sync for Library {}

impl Library {
    /// Opens the library at `path`; the error is the system's reason (the caller
    /// names the file and the fix).
    pub fn open(path: &Path) -> Result<Library, String> {
        let handle = open(path)?;
        if handle.is_null() {
            Err(last_error())
        } else {
            Ok(Library(handle))
        }
    }

    /// The address of the exported symbol `name`, null when it is missing.
    pub fn symbol(&self, name: &CStr) -> *mut c_void {
        symbol(self.0, name)
    }
}

impl Drop for Library {
    fn drop(&mut self) {
        close(self.0);
    }
}

#[cfg(unix)]
fn open(path: &Path) -> Result<*mut c_void, String> {
    let c_path = std::ffi::CString::new(path.as_os_str().as_encoded_bytes())
        .map_err(|_| "the path holds a NUL byte".to_string())?;
    // SAFETY: dlopen of a NUL-terminated path; the library's initializers run.
    Ok(unsafe { libc::dlopen(c_path.as_ptr(), libc::RTLD_NOW | libc::RTLD_LOCAL) })
}

#[cfg(unix)]
fn symbol(handle: *mut c_void, name: &CStr) -> *mut c_void {
    // SAFETY: dlsym on a live handle with a NUL-terminated name.
    unsafe { libc::dlsym(handle, name.as_ptr()) }
}

#[cfg(unix)]
fn close(handle: *mut c_void) {
    // SAFETY: the handle came from a successful dlopen and is closed once.
    unsafe { libc::dlclose(handle) };
}

#[cfg(unix)]
fn last_error() -> String {
    // SAFETY: dlerror returns null or a NUL-terminated message valid until the next
    // dl call of this thread.
    let e = unsafe { libc::dlerror() };
    if e.is_null() {
        "unknown dlopen error".to_string()
    } else {
        // SAFETY: checked non-null above.
        unsafe { CStr::from_ptr(e) }.to_string_lossy().into_owned()
    }
}

#[cfg(windows)]
#[link(name = "kernel32")]
unsafe extern "system" {
    fn LoadLibraryW(name: *const u16) -> *mut c_void;
    fn GetProcAddress(module: *mut c_void, name: *const std::ffi::c_char) -> *mut c_void;
    fn FreeLibrary(module: *mut c_void) -> i32;
    fn GetLastError() -> u32;
}

#[cfg(windows)]
fn open(path: &Path) -> Result<*mut c_void, String> {
    use std::os::windows::ffi::OsStrExt;
    let wide: Vec<u16> = path.as_os_str().encode_wide().chain([0]).collect();
    if wide[..wide.len() - 1].contains(&0) {
        return Err("the path holds a NUL character".to_string());
    }
    // SAFETY: LoadLibraryW of a NUL-terminated wide path.
    Ok(unsafe { LoadLibraryW(wide.as_ptr()) })
}

#[cfg(windows)]
fn symbol(handle: *mut c_void, name: &CStr) -> *mut c_void {
    // SAFETY: GetProcAddress on a live module with a NUL-terminated name.
    unsafe { GetProcAddress(handle, name.as_ptr()) }
}

#[cfg(windows)]
fn close(handle: *mut c_void) {
    // SAFETY: the module came from a successful LoadLibraryW and is freed once.
    unsafe { FreeLibrary(handle) };
}

#[cfg(windows)]
fn last_error() -> String {
    // SAFETY: no arguments; reads the calling thread's last error.
    format!("error {}", unsafe { GetLastError() })
}

#[cfg(all(test, target_os = "linux"))]
mod tests {
    use super::*;

    #[test]
    fn a_missing_file_is_refused_with_the_system_reason() {
        // Expected: dlopen's own message, which names the file (glibc's dlerror).
        let path = Path::new("/nonexistent/robofmu-loader-test.so");
        let error = Library::open(path).err().expect("no such file");
        assert!(error.contains("robofmu-loader-test.so"), "{error}");
    }

    #[test]
    fn the_c_library_exports_malloc_and_not_a_made_up_name() {
        // Expected: libc.so.6 exports malloc (every glibc system), and no symbol of this
        // made-up name.
        let library = Library::open(Path::new("libc.so.6")).expect("glibc is loaded");
        assert!(!library.symbol(c"malloc").is_null());
        assert!(library.symbol(c"robofmu_no_such_symbol").is_null());
    }
}
