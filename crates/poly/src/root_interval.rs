//! [`RootInterval`]: an interval known to hold exactly one distinct real root.

/// An isolating interval: exactly one distinct real root `r` of the polynomial it came from
/// lies in it.
///
/// When `lo < hi` the root is in the **open** interval `(lo, hi)`; when `lo == hi` the interval
/// is the single point and `r = lo` exactly ([`is_point`](RootInterval::is_point)). Intervals
/// returned together are disjoint and sorted.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct RootInterval<T> {
    /// Lower end.
    pub lo: T,
    /// Upper end.
    pub hi: T,
}

impl<T: PartialEq> RootInterval<T> {
    /// True when the interval is a single point, which is then exactly the root.
    pub fn is_point(&self) -> bool {
        self.lo == self.hi
    }
}

impl RootInterval<f64> {
    /// Width `hi − lo`.
    ///
    /// # Accuracy
    /// One rounding: within half an ulp of the true width.
    pub fn width(&self) -> f64 {
        self.hi - self.lo
    }

    /// True when `x` is in the interval (the open interval, or the point).
    pub fn contains(&self, x: f64) -> bool {
        if self.is_point() {
            x == self.lo
        } else {
            self.lo < x && x < self.hi
        }
    }
}
