//! A rolling disk's contact force averaged over a period of the acceleration's cutoff. On a
//! mesh the instantaneous force can ring in the mesh's highest modes, which the steps the
//! accuracy asks for do not follow: on D50's 10 elements started carrying the disk its least
//! value was 1.5·10⁻³ of the weight off at the defaults, and set down at rest on the undamped
//! zip-line the touch's ringing moved it by 1.7·10⁻² from rtol 3.3·10⁻⁵ to 10⁻⁷. The mean over
//! the cutoff's period T keeps what is slower than the cutoff (a component at f by
//! sin(π f T)/(π f T): 0.7 % less at 2 Hz under 30 Hz) and is nil for whole periods of it; it is
//! read exactly from the disk's momentum, since its weight and the contact force are all that
//! act on it: R̄(t) = m (v(t + T/2) − v(t − T/2)) / T − m g, resolved in the contact frame at t.
//! The velocity integrates the ringing, so the mean needs no quadrature of it (both cases: the
//! defaults within 5·10⁻⁵ of the weight of rtol 10⁻⁷). A law whose rider is not a free rigid
//! body (the moving force and mass, the thesis' reduced system) has no such balance and no
//! mean.

use std::collections::VecDeque;

use crate::run::extremes::{Range, Turning, Watch};

/// Samples of the velocity a window spans: the means' extremes are taken on the parabola
/// through three of them, whose error on a component at the cutoff is of order
/// (2π/16)⁴/24 ≈ 10⁻³ of its amplitude, already damped in the mean.
const SAMPLES_PER_WINDOW: usize = 16;

/// What the run shows of a disk at a sample: its centre's velocity (global) and the contact
/// frame (tangent, normal; global), `None` while it flies.
#[derive(Clone, Copy)]
pub(super) struct Seen {
    pub velocity: [f64; 2],
    pub frame: Option<[[f64; 2]; 2]>,
}

/// The windowed means of the contact forces of the disks that have them.
pub(super) struct ContactMeans {
    window: f64,
    origin: f64,
    /// The next sample is at `origin + next × window / SAMPLES_PER_WINDOW`.
    next: u64,
    disks: Vec<Option<DiskMean>>,
}

/// One disk's samples over the last window, its last three means and their extremes.
struct DiskMean {
    mass: f64,
    gravity: f64,
    samples: VecDeque<(f64, Seen)>,
    means: VecDeque<(f64, [f64; 3])>,
    watch: Watch,
}

impl ContactMeans {
    /// Means over `window` seconds from `origin` on, for disks given as (mass, gravity) where
    /// their law balances momentum, `None` where not.
    pub fn new(window: f64, origin: f64, disks: &[Option<(f64, f64)>]) -> Self {
        ContactMeans {
            window,
            origin,
            next: 0,
            disks: disks
                .iter()
                .map(|d| {
                    d.map(|(mass, gravity)| DiskMean {
                        mass,
                        gravity,
                        samples: VecDeque::with_capacity(SAMPLES_PER_WINDOW + 1),
                        means: VecDeque::with_capacity(3),
                        watch: Watch::new(3, Turning::OnTheParabola),
                    })
                })
                .collect(),
        }
    }

    /// Take in the samples on the even grid in [t0, t1]; `see` gives each disk as the
    /// solution shows it at a time (`None` while a disk is not on or over the beam).
    pub fn record_span(&mut self, t0: f64, t1: f64, see: impl Fn(f64) -> Vec<Option<Seen>>) {
        if self.disks.iter().all(Option::is_none) {
            return;
        }
        let spacing = self.window / SAMPLES_PER_WINDOW as f64;
        loop {
            let t = self.origin + self.next as f64 * spacing;
            if t > t1 {
                return;
            }
            self.next += 1;
            if t < t0 {
                continue;
            }
            let seen = see(t);
            for (d, s) in self.disks.iter_mut().zip(seen) {
                if let Some(d) = d {
                    d.take(t, s, self.window);
                }
            }
        }
    }

    /// Per disk, the least and greatest mean normal and tangential force and the friction
    /// coefficient the means need, |R̄_t| / R̄_n where R̄_n > 0 (`None` for a disk without a
    /// mean, or never on the beam a whole window).
    pub fn ranges(&self) -> Vec<Option<[Range; 3]>> {
        self.disks
            .iter()
            .map(|d| {
                d.as_ref().and_then(|d| {
                    let r = &d.watch.ranges;
                    r[0].seen().then_some([r[0], r[1], r[2]])
                })
            })
            .collect()
    }
}

impl DiskMean {
    fn take(&mut self, t: f64, seen: Option<Seen>, window: f64) {
        let Some(seen) = seen else {
            self.samples.clear();
            self.means.clear();
            return;
        };
        self.samples.push_back((t, seen));
        if self.samples.len() <= SAMPLES_PER_WINDOW {
            return;
        }
        if self.samples.len() > SAMPLES_PER_WINDOW + 1 {
            self.samples.pop_front();
        }
        let (first, last) = (&self.samples[0].1, &self.samples[SAMPLES_PER_WINDOW].1);
        let (tc, centre) = &self.samples[SAMPLES_PER_WINDOW / 2];
        let Some([tangent, normal]) = centre.frame else {
            self.means.clear();
            return;
        };
        let force = [
            self.mass * (last.velocity[0] - first.velocity[0]) / window,
            self.mass * (last.velocity[1] - first.velocity[1]) / window + self.mass * self.gravity,
        ];
        let along = |e: [f64; 2]| force[0] * e[0] + force[1] * e[1];
        let (rn, rt) = (along(normal), along(tangent));
        let mu = if rn > 0.0 { rt.abs() / rn } else { f64::NAN };
        let mean = [rn, rt, mu];
        if self.means.len() == 3 {
            self.means.pop_front();
        }
        self.means.push_back((*tc, mean));
        match self.means.len() {
            3 => {
                let (a, b, c) = (&self.means[0], &self.means[1], &self.means[2]);
                self.watch
                    .record_parabola([a.0, b.0, c.0], [&a.1[..], &b.1[..], &c.1[..]]);
            }
            _ => self.watch.record_point(*tc, &mean),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A disk of 80 kg pressed on a level track by its weight and a force growing at 300 N/s,
    /// ringing at 15 times the cutoff with 60 N: over each whole window the ringing's mean is
    /// zero and the growing force's is its value at the centre, so the means are exact, from
    /// samples taken in uneven spans.
    #[test]
    fn a_ringing_force_averages_to_its_slow_part() {
        let (m, g, window) = (80.0, 9.81, 1.0 / 30.0);
        let w = std::f64::consts::TAU * 15.0 / window;
        // m v̇_y = R − m g with R = m g + 300 t + 60 sin(w t).
        let vy = |t: f64| (150.0 * t * t - 60.0 / w * (w * t).cos() + 60.0 / w) / m;
        let mut means = ContactMeans::new(window, 0.0, &[Some((m, g)), None]);
        let see = |t: f64| {
            vec![
                Some(Seen {
                    velocity: [1.0, vy(t)],
                    frame: Some([[1.0, 0.0], [0.0, 1.0]]),
                }),
                None,
            ]
        };
        let mut t = 0.0;
        for h in [0.013, 0.2, 0.0004, 0.5, 0.29].iter().cycle().take(10) {
            let next = f64::min(t + h, 1.0);
            means.record_span(t, next, see);
            t = next;
        }
        let ranges = means.ranges();
        assert!(ranges[1].is_none());
        let [rn, rt, mu] = ranges[0].expect("a mean");
        assert_eq!((mu.min, mu.max), (0.0, 0.0));
        let spacing = window / SAMPLES_PER_WINDOW as f64;
        assert!(
            (rn.min_t - window / 2.0).abs() < 1e-12,
            "first mean at {}",
            rn.min_t
        );
        assert!(
            rn.max_t > 1.0 - window / 2.0 - 1.5 * spacing,
            "last mean at {}",
            rn.max_t
        );
        for (got, want) in [
            (rn.min, m * g + 300.0 * rn.min_t),
            (rn.max, m * g + 300.0 * rn.max_t),
            (rt.min, 0.0),
            (rt.max, 0.0),
        ] {
            assert!((got - want).abs() < 1e-9 * m * g, "{got} against {want}");
        }
    }
}
