//! The scene file's structure as serde reads it: every value with its location, nothing checked.

use super::*;

#[derive(Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub(super) struct SceneFile {
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) name: Option<Spanned<String>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) gravity: Option<Spanned<f64>>,
    pub(super) duration: Spanned<f64>,
    pub(super) track: Spanned<TrackFile>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) disk: Option<Spanned<DiskFile>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) disks: Option<Spanned<Vec<Spanned<DiskFile>>>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) train: Option<Spanned<TrainFile>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) vehicles: Option<Spanned<Vec<Spanned<VehicleFile>>>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) loads: Option<Spanned<Vec<Spanned<LoadFile>>>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) solver: Option<SolverFile>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) output: Option<OutputFile>,
}

#[derive(Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub(super) struct TrackFile {
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) curve: Option<Spanned<CurveFile>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) beam: Option<Spanned<BeamFile>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) profile: Option<Spanned<ProfileFile>>,
}

#[derive(Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
#[allow(non_snake_case)]
pub(super) struct BeamFile {
    pub(super) from: Spanned<[f64; 2]>,
    pub(super) to: Spanned<[f64; 2]>,
    pub(super) E: Spanned<f64>,
    pub(super) G: Spanned<f64>,
    pub(super) rho: Spanned<f64>,
    pub(super) A: Spanned<f64>,
    pub(super) Av: Spanned<f64>,
    pub(super) I: Spanned<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) depth: Option<Spanned<f64>>,
    pub(super) supports: Spanned<SupportsFile>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) elements: Option<Spanned<i64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) order: Option<Spanned<i64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) quadrature: Option<Spanned<String>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) initial: Option<Spanned<String>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) model: Option<Spanned<String>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) modes: Option<Spanned<i64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) damping: Option<Spanned<DampingFile>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) self_weight: Option<Spanned<bool>>,
}

#[derive(Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub(super) struct TrainFile {
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) hslm: Option<Spanned<String>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) axles: Option<Spanned<Vec<f64>>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) load: Option<Spanned<AxleLoads>>,
    pub(super) speed: Spanned<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) model: Option<Spanned<String>>,
}

/// One force for every axle, or one each.
#[derive(Clone, Deserialize, Serialize)]
#[serde(untagged)]
pub(super) enum AxleLoads {
    Each(Vec<f64>),
    All(f64),
}

#[derive(Clone, Default, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub(super) struct DampingFile {
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) ratio: Option<Spanned<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) modes: Option<Spanned<Vec<i64>>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) alpha: Option<Spanned<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) beta: Option<Spanned<f64>>,
}

#[derive(Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub(super) struct SupportsFile {
    pub(super) from: Spanned<String>,
    pub(super) to: Spanned<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) intermediate: Option<Spanned<Vec<Spanned<f64>>>>,
}

#[derive(Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub(super) struct LoadFile {
    pub(super) x: Spanned<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) fx: Option<Spanned<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) fy: Option<Spanned<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) mz: Option<Spanned<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) from: Option<Spanned<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) until: Option<Spanned<f64>>,
}

#[derive(Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub(super) struct ProbeFile {
    pub(super) name: Spanned<String>,
    pub(super) x: Spanned<f64>,
}

#[derive(Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub(super) struct CurveFile {
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) parabola: Option<ParabolaFile>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) line: Option<LineFile>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) expr: Option<ExprFile>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) points: Option<Spanned<Vec<Spanned<[f64; 2]>>>>,
}

#[derive(Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub(super) struct ParabolaFile {
    pub(super) k: Spanned<f64>,
}

#[derive(Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub(super) struct LineFile {
    pub(super) from: Spanned<[f64; 2]>,
    pub(super) to: Spanned<[f64; 2]>,
}

#[derive(Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub(super) struct ExprFile {
    pub(super) x: Spanned<String>,
    pub(super) y: Spanned<String>,
}

#[derive(Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub(super) struct DiskFile {
    pub(super) mass: Spanned<f64>,
    pub(super) radius: Spanned<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) s0: Option<Spanned<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) omega0: Option<Spanned<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) coupling: Option<Spanned<String>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) formulation: Option<Spanned<String>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) mu: Option<Spanned<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) patch: Option<Spanned<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) contact_loss: Option<Spanned<String>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) restitution: Option<Spanned<f64>>,
}

#[derive(Clone, Default, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub(super) struct SolverFile {
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) method: Option<Spanned<String>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) rtol: Option<Spanned<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) atol: Option<Spanned<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) rho_inf: Option<Spanned<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) accuracy: Option<Spanned<f64>>,
}

#[derive(Clone, Default, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub(super) struct OutputFile {
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) interval: Option<Spanned<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) probes: Option<Spanned<Vec<Spanned<ProbeFile>>>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) shapes: Option<Spanned<Vec<Spanned<f64>>>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) magnify: Option<Spanned<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) acceleration_cutoff_hz: Option<Spanned<f64>>,
}
