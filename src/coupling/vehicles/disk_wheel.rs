//! Where a disk wheel touches the track: the place under it that lifts its centre highest, on
//! the deck's patch-averaged axis plus the profile, with the corners of a piecewise-linear
//! profile as candidates.

use super::VehiclesOnBeam;
use crate::beam::PastFreeEnd;

/// Points a disk wheel's reach is scanned at before its contact is refined, where Newton's
/// method has not found it in [`DISK_NEWTON`] steps.
const DISK_SCAN: usize = 16;
const DISK_NEWTON: usize = 8;

/// Where a disk wheel of radius a touches the track: at the x that lifts its centre highest.
/// By that maximum the centre's height H moves with the deck as gᵀ at the contact does (the
/// contact's own shift moves H by nothing to first order), and with the centre's travel X by
/// (x − X)/√(a² − (x − X)²).
#[derive(Clone, Copy, Debug)]
pub struct DiskContact {
    pub rise: f64,
    pub rest: f64,
    /// The disk rests on a corner of the profile, its contact held there as it pivots.
    pub pivot: bool,
    /// The crest the disk rested on ([`Resting`]) has merged into a hollow since: before
    /// that another crest rose above it, which the disk has met unseen.
    pub crest_gone: bool,
}

/// On a road a disk bridges, the crest it rests on: where it was when the disk's centre was
/// over `centre`. The disk stays on that crest, followed as the centre moves, however high
/// another within reach, until the run moves it on.
#[derive(Clone, Copy, Debug)]
pub struct Resting {
    pub centre: f64,
    pub crest: f64,
}

impl VehiclesOnBeam<'_> {
    /// The track's height at x (the deck at q, on the mesh, averaged over the patch, and the
    /// profile) with its slope and curvature along x.
    pub(super) fn surface(&self, x: f64, mesh: &[f64]) -> [f64; 3] {
        self.on_deck(x, mesh, self.profile.at(x, x))
    }

    /// `profile` (the road's r, r', r'' at x) with the deck's, where x is on it.
    pub(super) fn on_deck(&self, x: f64, mesh: &[f64], profile: [f64; 3]) -> [f64; 3] {
        let beam = self.loaded.beam;
        let (b, length) = (self.patch, beam.length);
        let mut out = profile;
        if x > -b && x < length + b {
            for nb in beam.patch_basis_at(x, b, PastFreeEnd::Slab) {
                if let Some(i) = nb.w {
                    (0..3).for_each(|k| out[k] += nb.d[k] * mesh[i]);
                }
            }
        }
        out
    }

    /// Where a disk of radius `a` centred over X touches the track, and how it rises there:
    /// the x that lifts its centre highest, H(x) = f(x) + √(a² − (x − X)²). Newton's method on
    /// H' from x = X finds it in a few steps on a smooth track (H'' < 0 wherever the track
    /// bends less than the disk); where it does not settle (the disk on a corner of a
    /// piecewise-linear profile), a scan of the disk's reach and golden-section search about
    /// its best, to a billionth of the radius.
    /// `toward` (±1) is the side of the stretch the run is in: where the disk rests on two faces
    /// at once (in a hollow, at a breakpoint) the face it is going onto or coming off.
    /// `resting`, on a road the disk bridges, is the crest it rests on ([`Resting`]).
    pub(super) fn disk_contact(
        &self,
        at: f64,
        toward: f64,
        a: f64,
        mesh: &[f64],
        resting: Option<Resting>,
    ) -> (f64, DiskContact) {
        let centre = at + toward * 1e-9 * a;
        let height = |x: f64| -> f64 { self.surface(x, mesh)[0] + arc(x, centre, a) };
        let corners: Vec<f64> = self
            .profile
            .kinks()
            .into_iter()
            .filter(|k| (k - centre).abs() < a)
            .collect();
        let crests = self.profile.crest_scan(a).map(|count| count as usize);
        let (x, crest_gone) = match (crests, resting.filter(|r| (r.crest - centre).abs() < a)) {
            (Some(count), Some(r)) => match self.follow_crest(r, centre, a, mesh, count) {
                Followed::At(x) => (x, false),
                Followed::Gone(last) => {
                    (self.crest_from(centre, a, mesh, count, last, &height), true)
                }
                Followed::Short(last) => (
                    self.crest_from(centre, a, mesh, count, last, &height),
                    false,
                ),
            },
            (crests, _) => (
                self.highest_point(centre, a, mesh, &corners, crests, &height),
                false,
            ),
        };
        let u = (x - at) / a;
        let root = (1.0 - u * u).max(1e-12).sqrt();
        let profile = self.profile.at(x, x)[0];
        (
            x,
            DiskContact {
                rise: u / root,
                rest: profile + a * (root - 1.0),
                pivot: corners.contains(&x),
                crest_gone,
            },
        )
    }

    /// Where a disk of radius `a` centred over `centre`, resting on no crest it is held to,
    /// touches the track: the highest of Newton's maximum from the centre, each face's beside
    /// a corner within reach and the corners themselves, and on a road that bends faster than
    /// the disk (`crests`, the scan's count) every crest within reach; where none of these
    /// settles, a scan of the reach and golden-section search about its best.
    fn highest_point(
        &self,
        centre: f64,
        a: f64,
        mesh: &[f64],
        corners: &[f64],
        crests: Option<usize>,
        height: &dyn Fn(f64) -> f64,
    ) -> f64 {
        let newton = |start: f64| -> Option<f64> {
            let mut x = start;
            for _ in 0..DISK_NEWTON {
                let [_, f1, f2] = self.surface(x, mesh);
                let u = (x - centre) / a;
                let root = (1.0 - u * u).max(1e-12).sqrt();
                let (h1, h2) = (f1 - u / root, f2 - 1.0 / (a * root * root * root));
                if !(h2 < 0.0) {
                    return None;
                }
                let next =
                    (x - h1 / h2).clamp(centre - a * (1.0 - 1e-9), centre + a * (1.0 - 1e-9));
                let moved = (next - x).abs();
                x = next;
                if moved < 1e-10 * a {
                    return Some(x);
                }
            }
            None
        };
        let mut candidates: Vec<f64> = newton(centre).into_iter().collect();
        for &k in corners {
            for side in [-1.0, 1.0] {
                candidates.extend(newton(k + side * 1e-6 * a));
            }
        }
        let highest = |of: &[f64]| {
            of.iter()
                .copied()
                .max_by(|&p, &q| height(p).total_cmp(&height(q)))
        };
        // A centre within √(2ε) a of a corner, still over the face it rolls on, rests on that
        // face and on the corner at heights round-off cannot tell apart: the face is taken
        // unless the corner is higher by more than round-off, so that the contact does not
        // flicker onto the corner and its curvature to the corner's 1/a before the centre
        // passes it (a van's disk wheel pulled on the deck with 366 kN at one such instant).
        let face = highest(&candidates);
        let mut x = match (face, highest(corners)) {
            (Some(f), Some(k))
                if height(k) > height(f) + 8.0 * f64::EPSILON * (a + height(f).abs()) =>
            {
                k
            }
            (Some(f), _) => f,
            (None, k) => k.unwrap_or(centre),
        };
        candidates.extend(corners);
        // On a road that bends faster than the disk, Newton's crest may be one the disk
        // bridges: every crest within reach is a candidate.
        if let Some(count) = crests {
            let crest = self.highest_crest(centre, a, mesh, count, height);
            if height(crest) > height(x) {
                x = crest;
            }
        } else if candidates.is_empty() || height(x) < height(centre) {
            let reach = DISK_SCAN as f64;
            let at = |k: usize| centre + a * (2.0 * k as f64 / reach - 1.0) * (1.0 - 1e-12);
            let best = (0..=DISK_SCAN)
                .max_by(|&i, &j| height(at(i)).total_cmp(&height(at(j))))
                .unwrap_or(DISK_SCAN / 2);
            let (lo, hi) = (at(best.saturating_sub(1)), at((best + 1).min(DISK_SCAN)));
            x = golden_max(height, lo, hi, 1e-9 * a);
        }
        x
    }

    /// The highest of the local maxima of `height` over a disk's reach about `centre`
    /// ([`Self::scanned_crests`], refining those the scan's spacing may hide above the best
    /// sample).
    fn highest_crest(
        &self,
        centre: f64,
        a: f64,
        mesh: &[f64],
        count: usize,
        height: &dyn Fn(f64) -> f64,
    ) -> f64 {
        self.scanned_crests(centre, a, mesh, count, height, |best, hidden| best - hidden)
            .into_iter()
            .max_by(|p, q| p.0.total_cmp(&q.0))
            .map_or(centre, |(_, x)| x)
    }

    /// The local maxima of `height` over a disk's reach about `centre`, as (height, x): the
    /// reach scanned at `count` spaces (at least [`DISK_SCAN`]), and each sample that is a
    /// local maximum refined between its neighbours where it lies at or above `floor(best
    /// sample, hidden)`; the others stand at their samples. `hidden` is what a crest may rise
    /// above the samples beside it: between two samples h apart a height whose second
    /// derivative stays below K rises at most K h² / 8 above the higher; the disk's own arc only
    /// bends it down, and the deck's bending, far below the road's, is covered by taking twice
    /// that.
    fn scanned_crests(
        &self,
        centre: f64,
        a: f64,
        mesh: &[f64],
        count: usize,
        height: &dyn Fn(f64) -> f64,
        floor: impl Fn(f64, f64) -> f64,
    ) -> Vec<(f64, f64)> {
        let count = count.max(DISK_SCAN);
        let spacing = 2.0 * a / count as f64;
        let at = |k: usize| centre - a + spacing * k as f64;
        // `height` at the samples, the road summed along the grid rather than point by point.
        let road = self.profile.along(centre - a, spacing, count);
        let samples: Vec<f64> = (road.iter().enumerate())
            .map(|(k, &r)| {
                let x = at(k);
                self.on_deck(x, mesh, [r, 0.0, 0.0])[0] + arc(x, centre, a)
            })
            .collect();
        let best = samples.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let hidden = self.profile.curvature_bound() * spacing * spacing / 4.0;
        let floor = floor(best, hidden);
        (0..=count)
            .filter(|&k| {
                (k == 0 || samples[k] >= samples[k - 1])
                    && (k == count || samples[k] >= samples[k + 1])
            })
            .map(|k| {
                if samples[k] < floor {
                    return (samples[k], at(k));
                }
                let (lo, hi) = (at(k.saturating_sub(1)), at((k + 1).min(count)));
                let x = self
                    .crest_between(centre, a, mesh, lo, hi)
                    .unwrap_or_else(|| golden_max(height, lo, hi, 1e-9 * a));
                (height(x), x)
            })
            .collect()
    }

    /// The crest of the centre's height H between `lo` and `hi` where H rises at `lo` and falls
    /// at `hi`: the root of H' by Newton's method on H'' (the track's slope and curvature come
    /// with its height at no extra cost), kept inside the shrinking bracket by bisection, to a
    /// ten-billionth of the radius. A handful of the track's evaluations where golden section
    /// takes some eighty; `None` where H' does not change sign across the bracket.
    fn crest_between(&self, centre: f64, a: f64, mesh: &[f64], lo: f64, hi: f64) -> Option<f64> {
        let slopes = |x: f64| self.centre_slopes(x, centre, a, mesh);
        let (mut lo, mut hi) = (lo, hi);
        if !(slopes(lo)[0] > 0.0 && slopes(hi)[0] < 0.0) {
            return None;
        }
        let mut x = 0.5 * (lo + hi);
        for _ in 0..CREST_ITERATIONS {
            let [h1, h2] = slopes(x);
            if h1 > 0.0 {
                lo = x;
            } else {
                hi = x;
            }
            let newton = x - h1 / h2;
            let next = if h2 < 0.0 && newton > lo && newton < hi {
                newton
            } else {
                0.5 * (lo + hi)
            };
            let moved = (next - x).abs();
            x = next;
            if moved < 1e-10 * a || hi - lo < 1e-10 * a {
                return Some(x);
            }
        }
        Some(x)
    }

    /// The crest of H by Newton's method on H' from `start`, where it settles within [lo, hi]
    /// on a maximum in a few steps (`None` otherwise): a crest followed from where a stride
    /// predicts it, at a third of the evaluations of [`Self::crest_between`]'s bracket.
    fn newton_crest(
        &self,
        centre: f64,
        a: f64,
        mesh: &[f64],
        start: f64,
        lo: f64,
        hi: f64,
    ) -> Option<f64> {
        let mut x = start;
        for _ in 0..DISK_NEWTON {
            let [h1, h2] = self.centre_slopes(x, centre, a, mesh);
            if !(h2 < 0.0) {
                return None;
            }
            let next = x - h1 / h2;
            if !(next >= lo && next <= hi) {
                return None;
            }
            let moved = (next - x).abs();
            x = next;
            if moved < 1e-10 * a {
                return Some(x);
            }
        }
        None
    }

    /// H' and H'' of a disk of radius `a` centred over `centre` touching the track at x.
    fn centre_slopes(&self, x: f64, centre: f64, a: f64, mesh: &[f64]) -> [f64; 2] {
        let [_, f1, f2] = self.surface(x, mesh);
        let u = (x - centre) / a;
        let root = (1.0 - u * u).max(1e-12).sqrt();
        [f1 - u / root, f2 - 1.0 / (a * root * root * root)]
    }

    /// The crest `resting` names, followed from its centre to `centre`: in strides of the
    /// centre over which the crest, moving at dx/dX = κ / (κ − f'') (H' = 0 held), moves half
    /// the scan's spacing at the most, each refined within that of where the stride predicts
    /// it (by Newton's method from there, or in the bracket); a stride that finds no crest
    /// there is halved. Following rather than climbing keeps the disk on its own crest however
    /// fast it sweeps, and tells where it has gone ([`Followed`]).
    fn follow_crest(
        &self,
        resting: Resting,
        centre: f64,
        a: f64,
        mesh: &[f64],
        count: usize,
    ) -> Followed {
        let stride = a / count.max(DISK_SCAN) as f64;
        let (mut c, mut x) = (resting.centre, resting.crest);
        let mut step = centre - c;
        for _ in 0..FOLLOW_STRIDES {
            let [_, h2] = self.centre_slopes(x, c, a, mesh);
            let u = (x - c) / a;
            let kappa = 1.0 / (a * (1.0 - u * u).max(1e-12).powf(1.5));
            let speed = if h2 < 0.0 { -kappa / h2 } else { f64::INFINITY };
            let room = centre - c;
            step = step.abs().min(room.abs()).min(stride / speed) * room.signum();
            let next = c + step;
            let guess = x + speed.min(1e12) * step;
            let reach = a * (1.0 - 1e-9);
            let (lo, hi) = (
                (guess - stride).max(next - reach),
                (guess + stride).min(next + reach),
            );
            let found = (lo < hi).then(|| {
                self.newton_crest(next, a, mesh, guess.clamp(lo, hi), lo, hi)
                    .or_else(|| self.crest_between(next, a, mesh, lo, hi))
            });
            match found.flatten() {
                Some(found) => {
                    (c, x) = (next, found);
                    if c == centre {
                        return Followed::At(x);
                    }
                    step = 2.0 * step.abs();
                }
                None if step.abs() < 1e-9 * a => return Followed::Gone(x),
                None => step *= 0.5,
            }
        }
        Followed::Short(x)
    }

    /// The crest of H that `from` climbs to: walked uphill in half the scan's spacing (a
    /// sixteenth of the shortest wave, so that no hollow is stepped over) until H' turns, then
    /// refined in that bracket.
    fn crest_from(
        &self,
        centre: f64,
        a: f64,
        mesh: &[f64],
        count: usize,
        from: f64,
        height: &dyn Fn(f64) -> f64,
    ) -> f64 {
        let stride = a / count.max(DISK_SCAN) as f64;
        let (first, last) = (centre - a * (1.0 - 1e-9), centre + a * (1.0 - 1e-9));
        let rising = |x: f64| self.centre_slopes(x, centre, a, mesh)[0] > 0.0;
        let mut p = from.clamp(first, last);
        let up = if rising(p) { 1.0 } else { -1.0 };
        for _ in 0..=4 * count.max(DISK_SCAN) {
            let next = (p + up * stride).clamp(first, last);
            if next == p || rising(next) != (up > 0.0) {
                let (lo, hi) = (p.min(next), p.max(next));
                return self
                    .crest_between(centre, a, mesh, lo, hi)
                    .unwrap_or_else(|| golden_max(height, lo, hi, 1e-9 * a));
            }
            p = next;
        }
        p
    }

    /// How far the crest at `crest` (where the disk rests) lies above the highest other crest
    /// within the disk's reach, in radii: positive while the disk rests on the highest, zero
    /// where another comes level, which the disk then meets. Every other crest within what the
    /// scan may hide of that level is refined; the rest stand at their samples, which lie
    /// lower by more than the scan may hide, so the margin is continuous where it crosses
    /// zero; with it, the highest other crest. 1 where no other crest is within reach.
    pub(super) fn crest_margin(
        &self,
        centre: f64,
        a: f64,
        mesh: &[f64],
        crest: f64,
    ) -> (f64, Option<f64>) {
        let Some(count) = self.profile.crest_scan(a) else {
            return (1.0, None);
        };
        let height = |x: f64| -> f64 { self.surface(x, mesh)[0] + arc(x, centre, a) };
        let resting = height(crest);
        let other = self
            .scanned_crests(centre, a, mesh, count as usize, &height, |_, hidden| {
                resting - 2.0 * hidden
            })
            .into_iter()
            .filter(|(_, x)| (x - crest).abs() > 1e-6 * a)
            .max_by(|p, q| p.0.total_cmp(&q.0));
        match other {
            Some((h, x)) => ((resting - h) / a, Some(x)),
            None => (1.0, None),
        }
    }
}

/// Where [`VehiclesOnBeam::follow_crest`] took a crest.
enum Followed {
    /// To the centre asked about: the crest is there.
    At(f64),
    /// Into a hollow it merged with (it cannot be found within a billionth of the radius of
    /// where it was), last seen at the point given: climbing H from there carries the disk
    /// onto another crest, which rose above it before, unseen.
    Gone(f64),
    /// As far as [`FOLLOW_STRIDES`] took it: climbing H from there finds it.
    Short(f64),
}

/// Strides [`VehiclesOnBeam::follow_crest`] takes at the most: a crest followed over a step
/// of the run takes a few, one sweeping a hollow at sixty times the centre's speed some
/// hundred, and one near where it merges into a hollow halves its stride some thirty times
/// before it is given up.
const FOLLOW_STRIDES: usize = 400;

/// Newton steps with bisection a crest is refined in at the most: bisection alone halves a
/// bracket of a scan spacing (at least a 4096th of the reach) to a ten-billionth of the radius
/// in under 30.
const CREST_ITERATIONS: usize = 60;

/// How far above the track at x a disk of radius a centred over `centre` has its centre: the
/// centre's height H(x) is the track's plus this.
fn arc(x: f64, centre: f64, a: f64) -> f64 {
    let u = (x - centre) / a;
    a * (1.0 - u * u).max(0.0).sqrt()
}

/// The maximum of `height` bracketed by [lo, hi], by golden section to a bracket of `tol`.
fn golden_max(height: &dyn Fn(f64) -> f64, mut lo: f64, mut hi: f64, tol: f64) -> f64 {
    let golden = 0.5 * (5.0_f64.sqrt() - 1.0);
    while hi - lo > tol {
        let (m1, m2) = (hi - golden * (hi - lo), lo + golden * (hi - lo));
        // Far along a long deck 1e-9 of a small radius is below the positions' spacing: the
        // bracket stops shrinking there.
        if !(lo < m1 && m1 < m2 && m2 < hi) {
            break;
        }
        if height(m1) < height(m2) {
            lo = m1;
        } else {
            hi = m2;
        }
    }
    0.5 * (lo + hi)
}
