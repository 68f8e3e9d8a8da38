//! C arguments as Rust values, for both C interfaces: strings, arrays (a pointer and a
//! count) and output slots. A NULL pointer is never dereferenced; an array may be NULL only
//! when its count is 0. Each interface words the refusal in its own terms.

use std::ffi::{CStr, c_char};

/// An array announced with `count` elements but passed as NULL.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct NullArray {
    pub count: usize,
}

/// A C string as text (`None` for NULL); invalid UTF-8 is replaced, not refused.
///
/// # Safety
/// `s` is NULL or a NUL-terminated string.
pub unsafe fn text(s: *const c_char) -> Option<String> {
    (!s.is_null()).then(|| unsafe { CStr::from_ptr(s) }.to_string_lossy().into_owned())
}

/// A C array as a slice.
///
/// # Safety
/// `p` is NULL or points to `count` valid elements.
pub unsafe fn slice<'a, T>(p: *const T, count: usize) -> Result<&'a [T], NullArray> {
    match (p.is_null(), count) {
        (_, 0) => Ok(&[]),
        (true, _) => Err(NullArray { count }),
        (false, _) => Ok(unsafe { std::slice::from_raw_parts(p, count) }),
    }
}

/// A writable C array as a slice.
///
/// # Safety
/// `p` is NULL or points to `count` valid elements not aliased elsewhere.
pub unsafe fn slice_mut<'a, T>(p: *mut T, count: usize) -> Result<&'a mut [T], NullArray> {
    match (p.is_null(), count) {
        (_, 0) => Ok(&mut []),
        (true, _) => Err(NullArray { count }),
        (false, _) => Ok(unsafe { std::slice::from_raw_parts_mut(p, count) }),
    }
}

/// An output slot (`None` for NULL).
///
/// # Safety
/// `p` is NULL or valid for writes.
pub unsafe fn slot<'a, T>(p: *mut T) -> Option<&'a mut T> {
    unsafe { p.as_mut() }
}
