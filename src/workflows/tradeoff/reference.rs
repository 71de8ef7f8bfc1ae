//! The converged reference a grid is scored against: computed (rtol cut tenfold until the
//! headlines settle, and one mesh finer on a beam) or read from the store beside the scene.

use super::*;

/// The reference is taken as settled when a tenfold cut of rtol moves no headline by more than
/// this (relative): a decade below the tightest accuracy the command reports on.
pub const REFERENCE_SETTLED: f64 = 1e-7;

/// At most this many tenfold cuts of the reference's rtol: a second-order reference costs
/// 10^(1/3) ≈ 2.2 times more per cut.
pub(super) const REFERENCE_CUTS: usize = 2;

/// The reference run and how settled it is.
pub struct Reference {
    pub method: Method,
    pub rtol: f64,
    pub elements: Option<usize>,
    /// The elements' degree, where the plan sweeps it (otherwise the scene's).
    pub order: Option<usize>,
    /// Largest relative headline change at the last tenfold cut of rtol.
    pub settled_to: f64,
    /// Largest relative headline difference from the same run on a mesh twice as fine: the
    /// mesh's own error, which no cut of rtol shows (`None` on a rigid curve, and in a
    /// reference stored before it was measured).
    pub mesh_gap: Option<f64>,
    pub headlines: Vec<Headline>,
    pub history: Vec<(f64, Vec<f64>)>,
    pub wall_s: f64,
    /// The command that computes it again.
    pub made_by: String,
    /// The probes' windowed means, where a reference for them was made.
    pub means: Option<MeansReference>,
}

/// The reference for the probes' Hann-windowed means (`BeamRun::windowed_means`): a headline
/// the fast modes' phase leaves alone, so it converges where the extremes cannot (REPORT.md,
/// "A windowed mean reaches 10⁻⁶ on the sudden loads"). It has its own run, since the means
/// need a fourth-order method, not the extremes' reference's tenfold cuts of rtol.
#[derive(Clone, Debug)]
pub struct MeansReference {
    pub method: Method,
    pub rtol: f64,
    pub elements: Option<usize>,
    /// The elements' degree, where it is not the scene's.
    pub order: Option<usize>,
    pub values: Vec<f64>,
    /// The largest |w| of that run's probes: what an error in the means is relative to.
    pub scale: f64,
    /// The larger of how far the means move at a tenfold cut of rtol and on a mesh half as
    /// fine.
    pub resolves: f64,
    pub wall_s: f64,
    pub made_by: String,
}

/// The means' reference for a beam scene: [`Plan::means_method`] a decade below the tightest
/// rtol tried ([`Plan::means_rtol`]) on twice the finest mesh tried, of the highest degree
/// tried ([`Plan::means_mesh`]), checked at a tenfold rtol and on a mesh half as fine.
pub fn means_reference(scene: &Scene, plan: &Plan, made_by: &str) -> Result<MeansReference, Error> {
    let Some(beam) = scene.beam() else {
        return Err(Error::Input(format!(
            "{}: windowed means are a beam's headline; the scene has no beam",
            scene.name
        )));
    };
    let (elements, order) = plan.means_mesh();
    let elements = elements.unwrap_or(2 * beam.beam.elements);
    let method = plan.means_method();
    let run_on = |elements: usize, rtol: f64| {
        let s = with_mesh(scene, Some(elements), order, None);
        run::run(&s, &with_means(overrides(method, rtol, usize::MAX)), false)
    };
    let rtol = plan.means_rtol();
    let fine = run_on(elements, rtol)?;
    let looser = run_on(elements, 10.0 * rtol)?;
    let coarser = run_on(elements.div_ceil(2), rtol)?;
    let means = |r: &Run| windowed_means(r).unwrap_or_default().to_vec();
    let scale = headlines(&fine)
        .iter()
        .filter(|h| h.family == "w")
        .fold(0.0_f64, |m, h| m.max(h.value.abs()))
        .max(f64::MIN_POSITIVE);
    let mut reference = MeansReference {
        method,
        rtol,
        elements: Some(elements),
        order,
        values: means(&fine),
        scale,
        resolves: 0.0,
        wall_s: [&fine, &looser, &coarser]
            .iter()
            .map(|r| r.header().stats.wall_s)
            .sum(),
        made_by: made_by.to_string(),
    };
    reference.resolves =
        mean_error(&means(&looser), &reference).max(mean_error(&means(&coarser), &reference));
    Ok(reference)
}

impl Reference {
    /// The smallest error the reference can score a run to: how far it is settled in time,
    /// or in its mesh where that was measured.
    pub fn resolves(&self) -> f64 {
        self.settled_to.max(self.mesh_gap.unwrap_or(0.0))
    }
}

/// The method a reference is computed with: the most accurate for the kind of scene.
pub fn reference_method(scene: &Scene) -> Method {
    match &scene.model {
        Model::Rolling(_) => Method::Dopri5,
        Model::Beam(_) => Method::GenAlpha,
    }
}

/// Compute the reference; `made_by` is the command that does it again.
pub fn reference(scene: &Scene, plan: &Plan, made_by: &str) -> Result<Reference, Error> {
    let method = reference_method(scene);
    let elements = match &scene.model {
        Model::Rolling(_) => None,
        Model::Beam(_) => Some(2 * plan.meshes.iter().copied().max().unwrap_or(1)),
    };
    let order = plan.reference_order();
    let fine = with_mesh(scene, elements, order, None);
    let mut rtol = plan.reference_rtol();
    let run_at = |rtol: f64| run::run(&fine, &overrides(method, rtol, usize::MAX), false);
    let mut last = run_at(rtol)?;
    let mut wall = last.header().stats.wall_s;
    let mut settled_to = f64::INFINITY;
    for _ in 0..REFERENCE_CUTS {
        let next = run_at(rtol / 10.0)?;
        wall += next.header().stats.wall_s;
        settled_to = headline_error(&headlines(&last), &headlines(&next));
        rtol /= 10.0;
        last = next;
        if settled_to <= REFERENCE_SETTLED {
            break;
        }
    }
    // The cuts of rtol say nothing of the mesh; one run on a mesh twice as fine does. On the
    // undamped studies it is the larger of the two (docs/numerics.md, "The work–precision grids").
    let mesh_gap = match elements {
        Some(n) => {
            let finer = with_mesh(scene, Some(2 * n), order, None);
            let check = run::run(&finer, &overrides(method, rtol, usize::MAX), false)?;
            wall += check.header().stats.wall_s;
            Some(headline_error(&headlines(&last), &headlines(&check)))
        }
        None => None,
    };
    Ok(Reference {
        method,
        rtol,
        elements,
        order,
        settled_to,
        mesh_gap,
        headlines: headlines(&last),
        history: history(&last),
        wall_s: wall,
        made_by: made_by.to_string(),
        means: None,
    })
}
