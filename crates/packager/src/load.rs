//! Opens an FMU's cdylib with dlopen and lends its [`Description`] through the symbol
//! `robofmu_fmu_description`, after the header's check
//! ([`Header::check`]: magic, versions, fingerprint of this build).

use robofmu_fmi::description::{Description, Header, SYMBOL};
use std::ffi::{CStr, CString};
use std::path::Path;

/// A loaded cdylib, closed when dropped.
struct Library(*mut libc::c_void);

impl Drop for Library {
    fn drop(&mut self) {
        // SAFETY: the handle came from a successful dlopen and is closed once; nothing
        // borrowed from the library outlives `with_description`, which owns it.
        unsafe { libc::dlclose(self.0) };
    }
}

fn dl_error() -> String {
    // SAFETY: dlerror returns NULL or a NUL-terminated string valid until the next dl call.
    let e = unsafe { libc::dlerror() };
    if e.is_null() {
        "unknown dlopen error".to_string()
    } else {
        // SAFETY: checked non-NULL above.
        unsafe { CStr::from_ptr(e) }.to_string_lossy().into_owned()
    }
}

/// Calls `f` with the description of the cdylib at `path`; the error names the file
/// and the fix.
pub fn with_description<T>(
    path: &Path,
    f: impl FnOnce(&Description) -> Result<T, String>,
) -> Result<T, String> {
    let shown = path.display();
    let c_path = CString::new(path.as_os_str().as_encoded_bytes())
        .map_err(|_| format!("{shown}: the path holds a NUL byte"))?;
    // SAFETY: dlopen of a file path; the library's initializers are those of an FMU.
    let handle = unsafe { libc::dlopen(c_path.as_ptr(), libc::RTLD_NOW | libc::RTLD_LOCAL) };
    if handle.is_null() {
        return Err(format!(
            "{shown}: cannot load ({}); build it with `cargo build --release --workspace`",
            dl_error()
        ));
    }
    let library = Library(handle);
    let symbol = CString::new(SYMBOL).expect("a symbol name without NUL");
    // SAFETY: dlsym on a live handle with a NUL-terminated name.
    let address = unsafe { libc::dlsym(library.0, symbol.as_ptr()) };
    if address.is_null() {
        return Err(format!(
            "{shown}: no symbol {SYMBOL}; end the FMU crate with `robofmu_fmi::export_fmu!(Type);`"
        ));
    }
    // SAFETY: export_fmu! defines the symbol as `extern "C" fn() -> *const Header`.
    let header_of: extern "C" fn() -> *const Header = unsafe { std::mem::transmute(address) };
    // SAFETY: it returns the address of a static of the loaded library, alive until the
    // library is closed at the end of this function.
    let header = unsafe { header_of().as_ref() }
        .ok_or_else(|| format!("{shown}: {SYMBOL} returned no header"))?;
    let lend = header.check().map_err(|e| format!("{shown}: {e}"))?;
    let mut f = Some(f);
    let mut result = Err(format!("{shown}: {SYMBOL} lent no description"));
    lend(&mut |d| {
        result = match (d, f.take()) {
            (Ok(d), Some(f)) => f(d),
            (Err(e), _) => Err(format!("{shown}: the model's description is invalid: {e}")),
            (Ok(_), None) => Err(format!("{shown}: {SYMBOL} lent its description twice")),
        };
    });
    drop(library);
    result
}
