//! [`SlowestCell`]: the image cell that took longest to trace and what its rays asked of the
//! root finder, so `--stats` shows why a render is slow (issue 13, item 10): a ray whose
//! polynomial `f64` cannot decide goes to adaptive precision and then to exact rational
//! arithmetic (`paper-notes/isolation.md`), each step orders of magnitude dearer.

use std::time::Duration;

use poly::RootStats;

use super::SurfaceKind;

/// The root queries of some rays and how far they escalated beyond `f64`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Escalations {
    /// Root queries.
    pub queries: u64,
    /// Isolation pieces decided in adaptive precision ([`RootStats::adaptive_pieces`]).
    pub adaptive_pieces: u64,
    /// Of those, pieces that needed more than double-double precision.
    pub multiprecision_pieces: u64,
    /// Queries that built the exact rational Sturm sequence ([`RootStats::exact_fallbacks`]).
    pub exact_fallbacks: u64,
    /// Refinements finished in adaptive precision.
    pub adaptive_refines: u64,
    /// Refinements finished with exact rational signs.
    pub refine_fallbacks: u64,
    /// Queries whose restriction's rounding left a sign undecided
    /// ([`RootStats::slack_limited`]): the ray was then restricted exactly, or is undecided.
    pub slack_limited: u64,
}

impl Escalations {
    /// The counters of `r` (totals so far).
    pub fn of(r: &RootStats) -> Self {
        Escalations {
            queries: r.queries,
            adaptive_pieces: r.adaptive_pieces,
            multiprecision_pieces: r.multiprecision_pieces,
            exact_fallbacks: r.exact_fallbacks,
            adaptive_refines: r.adaptive_refines,
            refine_fallbacks: r.refine_fallbacks,
            slack_limited: r.slack_limited,
        }
    }

    /// What was counted after `before` (both totals of one workspace).
    pub fn since(&self, before: &Escalations) -> Self {
        Escalations {
            queries: self.queries - before.queries,
            adaptive_pieces: self.adaptive_pieces - before.adaptive_pieces,
            multiprecision_pieces: self.multiprecision_pieces - before.multiprecision_pieces,
            exact_fallbacks: self.exact_fallbacks - before.exact_fallbacks,
            adaptive_refines: self.adaptive_refines - before.adaptive_refines,
            refine_fallbacks: self.refine_fallbacks - before.refine_fallbacks,
            slack_limited: self.slack_limited - before.slack_limited,
        }
    }
}

/// The cell of the image that took longest: the render times each band of rows (a clock read
/// per cell would cost a tenth of a fast render), then traces the slowest band's cells again
/// one by one, and this is the slowest of them, with the time, rays and escalations of that
/// re-trace.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SlowestCell {
    /// Its top-left pixel `[x, y]`.
    pub pixel: [u32; 2],
    /// Its size in pixels (the scene's preview `Resolution`, 1 × 1 normally).
    pub size: [u32; 2],
    /// Time spent tracing it (in the re-trace).
    pub elapsed: Duration,
    /// Rays it traced (camera, shadow and secondary).
    pub rays: u64,
    /// Its root queries.
    pub escalations: Escalations,
    /// The object that took longest on the cell's centre camera ray, re-traced after the
    /// render (shadow and secondary rays are not re-traced); `None` when no object was
    /// tested.
    pub object: Option<SlowObject>,
}

/// One object's nearest-hit query on the slowest cell's centre camera ray, re-traced alone.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SlowObject {
    /// Zero-based index in the scene's objects (messages count from one).
    pub index: usize,
    /// Its kind of surface.
    pub kind: SurfaceKind,
    /// Time of the query.
    pub elapsed: Duration,
    /// Its root queries.
    pub escalations: Escalations,
}

impl std::fmt::Display for Escalations {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} root queries; adaptive-precision pieces {} (beyond double-double {}), \
             exact-rational fallbacks {}, refinements finished adaptively {} / exactly {}, \
             limited by the restriction's slack {}",
            self.queries,
            self.adaptive_pieces,
            self.multiprecision_pieces,
            self.exact_fallbacks,
            self.adaptive_refines,
            self.refine_fallbacks,
            self.slack_limited
        )
    }
}

impl std::fmt::Display for SlowestCell {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let ms = |d: Duration| d.as_secs_f64() * 1e3;
        let [x, y] = self.pixel;
        writeln!(
            f,
            "Slowest cell: pixel ({x}, {y}), {}x{} px, {:.3} ms, {} rays",
            self.size[0],
            self.size[1],
            ms(self.elapsed),
            self.rays
        )?;
        writeln!(f, "  {}", self.escalations)?;
        if let Some(o) = &self.object {
            writeln!(
                f,
                "  its camera ray's slowest object: object {} ({}), {:.3} ms",
                o.index + 1,
                o.kind.name(),
                ms(o.elapsed)
            )?;
            writeln!(f, "    {}", o.escalations)?;
        }
        Ok(())
    }
}
