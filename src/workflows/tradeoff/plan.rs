//! What a work–precision run tries: the grid's methods, tolerances, meshes, degrees and models,
//! and the settings of one run of it.

use super::*;

/// What to try.
#[derive(Clone, Debug)]
pub struct Plan {
    pub methods: Vec<Method>,
    pub rtols: Vec<f64>,
    /// Element counts (beam scenes; empty on a rigid curve).
    pub meshes: Vec<usize>,
    /// Lagrange degrees of the elements (beam scenes; empty: the scene's own).
    pub orders: Vec<usize>,
    /// Beam models (beam scenes; empty: the scene's own).
    pub models: Vec<BeamModel>,
    pub max_steps: usize,
    /// An rtol the reference starts a decade below even where the grid stops short of it:
    /// a grid cut for time must not loosen what its runs are scored against.
    pub reference_from: Option<f64>,
    /// Settings past the grid, each run once: a mesh finer and of a higher degree than any the
    /// grid tries, where only that reaches a target (the bridges' 10⁻⁶ in the windowed means).
    /// Chosen for what they reach, they may take [`POINT_STEPS_FACTOR`] times a grid run's steps,
    /// and are not judged by the pace of their first steps: the zip-line's first 2000 project
    /// 16–27 times the steps its runs take.
    pub points: Vec<GridPoint>,
}

/// How many times `max_steps` a point past the grid may take.
pub const POINT_STEPS_FACTOR: usize = 10;

impl Plan {
    /// The rtol the reference starts at: a decade below the tightest rtol tried, or below
    /// `reference_from` where that is tighter.
    pub fn reference_rtol(&self) -> f64 {
        let tightest = self.rtols.iter().copied().fold(1.0, f64::min);
        tightest.min(self.reference_from.unwrap_or(1.0)) / 10.0
    }

    /// The degree the reference is computed with: the highest tried (`None`: the scene's).
    pub fn reference_order(&self) -> Option<usize> {
        self.orders.iter().copied().max()
    }

    /// The mesh the windowed means' reference is made on: twice the finest tried, of the
    /// highest degree tried, the points past the grid included (`None`: the scene's).
    pub fn means_mesh(&self) -> (Option<usize>, Option<usize>) {
        let highest = |grid: &[usize], of_point: fn(&GridPoint) -> Option<usize>| {
            grid.iter()
                .copied()
                .chain(self.points.iter().filter_map(of_point))
                .max()
        };
        (
            highest(&self.meshes, |p| p.elements).map(|n| 2 * n),
            highest(&self.orders, |p| p.order),
        )
    }

    /// The rtol the windowed means' reference is made at: a decade below the tightest tried,
    /// the points past the grid included. On the sudden loads (grid to 1e-4) that is 1e-5,
    /// which settles the means to 10⁻⁹, mesh and time together (REPORT.md), in a minute or
    /// two. The bridges' stored means were made with their grid to 1e-5 (`--rtols`, in the
    /// command each records), so at 1e-6: at 1e-5 D44's resolved only 8.9·10⁻⁷, too near the
    /// 10⁻⁶ its point is scored to. The rubber's point at 1e-8 puts its means at 1e-9.
    pub fn means_rtol(&self) -> f64 {
        self.rtols
            .iter()
            .copied()
            .chain(self.points.iter().map(|p| p.rtol))
            .fold(1.0, f64::min)
            / 10.0
    }

    /// The method the windowed means' reference is made with: that of the tightest point past
    /// the grid, the setting chosen to reach deepest (on the zip-line generalized-α: ESDIRK4
    /// gives up there below rtol 1e-3), and otherwise ESDIRK4, whose fourth order settles the
    /// sudden loads' means to 10⁻⁹.
    pub fn means_method(&self) -> Method {
        self.points
            .iter()
            .min_by(|a, b| a.rtol.total_cmp(&b.rtol))
            .map_or(Method::Esdirk4, |p| p.method)
    }

    /// The steps a run of this point may take, and whether it spends them whole: a point past
    /// the grid does, and may take [`POINT_STEPS_FACTOR`] times a grid run's.
    pub fn budget(&self, point: &GridPoint) -> (usize, bool) {
        if self.points.contains(point) {
            (POINT_STEPS_FACTOR.saturating_mul(self.max_steps), true)
        } else {
            (self.max_steps, false)
        }
    }

    /// Every method that can integrate the scene, rtol from 1e-2 to 1e-8 (1e-6 on a beam), and
    /// on a beam the scene's mesh and one half as fine. Dormand–Prince is left out on a beam:
    /// explicit, it is held to the stability limit of the stiffest mode (its steps grow as √E,
    /// test `stiffness_from_rubber_to_fifty_times_steel`), and with a disk on the beam it
    /// factorises the state-dependent mass at every evaluation; `--methods` brings it back.
    pub fn default_for(scene: &Scene) -> Plan {
        match &scene.model {
            Model::Rolling(_) => Plan {
                methods: vec![Method::Dopri5, Method::TrBdf2, Method::Esdirk4],
                rtols: (2..=8).map(|k| 10f64.powi(-k)).collect(),
                meshes: Vec::new(),
                orders: Vec::new(),
                models: Vec::new(),
                max_steps: 200_000,
                reference_from: None,
                points: Vec::new(),
            },
            Model::Beam(b) => Plan {
                methods: vec![Method::GenAlpha, Method::Esdirk4, Method::TrBdf2],
                rtols: (2..=6).map(|k| 10f64.powi(-k)).collect(),
                meshes: vec![b.beam.elements.div_ceil(2), b.beam.elements],
                orders: Vec::new(),
                models: Vec::new(),
                max_steps: 20_000,
                reference_from: None,
                points: Vec::new(),
            },
        }
    }
}

/// The scene with its beam meshed into `elements` of degree `order` and modelled as `model`.
pub(super) fn with_mesh(
    scene: &Scene,
    elements: Option<usize>,
    order: Option<usize>,
    model: Option<BeamModel>,
) -> Scene {
    let mut s = scene.clone();
    if let Model::Beam(b) = &mut s.model {
        if let Some(n) = elements {
            b.beam.elements = n;
        }
        if let Some(p) = order {
            b.beam.order = p;
        }
        if let Some(m) = model {
            b.beam.model = m;
        }
    }
    s
}

/// "exact", "linear", "modal:16".
pub fn model_label(model: BeamModel) -> String {
    match model {
        BeamModel::Modal { modes } => format!("modal:{modes}"),
        other => other.name().to_string(),
    }
}

/// A beam model as `--models` names it: exact, linear or modal:N.
pub fn parse_model(text: &str) -> Result<BeamModel, Error> {
    match text {
        "exact" => Ok(BeamModel::Exact),
        "linear" => Ok(BeamModel::Linear),
        _ => text
            .strip_prefix("modal:")
            .and_then(|n| n.parse::<usize>().ok())
            .filter(|n| (1..=crate::beam::modal::MAX_MODES).contains(n))
            .map(|modes| BeamModel::Modal { modes })
            .ok_or_else(|| {
                Error::Input(format!(
                    "--models {}: a beam model is exact, linear or modal:N with N from 1 to {}",
                    crate::error::quote(text),
                    crate::beam::modal::MAX_MODES
                ))
            }),
    }
}

/// atol is a thousandth of rtol, so that the tolerance a run is asked for is its rtol: the
/// states here are metres, radians and their rates, of order 10⁻² and up.
pub(super) fn overrides(method: Method, rtol: f64, max_steps: usize) -> Overrides {
    Overrides {
        method: Some(method),
        rtol: Some(rtol),
        atol: Some(rtol * 1e-3),
        fixed_step: None,
        max_steps: Some(max_steps),
        ..Default::default()
    }
}

/// The same, recording the probes' windowed means.
pub(super) fn with_means(over: Overrides) -> Overrides {
    Overrides {
        windowed_means: true,
        ..over
    }
}
