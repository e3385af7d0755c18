//! Opens an FMU's cdylib with dlopen and lends its [`Description`] through the symbol
//! `robofmu_fmu_description`, after the header's check
//! ([`Header::check`]: magic, versions, fingerprint of this build).

use robofmu_fmi::description::{Description, Header, SYMBOL};
use robofmu_fmi_loader::Library;
use std::ffi::CString;
use std::path::Path;

/// Calls `f` with the description of the cdylib at `path`; the error names the file
/// and the fix.
pub fn with_description<T>(
    path: &Path,
    f: impl FnOnce(&Description) -> Result<T, String>,
) -> Result<T, String> {
    let shown = path.display();
    let library = Library::open(path).map_err(|e| {
        format!("{shown}: cannot load ({e}); build it with `cargo build --release --workspace`")
    })?;
    let symbol = CString::new(SYMBOL).expect("a symbol name without NUL");
    let address = library.symbol(&symbol);
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
