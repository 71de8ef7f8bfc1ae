//! The width of the contact patch, from physics, and how much a result depends on it.
//!
//! A beam theory carries a wheel's load on its axis. The load enters at the top face and
//! spreads through the section: EN 1991-2 §4.3.6 disperses a concentrated load at one
//! horizontal to one vertical down to the mid-plane of the deck, so on the axis it acts over a
//! length of about the depth h, widened by the Hertz contact at the face. A patch shorter than
//! that is not physics but the beam theory's artefact: under a point force a Timoshenko axis
//! kinks by P/(G Av), and a disk rolling over the kink feels a curvature of the averaged track
//! that grows as the patch shrinks (see `REPORT.md`, "What depends on the patch").
//!
//! The patch's kernel K(ξ) ∝ (1 − (ξ/b)²)⁴ has variance b²/11; a uniform load over ±c has c²/3.
//! The default b gives the kernel the second moment of the uniform load over
//! c = h/2 + a_H, a_H Hertz's half-width of a cylinder of the disk's radius pressed by its weight
//! on a face of the section's width A/h: b = c √(11/3).

use crate::beam::element::Section;

/// √(11/3): the kernel half-width with the second moment of a uniform load over ±1.
const KERNEL_PER_UNIFORM: f64 = 1.914_854_215_512_676;

/// The depth of the rectangle with the section's area and second moment: √(12 I / A). Exact for
/// a rectangle; an I-section is shallower than this (an HEB 360 is 0.36 m deep, its rectangle
/// 0.54 m), so a scene may give `track.beam.depth`.
pub fn rectangular_depth(section: &Section) -> f64 {
    (12.0 * section.rho_i / section.rho_a).sqrt()
}

/// Hertz's half-width of the contact of a cylinder of radius `radius`, pressed by `force`, on a
/// flat face of width A/h of the section's material: a = √(4 P R / (π E (A/h))), with
/// E A / h = ea / depth.
pub fn hertz_half_width(section: &Section, depth: f64, radius: f64, force: f64) -> f64 {
    (4.0 * force.abs() * radius * depth / (std::f64::consts::PI * section.ea)).sqrt()
}

/// The default half-width b of the patch: the kernel with the spread of the load dispersed
/// through half the depth, plus the Hertz contact, at one to one.
pub fn physical_half_width(section: &Section, depth: f64, radius: f64, force: f64) -> f64 {
    KERNEL_PER_UNIFORM * (0.5 * depth + hertz_half_width(section, depth, radius, force))
}

/// The half-width of the patch a train's axle rides on as a moving mass: the load dispersed
/// through half the depth at one to one (a wheel's Hertz contact on a rail is a few
/// millimetres, nothing beside it).
pub fn dispersed_half_width(depth: f64) -> f64 {
    KERNEL_PER_UNIFORM * 0.5 * depth
}

/// How strongly a disk's results depend on the patch width, from the kink the shear-flexible
/// axis takes under its weight.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sensitivity {
    /// P/(G Av): the angle the axis kinks by under the point force P (rad).
    pub kink_angle: f64,
    /// The kink rounded off over the patch moves the deflection under the disk by about
    /// θ b / 4; this is that over the size of the response.
    pub deflection: f64,
    /// The averaged track bends by about θ / b under the disk; rolling over it at speed v takes
    /// m v² θ / b of the normal force: this is that over the weight, v² θ / (g b).
    pub contact_force: f64,
}

impl Sensitivity {
    /// For a disk of weight `force` at speeds up to `speed` on a beam of shear stiffness
    /// `section.gav`, through a patch of half-width `half`, against a response of size
    /// `response` (m).
    pub fn of(
        section: &Section,
        force: f64,
        gravity: f64,
        speed: f64,
        half: f64,
        response: f64,
    ) -> Sensitivity {
        let kink_angle = force.abs() / section.gav;
        // Saturated rather than infinite: an absurd scene still prints a number.
        Sensitivity {
            kink_angle,
            deflection: (kink_angle * half / (4.0 * response.max(f64::MIN_POSITIVE))).min(f64::MAX),
            contact_force: if gravity > 0.0 {
                (speed * speed * kink_angle / (gravity * half)).min(f64::MAX)
            } else {
                0.0
            },
        }
    }

    /// What the results depend on the patch for, against the accuracy asked: one phrase each.
    pub fn warnings(&self, accuracy: f64) -> Vec<String> {
        let mut out = Vec::new();
        if self.deflection > accuracy {
            out.push(format!(
                "the deflection under the disk depends on the contact patch: the axis kinks by P/(G Av) = {:.2e} rad under the disk, which the patch rounds off by about {:.1e} of the response, above the accuracy {accuracy:.0e}",
                self.kink_angle, self.deflection
            ));
        }
        if self.contact_force > accuracy {
            out.push(format!(
                "the contact force and any loss of contact depend on the contact patch: rolling over the kink of {:.2e} rad takes about {:.1e} of the disk's weight, above the accuracy {accuracy:.0e}",
                self.kink_angle, self.contact_force
            ));
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The kernel's second moment against a uniform load's, by quadrature of the kernel.
    #[test]
    fn kernel_matches_the_spread_of_a_uniform_load() {
        let n = 200_000;
        let (mut m0, mut m2) = (0.0, 0.0);
        for k in 0..n {
            let x = -1.0 + (k as f64 + 0.5) * 2.0 / n as f64;
            let w = (1.0 - x * x).powi(4);
            m0 += w;
            m2 += w * x * x;
        }
        let c = 1.0 / KERNEL_PER_UNIFORM;
        assert!((m2 / m0 - c * c / 3.0).abs() < 1e-9);
    }

    #[test]
    fn a_rectangle_is_its_own_depth() {
        let (b, h, rho) = (0.3, 0.2, 1000.0);
        let s = Section {
            ea: 1.0,
            gav: 1.0,
            ei: 1.0,
            rho_a: rho * b * h,
            rho_i: rho * b * h.powi(3) / 12.0,
        };
        assert!((rectangular_depth(&s) - h).abs() < 1e-14);
    }
}
