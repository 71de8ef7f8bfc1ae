//! Rayleigh damping, C = α M + β K₀, with K₀ the stiffness about the undeformed state: the
//! same damped system on every beam model. On a modal beam it is diagonal, each mode damped by
//! ζ_k = α/(2ω_k) + βω_k/2; on the mesh it is the constant sparse matrix. A scene gives α and β,
//! or a ratio ζ at the natural frequencies ω_i, ω_j of two modes the mesh has, which gives
//! α = 2ζ ω_i ω_j/(ω_i + ω_j) and β = 2ζ/(ω_i + ω_j).

/// Damping as a scene gives it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum DampingSpec {
    /// The damping ratio at the natural frequencies of modes i and j (1-based).
    Ratio {
        zeta: f64,
        modes: [usize; 2],
    },
    Rayleigh {
        alpha: f64,
        beta: f64,
    },
}

impl DampingSpec {
    /// Whether the stiffness-proportional part is there, which damps a mode the more the higher
    /// it is (ζ grows as βω/2); the mass-proportional part alone leaves the high modes free.
    pub fn damps_high_modes(&self) -> bool {
        match *self {
            DampingSpec::Ratio { zeta, .. } => zeta > 0.0,
            DampingSpec::Rayleigh { beta, .. } => beta > 0.0,
        }
    }
}

/// C = α M + β K₀.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Rayleigh {
    pub alpha: f64,
    pub beta: f64,
}

impl Rayleigh {
    /// α and β from the scene's spec and the circular frequencies of the beam's lowest modes
    /// (ascending); `None` when a ratio names a mode past `omega`.
    pub fn resolve(spec: DampingSpec, omega: &[f64]) -> Option<Rayleigh> {
        match spec {
            DampingSpec::Rayleigh { alpha, beta } => Some(Rayleigh { alpha, beta }),
            DampingSpec::Ratio { zeta, modes } => {
                let (wi, wj) = (*omega.get(modes[0] - 1)?, *omega.get(modes[1] - 1)?);
                Some(Rayleigh {
                    alpha: 2.0 * zeta * wi * wj / (wi + wj),
                    beta: 2.0 * zeta / (wi + wj),
                })
            }
        }
    }

    /// The damping ratio this gives a mode of circular frequency ω.
    pub fn ratio_at(&self, omega: f64) -> f64 {
        self.alpha / (2.0 * omega) + self.beta * omega / 2.0
    }

    /// The highest mode a spec needs the frequency of.
    pub fn modes_needed(spec: DampingSpec) -> usize {
        match spec {
            DampingSpec::Ratio { modes, .. } => modes[0].max(modes[1]),
            DampingSpec::Rayleigh { .. } => 0,
        }
    }
}
