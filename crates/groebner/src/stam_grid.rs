//! Stam's `f64` loop on fixed-capacity dense grids: the per-ray form of
//! [`Tracked`](crate::tracked::Tracked) and [`stam_tracked_until`](crate::stam_loop) for a ray
//! against a patch of degree ≤ 3 in `u` and `v` (article §4.2, `Groebner()` in `ray3.c`;
//! `paper-notes/groebner.md` §5).
//!
//! Every polynomial is a `CAP_V × CAP_U` grid of coefficients and ideal-distance bounds held in
//! the caller's workspace: no allocation, no generic scalar, no grid reshaping, row loops
//! written to vectorise. Why it matters: the general path spent ~75% of a teapot render in
//! `sub_term`, `make_monic` and `normalize` (allocation and bookkeeping, not arithmetic).
//! In the plain [`Variant`] the arithmetic is that of the general tracked path operation for
//! operation (a test checks the bases bit for bit on the article's pair), except that bounds
//! outside the grid are folded into one scalar ([`Corner`]) and the zero rule is re-applied
//! only where a step changed the polynomial ([`ZeroRule`]); the solver's variant also stops at
//! the first eliminant, skips `Scale` inside `R2`, and at every `R2` folds the bounds beyond
//! each row's coefficients so that the loops run over the coefficients only
//! ([`Variant::SOLVER`]).
//!
//! Capacity: coefficients never reach a `v`-power above the inputs' (every leading monomial in
//! the `v`-first order carries the largest `v`-power, and S-polynomials and reductions never
//! raise it), so 4 rows hold them for inputs of `v`-degree ≤ 3; bounds can land higher and are
//! folded. `u`-degrees of the coefficients grow up to the eliminant's (≤ 18 for a bicubic,
//! Kajiya's bound); a run that would put a coefficient beyond `CAP_U` columns or need more than
//! `MAX_ELEMENTS` elements is abandoned ([`Dense::Full`]). Abandoning is always safe: the solver
//! then uses the resultant.

use poly::{Monomial, UNIT_ROUNDOFF};

use crate::tracked::{NOISE_ABORT_REL, ZERO_ERR_FACTOR, certificate_bound};

/// Columns (powers `u⁰ … u^(CAP_U−1)`) of a dense grid.
pub(crate) const CAP_U: usize = 32;
/// Rows (powers `v⁰ … v³`) of a dense grid.
pub(crate) const CAP_V: usize = 4;
const CAP: usize = CAP_U * CAP_V;

/// Most elements Stam's list may hold (the teapot needs at most 5: three rounds).
pub(crate) const MAX_ELEMENTS: usize = 12;

/// Slots used by a run: the elements plus one spare for the new S-polynomial.
pub(crate) const SLOTS: usize = MAX_ELEMENTS + 1;

/// Why a dense run stopped without a basis.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Dense {
    /// A grid or the element list would overflow its capacity.
    Full,
    /// The abort test held for a new element (see `NOISE_ABORT_REL`).
    Noise,
    /// A leading coefficient is not finite (wide-range input overflowed `f64`): NaN breaks
    /// the descent of the leading monomials, so the run stops.
    Overflow,
}

/// A polynomial with its ideal-distance bounds (see the `tracked` module docs), dense.
#[derive(Clone, Debug)]
pub(crate) struct DensePoly {
    /// `c[j * CAP_U + i]`: coefficient of `u^i v^j`.
    pub(crate) c: [f64; CAP],
    /// Bounds, same layout.
    d: [f64; CAP],
    /// Every non-zero `c` or `d` lies at `i < nu`, `j < nv` (upper bounds, kept tight enough
    /// to bound the loops).
    nu: usize,
    nv: usize,
    /// Per row, every non-zero coefficient lies at `i < cu[j]` (upper bounds: the leading
    /// monomial's search skips the rest).
    cu: [usize; CAP_V],
    /// The leading monomial (cached).
    lead: Option<Monomial>,
    /// Bounds that fell outside the grid, each weighted by its monomial at the box corner
    /// (`d_ij · u_max^i · v_max^j`, see [`Corner`]).
    far: f64,
}

/// Powers of the box corner `(u_max, v_max)`: the weights of bounds folded into
/// [`DensePoly::far`]. Folding is sound: for `|u| ≤ u_max`, `|v| ≤ v_max` a folded term
/// `d_ij |u|^i |v|^j` is at most its weight, and every operation maps the weight as it maps
/// the term (a shift by `x` multiplies it by `x`'s weight, a division by `|lc|` divides it).
/// The only difference from keeping the entry is that the zero rule no longer sees it at its
/// monomial (a coefficient there is then kept rather than dropped, which the bounds account
/// for either way).
#[derive(Clone, Debug)]
pub(crate) struct Corner {
    pow_u: [f64; 2 * CAP_U],
    pow_v: [f64; 2 * CAP_V],
}

impl Corner {
    pub(crate) fn new(u_max: f64, v_max: f64) -> Self {
        let mut pow_u = [1.0; 2 * CAP_U];
        let mut pow_v = [1.0; 2 * CAP_V];
        for k in 1..pow_u.len() {
            pow_u[k] = pow_u[k - 1] * u_max;
        }
        for k in 1..pow_v.len() {
            pow_v[k] = pow_v[k - 1] * v_max;
        }
        Corner { pow_u, pow_v }
    }

    fn weight(&self, i: usize, j: usize) -> f64 {
        self.pow_u[i] * self.pow_v[j]
    }

    fn u_max(&self) -> f64 {
        self.pow_u[1]
    }

    fn v_max(&self) -> f64 {
        self.pow_v[1]
    }
}

impl Default for DensePoly {
    fn default() -> Self {
        DensePoly {
            c: [0.0; CAP],
            d: [0.0; CAP],
            nu: 0,
            nv: 0,
            cu: [0; CAP_V],
            lead: None,
            far: 0.0,
        }
    }
}

impl DensePoly {
    /// Sets `self` to an exact input polynomial (bounds zero) given as a `4 × 4` grid.
    pub(crate) fn set_input(&mut self, grid: &[f64; 16]) {
        self.clear();
        for j in 0..4 {
            for i in 0..4 {
                self.c[j * CAP_U + i] = grid[4 * j + i];
            }
        }
        self.nu = 4;
        self.nv = 4;
        self.cu = [4; CAP_V];
        self.shrink();
    }

    fn clear(&mut self) {
        for j in 0..self.nv {
            self.c[j * CAP_U..j * CAP_U + self.nu].fill(0.0);
            self.d[j * CAP_U..j * CAP_U + self.nu].fill(0.0);
        }
        self.nu = 0;
        self.nv = 0;
        self.cu = [0; CAP_V];
        self.lead = None;
        self.far = 0.0;
    }

    /// Shrinks `nu`, `nv` to the non-zero content and refreshes the cached leading monomial
    /// and extent; with `zero_rule`, first applies the zero rule (see `Tracked::sub_term`) to
    /// every non-zero coefficient, `cancel` (an index) being zero by construction.
    fn tighten_with(&mut self, zero_rule: Option<ZeroRule>) {
        if let Some(rule) = zero_rule {
            // Dropping a term moves the polynomial away from the ideal by |c|.
            let v = self.c[rule.cancel];
            if v != 0.0 {
                self.d[rule.cancel] += v.abs();
                self.c[rule.cancel] = 0.0;
            }
            for j in rule.rows.0..rule.rows.1 {
                let (lo, hi) = (j * CAP_U + rule.cols.0, j * CAP_U + rule.cols.1);
                let (c, d) = (&mut self.c[lo..hi], &mut self.d[lo..hi]);
                for (c, d) in c.iter_mut().zip(d.iter_mut()) {
                    // `&`, not `&&`: no branch, so that the loop vectorises.
                    let zero = (*c != 0.0) & (c.abs() <= ZERO_ERR_FACTOR * *d);
                    *d += if zero { c.abs() } else { 0.0 };
                    // Cleared by a product and stored whole: `if zero { 0.0 } else { *c }`
                    // became a masked store (`vmaskmovpd`), slow on AMD cores — 45 % of this
                    // function's samples on the teapot (`paper-notes/bvh.md`, twenty-first
                    // session). `+ 0.0` turns the product's `−0.0` into the `+0.0` the select
                    // wrote; a kept `c` is unchanged (a kept `−0.0` becomes `+0.0`, equal).
                    *c = *c * f64::from(u8::from(!zero)) + 0.0;
                }
            }
        }
        // Bounds never return to zero, so `nu`, `nv` stay valid upper bounds; only the leading
        // monomial is looked up again (from the top row down).
        self.lead = None;
        for j in (0..self.nv).rev() {
            let row = &self.c[j * CAP_U..j * CAP_U + self.cu[j]];
            match row.iter().rposition(|&c| c != 0.0) {
                Some(i) => {
                    self.cu[j] = i + 1;
                    self.lead = Some(Monomial::new(i, j));
                    break;
                }
                None => self.cu[j] = 0,
            }
        }
    }

    fn tighten(&mut self) {
        self.tighten_with(None);
    }

    /// Shrinks `nu`, `nv` to the non-zero content (inputs only: elsewhere they are upper
    /// bounds, which is all the loops need).
    fn shrink(&mut self) {
        let (mut nu, mut nv) = (0, 0);
        for j in 0..self.nv {
            let row = j * CAP_U;
            let c = &self.c[row..row + self.nu];
            let d = &self.d[row..row + self.nu];
            if let Some(i) = c.iter().zip(d).rposition(|(&c, &d)| c != 0.0 || d != 0.0) {
                nu = nu.max(i + 1);
                nv = j + 1;
            }
        }
        self.nu = nu;
        self.nv = nv;
        self.tighten();
    }

    pub(crate) fn is_zero(&self) -> bool {
        self.lead.is_none()
    }

    /// `Err(Dense::Overflow)` when the leading coefficient is not finite: a NaN lead is never
    /// cancelled, which would stall the descent of `R2`. A non-finite coefficient below the
    /// lead either becomes a lead later (and stops the run here) or stays in an element whose
    /// certificate bound is then NaN, which certifies nothing.
    fn check_finite_lead(&self) -> Result<(), Dense> {
        match self.lead {
            Some(m) if !self.at(m).is_finite() => Err(Dense::Overflow),
            _ => Ok(()),
        }
    }

    /// The leading monomial in the `v`-first order ([`Monomial`]).
    pub(crate) fn lm(&self) -> Option<Monomial> {
        self.lead
    }

    fn at(&self, m: Monomial) -> f64 {
        self.c[m.v * CAP_U + m.u]
    }

    /// The tight `(stride, rows)` of the polynomial's grid, as [`poly::BiPoly`] keeps it (a
    /// scan: used by the certificate, not in the loop).
    pub(crate) fn grid_extent(&self) -> (usize, usize) {
        let (mut stride, mut rows) = (0, 0);
        for j in 0..self.nv {
            let row = &self.c[j * CAP_U..j * CAP_U + self.cu[j]];
            if let Some(i) = row.iter().rposition(|&c| c != 0.0) {
                stride = stride.max(i + 1);
                rows = j + 1;
            }
        }
        (stride, rows)
    }

    /// `true` when the polynomial is a non-zero constant.
    pub(crate) fn is_nonzero_constant(&self) -> bool {
        self.grid_extent() == (1, 1)
    }

    /// `true` when the polynomial lies in `K[u]` and is not constant.
    pub(crate) fn is_univariate_nonconstant(&self) -> bool {
        let (stride, rows) = self.grid_extent();
        rows == 1 && stride > 1
    }

    /// The coefficients of `v⁰` (the univariate element), lowest power first, tight.
    pub(crate) fn row0(&self) -> &[f64] {
        let (stride, _) = self.grid_extent();
        &self.c[..stride]
    }

    /// `p / lc(p)` (Stam's `Scale`), as `Tracked::make_monic`.
    pub(crate) fn make_monic(&mut self) {
        let Some(m) = self.lm() else {
            return;
        };
        let k = m.v * CAP_U + m.u;
        let lc = self.c[k];
        let inv = 1.0 / lc.abs();
        self.far *= inv;
        // One pass (c ← c/lc, d ← d/|lc| + u·|c/lc| where c ≠ 0), branch-free so that it
        // vectorises; the same values as the three passes of `Tracked::make_monic` (outside
        // the grid c is zero and stays zero).
        for j in 0..self.nv {
            let row = j * CAP_U;
            let (c, d) = (
                &mut self.c[row..row + self.nu],
                &mut self.d[row..row + self.nu],
            );
            for (c, d) in c.iter_mut().zip(d.iter_mut()) {
                *c /= lc;
                let add = if *c != 0.0 {
                    UNIT_ROUNDOFF * c.abs()
                } else {
                    0.0
                };
                *d = *d * inv + add;
            }
        }
        // The leading term is exactly one (x/x = 1 in IEEE arithmetic; set as the general
        // path does).
        self.c[k] = 1.0;
    }

    /// Folds the bounds that lie beyond the coefficients of their row into [`DensePoly::far`]
    /// (sound, see [`Corner`]) and shrinks the grid to the coefficients, so that the loops of
    /// later steps run over the coefficients only.
    fn compact(&mut self, corner: &Corner) {
        let mut nu = 0;
        let mut nv = 0;
        for j in 0..self.nv {
            let row = j * CAP_U;
            let from = self.cu[j].min(self.nu);
            for i in from..self.nu {
                let d = self.d[row + i];
                if d != 0.0 {
                    self.far += d * corner.weight(i, j);
                    self.d[row + i] = 0.0;
                }
            }
            if self.cu[j] > 0 {
                nu = nu.max(from);
                nv = j + 1;
            }
        }
        self.nu = nu;
        self.nv = nv;
    }

    /// `self ← self − c·x·q`, the term at `cancels` zero by construction; then the zero rule
    /// (as `Tracked::sub_term`).
    fn sub_term(
        &mut self,
        c: f64,
        x: Monomial,
        q: &DensePoly,
        cancels: Monomial,
        corner: &Corner,
    ) -> Result<(), Dense> {
        if (q.nu + x.u > CAP_U || q.nv + x.v > CAP_V) && {
            let (stride, rows) = q.grid_extent();
            stride + x.u > CAP_U || rows + x.v > CAP_V
        } {
            return Err(Dense::Full);
        }
        let (ac, two_ac) = (c.abs(), 2.0 * c.abs());
        let neg = -c;
        self.far += ac * q.far * corner.weight(x.u, x.v);
        for j in 0..q.nv {
            let tj = j + x.v;
            let (qc, qd) = (
                &q.c[j * CAP_U..j * CAP_U + q.nu],
                &q.d[j * CAP_U..j * CAP_U + q.nu],
            );
            // Entries that land inside the grid, then bounds beyond it (the coefficients
            // fit, checked above): folded.
            let fit = if tj < CAP_V { q.nu.min(CAP_U - x.u) } else { 0 };
            for (i, &dq) in qd.iter().enumerate().skip(fit) {
                self.far += ac * dq * corner.weight(i + x.u, tj);
            }
            if fit == 0 {
                continue;
            }
            let base = tj * CAP_U + x.u;
            let (pc, pd) = (&mut self.c[base..base + fit], &mut self.d[base..base + fit]);
            // Branch-free (vectorises); entries where q has neither a coefficient nor a
            // bound add nothing, as in `Tracked::sub_term`.
            for (((pc, pd), &qc), &dq) in pc.iter_mut().zip(pd.iter_mut()).zip(qc).zip(qd) {
                let add = ac * dq + UNIT_ROUNDOFF * (pc.abs() + two_ac * qc.abs());
                *pd += if qc != 0.0 || dq != 0.0 { add } else { 0.0 };
                *pc += qc * neg;
            }
        }
        for j in 0..q.nv.min(CAP_V.saturating_sub(x.v)) {
            let t = &mut self.cu[j + x.v];
            *t = (*t).max((q.cu[j] + x.u).min(CAP_U));
        }
        self.nu = self.nu.max(q.nu + x.u).min(CAP_U);
        self.nv = self.nv.max(q.nv + x.v).min(CAP_V);
        self.tighten_with(Some(ZeroRule {
            cancel: cancels.v * CAP_U + cancels.u,
            rows: (x.v.min(CAP_V), (q.nv + x.v).min(CAP_V)),
            cols: (x.u.min(CAP_U), (q.nu + x.u).min(CAP_U)),
        }));
        Ok(())
    }

    /// Cancels the term at `t` with `q` (as `Tracked::cancel_with`).
    fn cancel_with(&mut self, t: Monomial, q: &DensePoly, corner: &Corner) -> Result<(), Dense> {
        let lq = q.lm().expect("a reducer is non-zero");
        let x = lq.quotient_of(t).expect("LM(q) divides t");
        let c = self.at(t) / q.at(lq);
        self.sub_term(c, x, q, t, corner)
    }

    /// `self ← SP(f, g)` (as `Tracked::s_poly`).
    fn set_s_poly(&mut self, f: &DensePoly, g: &DensePoly, corner: &Corner) -> Result<(), Dense> {
        self.clear();
        let (Some(lf), Some(lg)) = (f.lm(), g.lm()) else {
            return Ok(());
        };
        let l = lf.lcm(lg);
        let (cf, cg) = (1.0 / f.at(lf), 1.0 / g.at(lg));
        // self ← cf · (l / lf) · f, bounds as `Tracked::mul_term`.
        let x = lf.quotient_of(l).expect("LM(f) | lcm");
        let (stride, rows) = f.grid_extent();
        if stride + x.u > CAP_U || rows + x.v > CAP_V {
            return Err(Dense::Full);
        }
        let acf = cf.abs();
        self.far = f.far * acf * corner.weight(x.u, x.v);
        for j in 0..f.nv {
            let frow = j * CAP_U;
            let tj = j + x.v;
            for i in 0..f.nu {
                let ti = i + x.u;
                if ti >= CAP_U || tj >= CAP_V {
                    self.far += f.d[frow + i] * acf * corner.weight(ti, tj);
                    continue;
                }
                let t = tj * CAP_U + ti;
                self.d[t] = f.d[frow + i] * acf;
                if j < rows && i < stride {
                    self.c[t] = f.c[frow + i] * cf;
                }
            }
        }
        for j in 0..rows {
            let (frow, srow) = (j * CAP_U, (j + x.v) * CAP_U + x.u);
            for i in 0..stride {
                let a = f.c[frow + i];
                if a != 0.0 {
                    self.d[srow + i] += UNIT_ROUNDOFF * acf * a.abs();
                }
            }
        }
        for j in 0..f.nv.min(CAP_V.saturating_sub(x.v)) {
            self.cu[j + x.v] = (f.cu[j] + x.u).min(CAP_U);
        }
        self.nu = (f.nu + x.u).min(CAP_U);
        self.nv = (f.nv + x.v).min(CAP_V);
        self.sub_term(cg, lg.quotient_of(l).expect("LM(g) | lcm"), g, l, corner)
    }

    /// `Σ d_ij u_max^i v_max^j` (as `Tracked::ideal_distance_at`).
    pub(crate) fn ideal_distance_at(&self, u_max: f64, v_max: f64) -> f64 {
        let mut total = 0.0;
        for j in (0..self.nv).rev() {
            let mut row = 0.0;
            for i in (0..self.nu).rev() {
                row = row * u_max + self.d[j * CAP_U + i];
            }
            total = total * v_max + row;
        }
        total + self.far
    }

    /// `Σ |c_ij| u_max^i v_max^j` over the polynomial's grid (`BiPoly::eval_abs` at
    /// non-negative arguments).
    pub(crate) fn size_at(&self, u_max: f64, v_max: f64) -> f64 {
        let (stride, rows) = self.grid_extent();
        let mut size = 0.0;
        for j in (0..rows).rev() {
            let r = self.c[j * CAP_U..j * CAP_U + stride]
                .iter()
                .rev()
                .fold(0.0, |a, c| a * u_max + c.abs());
            size = size * v_max + r;
        }
        size
    }

    /// The certificate's bound for this element on the box `|u| ≤ u_max`, `|v| ≤ v_max`
    /// ([`certificate_bound`], as for a `Tracked` element).
    pub(crate) fn certificate_bound(&self, u_max: f64, v_max: f64) -> f64 {
        let (stride, rows) = self.grid_extent();
        certificate_bound(
            self.ideal_distance_at(u_max, v_max),
            self.size_at(u_max, v_max),
            stride + rows,
        )
    }

    /// As `Tracked::is_noise`.
    fn is_noise(&self, corner: &Corner) -> bool {
        if self.is_zero() {
            return false;
        }
        let (u_max, v_max) = (corner.u_max(), corner.v_max());
        self.ideal_distance_at(u_max, v_max) >= self.size_at(u_max, v_max) * NOISE_ABORT_REL
    }
}

/// Where a reduction step applies the zero rule: the term it cancels (an index), and the
/// rectangle of rows and columns its update touched. Elsewhere coefficients and bounds are
/// those of the previous step, which passed the rule already; the general path re-tests them
/// after rescaling by `make_monic`, which can flip a test only for a coefficient within a few
/// units of round-off of `ZERO_ERR_FACTOR` times its bound. Either choice is sound: the rule
/// only decides which terms are kept, and the bounds account for every term it drops.
#[derive(Clone, Copy, Debug)]
struct ZeroRule {
    cancel: usize,
    rows: (usize, usize),
    cols: (usize, usize),
}

/// Two distinct slots, mutably.
fn pair(slots: &mut [DensePoly], a: usize, b: usize) -> (&mut DensePoly, &mut DensePoly) {
    assert_ne!(a, b, "two distinct slots");
    if a < b {
        let (lo, hi) = slots.split_at_mut(b);
        (&mut lo[a], &mut hi[0])
    } else {
        let (lo, hi) = slots.split_at_mut(a);
        (&mut hi[0], &mut lo[b])
    }
}

/// Stam's `R2` on slots `p`, `q` (as `r2_tracked`); returns the slots of the larger and the
/// smaller result.
fn r2(
    slots: &mut [DensePoly],
    p: usize,
    q: usize,
    corner: &Corner,
    variant: Variant,
) -> Result<(usize, usize), Dense> {
    let (mut p, mut q) = (p, q);
    slots[p].make_monic();
    slots[q].make_monic();
    if variant.compact {
        slots[p].compact(corner);
        slots[q].compact(corner);
    }
    if slots[p].lm() < slots[q].lm() {
        std::mem::swap(&mut p, &mut q);
    }
    loop {
        let (Some(lp), Some(lq)) = (slots[p].lm(), slots[q].lm()) else {
            return Ok((p, q));
        };
        if !lq.divides(lp) {
            return Ok((p, q));
        }
        let (sp, sq) = pair(slots, p, q);
        sp.cancel_with(lp, sq, corner)?;
        if sp.is_zero() {
            return Ok((q, p));
        }
        sp.check_finite_lead()?;
        // In the solver's variant, unlike Stam's `Scale` (and `r2_tracked`), the remainder is
        // not made monic after every step, only at the next `r2`: `cancel_with` divides by
        // the reducer's leading coefficient anyway, the bounds hold for any scaling, and the
        // zero rule, the noise test and the certificate are scale-invariant. Measured on
        // teapot.scene (300², one thread): 14% less time per test, 5% fewer certified
        // systems (the rounding differs).
        if !variant.lazy_monic {
            sp.make_monic();
        }
        if slots[p].lm() < slots[q].lm() {
            std::mem::swap(&mut p, &mut q);
        }
    }
}

/// How [`stam_dense`] departs from Stam's loop as `stam_tracked_until` runs it (all `false`:
/// the same arithmetic; the solver sets both, see the comments where they apply).
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Variant {
    /// Stop at the first new element in `K[u]` or constant.
    pub(crate) stop_at_eliminant: bool,
    /// Within `R2`, do not make the remainder monic after every step.
    pub(crate) lazy_monic: bool,
    /// At each `R2`, fold the bounds beyond the coefficients ([`DensePoly::compact`]).
    pub(crate) compact: bool,
}

impl Variant {
    /// The `f64` solver's variant.
    pub(crate) const SOLVER: Variant = Variant {
        stop_at_eliminant: true,
        lazy_monic: true,
        compact: true,
    };
}

/// Stam's loop (as `stam_tracked_until` with the `is_noise` abort) on the inputs in slots 0
/// and 1, in the given [`Variant`]. On success `order[..len]` lists the slots of the non-zero elements `F_1 … F_N`.
pub(crate) fn stam_dense(
    slots: &mut [DensePoly],
    order: &mut [usize; MAX_ELEMENTS],
    corner: &Corner,
    variant: Variant,
) -> Result<usize, Dense> {
    debug_assert!(slots.len() >= SLOTS, "a workspace has SLOTS slots");
    let (a, b) = r2(slots, 0, 1, corner, variant)?;
    order[0] = a;
    order[1] = b;
    let mut len = 2;
    let mut spare = 2;
    let mut i = 0;
    while !slots[order[i + 1]].is_zero() {
        if len >= MAX_ELEMENTS {
            return Err(Dense::Full);
        }
        let s = spare;
        set_s_poly_slots(slots, s, order[i], order[i + 1], corner)?;
        slots[s].check_finite_lead()?;
        slots[s].make_monic();
        let (gi, s) = r2(slots, s, order[i], corner, variant)?;
        order[i] = gi;
        let (gi1, s) = r2(slots, s, order[i + 1], corner, variant)?;
        order[i + 1] = gi1;
        if slots[s].is_noise(corner) {
            return Err(Dense::Noise);
        }
        order[len] = s;
        len += 1;
        // Stop at the first element in K[u] (the eliminant) or constant: the certificate
        // holds for any element of the ideal with its bound, and the next round, which in
        // exact arithmetic reduces the S-polynomial to zero and leaves the eliminant as it
        // is, in f64 reduces the eliminant and its neighbour again and inflates their
        // bounds. Measured on teapot.scene (300², one thread): 7.0% of the systems
        // certified instead of 2.4%, and 25% less time per test.
        let new = &slots[s];
        if variant.stop_at_eliminant
            && (new.is_univariate_nonconstant() || new.is_nonzero_constant())
        {
            break;
        }
        // The next spare: a slot not in use.
        spare = (0..slots.len())
            .find(|k| !order[..len].contains(k))
            .ok_or(Dense::Full)?;
        i += 1;
    }
    // Keep the non-zero elements, in order.
    let mut kept = 0;
    for k in 0..len {
        if !slots[order[k]].is_zero() {
            order[kept] = order[k];
            kept += 1;
        }
    }
    Ok(kept)
}

/// `slots[s] ← SP(slots[f], slots[g])` for three distinct slots.
fn set_s_poly_slots(
    slots: &mut [DensePoly],
    s: usize,
    f: usize,
    g: usize,
    corner: &Corner,
) -> Result<(), Dense> {
    assert!(s != f && s != g && f != g, "distinct slots");
    // The target mutably and the two others shared, without copying any of them.
    let (left, rest) = slots.split_at_mut(s);
    let (target, right) = rest.split_first_mut().expect("s is a slot");
    let (left, right) = (&*left, &*right);
    let at = |k: usize| if k < s { &left[k] } else { &right[k - s - 1] };
    target.set_s_poly(at(f), at(g), corner)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stam_loop::stam_tracked_until;
    use crate::testutil::article_pair;
    use crate::tracked::Tracked;
    use poly::BiPoly;

    fn grid(p: &BiPoly<f64>) -> [f64; 16] {
        let mut c = [0.0; 16];
        for (j, row) in p.rows_iter().enumerate() {
            c[4 * j..4 * j + row.len()].copy_from_slice(row);
        }
        c
    }

    /// Runs both loops; `None` when either abandons (they must agree on that).
    fn both(f1: &BiPoly<f64>, f2: &BiPoly<f64>, um: f64, vm: f64) {
        let general = stam_tracked_until(Tracked::new(f1.clone()), Tracked::new(f2.clone()), |t| {
            t.is_noise(&um, &vm)
        })
        .unwrap();
        let mut slots = vec![DensePoly::default(); SLOTS];
        slots[0].set_input(&grid(f1));
        slots[1].set_input(&grid(f2));
        let mut order = [0; MAX_ELEMENTS];
        let dense = stam_dense(
            &mut slots,
            &mut order,
            &Corner::new(um, vm),
            Variant::default(),
        );
        match (general, dense) {
            (None, Err(Dense::Noise)) => {}
            (Some(g), Ok(len)) => {
                assert_eq!(g.len(), len, "basis size");
                for (t, &k) in g.iter().zip(&order[..len]) {
                    let d = &slots[k];
                    let (stride, rows) = d.grid_extent();
                    assert_eq!((stride, rows), (t.poly.stride(), t.poly.rows()), "grid");
                    for j in 0..rows {
                        for i in 0..stride {
                            assert_eq!(
                                d.c[j * CAP_U + i].to_bits(),
                                t.poly.coeff(i, j).to_bits(),
                                "coefficient u^{i} v^{j}"
                            );
                        }
                    }
                    assert_eq!(
                        d.ideal_distance_at(um, vm).to_bits(),
                        t.ideal_distance_at(&um, &vm).to_bits(),
                        "bound"
                    );
                }
            }
            (g, d) => panic!("general {:?} vs dense {d:?}", g.map(|g| g.len())),
        }
    }

    #[test]
    fn same_basis_as_the_general_loop_bit_for_bit() {
        let (f1, f2) = article_pair();
        both(&f1.to_f64(), &f2.to_f64(), 2.0, 2.0);
    }
}
