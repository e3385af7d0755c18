//! Where a scalar of the table stands in an array: the [`ArrayElement`] metadata that
//! FMI 2.0 names (`base[i]`) and an FMI 3.0 array (`base` with a `<Dimension>`) are
//! made from. The array declaration itself is [`arrays`](super::arrays).

/// Position of a scalar in an array variable `base[1..length]`: the FMI 2.0 name is
/// `base[index + 1]` (`der(base[index + 1])` for the derivative of an array state);
/// an FMI 3.0 front-end declares one array `base` (`der(base)`) with
/// `<Dimension start="length"/>` from its elements.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ArrayElement {
    pub base: &'static str,
    /// 0-based.
    pub index: usize,
    pub length: usize,
    /// Step of the value references from one element to the next.
    pub stride: u32,
    /// The element is the time derivative of `base[index + 1]`.
    pub derivative: bool,
}

impl ArrayElement {
    /// The FMI 2.0 name of element `index`.
    pub fn name(&self, index: usize) -> String {
        if self.derivative {
            numbered(&["der(", self.base, "["], index + 1, "])")
        } else {
            numbered(&[self.base, "["], index + 1, "]")
        }
    }

    /// Value reference of element `index` of the array whose element `self.index`
    /// has the value reference `vr`.
    pub fn value_reference(&self, vr: u32, index: usize) -> u32 {
        vr - self.index as u32 * self.stride + index as u32 * self.stride
    }
}

/// `prefix` (its parts joined), `number` and `suffix` in one allocation, without the
/// formatting machinery: every element name is built so at instantiation.
pub(crate) fn numbered(prefix: &[&str], number: usize, suffix: &str) -> String {
    let length: usize = prefix.iter().map(|p| p.len()).sum::<usize>() + 20 + suffix.len();
    let mut out = String::with_capacity(length);
    prefix.iter().for_each(|p| out.push_str(p));
    push_number(&mut out, number);
    out.push_str(suffix);
    out
}

fn push_number(out: &mut String, n: usize) {
    if n >= 10 {
        push_number(out, n / 10);
    }
    out.push(char::from(b'0' + (n % 10) as u8));
}
