//! C arguments as Rust values, for both C interfaces: strings, arrays (a pointer and a
//! count) and output slots. A NULL pointer is never dereferenced; an array may be NULL only
//! when its count is 0. Each interface words the refusal in its own terms.

use std::ffi::{CStr, c_char};

/// Why a C array (a pointer and a count) is not one: NULL with a count, or a count whose
/// bytes exceed the largest object the address space can hold (`isize::MAX` bytes, the
/// bound of every Rust slice), checked before anything is read or copied.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BadArray {
    Null { count: usize },
    TooLong { count: usize, size: usize },
}

impl BadArray {
    /// The reason, for an array called `what`.
    pub fn reason(&self, what: &str) -> String {
        match *self {
            Self::Null { count } => format!("{what} is NULL but {count} elements were announced"),
            Self::TooLong { count, size } => format!(
                "{what}: count = {count} is invalid: {count} elements of {size} bytes exceed the largest array the address space can hold ({} bytes)",
                isize::MAX
            ),
        }
    }
}

/// `count` elements of `T` fit in one object (`count * size_of::<T>() <= isize::MAX`).
fn fits<T>(count: usize) -> Result<(), BadArray> {
    let size = size_of::<T>().max(1);
    if count <= isize::MAX as usize / size {
        Ok(())
    } else {
        Err(BadArray::TooLong { count, size })
    }
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
pub unsafe fn slice<'a, T>(p: *const T, count: usize) -> Result<&'a [T], BadArray> {
    match (p.is_null(), count) {
        (_, 0) => Ok(&[]),
        (true, _) => Err(BadArray::Null { count }),
        (false, _) => fits::<T>(count).map(|()| unsafe { std::slice::from_raw_parts(p, count) }),
    }
}

/// A copy of `values` in memory allocated fallibly: `None` where the allocator refuses
/// (a count the address space could hold but the memory cannot), never an abort.
pub fn try_copy<T: Copy>(values: &[T]) -> Option<Vec<T>> {
    let mut out = Vec::new();
    out.try_reserve_exact(values.len()).ok()?;
    out.extend_from_slice(values);
    Some(out)
}

/// A writable C array as a slice.
///
/// # Safety
/// `p` is NULL or points to `count` valid elements not aliased elsewhere.
pub unsafe fn slice_mut<'a, T>(p: *mut T, count: usize) -> Result<&'a mut [T], BadArray> {
    match (p.is_null(), count) {
        (_, 0) => Ok(&mut []),
        (true, _) => Err(BadArray::Null { count }),
        (false, _) => {
            fits::<T>(count).map(|()| unsafe { std::slice::from_raw_parts_mut(p, count) })
        }
    }
}

/// An output slot (`None` for NULL).
///
/// # Safety
/// `p` is NULL or valid for writes.
pub unsafe fn slot<'a, T>(p: *mut T) -> Option<&'a mut T> {
    unsafe { p.as_mut() }
}
